#include "nbar/analysis/cylinders.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "nbar/model/units.hpp"

namespace nbar {

namespace {

// The barrel of slider `s`: the moving two-point body whose points are the guide's, or -1.
int barrel_of(const Model& m, const Slider& s) {
  for (std::size_t b = 0; b < m.bodies.size(); ++b) {
    const auto& p = m.bodies[b].points;
    if (static_cast<int>(b) != s.body && p.size() == 2 && std::is_permutation(p.begin(), p.end(), s.along.begin()))
      return static_cast<int>(b);
  }
  return -1;
}

// Where `point` is along the guide: 0 at its first point, 1 at its second.
double along_fraction(const std::vector<Eigen::Vector2d>& p, const std::array<int, 2>& along, int point) {
  const Eigen::Vector2d axis = p[along[1]] - p[along[0]];
  return axis.dot(p[point] - p[along[0]]) / axis.squaredNorm();
}

std::string short_length_text(const Model& m, double metres) {
  return fmt::format("{:.4g} {}", metres / m.units.length_scale, m.units.length);
}

}  // namespace

bool has_cylinder(const Model& model) {
  return std::any_of(model.sliders.begin(), model.sliders.end(), [&](const Slider& s) {
    return barrel_of(model, s) >= 0 && model.bodies[s.body].points.size() >= 2;
  });
}

std::vector<Warning> cylinder_warnings(const Mechanism& mech) {
  if (!has_cylinder(mech.model())) return {};
  try {
    SweepOptions options;
    options.order = 0;
    const double planned = sweep_sample_count(mech.model());
    if (planned > kCylinderCheckSamples) options.steps = kCylinderCheckSamples;
    return cylinder_warnings(mech, run_sweep(mech, options));
  } catch (const Error&) {
    return {};
  }
}

std::vector<Warning> cylinder_warnings(const Mechanism& mech, const SweepResult& sweep) {
  const Model& m = mech.model();
  std::vector<Warning> out;
  if (sweep.samples.empty()) return out;
  const double slack = 1e-9;
  const auto start = point_positions(mech, sweep.samples.front().positions());
  for (const Slider& s : m.sliders) {
    const int barrel = barrel_of(m, s);
    const Body& rod = m.bodies[s.body];
    if (barrel < 0 || rod.points.size() < 2) continue;
    const double barrel_length = (start[s.along[1]] - start[s.along[0]]).norm();
    if (barrel_length <= 0) continue;
    for (int p : rod.points) {
      if (p == s.point) continue;
      const double at_start = along_fraction(start, s.along, p);
      if (at_start < -slack || at_start > 1 + slack) continue;  // not the piston end
      int first_out = -1;
      double farthest = 0;  // out of the barrel, as a fraction of its length
      for (const Sample& sample : sweep.samples) {
        const double f = along_fraction(point_positions(mech, sample.positions()), s.along, p);
        const double outside = f > 1 ? f - 1 : f < 0 ? -f : 0.0;
        if (outside > slack && first_out < 0) first_out = sample.step;
        farthest = std::max(farthest, outside);
      }
      if (first_out < 0) continue;
      std::string where;
      if (!m.drivers.empty() && static_cast<std::size_t>(first_out) < sweep.samples.size() &&
          !sweep.samples[first_out].driver_values.empty())
        where = fmt::format(" ({} = {})", m.drivers[0].name,
                            format_driver_value(m, 0, sweep.samples[first_out].driver_values[0]));
      out.push_back(
          {"rod_leaves_barrel", first_out,
           fmt::format("cylinder {}/{}: the piston end {} leaves the barrel {}-{} ({} long) at step {}{} and gets "
                       "{} out of it: make the barrel or the rod longer, or the stroke shorter",
                       m.bodies[barrel].name, rod.name, m.points[p].name, m.points[s.along[0]].name,
                       m.points[s.along[1]].name, short_length_text(m, barrel_length), first_out, where,
                       short_length_text(m, farthest * barrel_length))});
    }
  }
  return out;
}

}  // namespace nbar
