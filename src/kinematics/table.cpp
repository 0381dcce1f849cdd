#include "nbar/kinematics/table.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace nbar {

namespace {

const char* const kPointSuffix[] = {"", "v", "a", "j", "d4", "d5"};
const char* const kAngleName[] = {"angle", "omega", "alpha", "jerk", "d4", "d5"};

std::string per_time(const std::string& unit, int order) {
  if (order == 0) return unit;
  if (order == 1) return unit + "/s";
  return unit + "/s^" + std::to_string(order);
}

// The multiple of 2 pi that brings `angle` closest to `reference`.
double unwrap(double angle, double reference) {
  const double two_pi = 2.0 * std::numbers::pi;
  return angle + two_pi * std::round((reference - angle) / two_pi);
}

}  // namespace

ResultTable make_table(const Mechanism& mech, const SweepResult& sweep) {
  const Model& m = mech.model();
  const Units& u = m.units;
  const int order = sweep.order;
  ResultTable t;
  auto add = [&](std::string name, std::string unit) {
    t.columns.push_back(std::move(name));
    t.units.push_back(std::move(unit));
  };
  add("step", "");
  add("t", "s");
  for (const Driver& d : m.drivers) add(d.name, d.is_angular() ? u.angle : u.length);
  for (const Point& p : m.points)
    for (int k = 0; k <= order; ++k) {
      add(p.name + "." + kPointSuffix[k] + "x", per_time(u.length, k));
      add(p.name + "." + kPointSuffix[k] + "y", per_time(u.length, k));
    }
  std::vector<int> angled;
  for (std::size_t b = 0; b < m.bodies.size(); ++b) {
    if (m.bodies[b].points.size() < 2) continue;
    angled.push_back(static_cast<int>(b));
    for (int k = 0; k <= order; ++k) add(m.bodies[b].name + "." + kAngleName[k], per_time(u.angle, k));
  }
  for (const FourBarLoop& loop : mech.four_bar_loops()) add(loop.name + ".mu", u.angle);

  // A body driven by an absolute angle starts at its driver's value, not at atan2's range.
  std::vector<double> previous(m.bodies.size(), 0.0);
  std::vector<bool> started(m.bodies.size(), false);
  for (std::size_t d = 0; d < m.drivers.size(); ++d) {
    const Driver& drv = m.drivers[d];
    if (drv.kind == DriverKind::Angle && drv.relative_to < 0 && !sweep.samples.empty()) {
      previous[drv.body] = sweep.samples.front().driver_values[d];
      started[drv.body] = true;
    }
  }

  for (const Sample& s : sweep.samples) {
    std::vector<double> row;
    row.reserve(t.columns.size());
    row.push_back(s.step);
    row.push_back(s.time);
    for (std::size_t d = 0; d < m.drivers.size(); ++d)
      row.push_back(s.driver_values[d] / (m.drivers[d].is_angular() ? u.angle_scale : u.length_scale));
    for (std::size_t p = 0; p < m.points.size(); ++p) {
      const Motion2 motion = point_motion(mech, s, static_cast<int>(p));
      for (int k = 0; k <= order; ++k) {
        row.push_back(motion.x[k] / u.length_scale);
        row.push_back(motion.y[k] / u.length_scale);
      }
    }
    for (int b : angled) {
      std::vector<double> a = body_angle_motion(mech, s, b);
      a[0] = started[b] ? unwrap(a[0], previous[b]) : a[0];
      previous[b] = a[0];
      started[b] = true;
      for (int k = 0; k <= order; ++k) row.push_back(a[k] / u.angle_scale);
    }
    if (!mech.four_bar_loops().empty()) {
      const auto points = point_positions(mech, s.taylor.col(0));
      for (const FourBarLoop& loop : mech.four_bar_loops()) row.push_back(transmission_angle(loop, points) / u.angle_scale);
    }
    t.rows.push_back(std::move(row));
  }
  return t;
}

bool glob_match(const std::string& pattern, const std::string& text) {
  std::size_t p = 0, t = 0, star = std::string::npos, mark = 0;
  while (t < text.size()) {
    if (p < pattern.size() && pattern[p] == '*') {
      star = p++;
      mark = t;
    } else if (p < pattern.size() && pattern[p] == text[t]) {
      ++p;
      ++t;
    } else if (star != std::string::npos) {
      p = star + 1;
      t = ++mark;
    } else {
      return false;
    }
  }
  while (p < pattern.size() && pattern[p] == '*') ++p;
  return p == pattern.size();
}

ResultTable select_columns(const ResultTable& table, const std::vector<std::string>& patterns) {
  std::vector<std::size_t> picked;
  for (const std::string& pattern : patterns) {
    bool any = false;
    for (std::size_t c = 0; c < table.columns.size(); ++c) {
      if (!glob_match(pattern, table.columns[c])) continue;
      any = true;
      if (std::find(picked.begin(), picked.end(), c) == picked.end()) picked.push_back(c);
    }
    if (!any) throw std::invalid_argument("no column matches '" + pattern + "'");
  }
  ResultTable out;
  for (std::size_t c : picked) {
    out.columns.push_back(table.columns[c]);
    out.units.push_back(table.units[c]);
  }
  for (const auto& row : table.rows) {
    std::vector<double> r;
    r.reserve(picked.size());
    for (std::size_t c : picked) r.push_back(row[c]);
    out.rows.push_back(std::move(r));
  }
  return out;
}

}  // namespace nbar
