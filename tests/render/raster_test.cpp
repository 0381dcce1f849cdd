// ImageCanvas: cairo's rasterisation of the Canvas primitives, the drawing of a four-bar on it,
// and PNG files.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>

#include <unistd.h>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <numbers>
#include <set>
#include <string>

#include "nbar/io/model_file.hpp"
#include "nbar/kinematics/mechanism.hpp"
#include "nbar/kinematics/sweep.hpp"
#include "nbar/model/diagnostics.hpp"
#include "nbar/render/drawing.hpp"
#include "nbar/render/image_canvas.hpp"
#include "render/render_support.hpp"

namespace {

using nbar::render::Anchor;
using nbar::render::Colour;
using nbar::render::ImageCanvas;
using nbar::render::Outline;
using nbar::render::Paint;
using nbar::render::Stroke;
using V = Eigen::Vector2d;

const Colour kWhite = Colour::rgb(0xffffff);

bool same(const Colour& a, const Colour& b) { return a.r == b.r && a.g == b.g && a.b == b.b && a.a == b.a; }
bool background(const ImageCanvas& c, int x, int y) { return same(c.pixel(x, y), kWhite); }

std::filesystem::path raster_temp_dir() {
  static const nbar::render::test_support::TempDir dir("nbar-raster-test-");
  return dir.path;
}

std::vector<V> square(double x0, double y0, double x1, double y1) { return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}; }

TEST(ImageCanvas, StartsWhiteAndOpaque) {
  ImageCanvas c(40, 30);
  EXPECT_EQ(c.width(), 40);
  EXPECT_EQ(c.height(), 30);
  EXPECT_GE(c.stride(), 4 * 40);
  for (int y = 0; y < 30; ++y)
    for (int x = 0; x < 40; ++x) ASSERT_TRUE(background(c, x, y));
  // BGRA bytes.
  const std::uint8_t* p = c.data();
  EXPECT_EQ(p[0], 255);
  EXPECT_EQ(p[3], 255);
}

TEST(ImageCanvas, PolygonFillAndStrokeLandWhereTheyAreDrawn) {
  ImageCanvas c(100, 100);
  const Colour red = Colour::rgb(0xff0000), blue = Colour::rgb(0x0000ff);
  c.polygon(square(20, 20, 80, 60), Paint{red, Stroke{blue, 4, {}}});
  EXPECT_TRUE(same(c.pixel(50, 40), red));
  EXPECT_TRUE(same(c.pixel(50, 20), blue));  // on the edge: the stroke, painted after the fill
  EXPECT_TRUE(background(c, 50, 70));
  EXPECT_TRUE(background(c, 10, 40));
  // BGRA order in memory.
  const std::uint8_t* p = c.data() + 40 * c.stride() + 4 * 50;
  EXPECT_EQ(p[0], 0);
  EXPECT_EQ(p[1], 0);
  EXPECT_EQ(p[2], 255);
  EXPECT_EQ(p[3], 255);
}

TEST(ImageCanvas, OutlineIsFilledEvenOddWithPolygonAndCircleHoles) {
  ImageCanvas c(200, 100);
  const Colour green = Colour::rgb(0x00a000);
  Outline o;
  o.outer = square(10, 10, 190, 90);
  o.polygon_holes.push_back(square(30, 30, 70, 70));
  o.circle_holes.push_back({V(140, 50), 20});
  c.outline(o, Paint{green, std::nullopt});
  EXPECT_TRUE(same(c.pixel(20, 20), green));
  EXPECT_TRUE(same(c.pixel(100, 50), green));
  EXPECT_TRUE(background(c, 50, 50));   // in the square hole
  EXPECT_TRUE(background(c, 140, 50));  // in the round hole
  EXPECT_TRUE(background(c, 150, 45));
  EXPECT_TRUE(same(c.pixel(140, 25), green));  // just outside the round hole
  EXPECT_TRUE(background(c, 5, 5));
}

TEST(ImageCanvas, CirclesPolylinesDashesAndTranslucency) {
  ImageCanvas c(120, 60);
  const Colour ink = Colour::rgb(0x202020);
  c.circle(V(20, 30), 10, Paint{ink, std::nullopt});
  EXPECT_TRUE(same(c.pixel(20, 30), ink));
  EXPECT_TRUE(same(c.pixel(27, 30), ink));
  EXPECT_TRUE(background(c, 33, 30));
  // A dashed line: 6 on, 6 off from x = 40.
  c.polyline({V(40, 10.5), V(112, 10.5)}, Stroke{ink, 3, {6, 6}});
  EXPECT_FALSE(background(c, 43, 10));
  EXPECT_TRUE(background(c, 49, 10));  // in the gap 46-52, less the round caps' 1.5 px
  EXPECT_FALSE(background(c, 55, 10));
  // Half-transparent black over white is mid grey.
  c.polygon(square(40, 30, 100, 55), Paint{Colour::rgb(0x000000, 128), std::nullopt});
  const Colour g = c.pixel(70, 42);
  EXPECT_NEAR(g.r, 127, 2);
  EXPECT_EQ(g.r, g.g);
  EXPECT_EQ(g.a, 255);
}

TEST(ImageCanvas, WithoutAntialiasingOnlyTheColoursDrawnAppear) {
  ImageCanvas c(120, 80);
  c.set_antialias(false);
  EXPECT_FALSE(c.antialias());
  const Colour red = Colour::rgb(0xd62728), ink = Colour::rgb(0x222222);
  c.circle(V(40.3, 40.7), 17.2, Paint{red, Stroke{ink, 1.5, {}}});
  c.polyline({V(3, 3), V(117, 71)}, Stroke{ink, 2.2, {}});
  c.text(V(70, 30), "O2 P", 14, Anchor::Start, ink);
  std::set<std::uint32_t> colours;
  for (int y = 0; y < c.height(); ++y)
    for (int x = 0; x < c.width(); ++x) {
      const Colour p = c.pixel(x, y);
      colours.insert((std::uint32_t{p.r} << 16) | (std::uint32_t{p.g} << 8) | p.b);
    }
  EXPECT_EQ(colours, (std::set<std::uint32_t>{0xffffff, 0xd62728, 0x222222}));

  ImageCanvas smooth(120, 80);
  smooth.circle(V(40.3, 40.7), 17.2, Paint{red, Stroke{ink, 1.5, {}}});
  std::set<std::uint32_t> blended;
  for (int y = 0; y < smooth.height(); ++y)
    for (int x = 0; x < smooth.width(); ++x) {
      const Colour p = smooth.pixel(x, y);
      blended.insert((std::uint32_t{p.r} << 16) | (std::uint32_t{p.g} << 8) | p.b);
    }
  EXPECT_GT(blended.size(), 3u);
}

TEST(ImageCanvas, TextIsDrawnAtItsAnchor) {
  auto ink_columns = [](const ImageCanvas& c) {
    int lo = c.width(), hi = -1;
    for (int y = 0; y < c.height(); ++y)
      for (int x = 0; x < c.width(); ++x)
        if (!background(c, x, y)) lo = std::min(lo, x), hi = std::max(hi, x);
    return std::pair{lo, hi};
  };
  const Colour ink = Colour::rgb(0x000000);
  ImageCanvas start(200, 40), middle(200, 40), end(200, 40);
  start.text(V(100, 28), "Coupler", 16, Anchor::Start, ink);
  middle.text(V(100, 28), "Coupler", 16, Anchor::Middle, ink);
  end.text(V(100, 28), "Coupler", 16, Anchor::End, ink);
  const auto [s0, s1] = ink_columns(start);
  const auto [m0, m1] = ink_columns(middle);
  const auto [e0, e1] = ink_columns(end);
  ASSERT_GE(s1, 0) << "no text drawn";
  EXPECT_GE(s0, 99);
  EXPECT_GT(s1 - s0, 30);  // a word of 7 letters at 16 px
  EXPECT_LE(e1, 101);
  EXPECT_NEAR(0.5 * (m0 + m1), 100, 3);
  // Above the baseline.
  for (int x = 0; x < 200; ++x) EXPECT_TRUE(background(start, x, 33));
}

// ------------------------------------------------------------------------------- a four-bar

struct FourBar {
  nbar::io::LoadedModel file = nbar::io::load_model_file(std::string(NBAR_EXAMPLES_DIR) + "/fourbar-crank-rocker.yaml");
  nbar::Mechanism mech{file.model};
  nbar::SweepResult sweep = nbar::run_sweep(mech, nbar::SweepOptions{73, 0});
};

// Points where two or more links meet (ground counts as one), and fixed points.
std::vector<int> joints(const nbar::Model& m) {
  std::vector<int> out;
  for (std::size_t p = 0; p < m.points.size(); ++p) {
    int links = m.points[p].ground ? 1 : 0;
    for (const nbar::Body& b : m.bodies)
      for (int q : b.points) links += q == static_cast<int>(p);
    if (links >= 2 || m.points[p].ground) out.push_back(static_cast<int>(p));
  }
  return out;
}

TEST(ImageCanvas, DrawsAFourBarWhereTheViewPutsIt) {
  const FourBar fb;
  ASSERT_TRUE(fb.sweep.complete);
  nbar::render::DrawOptions options;
  options.width = 640;
  options.height = 480;
  options.labels = true;
  const nbar::render::View view = nbar::render::fit_view(fb.mech, fb.sweep, options);
  const nbar::Model& m = fb.mech.model();

  for (int step : {0, 20, 50}) {
    SCOPED_TRACE("step " + std::to_string(step));
    ImageCanvas c(options.width, options.height);
    const auto points = nbar::render::sample_points(fb.mech, fb.sweep.samples[step]);
    nbar::render::draw_mechanism(c, view, fb.mech, fb.sweep, points, options);

    // Every joint and pivot is marked: its pixel is drawn on, or a ring of ink surrounds it
    // (joints are small circles filled with the paper colour).
    const std::vector<int> marked = joints(m);
    ASSERT_GE(marked.size(), 4u);
    for (int p : marked) {
      SCOPED_TRACE("point " + m.points[p].name);
      const V at = view.to_pixels(points[p]);
      const int x = static_cast<int>(std::lround(at.x())), y = static_cast<int>(std::lround(at.y()));
      ASSERT_TRUE(x >= 0 && y >= 0 && x < c.width() && y < c.height());
      int ring = 0;
      for (int k = 0; k < 16; ++k) {
        const double a = 2 * std::numbers::pi * k / 16;
        const int rx = static_cast<int>(std::lround(at.x() + 4.5 * std::cos(a)));
        const int ry = static_cast<int>(std::lround(at.y() + 4.5 * std::sin(a)));
        ring += !background(c, rx, ry);
      }
      EXPECT_TRUE(!background(c, x, y) || ring == 16) << "ring " << ring << "/16";
    }
    // Points on no joint (the coupler point P) are dots.
    const int P = m.find_point("P");
    const V at = view.to_pixels(points[P]);
    EXPECT_FALSE(background(c, static_cast<int>(std::lround(at.x())), static_cast<int>(std::lround(at.y()))));

    // Nothing within 2 px of the edge.
    for (int y = 0; y < c.height(); ++y)
      for (int x = 0; x < c.width(); ++x)
        if (x < 2 || y < 2 || x >= c.width() - 2 || y >= c.height() - 2) {
          ASSERT_TRUE(background(c, x, y)) << x << "," << y;
        }
  }
}

TEST(ImageCanvas, TracedPathIsColoured) {
  const FourBar fb;
  nbar::render::DrawOptions options;
  options.width = 500;
  options.height = 400;
  const int P = fb.mech.model().find_point("P");
  const nbar::render::View view = nbar::render::fit_view(fb.mech, fb.sweep, options);
  const auto points = nbar::render::sample_points(fb.mech, fb.sweep.samples[0]);
  ImageCanvas plain(options.width, options.height), traced(options.width, options.height);
  nbar::render::draw_mechanism(plain, view, fb.mech, fb.sweep, points, options);
  options.traces = {P};
  nbar::render::draw_mechanism(traced, view, fb.mech, fb.sweep, points, options);

  // Where P goes over the sweep, the traced picture differs from the plain one (the path is
  // dashed, so within a pixel or two of most samples).
  int on_path = 0, samples = 0;
  for (const nbar::Sample& s : fb.sweep.samples) {
    const V at = view.to_pixels(nbar::render::sample_points(fb.mech, s)[P]);
    bool changed = false;
    for (int dy = -2; dy <= 2; ++dy)
      for (int dx = -2; dx <= 2; ++dx) {
        const int x = static_cast<int>(std::lround(at.x())) + dx, y = static_cast<int>(std::lround(at.y())) + dy;
        changed = changed || !same(plain.pixel(x, y), traced.pixel(x, y));
      }
    on_path += changed;
    ++samples;
  }
  EXPECT_GT(on_path, samples * 2 / 3) << on_path << " of " << samples;
  // And far from the path nothing changed: the corners.
  EXPECT_TRUE(same(plain.pixel(5, 5), traced.pixel(5, 5)));
}

TEST(ImageCanvas, PngRoundTrip) {
  const FourBar fb;
  nbar::render::DrawOptions options;
  options.width = 321;  // odd sizes: rows are padded to the stride
  options.height = 203;
  options.traces = {fb.mech.model().find_point("P")};
  options.labels = true;
  ImageCanvas c(options.width, options.height);
  nbar::render::draw_sample(c, fb.mech, fb.sweep, 10, options);
  const std::string path = (raster_temp_dir() / "fourbar.png").string();
  c.write_png(path);
  const ImageCanvas back = ImageCanvas::read_png(path);
  ASSERT_EQ(back.width(), c.width());
  ASSERT_EQ(back.height(), c.height());
  for (int y = 0; y < c.height(); ++y)
    ASSERT_EQ(0, std::memcmp(c.data() + y * c.stride(), back.data() + y * back.stride(), 4 * c.width())) << "row " << y;
  // The bytes a front-end sends are the file's bytes.
  std::ifstream file(path, std::ios::binary);
  const std::vector<std::uint8_t> written((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  const std::vector<std::uint8_t> bytes = c.png_bytes();
  EXPECT_EQ(bytes, written);
  ASSERT_GT(bytes.size(), 8u);
  EXPECT_EQ(std::vector<std::uint8_t>(bytes.begin(), bytes.begin() + 8),
            (std::vector<std::uint8_t>{0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'}));
  std::filesystem::remove(path);
}

TEST(ImageCanvas, FileErrorsNameThePath) {
  ImageCanvas c(10, 10);
  const std::string bad = "/nonexistent-nbar-dir/picture.png";
  try {
    c.write_png(bad);
    FAIL() << "no exception";
  } catch (const nbar::Error& e) {
    EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
  }
  try {
    (void)ImageCanvas::read_png(bad);
    FAIL() << "no exception";
  } catch (const nbar::Error& e) {
    EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
  }
  EXPECT_THROW(ImageCanvas(0, 10), nbar::Error);
}

}  // namespace
