#include "nbar/io/model_export.hpp"

#include "model/double_text.hpp"
#include "nbar/model/diagnostics.hpp"
#include "yaml_support.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>

namespace nbar::io {

namespace {

// A value in the model's units: to 15 significant digits when they read back within two units
// in the last place, else the shortest text that reads back exactly. A user's 720 deg/s, kept
// in rad/s, comes back as 719.9999999999999, the conversion's rounding and not a number anyone
// wrote; a computed coordinate (a synthesised design's) keeps all its digits.
std::string number(double v) {
  const std::string rounded = fmt::format("{:.15g}", v);
  double back = 0.0;
  parse_double(rounded.data(), rounded.data() + rounded.size(), back);
  const double ulp = std::nextafter(std::abs(v), HUGE_VAL) - std::abs(v);
  return std::abs(back - v) <= 2.0 * ulp ? rounded : fmt::format("{}", v);
}

// Names are written plain when YAML cannot read them as anything else, otherwise quoted.
std::string quoted(const std::string& text) {
  std::string out = "\"";
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char ch = text[i];
    const auto c = static_cast<unsigned char>(ch);
    if (c >= 0x80) {
      // Whole characters only: a byte that is not UTF-8 (from a caller that bypassed the
      // readers) becomes U+FFFD, so that the file written always reads back.
      const std::size_t length = yaml::utf8_character_length(text, i);
      if (length == 0) {
        out += "\\uFFFD";
      } else {
        out.append(text, i, length);
        i += length - 1;
      }
    } else if (ch == '"' || ch == '\\') {
      out += '\\';
      out += ch;
    } else if (c < 0x20 || c == 0x7f) {
      out += fmt::format("\\x{:02x}", c);
    } else {
      out += ch;
    }
  }
  return out + "\"";
}
// A comment line as it can be written: a line break (a file name may hold one) would start
// YAML of its own, and a byte that is not UTF-8 would make the file unreadable.
std::string comment_text(const std::string& text) {
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c < 0x20 || c == 0x7f) {
      out += ' ';
    } else if (c < 0x80) {
      out += text[i];
    } else if (const std::size_t length = yaml::utf8_character_length(text, i); length > 0) {
      out.append(text, i, length);
      i += length - 1;
    } else {
      out += "\xEF\xBF\xBD";  // U+FFFD
    }
  }
  return out;
}

std::string name(const std::string& text) {
  bool plain = !text.empty() && text != "null" && text != "Null" && text != "NULL";
  for (std::size_t i = 0; i < text.size() && plain; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    plain = c < 0x80 && (std::isalnum(c) || c == '_' || (i > 0 && (c == '-' || c == '.')));
  }
  return plain ? text : quoted(text);
}

// The points the file names: not those the reader makes for a guide given by a point and an angle.
std::string point_list(const Model& m, const std::vector<int>& points) {
  std::string out = "[";
  bool first = true;
  for (int p : points) {
    if (m.points[p].guide_direction) continue;
    out += (first ? "" : ", ") + name(m.points[p].name);
    first = false;
  }
  return out + "]";
}
std::string point_pair(const Model& m, const std::array<int, 2>& p) {
  return fmt::format("[{}, {}]", name(m.points[p[0]].name), name(m.points[p[1]].name));
}
// A guide as the file gave it: two points, or a point and its angle in the model's unit.
std::string guide_text(const Model& m, const std::array<int, 2>& along) {
  if (!m.points[along[1]].guide_direction) return point_pair(m, along);
  const Eigen::Vector2d d = m.points[along[1]].position - m.points[along[0]].position;
  std::string carrier;  // a moving guide: the body that holds its direction point
  for (const Body& b : m.bodies)
    if (std::find(b.points.begin(), b.points.end(), along[1]) != b.points.end()) carrier = ", body: " + name(b.name);
  return fmt::format("{{point: {}, angle: {}{}}}", name(m.points[along[0]].name),
                     number(std::atan2(d.y(), d.x()) / m.units.angle_scale), carrier);
}

// The name the parser gives a driver without `name:`.
std::string default_driver_name(const Model& m, const Driver& d) {
  switch (d.kind) {
    case DriverKind::Angle:
      return m.bodies[d.body].name + (d.relative_to >= 0 ? "/" + m.bodies[d.relative_to].name : std::string());
    case DriverKind::Distance: return m.points[d.points[0]].name + "-" + m.points[d.points[1]].name;
    case DriverKind::Slide: return m.bodies[m.sliders[d.slider].body].name;
  }
  return {};
}

void refuse_kinetics(const Model& m) {
  std::string what;
  for (const Body& b : m.bodies)
    if (b.shape || b.inertia || b.material) what = "body '" + b.name + "' has a mass, shape or material";
  if (!m.gravity.isZero()) what = "it has gravity";
  if (!m.point_loads.empty() || !m.torques.empty()) what = "it has loads";
  if (!m.springs.empty()) what = "it has springs";
  if (!what.empty())
    throw Error(ErrorKind::BadInput, "only kinematic models can be written as model files yet: " + what);
}

}  // namespace

void write_model_yaml(std::ostream& out, const Model& m, const std::vector<std::string>& comments) {
  refuse_kinetics(m);
  const double unit = m.units.length_scale;
  for (const std::string& c : comments) out << (c.empty() ? "#" : "# " + comment_text(c)) << '\n';
  if (!m.name.empty()) out << "name: " << quoted(m.name) << '\n';
  out << "units: {length: " << m.units.length << ", angle: " << m.units.angle << "}\n";
  out << "points:\n";
  for (const Point& p : m.points)
    if (!p.guide_direction)
      out << "  " << name(p.name) << ": [" << number(p.position.x() / unit) << ", " << number(p.position.y() / unit)
          << "]\n";
  std::vector<int> ground;
  for (std::size_t i = 0; i < m.points.size(); ++i)
    if (m.points[i].ground && !m.points[i].guide_direction) ground.push_back(static_cast<int>(i));
  if (!ground.empty()) out << "ground: " << point_list(m, ground) << '\n';
  if (!m.bodies.empty()) out << "bodies:\n";
  for (const Body& b : m.bodies) out << "  " << name(b.name) << ": " << point_list(m, b.points) << '\n';
  std::vector<std::string> lengths;
  for (const Body& b : m.bodies)
    if (b.length) lengths.push_back(name(b.name) + ": " + number(*b.length / unit));
  if (!lengths.empty()) {
    out << "lengths: {";
    for (std::size_t i = 0; i < lengths.size(); ++i) out << (i ? ", " : "") << lengths[i];
    out << "}\n";
  }
  if (!m.sliders.empty()) out << "sliders:\n";
  for (const Slider& s : m.sliders)
    out << "  - {body: " << name(m.bodies[s.body].name) << ", point: " << name(m.points[s.point].name)
        << ", along: " << guide_text(m, s.along) << "}\n";
  if (!m.slots.empty()) out << "slots:\n";
  for (const Slot& s : m.slots)
    out << "  - {point: " << name(m.points[s.point].name) << ", along: " << guide_text(m, s.along) << "}\n";

  if (!m.drivers.empty()) out << "drivers:\n";
  for (const Driver& d : m.drivers) {
    const double scale = d.is_angular() ? m.units.angle_scale : m.units.length_scale;
    out << "  - {";
    switch (d.kind) {
      case DriverKind::Angle:
        out << "angle: " << name(m.bodies[d.body].name);
        if (d.relative_to >= 0) out << ", relative_to: " << name(m.bodies[d.relative_to].name);
        break;
      case DriverKind::Distance: out << "distance: " << point_pair(m, d.points); break;
      case DriverKind::Slide: out << "slide: " << name(m.bodies[m.sliders[d.slider].body].name); break;
    }
    if (d.name != default_driver_name(m, d)) out << ", name: " << quoted(d.name);
    if (d.law) {
      out << ", law: " << quoted(d.law->text());
    } else {
      if (d.from) out << ", from: " << number(*d.from / scale);
      if (d.to) out << ", to: " << number(*d.to / scale);
      out << ", speed: " << number(d.speed / scale);
      if (d.accel != 0.0) out << ", accel: " << number(d.accel / scale);
    }
    if (d.free) out << ", free: true";
    if (d.initial_speed != 0.0) out << ", initial_speed: " << number(d.initial_speed / scale);
    if (d.at_limits == AtLimits::Reverse) out << ", at_limits: reverse";
    if (d.cycles) out << ", cycles: " << *d.cycles;
    out << "}\n";
  }
  if (m.has_time_law()) {
    out << "sweep: {duration: " << number(m.sweep.duration);
    if (m.sweep.time_step) out << ", step: " << number(*m.sweep.time_step);
    out << "}\n";
  } else {
    out << "sweep: {steps: " << m.sweep.steps << "}\n";
  }
}

std::string model_yaml(const Model& model, const std::vector<std::string>& comments) {
  std::ostringstream out;
  write_model_yaml(out, model, comments);
  return out.str();
}

std::vector<std::string> design_comments(const synthesis::DesignCheck& check, const Units& units) {
  const double angle = 1.0 / units.angle_scale;  // lengths are in `units` already, angles in rad
  std::vector<std::string> lines;
  if (!check.invalid.empty()) {
    lines.push_back("Not a valid four-bar: " + check.invalid);
    return lines;
  }
  lines.push_back(fmt::format("Link lengths ({}): frame {:.6g}, input {:.6g}, coupler {:.6g}, output {:.6g}",
                              units.length, check.frame, check.input, check.coupler, check.output));
  lines.push_back(fmt::format("Grashof class: {}; the input {}", to_string(check.grashof.kind),
                              check.input_turns_fully ? "turns fully" : "rocks"));
  lines.push_back(fmt::format("Defects: {}", synthesis::describe_defects(check)));
  lines.push_back(
      fmt::format("Minimum transmission angle: {:.4g} {} over the designed motion, {:.4g} {} over the "
                  "input's whole range",
                  check.min_transmission * angle, units.angle, check.min_transmission_full * angle, units.angle));
  std::string at = "Input angle at the targets (" + units.angle + "):";
  for (const synthesis::TargetCheck& t : check.targets)
    at += t.on_branch ? fmt::format(" {:.6g}", t.input_angle * angle) : std::string(" (off the branch)");
  lines.push_back(at);
  return lines;
}

std::vector<std::string> design_angle_comments(const synthesis::FourBarDesign& design) {
  const auto turned = [](double offset) { return std::abs(std::remainder(offset, 2 * std::numbers::pi)) > 1e-12; };
  std::vector<std::string> lines;
  if (turned(design.input_angle_offset))
    lines.push_back(
        "The input angle is the direction O2 -> Ip, a pointer on the input opposite to A "
        "(the synthesis gave the input a negative length)");
  if (turned(design.output_angle_offset))
    lines.push_back(
        "The output angle (output.angle) is the direction O4 -> Op, a pointer on the output opposite to B "
        "(the synthesis gave the output a negative length)");
  return lines;
}

std::string design_yaml(const synthesis::FourBarDesign& design, const synthesis::DesignCheck& check,
                        const std::string& name, const Units& units, const std::vector<std::string>& comments) {
  std::vector<std::string> all = comments;
  for (std::string& line : design_comments(check, units)) all.push_back(std::move(line));
  for (std::string& line : design_angle_comments(design)) all.push_back(std::move(line));
  return model_yaml(synthesis::make_fourbar_model(design, name, units, check.motion), all);
}

}  // namespace nbar::io
