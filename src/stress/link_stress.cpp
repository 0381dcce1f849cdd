#include "stress/link_stress.hpp"

#include <algorithm>
#include <cmath>

namespace nbar {

namespace {

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }
Eigen::Vector2d perp(const Eigen::Vector2d& v) { return {-v.y(), v.x()}; }

// Where to cut: evenly along the body, and more closely around every joint and hole, where
// the internal forces jump and the section is smallest. Never through a joint's centre, where
// it would be ambiguous which side the joint's force acts on.
std::vector<double> section_positions(const Model& m, const Body& body, const Eigen::Vector2d& origin,
                                      const Eigen::Vector2d& axis, int count) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const Eigen::Vector2d& v : body.shape->outline) {
    lo = std::min(lo, axis.dot(v - origin));
    hi = std::max(hi, axis.dot(v - origin));
  }
  const double length = hi - lo;
  struct Feature {
    double s, radius;
  };
  std::vector<Feature> features;
  for (int p : body.points) {
    const Eigen::Vector2d& at = m.points[p].position;
    double radius = 0.03 * length;
    for (const Circle& c : body.shape->circle_holes)
      if ((c.centre - at).norm() <= 1e-9 * length) radius = c.radius;
    features.push_back({axis.dot(at - origin), radius});
  }
  for (const Circle& c : body.shape->circle_holes) features.push_back({axis.dot(c.centre - origin), c.radius});

  const double offsets[] = {0.15, 0.35, 0.6, 1.0, 1.5, 2.2};
  const int clustered = 2 * static_cast<int>(std::size(offsets)) * static_cast<int>(features.size());
  const int even = std::max(100, count - clustered);
  std::vector<double> s;
  for (int i = 0; i < even; ++i) s.push_back(lo + (i + 0.5) * length / even);
  for (const Feature& f : features)
    for (double o : offsets) {
      s.push_back(f.s - o * f.radius);
      s.push_back(f.s + o * f.radius);
    }
  const double margin = 1e-6 * length;
  std::vector<double> kept;
  for (double x : s) {
    if (x <= lo + margin || x >= hi - margin) continue;
    bool at_joint = false;
    for (int p : body.points) at_joint = at_joint || std::abs(x - axis.dot(m.points[p].position - origin)) < margin;
    if (!at_joint) kept.push_back(x);
  }
  std::sort(kept.begin(), kept.end());
  kept.erase(std::unique(kept.begin(), kept.end(), [&](double a, double b) { return b - a < margin; }), kept.end());
  return kept;
}

}  // namespace

LinkStress::LinkStress(const InverseDynamics& dynamics, int sections) : dynamics_(dynamics) {
  const Model& m = dynamics.mechanism().model();
  bodies_.resize(m.bodies.size());
  for (std::size_t b = 0; b < m.bodies.size(); ++b) {
    const Body& body = m.bodies[b];
    if (!body.shape || body.thickness <= 0.0 || body.points.size() < 2) continue;
    BodySections& bs = bodies_[b];
    bs.origin = m.points[body.points[0]].position;
    bs.axis = (m.points[body.points[1]].position - bs.origin).normalized();
    const Eigen::Vector2d across = perp(bs.axis);
    // The body's mass spread evenly over its plate (given masses too).
    const double area = area_properties(*body.shape).area;
    const double mass = dynamics.masses()[b].mass;
    const double per_area = area > 0.0 ? mass / area : 0.0;
    for (double s : section_positions(m, body, bs.origin, bs.axis, sections)) {
      const Eigen::Vector2d cut = bs.origin + s * bs.axis;
      const auto intervals = section_intervals(*body.shape, cut, across);
      if (intervals.empty()) continue;
      Section sec;
      sec.position = s;
      sec.props = section_properties(intervals, body.thickness);
      sec.centroid = cut + sec.props.centroid * across;
      for (int side = 0; side < 2; ++side) {
        const AreaProperties a = clipped_area_properties(*body.shape, cut, side == 0 ? Eigen::Vector2d(-bs.axis) : bs.axis);
        sec.part[side] = {per_area * a.area, a.centroid, per_area * a.polar()};
      }
      bs.sections.push_back(sec);
    }
  }
}

PartLoads LinkStress::part_loads(const Sample& sample, const DynamicsResult& forces, int body, int section,
                                 int side) const {
  const Mechanism& mech = dynamics_.mechanism();
  const Model& m = mech.model();
  const Section& sec = bodies_[body].sections[section];
  const BodyMotion bm = body_motion(mech, sample, body);
  const Eigen::Vector2d cut = bm.point(bodies_[body].origin + sec.position * bodies_[body].axis, 0);
  const Eigen::Vector2d axis = bm.direction[0].normalized();
  const Eigen::Vector2d centre = bm.point(sec.centroid, 0);
  auto inside = [&](const Eigen::Vector2d& x) { return side * axis.dot(x - cut) > 0.0; };

  PartLoads loads;
  auto add = [&](const Eigen::Vector2d& at, const Eigen::Vector2d& f) {
    loads.force += f;
    loads.moment += cross(at - centre, f);
  };
  const auto& links = dynamics_.joint_links();
  for (std::size_t i = 0; i < links.size(); ++i) {
    if (links[i].link != body) continue;
    const Motion2 p = point_motion(mech, sample, links[i].point);
    const Eigen::Vector2d at(p.x[0], p.y[0]);
    if (inside(at)) add(at, forces.pin_forces[i]);
  }
  for (const AppliedLoad& l : forces.applied) {
    if (l.body != body || !inside(l.at)) continue;
    add(l.at, l.force);
    loads.moment += l.couple;
  }
  const Part& part = sec.part[side < 0 ? 0 : 1];
  if (part.mass > 0.0) {
    const Eigen::Vector2d g = bm.point(part.centre, 0), a = bm.point(part.centre, 2);
    add(g, part.mass * (m.gravity - a));  // weight and d'Alembert force
    loads.moment -= part.inertia * bm.alpha;
  }
  return loads;
}

std::vector<SectionStress> LinkStress::profile(const Sample& sample, const DynamicsResult& forces, int body) const {
  const Body& b = dynamics_.mechanism().model().bodies[body];
  const BodyMotion bm = body_motion(dynamics_.mechanism(), sample, body);
  const Eigen::Vector2d axis = bm.direction[0].normalized();
  std::vector<SectionStress> out;
  for (int k = 0; k < section_count(body); ++k) {
    const Section& sec = bodies_[body].sections[k];
    const PartLoads loads = part_loads(sample, forces, body, k, -1);
    // The rest of the body holds this part in equilibrium: the internal force is the opposite.
    const Eigen::Vector2d internal = -loads.force;
    SectionStress s;
    s.position = sec.position;
    s.area = sec.props.area;
    s.inertia = sec.props.inertia;
    s.axial = internal.dot(axis);
    s.shear = cross(axis, internal);
    s.moment = -loads.moment;
    auto sigma = [&](double y) {
      return s.axial / s.area - (s.inertia > 0.0 ? s.moment * (y - sec.props.centroid) / s.inertia : 0.0);
    };
    s.sigma_low = sigma(sec.props.s_min);
    s.sigma_high = sigma(sec.props.s_max);
    s.tau_max = s.inertia > 0.0 ? std::abs(s.shear) * sec.props.max_first_moment / (s.inertia * b.thickness) : 0.0;
    const double sigma_neutral = sigma(sec.props.shear_level);
    const double candidates[3] = {std::abs(s.sigma_low), std::abs(s.sigma_high),
                                  std::sqrt(sigma_neutral * sigma_neutral + 3.0 * s.tau_max * s.tau_max)};
    const int worst = static_cast<int>(std::max_element(candidates, candidates + 3) - candidates);
    s.von_mises = candidates[worst];
    const double y[3] = {sec.props.s_min, sec.props.s_max, sec.props.shear_level};
    s.sigma = worst == 0 ? s.sigma_low : worst == 1 ? s.sigma_high : sigma_neutral;
    s.tau = worst == 2 ? s.tau_max : 0.0;
    s.where = {sec.position, y[worst]};
    out.push_back(s);
  }
  return out;
}

std::vector<StressPeak> stress_peaks(const InverseDynamics& dynamics, const LinkStress& stress,
                                     const SweepResult& sweep) {
  const Model& m = dynamics.mechanism().model();
  std::vector<StressPeak> peaks;
  for (std::size_t b = 0; b < m.bodies.size(); ++b)
    if (stress.analysed(static_cast<int>(b))) peaks.push_back({static_cast<int>(b), -1, {}, std::nullopt});
  for (const Sample& sample : sweep.samples) {
    const DynamicsResult forces = dynamics.solve(sample);
    for (StressPeak& peak : peaks) {
      for (const SectionStress& s : stress.profile(sample, forces, peak.body)) {
        if (peak.step < 0 || s.von_mises > peak.at.von_mises) {
          peak.step = sample.step;
          peak.at = s;
        }
      }
    }
  }
  for (StressPeak& peak : peaks) {
    const auto& material = m.bodies[peak.body].material;
    if (material && material->yield_strength && peak.at.von_mises > 0.0)
      peak.safety_factor = *material->yield_strength / peak.at.von_mises;
  }
  return peaks;
}

}  // namespace nbar
