#include "nbar/dynamics/inverse_dynamics.hpp"

#include <atomic>

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "model/linear_algebra.hpp"
#include "model/plane_vectors.hpp"
#include "nbar/model/diagnostics.hpp"

namespace nbar {

namespace {

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

struct DynamicsWorkspace::Scratch {
  // What a body receives directly, valued once the unknowns are known (column -1: known).
  struct Pending {
    AppliedLoad load;
    int column = -1;
  };
  // A force on a joint's pin, handed to the pin's balancing link afterwards (column -1: known).
  struct PinLoad {
    int point = -1;
    Eigen::Vector2d force{0, 0};
    int column = -1;
  };
  Eigen::MatrixXd matrix;  // the Newton-Euler equations: 3 rows per body, one column per unknown
  Eigen::VectorXd rhs, unknowns;
  Eigen::PartialPivLU<Eigen::MatrixXd> lu;
  Eigen::SparseMatrix<double> sparse;  // large systems: the same equations, factorised sparsely
  Eigen::SparseLU<Eigen::SparseMatrix<double>> sparse_lu;
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> least_squares;
  std::vector<Eigen::Vector2d> cg;  // every body's centre of mass, current pose
  std::vector<Pending> pending;
  std::vector<PinLoad> on_pins;
  std::vector<Eigen::Vector2d> pin_balance;
};

DynamicsWorkspace::DynamicsWorkspace() : scratch_(std::make_unique<Scratch>()) {}
DynamicsWorkspace::~DynamicsWorkspace() = default;
DynamicsWorkspace::DynamicsWorkspace(DynamicsWorkspace&&) noexcept = default;
DynamicsWorkspace& DynamicsWorkspace::operator=(DynamicsWorkspace&&) noexcept = default;

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

// One solve, step by step: the equations are assembled column by column into the workspace,
// solved, and the forces read back. The order of every sum is part of the result (the golden
// outputs are compared byte for byte), so steps keep the order they always had.
class InverseDynamics::Assembly {
 public:
  Assembly(const InverseDynamics& id, const Sample& sample, DynamicsWorkspace::Scratch& w, DynamicsResult& out)
      : id_(id), m_(id.mechanism().model()), sample_(sample), w_(w), out_(out), r_(out.motion.r), v_(out.motion.v) {
    w_.matrix.setZero(id.equations_, id.unknowns_);
    w_.rhs.setZero(id.equations_);
    w_.cg.resize(m_.bodies.size());
    w_.pending.clear();
    w_.on_pins.clear();
  }

  void inertia_and_weight() {
    for (std::size_t b = 0; b < m_.bodies.size(); ++b) {
      const BodyMotion bm = body_motion(m_, out_.motion, static_cast<int>(b));
      const MassProperties& mp = id_.masses_[b];
      w_.cg[b] = bm.point(mp.cg, 0);
      const Eigen::Vector2d vg = bm.point(mp.cg, 1), ag = bm.point(mp.cg, 2);
      w_.rhs.segment<2>(3 * b) = mp.mass * ag;
      w_.rhs(3 * b + 2) = mp.inertia * bm.alpha;
      out_.kinetic_energy += 0.5 * mp.mass * vg.squaredNorm() + 0.5 * mp.inertia * bm.omega * bm.omega;
      out_.potential_energy -= mp.mass * m_.gravity.dot(w_.cg[b]);
      w_.rhs.segment<2>(3 * b) -= mp.mass * m_.gravity;  // weight, a known force at the cg
    }
  }

  // Each independent pin force acts on its link, and its opposite on the joint's balancing link.
  void pin_columns() {
    for (std::size_t i = 0; i < id_.joint_links_.size(); ++i) {
      const int col = id_.pin_column_[i];
      if (col < 0) continue;
      const JointLink& jl = id_.joint_links_[i];
      const int dep = dependent_body(jl.point);
      for (int axis = 0; axis < 2; ++axis) {
        const Eigen::Vector2d e = axis == 0 ? Eigen::Vector2d(1, 0) : Eigen::Vector2d(0, 1);
        if (jl.link >= 0) force_column(jl.link, col + axis, e, r_[jl.point]);
        if (dep >= 0) force_column(dep, col + axis, -e, r_[jl.point]);
      }
    }
  }

  void slider_and_slot_columns() {
    for (std::size_t s = 0; s < m_.sliders.size(); ++s) {
      const Slider& sl = m_.sliders[s];
      const int guide = id_.slider_guide_[s];
      const Eigen::Vector2d n = guide_normal(sl.along);
      const int col = id_.slider_base_ + 2 * static_cast<int>(s);
      unknown_on_body(sl.body, col, n, r_[sl.point]);
      unknown_couple(sl.body, col + 1, 1.0, r_[sl.point]);
      if (guide >= 0) {
        unknown_on_body(guide, col, -n, r_[sl.point]);
        unknown_couple(guide, col + 1, -1.0, r_[sl.point]);
      }
    }
    for (std::size_t s = 0; s < m_.slots.size(); ++s) {
      const Slot& sl = m_.slots[s];
      const Eigen::Vector2d n = guide_normal(sl.along);
      const int col = id_.slot_base_ + static_cast<int>(s);
      unknown_at_point(sl.point, -1, col, n);
      if (id_.slot_guide_[s] >= 0) unknown_on_body(id_.slot_guide_[s], col, -n, r_[sl.point]);
    }
  }

  void driver_columns() {
    for (std::size_t d = 0; d < m_.drivers.size(); ++d) {
      const Driver& drv = m_.drivers[d];
      const int col = id_.driver_base_ + static_cast<int>(d);
      switch (drv.kind) {
        case DriverKind::Angle:  // a motor at the body's first point (a crank's pivot)
          unknown_couple(drv.body, col, 1.0, first_point(drv.body));
          if (drv.relative_to >= 0) unknown_couple(drv.relative_to, col, -1.0, first_point(drv.body));
          break;
        case DriverKind::Distance: {
          const Eigen::Vector2d e = (r_[drv.points[1]] - r_[drv.points[0]]).normalized();
          unknown_at_point(drv.points[1], -1, col, e);
          unknown_at_point(drv.points[0], -1, col, -e);
          break;
        }
        case DriverKind::Slide: {
          const Slider& sl = m_.sliders[drv.slider];
          const int guide = id_.slider_guide_[drv.slider];
          const Eigen::Vector2d w = (r_[sl.along[1]] - r_[sl.along[0]]).normalized();
          unknown_on_body(sl.body, col, w, r_[sl.point]);
          if (guide >= 0) unknown_on_body(guide, col, -w, r_[sl.point]);
          break;
        }
      }
    }
  }

  void known_loads() {
    const double t = sample_.time;
    // A law undefined at t is said at the force or torque whose law it is.
    const auto law_at = [t](const Law& law, EntityRef::Kind kind, std::size_t index, int which) {
      try {
        return law.value(t);
      } catch (const Error& e) {
        throw Error(e.kind(), e.message(), EntityRef{kind, static_cast<int>(index), which});
      }
    };
    for (std::size_t i = 0; i < m_.point_loads.size(); ++i) {
      const PointLoad& load = m_.point_loads[i];
      known_at_point(
          load.point, load.body,
          {law_at(load.fx, EntityRef::Kind::PointLoad, i, 0), law_at(load.fy, EntityRef::Kind::PointLoad, i, 1)});
    }
    for (std::size_t i = 0; i < m_.torques.size(); ++i) {
      const BodyTorque& torque = m_.torques[i];
      double value = law_at(torque.torque, EntityRef::Kind::Torque, i, 0);
      if (torque.no_load_speed) value *= 1.0 - body_motion(m_, out_.motion, torque.body).omega / *torque.no_load_speed;
      known_couple(torque.body, value, first_point(torque.body));
    }
    for (const Spring& s : m_.springs) {
      const Eigen::Vector2d d = r_[s.points[1]] - r_[s.points[0]];
      const double length = d.norm();
      const Eigen::Vector2d e = d / length;
      const double tension =
          s.stiffness * (length - s.free_length) + s.preload + s.damping * e.dot(v_[s.points[1]] - v_[s.points[0]]);
      known_at_point(s.points[0], -1, tension * e);
      known_at_point(s.points[1], -1, -tension * e);
      out_.potential_energy += 0.5 * s.stiffness * (length - s.free_length) * (length - s.free_length) +
                               s.preload * (length - s.free_length);
    }
  }

  // Square and regular (drivers matching Gruebler's count, no redundancy): LU. Otherwise the
  // minimum-norm least-squares solution, which is exact when the equations are consistent.
  void factorise_and_solve() {
    const Eigen::MatrixXd& A = w_.matrix;
    bool solved = false;
    if (id_.equations_ == id_.unknowns_ && id_.unknowns_ > kDenseLimit) {
      solved = sparse_solve();
    } else if (id_.equations_ == id_.unknowns_ && id_.unknowns_ > 0) {
      w_.lu.compute(A);
      if (w_.lu.rcond() > 1e-12) {
        w_.unknowns = w_.lu.solve(w_.rhs);
        solved = true;
      } else {
        solved = equilibrated_solve();
      }
    }
    if (!solved) {
      w_.least_squares.setThreshold(1e-10);
      w_.least_squares.compute(A);
      w_.unknowns = w_.least_squares.solve(w_.rhs);
      out_.unique = w_.least_squares.rank() == id_.unknowns_;
    }
    out_.residual = id_.equations_ > 0 ? (A * w_.unknowns - w_.rhs).lpNorm<Eigen::Infinity>() : 0.0;
  }

  // The moment rows hold lengths where the force rows hold ones, so at an extreme size (a
  // drawing of picometres, or of thousands of kilometres) a regular system looks singular to the
  // condition of A itself, and the least squares then dropped the moment rows as noise (a crank's
  // torque came out at 25% of weight x size). Rows and columns scaled to a largest entry of 1,
  // the system is judged by its own condition. Only tried where the plain LU gave up, so that every
  // other system is solved exactly as before.
  bool equilibrated_solve() {
    const Eigen::MatrixXd& A = w_.matrix;
    const Eigen::VectorXd row_size = A.rowwise().lpNorm<Eigen::Infinity>();
    if (!(row_size.minCoeff() > 0.0) || !row_size.allFinite()) return false;
    const Eigen::VectorXd row_scale = row_size.cwiseInverse();
    Eigen::MatrixXd scaled = row_scale.asDiagonal() * A;
    const Eigen::VectorXd column_size = scaled.colwise().lpNorm<Eigen::Infinity>().transpose();
    if (!(column_size.minCoeff() > 0.0)) return false;
    const Eigen::VectorXd column_scale = column_size.cwiseInverse();
    scaled = scaled * column_scale.asDiagonal();
    const Eigen::PartialPivLU<Eigen::MatrixXd> lu(scaled);
    if (!(lu.rcond() > 1e-12)) return false;
    w_.unknowns = column_scale.asDiagonal() * lu.solve(row_scale.asDiagonal() * w_.rhs);
    return w_.unknowns.allFinite();
  }

  // Sparse LU of the assembled equations; false when it finds them singular (redundant
  // constraints), which the least-squares solution then handles.
  bool sparse_solve() {
    w_.sparse = w_.matrix.sparseView();
    w_.sparse_lu.analyzePattern(w_.sparse);
    w_.sparse_lu.factorize(w_.sparse);
    if (w_.sparse_lu.info() != Eigen::Success) return false;
    w_.unknowns = w_.sparse_lu.solve(w_.rhs);
    return w_.sparse_lu.info() == Eigen::Success && w_.unknowns.allFinite();
  }

  void read_back() {
    const Eigen::VectorXd& x = w_.unknowns;
    out_.pin_forces.assign(id_.joint_links_.size(), Eigen::Vector2d::Zero());
    w_.pin_balance.assign(id_.joints_.size(), Eigen::Vector2d::Zero());
    for (const DynamicsWorkspace::Scratch::PinLoad& p : w_.on_pins)
      w_.pin_balance[id_.node_of_point_[p.point]] += p.column >= 0 ? Eigen::Vector2d(p.force * x(p.column)) : p.force;
    for (std::size_t i = 0; i < id_.joint_links_.size(); ++i) {
      if (id_.pin_column_[i] < 0) continue;
      out_.pin_forces[i] = x.segment<2>(id_.pin_column_[i]);
      w_.pin_balance[id_.node_of_point_[id_.joint_links_[i].point]] -= out_.pin_forces[i];
    }
    for (std::size_t n = 0; n < id_.joints_.size(); ++n) out_.pin_forces[id_.dependent_[n]] = w_.pin_balance[n];
    out_.applied.reserve(w_.pending.size());
    for (DynamicsWorkspace::Scratch::Pending& p : w_.pending) {
      if (p.column >= 0) {
        p.load.force *= x(p.column);
        p.load.couple *= x(p.column);
      }
      out_.applied.push_back(p.load);
    }
    for (std::size_t s = 0; s < m_.sliders.size(); ++s) {
      out_.slider_normal.push_back(x(id_.slider_base_ + 2 * s));
      out_.slider_couple.push_back(x(id_.slider_base_ + 2 * s + 1));
    }
    for (std::size_t s = 0; s < m_.slots.size(); ++s) out_.slot_normal.push_back(x(id_.slot_base_ + s));
    for (std::size_t d = 0; d < m_.drivers.size(); ++d) out_.driver_effort.push_back(x(id_.driver_base_ + d));
  }

 private:
  void force_column(int b, int col, const Eigen::Vector2d& c, const Eigen::Vector2d& at) {
    w_.matrix(3 * b, col) += c.x();
    w_.matrix(3 * b + 1, col) += c.y();
    w_.matrix(3 * b + 2, col) += cross(at - w_.cg[b], c);
  }
  void known_force(int b, const Eigen::Vector2d& f, const Eigen::Vector2d& at) {
    w_.rhs.segment<2>(3 * b) -= f;
    w_.rhs(3 * b + 2) -= cross(at - w_.cg[b], f);
  }
  void unknown_on_body(int b, int col, const Eigen::Vector2d& c, const Eigen::Vector2d& at) {
    force_column(b, col, c, at);
    w_.pending.push_back({AppliedLoad{b, at, c, 0.0}, col});
  }
  void known_on_body(int b, const Eigen::Vector2d& f, const Eigen::Vector2d& at) {
    known_force(b, f, at);
    w_.pending.push_back({AppliedLoad{b, at, f, 0.0}, -1});
  }
  // Couples act on the whole body; `at` only tells a stress section which side has them.
  void unknown_couple(int b, int col, double c, const Eigen::Vector2d& at) {
    w_.matrix(3 * b + 2, col) += c;
    w_.pending.push_back({AppliedLoad{b, at, {0, 0}, c}, col});
  }
  void known_couple(int b, double c, const Eigen::Vector2d& at) {
    w_.rhs(3 * b + 2) -= c;
    w_.pending.push_back({AppliedLoad{b, at, {0, 0}, c}, -1});
  }
  Eigen::Vector2d first_point(int b) const { return r_[m_.bodies[b].points[0]]; }
  int dependent_body(int p) const { return id_.joint_links_[id_.dependent_[id_.node_of_point_[p]]].link; }
  Eigen::Vector2d guide_normal(const std::array<int, 2>& along) const {
    const Eigen::Vector2d w = r_[along[1]] - r_[along[0]];
    return Eigen::Vector2d(perp(w) / w.norm());
  }
  // A force at a point goes to the named body, else to the joint's pin there (which hands it to
  // its balancing link), else to the only body that has the point; a ground point's goes to
  // the frame.
  void unknown_at_point(int p, int body, int col, const Eigen::Vector2d& c) {
    if (body >= 0) return unknown_on_body(body, col, c, r_[p]);
    if (id_.node_of_point_[p] >= 0) {
      w_.on_pins.push_back({p, c, col});
      if (dependent_body(p) >= 0) force_column(dependent_body(p), col, c, r_[p]);
    } else if (id_.single_body_of_point_[p] >= 0) {
      unknown_on_body(id_.single_body_of_point_[p], col, c, r_[p]);
    }
  }
  void known_at_point(int p, int body, const Eigen::Vector2d& f) {
    if (body >= 0) return known_on_body(body, f, r_[p]);
    if (id_.node_of_point_[p] >= 0) {
      w_.on_pins.push_back({p, f, -1});
      if (dependent_body(p) >= 0) known_force(dependent_body(p), f, r_[p]);
    } else if (id_.single_body_of_point_[p] >= 0) {
      known_on_body(id_.single_body_of_point_[p], f, r_[p]);
    }
  }

  const InverseDynamics& id_;
  const Model& m_;
  const Sample& sample_;
  DynamicsWorkspace::Scratch& w_;
  DynamicsResult& out_;
  const std::vector<Eigen::Vector2d>& r_;
  const std::vector<Eigen::Vector2d>& v_;
};

DynamicsResult InverseDynamics::solve(const Sample& sample, DynamicsWorkspace& workspace) const {
  if (sample.taylor.cols() < 3)
    throw Error(ErrorKind::BadInput, "inverse dynamics needs accelerations: solve the sweep with order 2 or more");
  ++solves;
  DynamicsResult out;
  out.motion = sample_motion(*mechanism_, sample);
  if (!workspace.scratch_) workspace.scratch_ = std::make_unique<DynamicsWorkspace::Scratch>();  // moved from
  Assembly assembly(*this, sample, *workspace.scratch_, out);
  assembly.inertia_and_weight();
  assembly.pin_columns();
  assembly.slider_and_slot_columns();
  assembly.driver_columns();
  assembly.known_loads();
  assembly.factorise_and_solve();
  assembly.read_back();
  return out;
}

DynamicsResult InverseDynamics::solve(const Sample& sample) const {
  thread_local DynamicsWorkspace workspace;
  return solve(sample, workspace);
}

}  // namespace nbar
