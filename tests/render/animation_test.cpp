// Animations: GIF files read back frame by frame, SVG parsed as XML, the HTML page run in
// headless Chromium, MP4 by ffmpeg when it is there, every example in every format, and the
// nbar animate command.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <tinyxml2.h>
#include <unistd.h>
#include <iterator>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "nbar/io/model_file.hpp"
#include "nbar/kinematics/mechanism.hpp"
#include "nbar/kinematics/sweep.hpp"
#include "nbar/model/diagnostics.hpp"
#include "nbar/render/animation.hpp"
#include "nbar/render/image_canvas.hpp"
#include "render/render_support.hpp"

namespace {

namespace fs = std::filesystem;
using nbar::render::Animation;
using nbar::render::DrawOptions;
using nbar::render::ImageCanvas;

fs::path animation_temp_dir() {
  static const nbar::render::test_support::TempDir dir("nbar-animation-test-");
  return dir.path;
}

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

using nbar::render::test_support::quote;
using nbar::render::test_support::run;

struct Example {
  explicit Example(const std::string& name, int steps = 73)
      : file(nbar::io::load_model_file(std::string(NBAR_EXAMPLES_DIR) + "/" + name)),
        shared(std::make_shared<const nbar::Mechanism>(file.model)),
        mech(*shared),
        sweep(nbar::run_sweep(mech, nbar::SweepOptions{steps, 0})) {}
  nbar::io::LoadedModel file;
  std::shared_ptr<const nbar::Mechanism> shared;
  const nbar::Mechanism& mech;
  nbar::SweepResult sweep;
};

DrawOptions small(int width = 240, int height = 180) {
  DrawOptions o;
  o.width = width;
  o.height = height;
  o.margin = 10;
  return o;
}

// ------------------------------------------------------------------------------ GIF reader

struct Gif {
  int width = 0, height = 0;
  std::vector<std::uint8_t> palette;               // global, RGB
  std::vector<std::vector<std::uint32_t>> frames;  // composed, 0xRRGGBB per pixel
  std::vector<int> delays;                         // 1/100 s
  bool loops_forever = false;
  std::string error;
};

// LZW-decodes the sub-blocks of one image into colour indices.
std::vector<std::uint8_t> lzw_decode(const std::vector<std::uint8_t>& data, int min_code_size) {
  const int clear = 1 << min_code_size, end = clear + 1;
  std::vector<std::vector<std::uint8_t>> table;
  auto reset = [&] {
    table.assign(clear + 2, {});
    for (int i = 0; i < clear; ++i) table[i] = {static_cast<std::uint8_t>(i)};
  };
  reset();
  int size = min_code_size + 1;
  std::size_t bit = 0;
  int previous = -1;
  std::vector<std::uint8_t> out;
  while (bit + size <= 8 * data.size()) {
    int code = 0;
    for (int i = 0; i < size; ++i, ++bit) code |= ((data[bit / 8] >> (bit % 8)) & 1) << i;
    if (code == clear) {
      reset();
      size = min_code_size + 1;
      previous = -1;
      continue;
    }
    if (code == end) break;
    std::vector<std::uint8_t> entry;
    if (code < static_cast<int>(table.size())) {
      entry = table[code];
      if (previous >= 0 && table.size() < 4096) {
        auto added = table[previous];
        added.push_back(entry[0]);
        table.push_back(added);
      }
    } else if (previous >= 0 && code == static_cast<int>(table.size())) {
      entry = table[previous];
      entry.push_back(entry[0]);
      table.push_back(entry);
    } else {
      throw std::runtime_error("bad LZW code");
    }
    out.insert(out.end(), entry.begin(), entry.end());
    previous = code;
    if (static_cast<int>(table.size()) == (1 << size) && size < 12) ++size;
  }
  return out;
}

Gif read_gif(const std::string& bytes) {
  Gif g;
  std::size_t at = 0;
  auto need = [&](std::size_t n) {
    if (at + n > bytes.size()) throw std::runtime_error("truncated");
  };
  auto u8 = [&] {
    need(1);
    return static_cast<std::uint8_t>(bytes[at++]);
  };
  auto u16 = [&] {
    const int lo = u8();
    return lo | (u8() << 8);
  };
  auto sub_blocks = [&] {
    std::vector<std::uint8_t> data;
    for (int n = u8(); n != 0; n = u8())
      for (int i = 0; i < n; ++i) data.push_back(u8());
    return data;
  };
  try {
    need(6);
    if (bytes.compare(0, 6, "GIF89a") != 0) throw std::runtime_error("not GIF89a");
    at = 6;
    g.width = u16();
    g.height = u16();
    const int packed = u8();
    u8();
    u8();
    if (packed & 0x80)
      for (int i = 0; i < 3 * (1 << ((packed & 7) + 1)); ++i) g.palette.push_back(u8());
    std::vector<std::uint32_t> screen(static_cast<std::size_t>(g.width) * g.height, 0);
    int transparent = -1, delay = 0;
    for (;;) {
      const int block = u8();
      if (block == 0x3B) break;
      if (block == 0x21) {
        const int label = u8();
        const auto data = sub_blocks();
        if (label == 0xF9 && data.size() == 4) {
          delay = data[1] | (data[2] << 8);
          transparent = (data[0] & 1) ? data[3] : -1;
        } else if (label == 0xFF && data.size() == 14 &&
                   std::string(data.begin(), data.begin() + 11) == "NETSCAPE2.0") {
          g.loops_forever = data[11] == 1 && data[12] == 0 && data[13] == 0;
        }
      } else if (block == 0x2C) {
        const int left = u16(), top = u16(), w = u16(), h = u16(), flags = u8();
        if (flags & 0x40) throw std::runtime_error("interlaced");
        std::vector<std::uint8_t> palette = g.palette;
        if (flags & 0x80) {
          palette.clear();
          for (int i = 0; i < 3 * (1 << ((flags & 7) + 1)); ++i) palette.push_back(u8());
        }
        const int min_code = u8();
        const auto indices = lzw_decode(sub_blocks(), min_code);
        if (indices.size() < static_cast<std::size_t>(w) * h) throw std::runtime_error("short image data");
        if (left + w > g.width || top + h > g.height) throw std::runtime_error("image outside the screen");
        for (int y = 0; y < h; ++y)
          for (int x = 0; x < w; ++x) {
            const int i = indices[static_cast<std::size_t>(y) * w + x];
            if (i == transparent) continue;
            if (3 * i + 2 >= static_cast<int>(palette.size())) throw std::runtime_error("index outside the palette");
            screen[static_cast<std::size_t>(top + y) * g.width + left + x] =
                (std::uint32_t{palette[3 * i]} << 16) | (std::uint32_t{palette[3 * i + 1]} << 8) | palette[3 * i + 2];
          }
        g.frames.push_back(screen);
        g.delays.push_back(delay);
        transparent = -1;
      } else {
        throw std::runtime_error("unknown block " + std::to_string(block));
      }
    }
  } catch (const std::exception& e) {
    g.error = e.what();
  }
  return g;
}

std::uint32_t rgb(const ImageCanvas& c, int x, int y) {
  const auto p = c.pixel(x, y);
  return (std::uint32_t{p.r} << 16) | (std::uint32_t{p.g} << 8) | p.b;
}

// ---------------------------------------------------------------------------------- frames

TEST(Animation, FramesAreEvenlySpacedAndALoopDoesNotRepeatItsStart) {
  const Example crank("fourbar-crank-rocker.yaml", 361);  // 0 to 360 deg
  const Animation a(crank.shared, crank.sweep, small());
  EXPECT_TRUE(a.periodic());
  EXPECT_EQ(a.frame_count(), Animation::kDefaultMaxFrames);
  EXPECT_EQ(a.steps().front(), 0);
  EXPECT_EQ(a.steps()[1], 3);
  EXPECT_EQ(a.steps().back(), 357);
  EXPECT_DOUBLE_EQ(a.duration(), 120 / 24.0);

  const Animation all(crank.shared, crank.sweep, small(), 1000, 30);
  EXPECT_EQ(all.frame_count(), 360);  // every distinct pose, no more
  EXPECT_EQ(all.steps().back(), 359);

  const Example few("fourbar-crank-rocker.yaml", 13);
  const Animation every(few.shared, few.sweep, small());
  EXPECT_EQ(every.frame_count(), 12);
  for (int k = 0; k < 12; ++k) EXPECT_EQ(every.steps()[k], k);

  // A swing that does not come back: its last sample is shown.
  const Example rocker("fourbar-double-rocker.yaml", 50);
  const Animation swing(rocker.shared, rocker.sweep, small(), 10);
  if (!swing.periodic()) {
    EXPECT_EQ(swing.frame_count(), 10);
    EXPECT_EQ(swing.steps().front(), 0);
    EXPECT_EQ(swing.steps().back(), static_cast<int>(rocker.sweep.samples.size()) - 1);
  }
  EXPECT_THROW(Animation(crank.shared, nbar::SweepResult{}, small()), nbar::Error);
  EXPECT_THROW(Animation(crank.shared, crank.sweep, small(), 10, 0.0), nbar::Error);
}

// ------------------------------------------------------------------------------------- GIF

TEST(Animation, GifHasEveryFrameLoopsForeverAndShowsTheDrawing) {
  const Example ex("fourbar-crank-rocker.yaml");
  DrawOptions options = small(260, 190);
  options.traces = {ex.mech.model().find_point("P")};
  options.labels = true;
  const Animation a(ex.shared, ex.sweep, options, 9, 12.5);
  const fs::path path = animation_temp_dir() / "fourbar.gif";
  a.write_gif(path.string());
  const std::string bytes = read_file(path);
  ASSERT_GE(bytes.size(), 6u);
  EXPECT_EQ(bytes.substr(0, 6), "GIF89a");

  const Gif g = read_gif(bytes);
  ASSERT_EQ(g.error, "");
  EXPECT_EQ(g.width, 260);
  EXPECT_EQ(g.height, 190);
  EXPECT_TRUE(g.loops_forever);
  ASSERT_EQ(g.frames.size(), 9u);
  int total = 0;
  for (int d : g.delays) {
    EXPECT_TRUE(d == 8 || d == 9) << d;  // 1/12.5 s
    total += d;
  }
  EXPECT_EQ(total, 72);  // 9 frames at 12.5 a second, to the hundredth

  // Each frame, composed, is the picture drawn without antialiasing.
  for (int k = 0; k < 9; ++k) {
    SCOPED_TRACE("frame " + std::to_string(k));
    const ImageCanvas drawn = a.render_frame(k, false);
    int differ = 0;
    for (int y = 0; y < g.height; ++y)
      for (int x = 0; x < g.width; ++x)
        differ += g.frames[k][static_cast<std::size_t>(y) * g.width + x] != rgb(drawn, x, y);
    EXPECT_EQ(differ, 0);
  }
  EXPECT_NE(g.frames[0], g.frames[4]);  // it moves
}

TEST(Animation, GifWithMoreColoursThanAPaletteMapsToTheNearest) {
  // A big antialiased-looking picture cannot happen without antialiasing, but labels, traces
  // and translucent plates over each other add colours; whatever the count, every pixel must
  // come out near its colour.
  const Example ex("stephenson-sixbar.yaml", 40);
  DrawOptions options = small(300, 220);
  options.labels = true;
  for (std::size_t p = 0; p < ex.mech.model().points.size(); ++p) options.traces.push_back(static_cast<int>(p));
  const Animation a(ex.shared, ex.sweep, options, 5);
  const fs::path path = animation_temp_dir() / "sixbar.gif";
  a.write_gif(path.string());
  const Gif g = read_gif(read_file(path));
  ASSERT_EQ(g.error, "");
  ASSERT_EQ(g.frames.size(), 5u);
  const ImageCanvas drawn = a.render_frame(2, false);
  int far = 0;
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x) {
      const std::uint32_t want = rgb(drawn, x, y), got = g.frames[2][static_cast<std::size_t>(y) * g.width + x];
      for (int shift : {0, 8, 16})
        far += std::abs(static_cast<int>((want >> shift) & 0xff) - static_cast<int>((got >> shift) & 0xff)) > 40;
    }
  EXPECT_LT(far, g.width * g.height / 1000);
}

TEST(Animation, UnwritableFilesAreReportedWithTheirPath) {
  const Example ex("fourbar-crank-rocker.yaml", 13);
  const Animation a(ex.shared, ex.sweep, small(), 3);
  const std::string bad = "/nonexistent-nbar-dir/a";
  for (auto write : {&Animation::write_gif, &Animation::write_svg_animation, &Animation::write_html_animation}) {
    try {
      (a.*write)(bad);
      ADD_FAILURE() << "no exception";
    } catch (const nbar::Error& e) {
      EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
    }
  }
}

// ------------------------------------------------------------------------------------- SVG

const tinyxml2::XMLElement* find_id(const tinyxml2::XMLElement* e, const std::string& id) {
  if (!e) return nullptr;
  if (const char* a = e->Attribute("id"); a && id == a) return e;
  for (auto* c = e->FirstChildElement(); c; c = c->NextSiblingElement())
    if (auto* f = find_id(c, id)) return f;
  return nullptr;
}

int count_values(const char* values) {
  if (!values) return 0;
  int n = 1;
  for (const char* c = values; *c; ++c) n += *c == ';';
  return n;
}

TEST(Animation, SvgIsWellFormedAndMovesEveryBody) {
  const Example ex("fourbar-crank-rocker.yaml");
  DrawOptions options = small();
  options.labels = true;
  options.traces = {ex.mech.model().find_point("P")};
  const Animation a(ex.shared, ex.sweep, options, 24, 12);
  const fs::path path = animation_temp_dir() / "fourbar.svg";
  a.write_svg_animation(path.string());
  const std::string text = read_file(path);

  tinyxml2::XMLDocument doc;
  ASSERT_EQ(doc.Parse(text.c_str(), text.size()), tinyxml2::XML_SUCCESS) << doc.ErrorStr();
  const tinyxml2::XMLElement* svg = doc.RootElement();
  ASSERT_STREQ(svg->Name(), "svg");
  for (const nbar::Body& body : ex.mech.model().bodies) {
    SCOPED_TRACE(body.name);
    const auto* g = find_id(svg, "body-" + body.name);
    ASSERT_NE(g, nullptr);
    std::set<std::string> types;
    for (auto* t = g->FirstChildElement("animateTransform"); t; t = t->NextSiblingElement("animateTransform")) {
      types.insert(t->Attribute("type"));
      EXPECT_STREQ(t->Attribute("additive"), "sum");
      EXPECT_STREQ(t->Attribute("repeatCount"), "indefinite");
      EXPECT_STREQ(t->Attribute("dur"), "2s");
      EXPECT_EQ(count_values(t->Attribute("values")), 25);  // every frame and back to the first
    }
    EXPECT_EQ(types, (std::set<std::string>{"translate", "rotate"}));
  }
  // Labels of moving points follow them; traces stay.
  for (const char* p : {"A", "B", "P"}) {
    const auto* g = find_id(svg, std::string("label-") + p);
    ASSERT_NE(g, nullptr) << p;
    EXPECT_NE(g->FirstChildElement("animateTransform"), nullptr) << p;
  }
  const auto* traces = find_id(svg, "traces");
  ASSERT_NE(traces, nullptr);
  EXPECT_EQ(traces->FirstChildElement("animateTransform"), nullptr);
  EXPECT_LT(text.size(), 60000u);
}

// ------------------------------------------------------------------------------------ HTML

void expect_offline(const std::string& html) {
  const std::string svg_ns = "http://www.w3.org/2000/svg";
  for (std::size_t at = html.find("http://"); at != std::string::npos; at = html.find("http://", at + 1))
    EXPECT_EQ(html.compare(at, svg_ns.size(), svg_ns), 0) << html.substr(at, 60);
  EXPECT_EQ(html.find("https://"), std::string::npos);
  EXPECT_EQ(html.find("<link"), std::string::npos);
  EXPECT_EQ(html.find(" src="), std::string::npos);
}

TEST(Animation, HtmlIsSelfContained) {
  const Example ex("fourbar-crank-rocker.yaml");
  DrawOptions options = small();
  options.labels = true;
  const Animation a(ex.shared, ex.sweep, options, 30);
  const std::string html = a.html_animation();
  expect_offline(html);
  EXPECT_NE(html.find("<meta name=\"viewport\""), std::string::npos);
  EXPECT_NE(html.find("<svg "), std::string::npos);
  EXPECT_NE(html.find("id=\"play\""), std::string::npos);
  EXPECT_NE(html.find("type=\"range\""), std::string::npos);
  EXPECT_NE(html.find("data-errors=\"\""), std::string::npos);
  EXPECT_NE(html.find("crank = "), std::string::npos);  // the driver's value per frame
  EXPECT_LT(html.size(), 80000u);
}

using nbar::render::test_support::browser_command;

std::string body_attribute(const std::string& dom, const std::string& name) {
  const std::size_t body = dom.find("<body");
  if (body == std::string::npos) return "<no body>";
  const std::size_t end = dom.find('>', body);
  const std::string tag = dom.substr(body, end - body);
  const std::string key = " " + name + "=\"";
  const std::size_t at = tag.find(key);
  if (at == std::string::npos) return "<absent>";
  const std::size_t value = at + key.size();
  return tag.substr(value, tag.find('"', value) - value);
}

TEST(Animation, HtmlPlaysInHeadlessChromium) {
  REQUIRE_CHROMIUM(browser);
  const Example ex("fourbar-crank-rocker.yaml", 361);
  DrawOptions options;  // full size
  options.labels = true;
  options.traces = {ex.mech.model().find_point("P")};
  const Animation a(ex.shared, ex.sweep, options);  // 120 frames at 24 a second: 5 s per loop
  const fs::path dir = animation_temp_dir();
  const fs::path page = dir / "fourbar.html", dom = dir / "dom.html", shot = dir / "shot.png";
  a.write_html_animation(page.string());

  const std::string command = browser_command(browser, dir / "profile") + " --virtual-time-budget=3000 --dump-dom " +
                              quote("file://" + page.string()) + " > " + quote(dom.string()) + " 2> " +
                              quote((dir / "dom.err").string());
  ASSERT_EQ(run(command), 0) << command << "\n" << read_file(dir / "dom.err");
  const std::string after = read_file(dom);
  const std::string frame = body_attribute(after, "data-frame");
  EXPECT_EQ(body_attribute(after, "data-errors"), "");
  ASSERT_FALSE(frame.empty());
  EXPECT_GT(std::atoi(frame.c_str()), 10) << "frame " << frame;  // about 72 after 3 s
  EXPECT_NE(after.find("transform=\"translate("), std::string::npos);

  const std::string screenshot =
      browser_command(browser, dir / "profile") +
      " --virtual-time-budget=1500 --window-size=800,600 --screenshot=" + quote(shot.string()) + " " +
      quote("file://" + page.string()) + " > " + quote((dir / "shot.err").string()) + " 2>&1";
  ASSERT_EQ(run(screenshot), 0) << read_file(dir / "shot.err");
  const ImageCanvas png = ImageCanvas::read_png(shot.string());
  EXPECT_EQ(png.width(), 800);
  std::set<std::uint32_t> colours;
  for (int y = 0; y < png.height(); y += 2)
    for (int x = 0; x < png.width(); x += 2) colours.insert(rgb(png, x, y));
  EXPECT_GT(colours.size(), 20u);
}

TEST(Animation, HeadlessChromiumReportsScriptErrors) {
  // The page's error recorder works: a broken script shows in data-errors (so the test above
  // would see a failure of the player).
  REQUIRE_CHROMIUM(browser);
  const Example ex("fourbar-crank-rocker.yaml", 13);
  const Animation a(ex.shared, ex.sweep, small(), 12);
  std::string html = a.html_animation();
  html.insert(html.rfind("</body>"), "<script>no_such_function_in_nbar();</script>\n");
  const fs::path dir = animation_temp_dir();
  const fs::path page = dir / "broken.html", dom = dir / "broken-dom.html";
  std::ofstream(page) << html;
  ASSERT_EQ(run(browser_command(browser, dir / "profile2") + " --virtual-time-budget=500 --dump-dom " +
                quote("file://" + page.string()) + " > " + quote(dom.string()) + " 2>/dev/null"),
            0);
  EXPECT_NE(body_attribute(read_file(dom), "data-errors").find("no_such_function_in_nbar"), std::string::npos);
}

// ------------------------------------------------------------------------------------- MP4

TEST(Animation, Mp4ByFfmpeg) {
  const Example ex("fourbar-crank-rocker.yaml", 25);
  const Animation a(ex.shared, ex.sweep, small(201, 151), 12);  // odd sizes are padded
  const fs::path path = animation_temp_dir() / "fourbar.mp4";
  if (!Animation::program_available("ffmpeg")) GTEST_SKIP() << "ffmpeg is not installed";
  a.write_mp4(path.string());
  const std::string bytes = read_file(path);
  ASSERT_GT(bytes.size(), 100u);
  EXPECT_EQ(bytes.substr(4, 4), "ftyp");
}

TEST(Animation, Mp4WithoutFfmpegSaysSo) {
  const Example ex("fourbar-crank-rocker.yaml", 13);
  const Animation a(ex.shared, ex.sweep, small(), 3);
  const fs::path empty = animation_temp_dir() / "empty-path";
  fs::create_directories(empty);
  const char* old = std::getenv("PATH");
  const std::string saved = old ? old : "";
  ::setenv("PATH", empty.c_str(), 1);
  try {
    a.write_mp4((animation_temp_dir() / "never.mp4").string());
    ADD_FAILURE() << "no exception";
  } catch (const nbar::Error& e) {
    EXPECT_NE(std::string(e.what()).find("ffmpeg"), std::string::npos);
  }
  ::setenv("PATH", saved.c_str(), 1);
  EXPECT_FALSE(fs::exists(animation_temp_dir() / "never.mp4"));
}

// -------------------------------------------------------------------------------- examples

TEST(Animation, EveryExampleAnimatesInEveryFormat) {
  const fs::path dir = animation_temp_dir() / "examples";
  fs::create_directories(dir);
  int count = 0;
  for (const auto& entry : fs::directory_iterator(NBAR_EXAMPLES_DIR)) {
    if (entry.path().extension() != ".yaml") continue;
    const std::string name = entry.path().filename().string();
    SCOPED_TRACE(name);
    const Example ex(name, 19);
    ASSERT_FALSE(ex.sweep.samples.empty());
    DrawOptions options = small(200, 150);
    options.labels = true;
    const Animation a(ex.shared, ex.sweep, options, 6);
    const std::string stem = (dir / entry.path().stem()).string();
    ASSERT_NO_THROW(a.write_gif(stem + ".gif"));
    ASSERT_NO_THROW(a.write_html_animation(stem + ".html"));
    const Gif g = read_gif(read_file(stem + ".gif"));
    EXPECT_EQ(g.error, "");
    EXPECT_EQ(g.frames.size(), static_cast<std::size_t>(a.frame_count()));
    const std::string html = read_file(stem + ".html");
    expect_offline(html);
    const std::string svg = a.svg_animation();
    tinyxml2::XMLDocument doc;
    EXPECT_EQ(doc.Parse(svg.c_str(), svg.size()), tinyxml2::XML_SUCCESS) << doc.ErrorStr();
    ++count;
  }
  EXPECT_GE(count, 10);
}

// ------------------------------------------------------------------------------ nbar animate

TEST(AnimateCommand, WritesEachFormatAndRejectsOthers) {
  const fs::path dir = animation_temp_dir() / "cli";
  fs::create_directories(dir);
  const std::string cli = quote(NBAR_CLI_PATH);
  const std::string model = quote(std::string(NBAR_EXAMPLES_DIR) + "/fourbar-crank-rocker.yaml");
  const std::string quiet = " 2> " + quote((dir / "err.txt").string());
  for (const char* ext : {"gif", "svg", "html", "HTML"}) {
    const fs::path out = dir / (std::string("crank.") + ext);
    EXPECT_EQ(run(cli + " animate " + model + " -o " + quote(out.string()) +
                  " --frames 8 --fps 10 --steps 37 --labels --trace P,B --width 300 --height 200" + quiet),
              0)
        << ext << ": " << read_file(dir / "err.txt");
    EXPECT_GT(fs::file_size(out), 500u) << ext;
  }
  EXPECT_EQ(read_file(dir / "crank.gif").substr(0, 6), "GIF89a");
  const Gif g = read_gif(read_file(dir / "crank.gif"));
  EXPECT_EQ(g.width, 300);
  EXPECT_EQ(g.frames.size(), 8u);

  EXPECT_EQ(run(cli + " animate " + model + " -o " + quote((dir / "x.avi").string()) + quiet), 2);
  EXPECT_NE(read_file(dir / "err.txt").find(".gif, .svg, .html or .mp4"), std::string::npos);
  EXPECT_EQ(run(cli + " animate " + model + " -o " + quote((dir / "x.gif").string()) + " --trace Q" + quiet), 2);
  EXPECT_NE(read_file(dir / "err.txt").find("'Q'"), std::string::npos);
  EXPECT_EQ(run(cli + " animate " + quote((dir / "missing.yaml").string()) + " -o " + quote((dir / "x.gif").string()) +
                quiet),
            1);
  EXPECT_EQ(run(cli + " animate " + model + quiet), 2);  // no -o
  EXPECT_EQ(run(cli + " animate " + model + " -o /nonexistent-nbar-dir/a.gif" + quiet), 2);
  EXPECT_NE(read_file(dir / "err.txt").find("/nonexistent-nbar-dir/a.gif"), std::string::npos);
}

}  // namespace

namespace {

// A front-end (Python, the server) may drop its mechanism and sweep before the animation.
TEST(Animation, OutlivesTheSweepAndTheCallersMechanism) {
  const Example ex("fourbar-crank-rocker.yaml", 25);
  const Animation reference(ex.shared, ex.sweep, small(), 6);
  std::unique_ptr<Animation> kept;
  {
    auto mech = std::make_shared<const nbar::Mechanism>(ex.file.model);
    const nbar::SweepResult sweep = nbar::run_sweep(*mech, nbar::SweepOptions{25, 2});
    kept = std::make_unique<Animation>(std::move(mech), sweep, small(), 6);
  }  // the sweep and the caller's pointer are gone
  for (int k = 0; k < 6; ++k) {
    const ImageCanvas a = kept->render_frame(k), b = reference.render_frame(k);
    const std::size_t bytes = static_cast<std::size_t>(a.stride()) * 180;
    EXPECT_TRUE(std::equal(a.data(), a.data() + bytes, b.data())) << "frame " << k;
  }
  EXPECT_EQ(kept->html_animation(), reference.html_animation());
  EXPECT_EQ(kept->gif_bytes(), reference.gif_bytes());
}

TEST(Animation, GifBytesAreTheFilesBytes) {
  const Example ex("fourbar-crank-rocker.yaml", 13);
  const Animation a(ex.shared, ex.sweep, small(), 4);
  const fs::path path = animation_temp_dir() / "bytes.gif";
  a.write_gif(path.string());
  std::ifstream file(path, std::ios::binary);
  const std::vector<std::uint8_t> written((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  const std::vector<std::uint8_t> bytes = a.gif_bytes();
  EXPECT_EQ(bytes, written);
  ASSERT_GT(bytes.size(), 6u);
  EXPECT_EQ(std::string(bytes.begin(), bytes.begin() + 6), "GIF89a");
}

// A control that stops the writer at its n-th "frames" checkpoint only (and would let it go on
// if asked again): every writer stops there, with the Cancelled error, whichever pass it is in.
TEST(Animation, EveryWriterStopsBetweenFramesWhenItsControlSaysSo) {
  const Example ex("fourbar-crank-rocker.yaml", 13);
  Animation a(ex.shared, ex.sweep, small(), 6);
  const auto stop_at = [&](long n, long& calls) {
    calls = 0;
    nbar::RunControl control;
    control.on_progress = [n, &calls](const nbar::Progress& p) {
      return std::string(p.stage) != "frames" || ++calls != n;
    };
    a.set_control(control);
  };
  const auto expect_cancelled = [](const auto& write) {
    try {
      write();
      ADD_FAILURE() << "not stopped";
    } catch (const nbar::Error& e) {
      EXPECT_EQ(e.kind(), nbar::ErrorKind::Cancelled);
    }
  };
  long calls = 0;
  // The GIF: in the palette pass (frame 2) and in the frames pass (frame 6 + 3).
  for (long n : {2L, 9L}) {
    stop_at(n, calls);
    expect_cancelled([&] { (void)a.gif_bytes(); });
    EXPECT_EQ(calls, n);
  }
  stop_at(4, calls);
  expect_cancelled([&] { (void)a.svg_animation(); });
  stop_at(4, calls);
  expect_cancelled([&] { (void)a.html_animation(); });
  // Never stopped: every frame was checked, twice for the GIF.
  stop_at(-1, calls);
  EXPECT_EQ(a.gif_bytes(), Animation(ex.shared, ex.sweep, small(), 6).gif_bytes());
  EXPECT_EQ(calls, 12);
  if (Animation::program_available("ffmpeg")) {
    stop_at(3, calls);
    expect_cancelled([&] { (void)a.mp4_bytes(); });
  }
}

}  // namespace
