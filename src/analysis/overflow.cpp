#include "overflow.hpp"

#include <cmath>
#include <string>

#include "nbar/model/units.hpp"

namespace nbar::detail {

namespace {

bool finite(double v) { return std::isfinite(v); }

bool all_finite(const DynamicsResult& r) {
  for (const Eigen::Vector2d& f : r.pin_forces)
    if (!f.allFinite()) return false;
  for (const auto* list : {&r.slider_normal, &r.slider_couple, &r.slot_normal, &r.driver_effort})
    for (double v : *list)
      if (!finite(v)) return false;
  for (const AppliedLoad& a : r.applied)
    if (!a.force.allFinite() || !finite(a.couple)) return false;
  return finite(r.kinetic_energy) && finite(r.potential_energy) && finite(r.residual);
}

bool all_finite(const SectionStress& s) {
  for (double v : {s.position, s.area, s.inertia, s.axial, s.shear, s.moment, s.sigma_low, s.sigma_high, s.tau_max,
                   s.von_mises, s.sigma, s.tau})
    if (!finite(v)) return false;
  return s.where.allFinite();
}

// A law's size at t; a law undefined there counts as nothing (another check reports it).
double law_size(const Law& law, double t) {
  try {
    const double v = std::abs(law.value(t));
    return finite(v) ? v : HUGE_VAL;
  } catch (const Error&) {
    return 0.0;
  }
}

struct Culprit {
  EntityRef where;
  std::string what;
  double size = -1.0;
  void consider(EntityRef ref, double candidate, std::string description) {
    if (candidate > size) {
      where = ref;
      size = candidate;
      what = std::move(description);
    }
  }
};

// The largest input load at time t, in newtons (or newton-metres), gravity included.
Culprit largest_load(const Model& m, double t) {
  Culprit c;
  const double g = std::max(1.0, m.gravity.norm());
  for (std::size_t b = 0; b < m.bodies.size(); ++b) {
    const MassProperties mp = mass_properties(m.bodies[b]);
    c.consider({EntityRef::Kind::Body, static_cast<int>(b)}, std::max(mp.mass * g, mp.inertia),
               "the mass of body '" + m.bodies[b].name + "'");
  }
  for (std::size_t i = 0; i < m.point_loads.size(); ++i)
    c.consider({EntityRef::Kind::PointLoad, static_cast<int>(i)},
               std::max(law_size(m.point_loads[i].fx, t), law_size(m.point_loads[i].fy, t)),
               "force #" + std::to_string(i + 1));
  for (std::size_t i = 0; i < m.torques.size(); ++i)
    c.consider({EntityRef::Kind::Torque, static_cast<int>(i)}, law_size(m.torques[i].torque, t),
               "torque #" + std::to_string(i + 1));
  for (std::size_t i = 0; i < m.springs.size(); ++i)
    c.consider({EntityRef::Kind::Spring, static_cast<int>(i)},
               std::max(std::abs(m.springs[i].stiffness), std::abs(m.springs[i].damping)),
               m.springs[i].name.empty() ? "spring #" + std::to_string(i + 1) : "spring '" + m.springs[i].name + "'");
  return c;
}

[[noreturn]] void fail(const Model& m, double t, const std::string& what) {
  const Culprit c = largest_load(m, t);
  if (c.size < 0.0) throw Error(ErrorKind::InvalidModel, what + ": the model's numbers are too large to compute with");
  throw Error(ErrorKind::InvalidModel, what + ": " + c.what + " is too large to compute with", c.where);
}

}  // namespace

void check_finite_dynamics(const Model& model, const Sample& sample, const DynamicsResult& result) {
  if (all_finite(result)) [[likely]]
    return;
  fail(model, sample.time,
       "at step " + std::to_string(sample.step) + " the joint forces overflow (are not finite numbers)");
}

void check_finite_stress(const Model& model, const std::vector<Sample>& samples, const std::vector<StressPeak>& peaks) {
  for (const StressPeak& p : peaks) {
    if (all_finite(p.at) && (!p.safety_factor || finite(*p.safety_factor))) continue;
    const double t = p.step >= 0 && p.step < static_cast<int>(samples.size()) ? samples[p.step].time : 0.0;
    fail(model, t, "the stresses in body '" + model.bodies[p.body].name + "' overflow (are not finite numbers)");
  }
}

}  // namespace nbar::detail
