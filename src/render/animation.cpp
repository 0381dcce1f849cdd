#include "nbar/render/animation.hpp"
#include "nbar/model/diagnostics.hpp"
#include "nbar/model/file_errors.hpp"
#include "nbar/render/stress_map.hpp"

#include <stdlib.h>

#include <unistd.h>
#include <filesystem>
#include <iterator>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <optional>
#include <stdexcept>
#include <utility>

namespace nbar::render {

namespace {

std::string fixed(double v, int decimals) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v + 0.0);
  std::string s(buf);
  if (s.find('.') != std::string::npos) {
    while (s.back() == '0') s.pop_back();
    if (s.back() == '.') s.pop_back();
  }
  return s == "-0" ? "0" : s;
}

std::string general(double v) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.4g", v + 0.0);
  return buf;
}

// A JavaScript string literal that is also safe inside <script>.
std::string js_string(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '<': out += "\\u003c"; break;
      case '>': out += "\\u003e"; break;
      case '&': out += "\\u0026"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", static_cast<unsigned>(c));
          out += buf;
        } else {
          out += c;
        }
    }
  }
  out += '"';
  return out;
}

void write_text_file(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  if (out) out << text;
  if (out) out.close();  // a full disk fails here, after the text was taken
  if (!out) throw Error(ErrorKind::Internal, cannot_write_message(path));
}

// The angle (deg) equal to `angle` modulo 360 that is nearest to `previous`.
double unwrap(double angle, double previous) { return previous + std::remainder(angle - previous, 360.0); }

// Inserts `markup` right after the start tag of the element with that id; false when absent.
bool insert_into(std::string& svg, const std::string& id, const std::string& markup) {
  std::string key = " id=\"";
  key += xml_escape(id);
  key += '"';
  const std::size_t at = svg.find(key);
  if (at == std::string::npos) return false;
  const std::size_t close = svg.find('>', at);
  if (close == std::string::npos) return false;
  svg.insert(close + 1, markup);
  return true;
}

// The shell-quoted form of a path.
std::string shell_quote(const std::string& text) {
  std::string out = "'";
  for (char c : text) {
    if (c == '\'')
      out += "'\\''";
    else
      out += c;
  }
  out += '\'';
  return out;
}

// The sweep with positions only: what pictures need, without the derivatives' memory.
SweepResult positions_only(const SweepResult& sweep) {
  SweepResult out = sweep;
  out.order = 0;
  for (Sample& s : out.samples) s.taylor = s.taylor.leftCols(std::min<Eigen::Index>(1, s.taylor.cols())).eval();
  return out;
}

}  // namespace

Animation::Animation(std::shared_ptr<const Mechanism> mechanism, const SweepResult& sweep, const DrawOptions& options,
                     int frames, double fps)
    : mechanism_(std::move(mechanism)),
      mech_(*mechanism_),
      sweep_(positions_only(sweep)),
      options_(options),
      fps_(fps),
      view_(fit_view(mech_, sweep_, options)) {
  const Mechanism& mech = mech_;
  if (sweep.samples.empty()) throw Error(ErrorKind::BadInput, "there is no solved pose to animate");
  if (!(fps > 0) || !std::isfinite(fps)) throw Error(ErrorKind::BadInput, "frames per second must be positive");
  const int n = static_cast<int>(sweep.samples.size());
  const auto first = sample_points(mech, sweep.samples.front());
  if (n > 2) {
    const auto last = sample_points(mech, sweep.samples.back());
    double gap = 0.0;
    for (std::size_t p = 0; p < first.size(); ++p) gap = std::max(gap, (last[p] - first[p]).norm());
    periodic_ = gap <= 1e-6 * mech.characteristic_length();
  }
  // Distinct poses: all samples, less the last when it repeats the first.
  const int distinct = periodic_ ? n - 1 : n;
  int count = frames > 0 ? frames : kDefaultMaxFrames;
  count = std::clamp(count, 1, distinct);
  for (int k = 0; k < count; ++k) {
    long step = 0;
    if (periodic_)
      step = std::lround(static_cast<double>(k) * distinct / count);
    else if (count > 1)
      step = std::lround(static_cast<double>(k) * (n - 1) / (count - 1));
    steps_.push_back(static_cast<int>(std::clamp<long>(step, 0, n - 1)));
  }
  for (int s : steps_) points_.push_back(sample_points(mech, sweep.samples[s]));
  // Solved once for every frame.
  if (options_.trace_paths.size() != options_.traces.size())
    options_.trace_paths = trace_paths(mech, sweep, options_.traces);
}

void Animation::show_stresses(const Analysis& analysis) {
  DrawOptions base = options_;
  const double scale = sweep_stress_scale(analysis);
  frame_stress_.clear();
  frame_markers_.clear();
  for (int step : steps_) {
    DrawOptions frame = base;
    add_stress_maps(frame, analysis, step, scale);
    frame_stress_.push_back(std::move(frame.stress_maps));
    frame_markers_.push_back(std::move(frame.markers));
  }
  options_.stress_scale = scale;
  // Room for the legend.
  DrawOptions with_maps = options_;
  if (!frame_stress_.empty()) with_maps.stress_maps = frame_stress_.front();
  view_ = fit_view(mech_, sweep_, with_maps);
}

ImageCanvas Animation::render_frame(int frame, bool antialias) const {
  ImageCanvas canvas(options_.width, options_.height);
  canvas.set_antialias(antialias);
  if (!frame_stress_.empty()) {
    DrawOptions options = options_;
    options.stress_maps = frame_stress_.at(frame);
    options.markers = frame_markers_.at(frame);
    draw_mechanism(canvas, view_, mech_, sweep_, points_.at(frame), options);
    return canvas;
  }
  draw_mechanism(canvas, view_, mech_, sweep_, points_.at(frame), options_);
  return canvas;
}

bool Animation::program_available(const std::string& name) {
  const char* path = std::getenv("PATH");
  std::string dirs = path ? path : "/usr/local/bin:/usr/bin:/bin";
  std::size_t start = 0;
  while (start <= dirs.size()) {
    std::size_t end = dirs.find(':', start);
    if (end == std::string::npos) end = dirs.size();
    std::string candidate(dirs, start, end - start);
    if (candidate.empty()) candidate.push_back('.');
    candidate.push_back('/');
    candidate.append(name);
    if (::access(candidate.c_str(), X_OK) == 0) return true;
    start = end + 1;
  }
  return false;
}

// ---------------------------------------------------------------------------------------- GIF

// gif_bytes() is in animation_gif.cpp, with cgif.
void Animation::write_gif(const std::string& path) const {
  const std::vector<std::uint8_t> bytes = gif_bytes();
  write_text_file(path, std::string(bytes.begin(), bytes.end()));
}

// -------------------------------------------------------------------------------- transforms

std::vector<std::vector<PixelTransform>> Animation::transforms() const {
  std::vector<std::vector<PixelTransform>> out;
  for (int k = 0; k < frame_count(); ++k) {
    control_.checkpoint("frames", k, frame_count());
    out.push_back(body_transforms(mech_, view_, points_[0], points_[k]));
  }
  // Where the loop goes on to: back to the first pose, or staying at the last for a frame.
  std::vector<PixelTransform> after = periodic_ ? body_transforms(mech_, view_, points_[0], points_[0]) : out.back();
  out.push_back(std::move(after));
  for (std::size_t k = 1; k < out.size(); ++k)
    for (std::size_t b = 0; b < out[k].size(); ++b)
      out[k][b].angle_deg = unwrap(out[k][b].angle_deg, out[k - 1][b].angle_deg);
  return out;
}

std::vector<std::string> Animation::body_group_ids() const {
  std::vector<std::string> ids;
  for (const Body& b : mech_.model().bodies) {
    std::string id = "body-";
    id += b.name;
    ids.push_back(id);
  }
  return ids;
}

// ---------------------------------------------------------------------------------------- SVG

namespace {

// Labels drawn as one group of texts, one per point in order, are given a group each
// ("label-<point>") so that they can follow their points.
void split_labels(std::string& svg, const Model& m) {
  if (svg.find(" id=\"label-") != std::string::npos) return;
  const std::size_t group = svg.find("<g id=\"labels\"");
  if (group == std::string::npos) return;
  std::size_t at = svg.find('>', group);
  for (std::size_t p = 0; p < m.points.size() && at != std::string::npos; ++p) {
    const std::size_t open = svg.find("<text", at);
    if (open == std::string::npos || open > svg.find("</g>", at)) return;
    std::string head = "<g id=\"";
    std::string id = "label-";
    id += m.points[p].name;
    head += xml_escape(id);
    head += "\">";
    svg.insert(open, head);
    const std::size_t close = svg.find("</text>", open + head.size());
    if (close == std::string::npos) return;
    svg.insert(close + 7, "</g>");
    at = close + 7 + 4;
  }
}

std::string animate_element(const std::string& type, const std::string& values, const std::string& dur) {
  std::string s = "<animateTransform attributeName=\"transform\" type=\"";
  s += type;
  s += "\" additive=\"sum\" calcMode=\"linear\" dur=\"";
  s += dur;
  s += "\" repeatCount=\"indefinite\" values=\"";
  s += values;
  s += "\"/>\n";
  return s;
}

}  // namespace

std::string Animation::svg_animation() const {
  if (shows_stresses())
    throw Error(ErrorKind::BadInput,
                "stress colours change from frame to frame, which only GIF and MP4 animations draw "
                "(an SVG animation moves the bodies of its first frame)");
  SvgCanvas svg(options_.width, options_.height);
  draw_mechanism(svg, view_, mech_, sweep_, points_[0], options_);
  std::string doc = svg.document();
  const auto motion = transforms();
  const std::string dur = fixed(duration(), 4) + "s";
  const std::vector<std::string> ids = body_group_ids();
  for (std::size_t b = 0; b < ids.size(); ++b) {
    std::string translate, rotate;
    for (std::size_t k = 0; k < motion.size(); ++k) {
      const PixelTransform& t = motion[k][b];
      if (k) translate += ';', rotate += ';';
      translate += fixed(t.shift.x(), 2);
      translate += ' ';
      translate += fixed(t.shift.y(), 2);
      rotate += fixed(t.angle_deg, 2);
      rotate += ' ';
      rotate += fixed(t.pivot.x(), 2);
      rotate += ' ';
      rotate += fixed(t.pivot.y(), 2);
    }
    // translate(shift) rotate(angle, pivot): the sum of the two, in this order.
    insert_into(doc, ids[b], animate_element("translate", translate, dur) + animate_element("rotate", rotate, dur));
  }
  // Point labels move with their points, without turning.
  const Model& m = mech_.model();
  split_labels(doc, m);
  for (std::size_t p = 0; p < m.points.size(); ++p) {
    if (m.points[p].ground) continue;
    std::string values;
    for (int k = 0; k <= frame_count(); ++k) {
      const int f = k < frame_count() ? k : periodic_ ? 0 : frame_count() - 1;
      const Eigen::Vector2d d = view_.to_pixels(points_[f][p]) - view_.to_pixels(points_[0][p]);
      if (k) values += ';';
      values += fixed(d.x(), 2);
      values += ' ';
      values += fixed(d.y(), 2);
    }
    std::string id = "label-";
    id += m.points[p].name;
    insert_into(doc, id, animate_element("translate", values, dur));
  }
  return doc;
}

void Animation::write_svg_animation(const std::string& path) const { write_text_file(path, svg_animation()); }

// --------------------------------------------------------------------------------------- HTML

std::string Animation::readout(int frame) const {
  const Model& m = mech_.model();
  const Sample& s = sweep_.samples[steps_[frame]];
  std::string text = "t = ";
  text += general(s.time);
  text += " s";
  for (std::size_t d = 0; d < m.drivers.size() && d < s.driver_values.size(); ++d) {
    text += ", ";
    text += m.drivers[d].name;
    text += " = ";
    text += format_driver_value(m, static_cast<int>(d), s.driver_values[d]);
  }
  return text;
}

namespace {

// The page up to the stage that holds the drawing: the title, the style sheet, and a script
// that records any script error in the body's data-errors (the browser tests read it).
void append_html_page_start(std::string& html, const std::string& title, int main_width) {
  html +=
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
      "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<title>";
  html += xml_escape(title);
  html +=
      " \u2014 nbar animation</title>\n<style>\n"
      "body{margin:0;font:15px/1.4 system-ui,sans-serif;color:#222;background:#f4f4f2}\n"
      "main{max-width:";
  html += std::to_string(main_width);
  html +=
      "px;margin:0 auto;padding:12px 16px}\n"
      "h1{font-size:1.15em;margin:0 0 8px}\n"
      ".stage{background:#fff;border:1px solid #ddd;border-radius:4px}\n"
      ".stage svg{display:block;width:100%;height:auto}\n"
      ".controls{display:flex;align-items:center;gap:10px;margin-top:10px}\n"
      ".controls input{flex:1;min-width:0}\n"
      "button{font:inherit;min-width:5em;padding:6px 12px}\n"
      "#counter{font-variant-numeric:tabular-nums;white-space:nowrap}\n"
      "#readout{font-variant-numeric:tabular-nums;margin:8px 0 0;color:#444}\n"
      "</style>\n</head>\n<body data-frame=\"0\" data-errors=\"\">\n"
      "<script>\n"
      "window.onerror = function (message, source, line) {\n"
      "  var b = document.body;\n"
      "  if (b) b.dataset.errors = (b.dataset.errors ? b.dataset.errors + '\\n' : '') + message + ' (line ' + line + "
      "')';\n"
      "};\n"
      "</script>\n<main>\n<h1>";
  html += xml_escape(title);
  html += "</h1>\n<div class=\"stage\">\n";
}

// After the stage: the play button, the frame slider and counter, the readout, and the start
// of the player's script.
void append_html_controls(std::string& html, int frames) {
  html +=
      "</div>\n<div class=\"controls\">\n"
      "<button id=\"play\" type=\"button\">Pause</button>\n"
      "<input id=\"scrub\" type=\"range\" min=\"0\" max=\"";
  html += std::to_string(frames - 1);
  html += "\" step=\"1\" value=\"0\" aria-label=\"Frame\">\n<span id=\"counter\">1 / ";
  html += std::to_string(frames);
  html += "</span>\n</div>\n<p id=\"readout\"></p>\n</main>\n<script>\n\"use strict\";\n(function () {\n";
}

// The body groups' ids and, per frame, [angle, pivot x, pivot y, shift x, shift y] per body.
void append_js_body_motion(std::string& html, const std::vector<std::string>& ids,
                           const std::vector<std::vector<PixelTransform>>& motion, int frames) {
  html += "const bodies = [";
  for (std::size_t b = 0; b < ids.size(); ++b) {
    if (b) html += ',';
    html += js_string(ids[b]);
  }
  html += "];\nconst motion = [\n";
  for (int k = 0; k < frames; ++k) {
    html += '[';
    for (std::size_t b = 0; b < ids.size(); ++b) {
      const PixelTransform& t = motion[k][b];
      if (b) html += ',';
      html += fixed(t.angle_deg, 2) + "," + fixed(t.pivot.x(), 2) + "," + fixed(t.pivot.y(), 2) + "," +
              fixed(t.shift.x(), 2) + "," + fixed(t.shift.y(), 2);
    }
    html += "],\n";
  }
  html += "];\n";
}

// The label groups of the moving points and, per frame, [dx, dy] per label from the first frame.
void append_js_label_shifts(std::string& html, const Model& m, const View& view,
                            const std::vector<std::vector<Eigen::Vector2d>>& points, int frames) {
  std::vector<int> moving;
  for (std::size_t p = 0; p < m.points.size(); ++p)
    if (!m.points[p].ground) moving.push_back(static_cast<int>(p));
  html += "const labels = [";
  for (std::size_t i = 0; i < moving.size(); ++i) {
    if (i) html += ',';
    std::string id = "label-";
    id += m.points[moving[i]].name;
    html += js_string(id);
  }
  html += "];\nconst shifts = [\n";
  for (int k = 0; k < frames; ++k) {
    html += '[';
    for (std::size_t i = 0; i < moving.size(); ++i) {
      const int p = moving[i];
      const Eigen::Vector2d d = view.to_pixels(points[k][p]) - view.to_pixels(points[0][p]);
      if (i) html += ',';
      html += fixed(d.x(), 2) + "," + fixed(d.y(), 2);
    }
    html += "],\n";
  }
  html += "];\n";
}

// Shows a frame (bodies, labels, slider, counter, readout), plays at fps, and answers the
// button, the slider and the arrow and space keys.
constexpr const char* kHtmlPlayerScript = R"JS(const n = motion.length;
const groups = bodies.map(function (id) { return document.getElementById(id); });
const labelGroups = labels.map(function (id) { return document.getElementById(id); });
const button = document.getElementById("play");
const scrub = document.getElementById("scrub");
const counter = document.getElementById("counter");
const text = document.getElementById("readout");
let frame = 0, timer = null, shown = 0;

function show(k) {
  frame = k;
  const m = motion[k];
  groups.forEach(function (g, b) {
    if (!g) return;
    const i = 5 * b;
    g.setAttribute("transform", "translate(" + m[i + 3] + " " + m[i + 4] + ") rotate(" + m[i] + " " + m[i + 1] +
                   " " + m[i + 2] + ")");
  });
  const s = shifts[k];
  labelGroups.forEach(function (g, i) {
    if (g) g.setAttribute("transform", "translate(" + s[2 * i] + " " + s[2 * i + 1] + ")");
  });
  scrub.value = String(k);
  counter.textContent = (k + 1) + " / " + n;
  text.textContent = readouts[k];
  document.body.dataset.frame = String(k);
  document.body.dataset.shown = String(++shown);
}

function play(on) {
  if (timer !== null) clearInterval(timer);
  timer = on && n > 1 ? setInterval(function () { show((frame + 1) % n); }, 1000 / fps) : null;
  button.textContent = timer !== null ? "Pause" : "Play";
}

button.addEventListener("click", function () { play(timer === null); });
scrub.addEventListener("input", function () { play(false); show(Number(scrub.value)); });
document.addEventListener("keydown", function (e) {
  if (e.target === scrub) return;
  if (e.key === " ") { e.preventDefault(); play(timer === null); }
  else if (e.key === "ArrowRight") { play(false); show((frame + 1) % n); }
  else if (e.key === "ArrowLeft") { play(false); show((frame + n - 1) % n); }
});
show(0);
play(true);
})();
</script>
</body>
</html>
)JS";

}  // namespace

std::string Animation::html_animation() const {
  if (shows_stresses())
    throw Error(ErrorKind::BadInput,
                "stress colours change from frame to frame, which only GIF and MP4 animations draw "
                "(an HTML animation moves the bodies of its first frame)");
  SvgCanvas svg(options_.width, options_.height);
  draw_mechanism(svg, view_, mech_, sweep_, points_[0], options_);
  std::string element = svg.element();
  const Model& m = mech_.model();
  split_labels(element, m);
  const int n = frame_count();

  const std::string title = m.name.empty() ? std::string("Mechanism") : m.name;
  std::string html;
  html.reserve(element.size() + 64 * static_cast<std::size_t>(n) * (m.bodies.size() + m.points.size() + 2));
  append_html_page_start(html, title, options_.width + 32);
  html += element;
  append_html_controls(html, n);
  html += "const fps = ";
  html += general(fps_);
  html += ";\n";
  append_js_body_motion(html, body_group_ids(), transforms(), n);
  append_js_label_shifts(html, m, view_, points_, n);
  html += "const readouts = [\n";
  for (int k = 0; k < n; ++k) html += js_string(readout(k)) + ",\n";
  html += "];\n";
  html += kHtmlPlayerScript;
  return html;
}

void Animation::write_html_animation(const std::string& path) const { write_text_file(path, html_animation()); }

// ---------------------------------------------------------------------------------------- MP4

void Animation::write_mp4(const std::string& path) const {
  if (!program_available("ffmpeg"))
    throw Error(ErrorKind::Internal, "MP4 needs the ffmpeg program: apt-get install ffmpeg");
  const int w = options_.width, h = options_.height;
  std::string command = "ffmpeg -y -loglevel error -f rawvideo -pix_fmt bgra -s ";
  command += std::to_string(w);
  command += 'x';
  command += std::to_string(h);
  command += " -r ";
  command += general(fps_);
  command += " -i - -an -pix_fmt yuv420p -vf 'pad=ceil(iw/2)*2:ceil(ih/2)*2' ";
  command += shell_quote(path);
  // A program that stops reading must not kill us with SIGPIPE.
  struct sigaction ignore {
  }, previous{};
  ignore.sa_handler = SIG_IGN;
  sigemptyset(&ignore.sa_mask);
  sigaction(SIGPIPE, &ignore, &previous);
  std::fflush(nullptr);
  FILE* pipe = ::popen(command.c_str(), "w");
  bool ok = pipe != nullptr;
  bool stopped = false;
  for (int k = 0; ok && k < frame_count(); ++k) {
    if ((stopped = control_.should_stop("frames", k, frame_count()))) break;
    const ImageCanvas image = render_frame(k, true);
    const std::uint8_t* data = image.data();
    for (int y = 0; ok && y < h; ++y)
      ok = std::fwrite(data + static_cast<std::ptrdiff_t>(y) * image.stride(), 4, w, pipe) ==
           static_cast<std::size_t>(w);
  }
  const int status = pipe ? ::pclose(pipe) : -1;
  sigaction(SIGPIPE, &previous, nullptr);
  if (stopped) {
    std::error_code ignored;
    std::filesystem::remove(path, ignored);
    control_.throw_stopped("frames");
  }
  if (!ok || status != 0) {
    std::string message = "cannot write ";
    message += path;
    message += ": ffmpeg failed";
    throw Error(ErrorKind::Internal, message);
  }
}

std::vector<std::uint8_t> Animation::mp4_bytes() const {
  // ffmpeg writes a seekable file (the index goes at its start): a private folder, removed after.
  char folder[] = "/tmp/nbar-mp4-XXXXXX";
  if (!::mkdtemp(folder)) throw Error(ErrorKind::Internal, "cannot make a temporary folder for the MP4");
  const std::string path = std::string(folder) + "/animation.mp4";
  std::vector<std::uint8_t> bytes;
  std::optional<Error> failure;  // thrown once the folder is removed
  try {
    write_mp4(path);
    std::ifstream in(path, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  } catch (const Error& e) {
    failure = e;
  }
  std::error_code ignored;
  std::filesystem::remove_all(folder, ignored);
  if (failure) throw *failure;
  return bytes;
}

}  // namespace nbar::render
