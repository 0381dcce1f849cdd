#include "nbar/stress/link_stress.hpp"

#include <algorithm>
#include <cmath>

#include "model/plane_vectors.hpp"

namespace nbar {

namespace {

// Where to cut: evenly along the body, and more closely around every joint and hole, where
// the internal forces jump and the section is smallest. Never through a joint's centre, where
// it would be ambiguous which side the joint's force acts on.
std::vector<double> section_positions(const Model& m, const Body& body, const Eigen::Vector2d& origin,
                                      const Eigen::Vector2d& axis, int count) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const Eigen::Vector2d& v : straight_edged(*body.shape).outline) {
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

  const double margin = 1e-6 * length;
  std::vector<double> kept;
  auto keep = [&](double x) {
    if (x <= lo + margin || x >= hi - margin) return;
    for (int p : body.points)
      if (std::abs(x - axis.dot(m.points[p].position - origin)) < margin) return;
    kept.push_back(x);
  };
  auto tidy = [&] {
    std::sort(kept.begin(), kept.end());
    kept.erase(std::unique(kept.begin(), kept.end(), [&](double a, double b) { return b - a < margin; }), kept.end());
  };
  const double offsets[] = {0.15, 0.35, 0.6, 1.0, 1.5, 2.2};
  for (const Feature& f : features)
    for (double o : offsets) {
      keep(f.s - o * f.radius);
      keep(f.s + o * f.radius);
    }
  tidy();
  const int even = std::max(100, count - static_cast<int>(kept.size()));
  for (int i = 0; i < even; ++i) keep(lo + (i + 0.5) * length / even);
  tidy();
  return kept;
}

}  // namespace

LinkStress::LinkStress(std::shared_ptr<const InverseDynamics> dynamics, int sections) : dynamics_(std::move(dynamics)) {
  const Model& m = dynamics_->mechanism().model();
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
    const double mass = dynamics_->masses()[b].mass;
    const double per_area = area > 0.0 ? mass / area : 0.0;
    const Region plate = straight_edged(*body.shape);  // sections cut arcs as chords within 1e-5 of the size
    for (double s : section_positions(m, body, bs.origin, bs.axis, sections)) {
      const Eigen::Vector2d cut = bs.origin + s * bs.axis;
      const auto intervals = section_intervals(plate, cut, across);
      if (intervals.empty()) continue;
      Section sec;
      sec.position = s;
      sec.props = section_properties(intervals, body.thickness);
      sec.centroid = cut + sec.props.centroid * across;
      for (int side = 0; side < 2; ++side) {
        const AreaProperties a = clipped_area_properties(plate, cut, side == 0 ? Eigen::Vector2d(-bs.axis) : bs.axis);
        sec.part[side] = {per_area * a.area, a.centroid, per_area * a.polar()};
      }
      bs.sections.push_back(sec);
    }
  }
}

LinkStress::StepLoads LinkStress::step_loads(const DynamicsResult& forces, int body) const {
  const Model& m = dynamics_->mechanism().model();
  StepLoads step;
  step.motion = body_motion(m, forces.motion, body);
  step.axis = step.motion.direction[0].normalized();
  const auto& links = dynamics_->joint_links();
  for (std::size_t i = 0; i < links.size(); ++i) {
    if (links[i].link != body) continue;
    step.at.push_back(forces.motion.r[links[i].point]);
    step.force.push_back(forces.pin_forces[i]);
    step.couple.push_back(0.0);
  }
  for (const AppliedLoad& l : forces.applied) {
    if (l.body != body) continue;
    step.at.push_back(l.at);
    step.force.push_back(l.force);
    step.couple.push_back(l.couple);
  }
  return step;
}

PartLoads LinkStress::part_loads(const StepLoads& step, int body, int section, int side) const {
  const Model& m = dynamics_->mechanism().model();
  const BodySections& bs = bodies_[body];
  const Section& sec = bs.sections[section];
  const BodyMotion& bm = step.motion;
  const Eigen::Vector2d cut = bm.point(bs.origin + sec.position * bs.axis, 0);
  const Eigen::Vector2d centre = bm.point(sec.centroid, 0);
  PartLoads loads;
  for (std::size_t i = 0; i < step.at.size(); ++i) {
    if (!(side * step.axis.dot(step.at[i] - cut) > 0.0)) continue;
    loads.force += step.force[i];
    loads.moment += cross(step.at[i] - centre, step.force[i]) + step.couple[i];
  }
  const Part& part = sec.part[side < 0 ? 0 : 1];
  if (part.mass > 0.0) {
    const Eigen::Vector2d g = bm.point(part.centre, 0);
    const Eigen::Vector2d f = part.mass * (m.gravity - bm.point(part.centre, 2));  // weight and d'Alembert force
    loads.force += f;
    loads.moment += cross(g - centre, f) - part.inertia * bm.alpha;
  }
  return loads;
}

PartLoads LinkStress::part_loads(const DynamicsResult& forces, int body, int section, int side) const {
  return part_loads(step_loads(forces, body), body, section, side);
}

std::vector<SectionStress> LinkStress::profile(const DynamicsResult& forces, int body) const {
  const Body& b = dynamics_->mechanism().model().bodies[body];
  const StepLoads step = step_loads(forces, body);
  const Eigen::Vector2d& axis = step.axis;
  std::vector<SectionStress> out;
  out.reserve(section_count(body));
  for (int k = 0; k < section_count(body); ++k) {
    const Section& sec = bodies_[body].sections[k];
    const PartLoads loads = part_loads(step, body, k, -1);
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

std::vector<StressPeak> stress_peaks(const LinkStress& stress, const SweepResult& sweep,
                                     const std::vector<DynamicsResult>& per_sample, const RunControl& control) {
  const Model& m = stress.dynamics().mechanism().model();
  std::vector<StressPeak> peaks;
  for (std::size_t b = 0; b < m.bodies.size(); ++b)
    if (stress.analysed(static_cast<int>(b))) peaks.push_back({static_cast<int>(b), -1, {}, std::nullopt});
  for (std::size_t i = 0; i < sweep.samples.size(); ++i) {
    control.checkpoint("stress", static_cast<long>(i), static_cast<long>(sweep.samples.size()));
    for (StressPeak& peak : peaks) {
      for (const SectionStress& s : stress.profile(per_sample[i], peak.body)) {
        // A section whose stress is not a number (an overflow) is kept as the peak, so that the
        // analysis reports it instead of passing over it.
        const bool worse = peak.step < 0 || !std::isfinite(s.von_mises) || s.von_mises > peak.at.von_mises;
        if (worse && (peak.step < 0 || std::isfinite(peak.at.von_mises))) {
          peak.step = sweep.samples[i].step;
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
