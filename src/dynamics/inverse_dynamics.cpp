#include "nbar/dynamics/inverse_dynamics.hpp"

#include <atomic>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace nbar {

namespace {

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }
Eigen::Vector2d perp(const Eigen::Vector2d& v) { return {-v.y(), v.x()}; }

// The body (other than `except`) that owns both points, or -1 for the ground.
int owner_of_pair(const Model& m, int p, int q, int except) {
  for (std::size_t b = 0; b < m.bodies.size(); ++b) {
    if (static_cast<int>(b) == except) continue;
    const auto& pts = m.bodies[b].points;
    if (std::find(pts.begin(), pts.end(), p) != pts.end() && std::find(pts.begin(), pts.end(), q) != pts.end())
      return static_cast<int>(b);
  }
  return -1;
}

}  // namespace

MassProperties mass_properties(const Body& body) {
  MassProperties m;
  if (body.shape) {
    const AreaProperties a = area_properties(*body.shape);
    m.area = a.area;
    m.from_shape = true;
    if (body.material && !body.inertia) {
      const double per_area = body.material->density * body.thickness;
      m.mass = per_area * a.area;
      m.cg = a.centroid;
      m.inertia = per_area * a.polar();
    }
  }
  if (body.inertia) {
    m.mass = body.inertia->mass;
    m.cg = body.inertia->cg;
    m.inertia = body.inertia->inertia;
    m.from_shape = false;
  }
  return m;
}

BodyFrame body_frame(const Model& model, int body) {
  const Body& b = model.bodies[body];
  if (b.points.size() >= 2) return {b.points[0], b.points[0], b.points[1]};
  for (const Slider& s : model.sliders)
    if (s.body == body) return {b.points[0], s.along[0], s.along[1]};
  return {b.points[0], -1, -1};
}

Eigen::Vector2d BodyMotion::point(const Eigen::Vector2d& drawn, int k) const {
  const Eigen::Vector2d d = drawn - drawn_origin;
  const double ll = drawn_direction.squaredNorm();
  if (ll == 0.0) return origin[k];
  const double a = d.dot(drawn_direction) / ll;
  const double b = cross(drawn_direction, d) / ll;
  return origin[k] + a * direction[k] + b * perp(direction[k]);
}

SampleMotion sample_motion(const Mechanism& mech, const Sample& sample) {
  const Model& m = mech.model();
  const int terms = static_cast<int>(sample.taylor.cols());
  SampleMotion out;
  out.r.resize(m.points.size());
  out.v.assign(m.points.size(), Eigen::Vector2d::Zero());
  out.a.assign(m.points.size(), Eigen::Vector2d::Zero());
  for (std::size_t p = 0; p < m.points.size(); ++p) {
    const int col = mech.column_of(static_cast<int>(p));
    if (col < 0) {
      out.r[p] = m.points[p].position;
      continue;
    }
    out.r[p] = sample.taylor.block<2, 1>(col, 0);
    if (terms > 1) out.v[p] = sample.taylor.block<2, 1>(col, 1);
    if (terms > 2) out.a[p] = 2.0 * sample.taylor.block<2, 1>(col, 2);  // 2! * coefficient
  }
  return out;
}

BodyMotion body_motion(const Model& m, const SampleMotion& motion, int body) {
  const BodyFrame f = body_frame(m, body);
  BodyMotion bm;
  bm.drawn_origin = m.points[f.origin].position;
  bm.drawn_direction = Eigen::Vector2d::Zero();
  const Eigen::Vector2d* of[3] = {&motion.r[f.origin], &motion.v[f.origin], &motion.a[f.origin]};
  for (int k = 0; k < 3; ++k) {
    bm.origin[k] = *of[k];
    bm.direction[k] = Eigen::Vector2d::Zero();
  }
  if (f.from >= 0) {
    bm.drawn_direction = m.points[f.to].position - m.points[f.from].position;
    bm.direction[0] = motion.r[f.to] - motion.r[f.from];
    bm.direction[1] = motion.v[f.to] - motion.v[f.from];
    bm.direction[2] = motion.a[f.to] - motion.a[f.from];
    const double ll = bm.direction[0].squaredNorm();
    bm.omega = cross(bm.direction[0], bm.direction[1]) / ll;
    bm.alpha = cross(bm.direction[0], bm.direction[2]) / ll;
  }
  return bm;
}

BodyMotion body_motion(const Mechanism& mech, const Sample& sample, int body) {
  return body_motion(mech.model(), sample_motion(mech, sample), body);
}

namespace {
std::atomic<long> solves{0};
}  // namespace

long InverseDynamics::solve_count() { return solves.load(); }

InverseDynamics::InverseDynamics(std::shared_ptr<const Mechanism> mechanism) : mechanism_(std::move(mechanism)) {
  const Model& m = mechanism_->model();
  const int bodies = static_cast<int>(m.bodies.size());
  for (int b = 0; b < bodies; ++b) {
    masses_.push_back(mass_properties(m.bodies[b]));
    frames_.push_back(body_frame(m, b));
  }
  std::vector<std::vector<int>> links_at(m.points.size());
  for (std::size_t p = 0; p < m.points.size(); ++p)
    if (m.points[p].ground) links_at[p].push_back(-1);
  for (int b = 0; b < bodies; ++b)
    for (int p : m.bodies[b].points) links_at[p].push_back(b);
  node_of_point_.assign(m.points.size(), -1);
  single_body_of_point_.assign(m.points.size(), -1);
  int column = 0;
  for (std::size_t p = 0; p < m.points.size(); ++p) {
    if (links_at[p].size() >= 2) {
      node_of_point_[p] = static_cast<int>(joints_.size());
      joints_.push_back(static_cast<int>(p));
      // Ground first in links_at: when present it is the link that balances the pin.
      const int first = static_cast<int>(joint_links_.size());
      dependent_.push_back(links_at[p].front() < 0 ? first : first + static_cast<int>(links_at[p].size()) - 1);
      for (int link : links_at[p]) {
        const bool dependent = static_cast<int>(joint_links_.size()) == dependent_.back();
        joint_links_.push_back({static_cast<int>(p), link});
        pin_column_.push_back(dependent ? -1 : column);
        if (!dependent) column += 2;
      }
    } else if (links_at[p].size() == 1 && links_at[p][0] >= 0) {
      single_body_of_point_[p] = links_at[p][0];
    }
  }
  for (const Slider& sl : m.sliders) slider_guide_.push_back(owner_of_pair(m, sl.along[0], sl.along[1], sl.body));
  for (const Slot& sl : m.slots) slot_guide_.push_back(owner_of_pair(m, sl.along[0], sl.along[1], -2));
  slider_base_ = column;
  slot_base_ = slider_base_ + 2 * static_cast<int>(m.sliders.size());
  driver_base_ = slot_base_ + static_cast<int>(m.slots.size());
  unknowns_ = driver_base_ + static_cast<int>(m.drivers.size());
  equations_ = 3 * bodies;
}

DynamicsResult InverseDynamics::solve(const Sample& sample) const {
  if (sample.taylor.cols() < 3)
    throw std::invalid_argument("inverse dynamics needs accelerations: solve the sweep with order 2 or more");
  ++solves;
  const Mechanism& mech = *mechanism_;
  const Model& m = mech.model();
  const int bodies = static_cast<int>(m.bodies.size());
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(equations_, unknowns_);
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(equations_);
  DynamicsResult out;
  out.motion = sample_motion(mech, sample);
  const std::vector<Eigen::Vector2d>& r = out.motion.r;
  const std::vector<Eigen::Vector2d>& v = out.motion.v;

  std::vector<Eigen::Vector2d> cg(bodies);
  for (int b = 0; b < bodies; ++b) {
    const BodyMotion bm = body_motion(m, out.motion, b);
    const MassProperties& mp = masses_[b];
    cg[b] = bm.point(mp.cg, 0);
    const Eigen::Vector2d vg = bm.point(mp.cg, 1), ag = bm.point(mp.cg, 2);
    rhs.segment<2>(3 * b) = mp.mass * ag;
    rhs(3 * b + 2) = mp.inertia * bm.alpha;
    out.kinetic_energy += 0.5 * mp.mass * vg.squaredNorm() + 0.5 * mp.inertia * bm.omega * bm.omega;
    out.potential_energy -= mp.mass * m.gravity.dot(cg[b]);
    rhs.segment<2>(3 * b) -= mp.mass * m.gravity;  // weight, a known force at the cg
  }

  // What each body receives directly, to be valued once the unknowns are known (col -1: known).
  struct Pending {
    AppliedLoad load;
    int col = -1;
  };
  std::vector<Pending> pending;
  // Forces on a joint's pin, to balance its dependent link afterwards (col -1: known).
  struct PinLoad {
    int point;
    Eigen::Vector2d force;
    int col;
  };
  std::vector<PinLoad> on_pins;
  auto force_column = [&](int b, int col, const Eigen::Vector2d& c, const Eigen::Vector2d& at) {
    A(3 * b, col) += c.x();
    A(3 * b + 1, col) += c.y();
    A(3 * b + 2, col) += cross(at - cg[b], c);
  };
  auto known_force = [&](int b, const Eigen::Vector2d& f, const Eigen::Vector2d& at) {
    rhs.segment<2>(3 * b) -= f;
    rhs(3 * b + 2) -= cross(at - cg[b], f);
  };
  auto unknown_on_body = [&](int b, int col, const Eigen::Vector2d& c, const Eigen::Vector2d& at) {
    force_column(b, col, c, at);
    pending.push_back({AppliedLoad{b, at, c, 0.0}, col});
  };
  auto known_on_body = [&](int b, const Eigen::Vector2d& f, const Eigen::Vector2d& at) {
    known_force(b, f, at);
    pending.push_back({AppliedLoad{b, at, f, 0.0}, -1});
  };
  // Couples act on the whole body; `at` only tells a stress section which side has them.
  auto unknown_couple = [&](int b, int col, double c, const Eigen::Vector2d& at) {
    A(3 * b + 2, col) += c;
    pending.push_back({AppliedLoad{b, at, {0, 0}, c}, col});
  };
  auto known_couple = [&](int b, double c, const Eigen::Vector2d& at) {
    rhs(3 * b + 2) -= c;
    pending.push_back({AppliedLoad{b, at, {0, 0}, c}, -1});
  };
  auto first_point = [&](int b) { return r[m.bodies[b].points[0]]; };
  auto dependent_body = [&](int p) { return joint_links_[dependent_[node_of_point_[p]]].link; };
  // A force at a point goes to the named body, else to the joint's pin there (which hands it to
  // its dependent link), else to the only body that has the point; a ground point's goes to
  // the frame.
  auto unknown_at_point = [&](int p, int body, int col, const Eigen::Vector2d& c) {
    if (body >= 0) return unknown_on_body(body, col, c, r[p]);
    if (node_of_point_[p] >= 0) {
      on_pins.push_back({p, c, col});
      if (dependent_body(p) >= 0) force_column(dependent_body(p), col, c, r[p]);
    } else if (single_body_of_point_[p] >= 0) {
      unknown_on_body(single_body_of_point_[p], col, c, r[p]);
    }
  };
  auto known_at_point = [&](int p, int body, const Eigen::Vector2d& f) {
    if (body >= 0) return known_on_body(body, f, r[p]);
    if (node_of_point_[p] >= 0) {
      on_pins.push_back({p, f, -1});
      if (dependent_body(p) >= 0) known_force(dependent_body(p), f, r[p]);
    } else if (single_body_of_point_[p] >= 0) {
      known_on_body(single_body_of_point_[p], f, r[p]);
    }
  };

  // Pin forces: each independent one acts on its link, and its opposite on the dependent link.
  for (std::size_t i = 0; i < joint_links_.size(); ++i) {
    const int col = pin_column_[i];
    if (col < 0) continue;
    const JointLink& jl = joint_links_[i];
    const int dep = dependent_body(jl.point);
    for (int axis = 0; axis < 2; ++axis) {
      const Eigen::Vector2d e = axis == 0 ? Eigen::Vector2d(1, 0) : Eigen::Vector2d(0, 1);
      if (jl.link >= 0) force_column(jl.link, col + axis, e, r[jl.point]);
      if (dep >= 0) force_column(dep, col + axis, -e, r[jl.point]);
    }
  }
  auto guide_normal = [&](const std::array<int, 2>& along) {
    const Eigen::Vector2d w = r[along[1]] - r[along[0]];
    return Eigen::Vector2d(perp(w) / w.norm());
  };
  for (std::size_t s = 0; s < m.sliders.size(); ++s) {
    const Slider& sl = m.sliders[s];
    const int guide = slider_guide_[s];
    const Eigen::Vector2d n = guide_normal(sl.along);
    const int col = slider_base_ + 2 * static_cast<int>(s);
    unknown_on_body(sl.body, col, n, r[sl.point]);
    unknown_couple(sl.body, col + 1, 1.0, r[sl.point]);
    if (guide >= 0) {
      unknown_on_body(guide, col, -n, r[sl.point]);
      unknown_couple(guide, col + 1, -1.0, r[sl.point]);
    }
  }
  for (std::size_t s = 0; s < m.slots.size(); ++s) {
    const Slot& sl = m.slots[s];
    const Eigen::Vector2d n = guide_normal(sl.along);
    const int col = slot_base_ + static_cast<int>(s);
    unknown_at_point(sl.point, -1, col, n);
    if (slot_guide_[s] >= 0) unknown_on_body(slot_guide_[s], col, -n, r[sl.point]);
  }
  for (std::size_t d = 0; d < m.drivers.size(); ++d) {
    const Driver& drv = m.drivers[d];
    const int col = driver_base_ + static_cast<int>(d);
    switch (drv.kind) {
      case DriverKind::Angle:  // a motor at the body's first point (a crank's pivot)
        unknown_couple(drv.body, col, 1.0, first_point(drv.body));
        if (drv.relative_to >= 0) unknown_couple(drv.relative_to, col, -1.0, first_point(drv.body));
        break;
      case DriverKind::Distance: {
        const Eigen::Vector2d e = (r[drv.points[1]] - r[drv.points[0]]).normalized();
        unknown_at_point(drv.points[1], -1, col, e);
        unknown_at_point(drv.points[0], -1, col, -e);
        break;
      }
      case DriverKind::Slide: {
        const Slider& sl = m.sliders[drv.slider];
        const int guide = slider_guide_[drv.slider];
        const Eigen::Vector2d w = (r[sl.along[1]] - r[sl.along[0]]).normalized();
        unknown_on_body(sl.body, col, w, r[sl.point]);
        if (guide >= 0) unknown_on_body(guide, col, -w, r[sl.point]);
        break;
      }
    }
  }

  for (const PointLoad& load : m.point_loads)
    known_at_point(load.point, load.body, {load.fx.value(sample.time), load.fy.value(sample.time)});
  for (const BodyTorque& t : m.torques) known_couple(t.body, t.torque.value(sample.time), first_point(t.body));
  for (const Spring& s : m.springs) {
    const Eigen::Vector2d d = r[s.points[1]] - r[s.points[0]];
    const double length = d.norm();
    const Eigen::Vector2d e = d / length;
    const double tension = s.stiffness * (length - s.free_length) + s.damping * e.dot(v[s.points[1]] - v[s.points[0]]);
    known_at_point(s.points[0], -1, tension * e);
    known_at_point(s.points[1], -1, -tension * e);
    out.potential_energy += 0.5 * s.stiffness * (length - s.free_length) * (length - s.free_length);
  }

  // Square and regular (drivers matching Gruebler's count, no redundancy): LU. Otherwise the
  // minimum-norm least-squares solution, which is exact when the equations are consistent.
  Eigen::VectorXd x;
  bool solved = false;
  if (equations_ == unknowns_ && unknowns_ > 0) {
    Eigen::PartialPivLU<Eigen::MatrixXd> lu(A);
    if (lu.rcond() > 1e-12) {
      x = lu.solve(rhs);
      solved = true;
    }
  }
  if (!solved) {
    Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod;
    cod.setThreshold(1e-10);
    cod.compute(A);
    x = cod.solve(rhs);
    out.unique = cod.rank() == unknowns_;
  }
  out.residual = equations_ > 0 ? (A * x - rhs).lpNorm<Eigen::Infinity>() : 0.0;

  out.pin_forces.assign(joint_links_.size(), Eigen::Vector2d::Zero());
  std::vector<Eigen::Vector2d> pin_balance(joints_.size(), Eigen::Vector2d::Zero());
  for (const PinLoad& p : on_pins)
    pin_balance[node_of_point_[p.point]] += p.col >= 0 ? Eigen::Vector2d(p.force * x(p.col)) : p.force;
  for (std::size_t i = 0; i < joint_links_.size(); ++i) {
    if (pin_column_[i] < 0) continue;
    out.pin_forces[i] = x.segment<2>(pin_column_[i]);
    pin_balance[node_of_point_[joint_links_[i].point]] -= out.pin_forces[i];
  }
  for (std::size_t n = 0; n < joints_.size(); ++n) out.pin_forces[dependent_[n]] = pin_balance[n];
  for (Pending& p : pending) {
    if (p.col >= 0) {
      p.load.force *= x(p.col);
      p.load.couple *= x(p.col);
    }
    out.applied.push_back(p.load);
  }
  for (std::size_t s = 0; s < m.sliders.size(); ++s) {
    out.slider_normal.push_back(x(slider_base_ + 2 * s));
    out.slider_couple.push_back(x(slider_base_ + 2 * s + 1));
  }
  for (std::size_t s = 0; s < m.slots.size(); ++s) out.slot_normal.push_back(x(slot_base_ + s));
  for (std::size_t d = 0; d < m.drivers.size(); ++d) out.driver_effort.push_back(x(driver_base_ + d));
  return out;
}

}  // namespace nbar
