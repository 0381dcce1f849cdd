#include "nbar/dynamics/forward_dynamics.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <exception>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>

#include "dynamics/augmented_system.hpp"
#include "dynamics/dop853_tableau.hpp"
#include "dynamics/forward_dynamics_testing.hpp"
#include "dynamics/golden_section.hpp"
#include "dynamics/initial_velocity.hpp"
#include "dynamics/joint_friction.hpp"
#include "dynamics/ordered_worker.hpp"
#include "kinematics/constraints.hpp"
#include "kinematics/linear_solver.hpp"
#include "kinematics/sparse_lu.hpp"
#include "nbar/dynamics/equations_of_motion.hpp"
#include "nbar/dynamics/inverse_dynamics.hpp"
#include "nbar/kinematics/position.hpp"

namespace nbar {

namespace {

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }
Eigen::Vector2d perp(const Eigen::Vector2d& v) { return {-v.y(), v.x()}; }

// A duration: "3.2e-17 s".
std::string seconds_text(double seconds) {
  std::ostringstream s;
  s.precision(3);
  s << seconds << " s";
  return s.str();
}

std::string time_text(double t) {
  std::ostringstream s;
  s.precision(9);
  s << "t = " << t << " s";
  return s.str();
}

// Why a run stops early: said at an entity of the model when there is one.
struct SimulationStop {
  std::string reason;
  EntityRef where;
  bool cancelled = false;  // by the run's control (a cancel, a deadline), not by the motion
};

void driver_values_at(const Mechanism& mech, const Eigen::VectorXd& q, const std::vector<double>* bodies,
                      const std::vector<double>& previous, std::vector<double>& out);

// The toggle's signed measure (docs/dynamics.md, Events). The reference keeps, from the kept
// rows' Jacobian at one state, the rows its rank-revealing QR chose as independent (S) and an
// orthonormal basis U of their gradients' span; at another state det(U^T J_S^T) / prod |J_s|
// changes sign where those rows become dependent: a toggle or change point. A rank deficiency the
// mechanism has everywhere (redundant constraints) is left out with the rows not in S. Dense and
// cubic in the size: evaluated only on the steps where the sparse gate (EquationsOfMotion::Gate)
// says the rows may be near dependent.
class ToggleMeasure {
 public:
  void reference(const Eigen::MatrixXd& jacobian) {
    rows_.clear();
    if (jacobian.rows() == 0) return;
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr;
    qr.setThreshold(1e-10);
    qr.compute(jacobian.transpose());
    const int rank = static_cast<int>(qr.rank());
    for (int i = 0; i < rank; ++i) rows_.push_back(qr.colsPermutation().indices()(i));
    const Eigen::MatrixXd basis = qr.householderQ();
    span_ = basis.leftCols(rank);
  }
  double measure(const Eigen::MatrixXd& jacobian) const {
    const int r = static_cast<int>(rows_.size());
    if (r == 0) return 1.0;
    Eigen::MatrixXd projected(r, r);
    double norms = 1.0;
    for (int i = 0; i < r; ++i) {
      projected.col(i) = span_.transpose() * jacobian.row(rows_[i]).transpose();
      norms *= jacobian.row(rows_[i]).norm();
    }
    return projected.determinant() / norms;
  }
  // The smallest singular value of those rows, each of unit length: how near they are to
  // dependent, whatever the measure's size elsewhere (a run started next to a change point has a
  // measure of nearly nothing at its start).
  double least_singular_value(const Eigen::MatrixXd& jacobian) const {
    const int r = static_cast<int>(rows_.size());
    if (r == 0) return 1.0;
    Eigen::MatrixXd unit(r, jacobian.cols());
    for (int i = 0; i < r; ++i) unit.row(i) = jacobian.row(rows_[i]).normalized();
    return Eigen::JacobiSVD<Eigen::MatrixXd>(unit).singularValues().minCoeff();
  }

 private:
  std::vector<int> rows_;
  Eigen::MatrixXd span_;
};

// The gate opens (the dense measure is evaluated on the step) where the square Jacobian's
// conditioning (EquationsOfMotion::Gate) falls below this fraction of its value at the start, or
// its determinant changes sign.
constexpr double kGateNear = 0.1;

// A toggle's row, and the state a reversal there mirrors, are where the positions are this
// fraction of the drawing from the toggle's: some ten times the blur that the constraint drift
// gives the positions next to it (docs/dynamics.md, Events), so that the Jacobian is regular
// there and the state clearly on the side it came from.
constexpr double kRegularDistance = 1e-4;

// A motion reversed at a toggle that meets it again without getting this fraction of the drawing
// away from it (three times kRegularDistance) bounces below what reversals can follow, and is
// likely coming to rest against it: the run stops there.
constexpr double kRestDistance = 3e-4;

// kStalledSteps steps shorter than kStalledStep of the run while next to a square Jacobian (its
// conditioning below kStalledConditioning of its size at the start, where the gate opens) stop
// the run: it approaches a toggle it does not reach (a prescribed motion into a stretched pose:
// steps from 1e-6 to 1e-10 s, for millions of steps). A toggle reached takes some hundreds of
// such steps.
constexpr double kStalledStep = 1e-7;
constexpr double kStalledConditioning = kGateNear;
constexpr long kStalledSteps = 20'000;

// The steps' thread makes a job's rows itself when the row thread has this many jobs or more
// still to do: the two threads then share the rows as their speeds allow (a four-bar's steps
// take about as long as its rows; alone, the row thread set the pace).
constexpr std::size_t kRowJobsBehind = 16;

// Set by tests (forward_dynamics_testing.hpp): the steps' thread makes every other job's rows.
std::atomic<bool> g_rows_on_both_threads{false};

// How near the kept rows are to dependent is the smallest singular value of their unit rows
// (ToggleMeasure::least_singular_value). The positions' drift (|Phi| about 1e-12 of the size)
// blurs it next to a change point to about sqrt(1e-12) = 1e-6 (docs/dynamics.md, Events): rows
// within that cannot be told from dependent. A motion that passes a change point onto the other
// branch makes the measure dip without changing sign: a dip within three times the blur is taken
// for the change point (exact kites dip to 0.9e-6 to 1.25e-6; a near miss dips to about
// sqrt(e r / L) for lengths off by e of the size, r the short link and L the long one).
constexpr double kToggleBlur = 1e-6;
// Rows still nearing dependence are at the toggle only well within the blur: the steps may not
// get nearer (at rtol 1e-12 they collapse at a tenth of it next to a parallelogram's change
// point), and taken at the blur itself every toggle came 1.3e-6 rad early, which reversals added
// up (150 us over 78 reversals of a parallelogram released 0.5 deg above its change point).
constexpr double kToggleReached = 0.1 * kToggleBlur;
// A toggle measure this small at the start (rows of unit length a few degrees from dependent)
// says the run starts next to a toggle.
constexpr double kSmallMeasure = 0.05;
constexpr double kChangePointDip = 3 * kToggleBlur;

// A start whose square Jacobian's conditioning (EquationsOfMotion::Gate) is below this is a toggle.
constexpr double kSingularStart = 1e-10;

// A body's centre of mass as a fixed combination of its frame points, r_cg = r_o + a u + b u_perp
// with u = r_to - r_from: linear in q, so the body's mass on the coordinates is constant.
struct BodyMass {
  int body = -1;
  double mass = 0.0;
  double rotary = 0.0;  // inertia / |u|^2: the kinetic energy of rotation is rotary |u'|^2 / 2
  BodyFrame frame;
  double a = 0.0, b = 0.0;
};

// The equations of motion of one mechanism: its constant mass matrix, the rows kept (constraints
// and the drivers that stay kinematic), and the loads. Evaluates the accelerations at (t, q, q')
// and makes the projections, both through one sparse augmented system (augmented_system.hpp).
class EquationsOfMotion {
 public:
  // What one evaluation gives besides q'': the powers the energy balance integrates.
  struct Rates {
    Eigen::VectorXd acceleration;
    double dissipated = 0.0;  // W, by dampers (>= 0)
    double work_in = 0.0;     // W, by applied loads and the kinematic drivers
  };

  // What says, cheaply, whether the kept rows may be near a toggle: the sign of the determinant of
  // the square Jacobian of every row (the free drivers' rows at their present values), and how
  // well conditioned it is with each row scaled to unit length (Hager's estimate of
  // 1 / cond_1 from its sparse LU, SparseLU::reciprocal_condition_estimate). Not the LU's
  // smallest-to-largest pivot ratio, which follows the links' directions as much as the rows'
  // dependence: its pivots, kept while they pass a threshold, shrink tenfold before another row
  // leads, and on a double crank far from any toggle it swung from 0.88 to 0.0098 (below a tenth
  // of its start's on 16 % of the steps, each of which then paid the dense measure), where the
  // conditioning stayed within 0.10 to 0.32. Not available (`square` false) with redundant rows.
  struct Gate {
    bool square = false;
    int sign = 0;
    double conditioning = 0.0;
  };

  EquationsOfMotion(const Mechanism& mech, std::vector<double> start) : mech_(mech), start_(std::move(start)) {
    const Model& m = mech.model();
    n_ = mech.coordinate_count();
    const auto& rows = mech.equations().rows;
    for (std::size_t r = 0; r < rows.size(); ++r)
      if (!rows[r].is_driver() || !m.drivers[rows[r].driver].free) kept_.push_back(static_cast<int>(r));
    selected_.assign(rows.size(), -1);
    for (std::size_t i = 0; i < kept_.size(); ++i) selected_[kept_[i]] = static_cast<int>(i);
    for (const int r : kept_) time_dependent_ = time_dependent_ || rows[r].is_driver();
    std::vector<AugmentedSystem::Entry> entries;
    const auto& pattern = mech.equations().pattern;
    for (std::size_t i = 0; i < pattern.size(); ++i)
      if (selected_[pattern[i].row] >= 0)
        entries.push_back({static_cast<int>(i), selected_[pattern[i].row], pattern[i].col});
    system_.emplace(n_, kept_rows(), build_masses(), std::move(entries));
    if (!mech.mobility().redundant.empty()) system_->rows_redundant();
    square_ = mech.row_count() == n_;
    if (square_) {
      std::vector<SparseLU::Entry> full;
      for (const JacobianEntry& e : pattern) full.push_back({e.row, e.col});
      full_lu_.set_pattern(n_, full);
      row_lengths_.resize(n_);
    }
    zero_force_.setZero(n_);
    lambda_.setZero(kept_rows());
    free_states_.resize(m.drivers.size());
    for (std::size_t d = 0; d < m.drivers.size(); ++d)
      if (m.drivers[d].free)
        set_driver_state(free_states_[d], start_[d] + m.drivers[d].initial_speed * Series::variable(kTerms, 0.0),
                         m.drivers[d].is_angular());
  }

  int coordinates() const { return n_; }
  int kept_rows() const { return static_cast<int>(kept_.size()); }

  // Every driver's state at t: the kinematic ones by their law or from their start at their
  // speed; the free ones (whose rows are dropped) at their start moving at their initial speed,
  // which only the initial velocity solve reads.
  void drivers_at(double t, std::vector<DriverState>& out) const {
    const Model& m = mech_.model();
    out.resize(m.drivers.size());
    for (std::size_t d = 0; d < m.drivers.size(); ++d) {
      if (m.drivers[d].free)
        out[d] = free_states_[d];  // the same at every t (free_states_)
      else
        kinematic_driver_at(t, d, out[d]);
    }
  }
  // The same into drivers_, where the free drivers' states, written at the first call, stay: their
  // copies at every factorisation were 1.4 % of a four-bar's run.
  void own_drivers_at(double t) {
    drivers_time_ = t;
    const Model& m = mech_.model();
    if (drivers_.size() != m.drivers.size()) return drivers_at(t, drivers_);
    for (std::size_t d = 0; d < m.drivers.size(); ++d)
      if (!m.drivers[d].free) kinematic_driver_at(t, d, drivers_[d]);
  }
  // A kinematic driver's state at t: by its law, or from its start at its speed.
  void kinematic_driver_at(double t, std::size_t d, DriverState& out) const {
    const Driver& drv = mech_.model().drivers[d];
    Series value;
    if (drv.law) {
      try {
        value = drv.law->series(t, kTerms);
      } catch (const Error& e) {
        throw SimulationStop{e.message(), {EntityRef::Kind::Driver, static_cast<int>(d), 0}};  // it says where in t
      }
    } else {
      const Series s = Series::variable(kTerms, t);
      value = start_[d] + drv.speed * s + 0.5 * drv.accel * (s * s);
    }
    set_driver_state(out, value, drv.is_angular());
  }

  // The drivers at t, the Jacobian at q, and the augmented matrix formed and factorised there.
  // Throws SimulationStop where a motion the kept rows allow has no inertia.
  void factorise(double t, const Eigen::VectorXd& q) {
    own_drivers_at(t);
    evaluate_jacobian(mech_, q, drivers_, jacobian_values_);
    factorise_jacobian(t);
  }
  // The same, and the kept rows' residuals at q, in one pass over the rows (a projection's start).
  const Eigen::VectorXd& factorise_with_residuals(double t, const Eigen::VectorXd& q) {
    own_drivers_at(t);
    evaluate_residuals_and_jacobian(mech_, q, drivers_, all_rows_, jacobian_values_);
    factorise_jacobian(t);
    return select(all_rows_, residual_);
  }
  void factorise_jacobian(double t) {
    if (system_->factorize(jacobian_values_)) return;
    // Fully driven, a motion the rows allow is one they have lost: the drivers and constraints
    // became dependent (a limit, a toggle), not a body without mass.
    if (!has_free_driver())
      throw SimulationStop{"the drivers cannot move the mechanism on at " + time_text(t) +
                               ": it reached a limit of its motion (a toggle or dead centre), where its drivers and "
                               "constraints became dependent",
                           driver_to_blame()};
    throw SimulationStop{"a free motion has no inertia at " + time_text(t) +
                             ": the bodies it moves have no mass or moment of inertia (give them `mass:` and "
                             "`inertia:`, or a shape and a material)",
                         driver_to_blame()};
  }
  // The Jacobian at q, at the time of the last factorisation, whose matrix stays (near q it
  // preconditions the solves with the new Jacobian), and the kept rows' residuals at q: one pass
  // over the rows.
  // `moved`: how far q is from where the Jacobian was evaluated last (the largest change of a
  // coordinate, m); within kSlightMove of the drawing's size the Schur complement formed there
  // stays (AugmentedSystem::jacobian_moved_slightly).
  const Eigen::VectorXd& update_jacobian_and_residuals(const Eigen::VectorXd& q, double moved) {
    evaluate_residuals_and_jacobian(mech_, q, drivers_, all_rows_, jacobian_values_);
    if (moved <= kSlightMove * mech_.drawing_size())
      system_->jacobian_moved_slightly();
    else
      system_->jacobian_changed();
    return select(all_rows_, residual_);
  }
  // Phi_t of the kept rows at q: the first Taylor coefficient of Phi with q' = 0.
  const Eigen::VectorXd& time_derivative(const Eigen::VectorXd& q) {
    if (!time_dependent_) {  // only the kinematic drivers' rows depend on t
      time_derivative_.setZero(kept_rows());
      return time_derivative_;
    }
    if (first_order_.rows() != n_) first_order_.setZero(n_, 2);  // q' stays zero
    first_order_.col(0) = q;
    evaluate_series_remainder(mech_, first_order_, 1, drivers_, all_rows_);
    return select(all_rows_, time_derivative_);
  }
  // gamma of the kept rows: Phi_q q'' = gamma on the acceleration level.
  const Eigen::VectorXd& gamma(const Eigen::VectorXd& q, const Eigen::VectorXd& qd) {
    if (second_order_.rows() != n_) second_order_.setZero(n_, 3);  // q''/2, the unknown, stays zero
    second_order_.col(0) = q;
    second_order_.col(1) = qd;
    evaluate_series_remainder(mech_, second_order_, 2, drivers_, all_rows_);
    select(all_rows_, gamma_);
    gamma_ *= -2.0;
    return gamma_;
  }
  // What residuals and time_derivative computed last.
  const Eigen::VectorXd& last_residuals() const { return residual_; }
  const Eigen::VectorXd& last_time_derivative() const { return time_derivative_; }
  // The largest |Phi_q x - c| the last solve left (the accelerations', a correction's).
  double last_solve_residual() const { return system_ ? system_->last_residual() : 0.0; }
  // Phi_q x with the present Jacobian.
  const Eigen::VectorXd& jacobian_times(const Eigen::VectorXd& x) {
    system_->apply(jacobian_values_, x, product_);
    return product_;
  }

  // The solves' scales (AugmentedSystem::Scales), and taking another's: the output rows' equations
  // take the run's, so that each row's solves do not depend on which rows the equations made first.
  AugmentedSystem::Scales scales() const { return system_ ? system_->scales() : AugmentedSystem::Scales{}; }
  void take_scales(const AugmentedSystem::Scales& scales) {
    if (system_) system_->take_scales(scales);
  }
  // The accelerations' next solve starts from no multipliers: its answer is then the same whatever
  // these equations solved before.
  void forget_warm_start() { lambda_.setZero(kept_rows()); }

  // The smallest change dx in the mass's metric with Phi_q dx = c (the present Jacobian): the
  // correction of a projection. The metric is M's: the projections of Bayo and Ledesma, which
  // reuse the factorisation of the accelerations' system.
  const Eigen::VectorXd& correction(const Eigen::VectorXd& c) {
    projection_lambda_.setZero(kept_rows());
    system_->solve(jacobian_values_, zero_force_, c, correction_, projection_lambda_, AugmentedSystem::Rounds::one);
    return correction_;
  }

  // q'' at (t, q, q') and the powers of the energy balance. Throws SimulationStop where the
  // accelerations are not determined: the kept rows dependent (a toggle), a free motion without
  // inertia.
  // `rounds`: the accelerations to rounding (a row's), or as the integrator's stages need them.
  const Rates& evaluate(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                        AugmentedSystem::Rounds rounds = AugmentedSystem::Rounds::to_rounding) {
    factorise(t, q);
    return evaluate_factorised(t, q, qd, rounds);
  }
  // The same with the factorisation made at (or near) q, at t, the Jacobian at q.
  const Rates& evaluate_factorised(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                                   AugmentedSystem::Rounds rounds = AugmentedSystem::Rounds::to_rounding) {
    double dissipated = 0.0, applied = 0.0;
    generalised_forces(t, q, qd, dissipated, applied, loads_);
    const double left = system_->solve(jacobian_values_, loads_, gamma(q, qd), rates_.acceleration, lambda_, rounds);
    // Where the rows have become dependent the acceleration constraints ask the impossible and
    // what is left of them stays of order 1; near (not at) a toggle the solve still converges.
    if (!(left <= kDependentRows)) {
      lambda_.setZero(kept_rows());  // no warm start from there
      throw SimulationStop{"the constraints became singular at " + time_text(t) +
                               ": the mechanism reached a toggle or dead-centre position, where its motion is "
                               "not determined by the loads",
                           driver_to_blame()};
    }
    if (!rates_.acceleration.allFinite()) lambda_.setZero(kept_rows());
    rates_.dissipated = dissipated;
    // The constraint forces -Phi_q^T lambda do work only through the rows that depend on time
    // (the kinematic drivers'): -lambda . Phi_q q' = lambda . Phi_t wherever the speeds keep the
    // constraints. Written so, a run without kinematic drivers has none; written as (M q'' - Q) . q'
    // it took in the stages' speeds' drift (a parallelogram under gravity alone: -1e-8 J of work
    // in 0.16 s at rtol 1e-8, which put the energy balance 1.2e-8 J off, where it is 1.3e-9).
    rates_.work_in = applied + (time_dependent_ ? lambda_.dot(time_derivative(q)) : 0.0);
    return rates_;
  }

  // Energies stored at (q, q'): kinetic, gravity, springs.
  void stored_energy(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, SimulationEnergy& e) {
    const Model& m = mech_.model();
    energy_product_.noalias() = mass() * qd;  // in storage kept: a temporary was allocated per row
    e.kinetic = 0.5 * qd.dot(energy_product_);
    e.gravity = 0.0;
    for (const BodyMass& b : bodies_) e.gravity -= b.mass * m.gravity.dot(centre_of_mass(b, q));
    e.spring = 0.0;
    for (const Spring& s : m.springs) {
      const double stretch = (position(s.points[1], q) - position(s.points[0], q)).norm() - s.free_length;
      e.spring += 0.5 * s.stiffness * stretch * stretch + s.preload * stretch;
    }
  }

  // The gate at (t, q), from the kinematics' own sparse LU (its pivots chosen once and replayed).
  Gate gate_at(double t, const Eigen::VectorXd& q) {
    // A step's end and the next step's start ask at the same q and time: the answer is kept.
    if (gate_known_ && gate_time_ == t && gate_q_.size() == q.size() && gate_q_ == q) return gate_;
    // The kinematic drivers at t: the rows recorded since the step's end left them at theirs.
    if (drivers_time_ != t) own_drivers_at(t);
    gate_ = gate_at_anew(q);
    gate_known_ = true;
    gate_time_ = t;
    gate_q_ = q;
    return gate_;
  }
  Gate gate_at_anew(const Eigen::VectorXd& q) {
    Gate gate;
    if (!square_) return gate;
    full_drivers_ = drivers_;
    driver_values_at(mech_, q, nullptr, start_, gate_values_);
    for (std::size_t d = 0; d < full_drivers_.size(); ++d)
      if (mech_.model().drivers[d].free)
        set_driver_state(full_drivers_[d], Series(kTerms, gate_values_[d]), mech_.model().drivers[d].is_angular());
    evaluate_jacobian(mech_, q, full_drivers_, full_values_);
    scale_rows_to_unit_length(full_values_);
    gate.square = true;
    if (!full_lu_.factorize(full_values_.data())) return gate;  // singular: sign 0
    gate.sign = full_lu_.determinant_sign();
    gate.conditioning = full_lu_.reciprocal_condition_estimate(full_values_.data());
    return gate;
  }
  // Each row of the Jacobian `values` (every row's, in the pattern's order) divided by its length,
  // so that the conditioning does not depend on the rows' units (a length constraint's gradient
  // is twice the link's length, an angle driver's a length). A row of zeros stays.
  void scale_rows_to_unit_length(std::vector<double>& values) {
    const auto& pattern = mech_.equations().pattern;
    std::fill(row_lengths_.begin(), row_lengths_.end(), 0.0);
    for (std::size_t i = 0; i < pattern.size(); ++i) row_lengths_[pattern[i].row] += values[i] * values[i];
    for (double& length : row_lengths_) length = length > 0.0 ? 1.0 / std::sqrt(length) : 1.0;
    for (std::size_t i = 0; i < pattern.size(); ++i) values[i] *= row_lengths_[pattern[i].row];
  }

  // The kept rows' Jacobian at the present values, dense, for the toggle's measure.
  Eigen::MatrixXd dense_jacobian() const {
    Eigen::MatrixXd out = Eigen::MatrixXd::Zero(kept_rows(), n_);
    const auto& pattern = mech_.equations().pattern;
    for (std::size_t i = 0; i < pattern.size(); ++i) {
      const int row = selected_[pattern[i].row];
      if (row >= 0) out(row, pattern[i].col) += jacobian_values_[i];
    }
    return out;
  }

  // Where a run's stop is said: at the first free driver, whose motion the loads decide; in a
  // fully driven run, at the first driver (said at the model's `sweep:` before, which it is not about).
  EntityRef driver_to_blame() const {
    const auto& drivers = mech_.model().drivers;
    for (std::size_t d = 0; d < drivers.size(); ++d)
      if (drivers[d].free) return {EntityRef::Kind::Driver, static_cast<int>(d), -1};
    if (!drivers.empty()) return {EntityRef::Kind::Driver, 0, -1};
    return {EntityRef::Kind::Model, -1, -1};
  }
  // Where a run whose steps collapse at t is stopped: at a time law of the loads that has grown
  // a million times past its size at the start (a torque 1/(t - 0.5), 1e14 N m near 0.5 s: its
  // pole, not the free driver, is what the steps cannot pass), with what it says; else nothing.
  std::optional<SimulationStop> law_to_blame(double t) const {
    const Model& m = mech_.model();
    std::optional<SimulationStop> blamed;
    double worst = kLawGrowth;
    const auto weigh = [&](const Law& law, EntityRef where) {
      try {
        const double now = std::abs(law.value(t)), start = std::abs(law.value(0.0));
        if (!(now > worst * std::max(start, 1e-300))) return;
        worst = now / std::max(start, 1e-300);
        std::ostringstream said;
        said.precision(3);
        said << "law '" << law.text() << "' is " << now << " there, against " << start << " at the start";
        blamed = SimulationStop{said.str(), where};
      } catch (const Error&) {  // undefined at 0 or t: the run said so where it happened
      }
    };
    for (std::size_t i = 0; i < m.point_loads.size(); ++i) {
      weigh(m.point_loads[i].fx, {EntityRef::Kind::PointLoad, static_cast<int>(i), 0});
      weigh(m.point_loads[i].fy, {EntityRef::Kind::PointLoad, static_cast<int>(i), 1});
    }
    for (std::size_t i = 0; i < m.torques.size(); ++i)
      weigh(m.torques[i].torque, {EntityRef::Kind::Torque, static_cast<int>(i), 0});
    return blamed;
  }
  bool has_free_driver() const {
    const auto& drivers = mech_.model().drivers;
    return std::any_of(drivers.begin(), drivers.end(), [](const Driver& d) { return d.free; });
  }

 private:
  static constexpr int kTerms = 3;
  static constexpr double kLawGrowth = 1e6;
  // A relative residual of the acceleration constraints above this after the solve: the rows
  // have become dependent.
  static constexpr double kDependentRows = 1e-6;
  // A projection's correction below this fraction of the drawing keeps the Schur complement: it
  // changes the Jacobian by about as much, relative, and each round of the solves' refinement then
  // gains six digits or more (two rounds to rounding, as with S formed anew).
  static constexpr double kSlightMove = 1e-6;

  const Eigen::SparseMatrix<double>& mass() const { return system_->mass(); }

  const Eigen::VectorXd& select(const Eigen::VectorXd& rows, Eigen::VectorXd& out) const {
    out.resize(kept_rows());
    for (int i = 0; i < kept_rows(); ++i) out(i) = rows(kept_[i]);
    return out;
  }

  Eigen::Vector2d position(int point, const Eigen::VectorXd& q) const { return mech_.point_position(point, q); }
  Eigen::Vector2d velocity(int point, const Eigen::VectorXd& qd) const {
    const int col = mech_.column_of(point);
    return col < 0 ? Eigen::Vector2d::Zero() : Eigen::Vector2d(qd.segment<2>(col));
  }
  void add_force(int point, const Eigen::Vector2d& force, Eigen::VectorXd& loads) const {
    const int col = mech_.column_of(point);
    if (col >= 0) loads.segment<2>(col) += force;
  }

  Eigen::Vector2d centre_of_mass(const BodyMass& b, const Eigen::VectorXd& q) const {
    const Eigen::Vector2d origin = position(b.frame.origin, q);
    if (b.frame.from < 0) return origin;
    const Eigen::Vector2d u = position(b.frame.to, q) - position(b.frame.from, q);
    return origin + b.a * u + b.b * perp(u);
  }

  // M = sum over bodies of m C^T C + (I / |u|^2) D^T D, where v_cg = C q' and u' = D q', as
  // triplets: each body's C and D touch its frame's (at most three) points only.
  std::vector<Eigen::Triplet<double>> build_masses() {
    const Model& m = mech_.model();
    std::vector<Eigen::Triplet<double>> mass;
    gravity_.setZero(n_);
    for (std::size_t i = 0; i < m.bodies.size(); ++i) {
      const MassProperties props = mass_properties(m.bodies[i]);
      BodyMass b;
      b.body = static_cast<int>(i);
      b.mass = props.mass;
      b.frame = body_frame(m, b.body);
      BodyMap to_cg, to_direction;
      to_cg.add(mech_, b.frame.origin, Eigen::Matrix2d::Identity());
      if (b.frame.from >= 0) {
        const Eigen::Vector2d drawn = m.points[b.frame.to].position - m.points[b.frame.from].position;
        const Eigen::Vector2d offset = props.cg - m.points[b.frame.origin].position;
        const double length2 = drawn.squaredNorm();
        b.a = offset.dot(drawn) / length2;
        b.b = cross(drawn, offset) / length2;
        b.rotary = props.inertia / length2;
        Eigen::Matrix2d along;
        along << b.a, -b.b, b.b, b.a;  // a I + b (rotation by 90 degrees)
        to_cg.add(mech_, b.frame.to, along);
        to_cg.add(mech_, b.frame.from, -along);
        to_direction.add(mech_, b.frame.to, Eigen::Matrix2d::Identity());
        to_direction.add(mech_, b.frame.from, -Eigen::Matrix2d::Identity());
      }
      to_cg.add_gram(b.mass, mass);
      to_direction.add_gram(b.rotary, mass);
      for (std::size_t k = 0; k < to_cg.columns.size(); ++k)
        gravity_(to_cg.columns[k]) += b.mass * to_cg.map.col(static_cast<int>(k)).dot(m.gravity);
      bodies_.push_back(b);
    }
    return mass;
  }
  // A 2 x k map from the coordinates of a body's frame points (columns) to a vector.
  struct BodyMap {
    std::vector<int> columns;
    Eigen::Matrix<double, 2, Eigen::Dynamic> map;
    void add(const Mechanism& mech, int point, const Eigen::Matrix2d& block) {
      const int col = mech.column_of(point);
      if (col < 0) return;
      for (int axis = 0; axis < 2; ++axis) {
        const auto found = std::find(columns.begin(), columns.end(), col + axis);
        const int k = static_cast<int>(found - columns.begin());
        if (found == columns.end()) {
          columns.push_back(col + axis);
          map.conservativeResize(2, k + 1);
          map.col(k).setZero();
        }
        map.col(k) += block.col(axis);
      }
    }
    // weight map^T map, as triplets on the columns.
    void add_gram(double weight, std::vector<Eigen::Triplet<double>>& out) const {
      for (std::size_t a = 0; a < columns.size(); ++a)
        for (std::size_t b = 0; b < columns.size(); ++b)
          out.emplace_back(columns[a], columns[b],
                           weight * map.col(static_cast<int>(a)).dot(map.col(static_cast<int>(b))));
    }
  };
  // Q(t, q, q'): gravity, forces, torques (motors by their torque-speed line), springs and
  // dampers; with the dampers' dissipated power and the applied loads' power.
  // Written into `loads`, with applied_loads_ as work space: nothing allocated.
  void generalised_forces(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double& dissipated,
                          double& applied, Eigen::VectorXd& loads) {
    loads = gravity_;
    Eigen::VectorXd& applied_loads = applied_loads_;
    applied_loads.setZero(n_);
    add_applied_loads(t, q, qd, applied_loads);
    applied = applied_loads.dot(qd);
    loads += applied_loads;
    dissipated = add_springs(q, qd, loads);
    dissipated += add_joint_friction(mech_, q, qd, loads);
  }

 public:
  // Q's parts by origin at (t, q, q'), each on its own (their sum is Q up to rounding).
  struct ForceParts {
    Eigen::VectorXd gravity, applied, springs, friction;
  };
  ForceParts force_parts(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd) const {
    ForceParts parts;
    parts.gravity = gravity_;
    parts.applied.setZero(n_);
    add_applied_loads(t, q, qd, parts.applied);
    parts.springs.setZero(n_);
    add_springs(q, qd, parts.springs);
    parts.friction.setZero(n_);
    add_joint_friction(mech_, q, qd, parts.friction);
    return parts;
  }
  // M, dense.
  Eigen::MatrixXd dense_mass() const { return Eigen::MatrixXd(mass()); }
  // The rows kept, as indices of the mechanism's rows.
  const std::vector<int>& kept() const { return kept_; }

 private:
  // The given forces and torques (a motor's by its torque-speed line), added to `loads`.
  void add_applied_loads(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, Eigen::VectorXd& loads) const {
    const Model& m = mech_.model();
    const auto law_at = [t](const Law& law, EntityRef::Kind kind, std::size_t index, int which) {
      try {
        return law.value(t);
      } catch (const Error& e) {
        throw SimulationStop{e.message(), EntityRef{kind, static_cast<int>(index), which}};  // it says where in t
      }
    };
    for (std::size_t i = 0; i < m.point_loads.size(); ++i) {
      const PointLoad& load = m.point_loads[i];
      add_force(load.point,
                {law_at(load.fx, EntityRef::Kind::PointLoad, i, 0), law_at(load.fy, EntityRef::Kind::PointLoad, i, 1)},
                loads);
    }
    for (std::size_t i = 0; i < m.torques.size(); ++i) {
      const BodyTorque& torque = m.torques[i];
      const BodyFrame f = body_frame(m, torque.body);
      if (f.from < 0) continue;
      const Eigen::Vector2d u = position(f.to, q) - position(f.from, q);
      double value = law_at(torque.torque, EntityRef::Kind::Torque, i, 0);
      if (torque.no_load_speed) {
        const double omega = cross(u, velocity(f.to, qd) - velocity(f.from, qd)) / u.squaredNorm();
        value *= 1.0 - omega / *torque.no_load_speed;
      }
      // Virtual work T d(theta), with d(theta) = u x du / |u|^2.
      const Eigen::Vector2d on_to = value * perp(u) / u.squaredNorm();
      add_force(f.to, on_to, loads);
      add_force(f.from, -on_to, loads);
    }
  }
  // The springs' and dampers' forces, added to `loads`; returns the dampers' dissipated power.
  double add_springs(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, Eigen::VectorXd& loads) const {
    double dissipated = 0.0;
    for (const Spring& s : mech_.model().springs) {
      const Eigen::Vector2d d = position(s.points[1], q) - position(s.points[0], q);
      const double length = d.norm();
      const Eigen::Vector2d e = d / length;
      const double rate = e.dot(velocity(s.points[1], qd) - velocity(s.points[0], qd));
      const double tension = s.stiffness * (length - s.free_length) + s.preload + s.damping * rate;
      add_force(s.points[0], tension * e, loads);
      add_force(s.points[1], -tension * e, loads);
      dissipated += s.damping * rate * rate;
    }
    return dissipated;
  }
  const Mechanism& mech_;
  std::vector<double> start_;
  int n_ = 0;
  std::vector<int> kept_;        // rows of Phi kept, in order
  std::vector<int> selected_;    // per row: its place among the kept, or -1
  bool time_dependent_ = false;  // a kept row is a kinematic driver's: Phi_t may be nonzero
  Eigen::VectorXd gravity_;
  std::vector<BodyMass> bodies_;
  std::optional<AugmentedSystem> system_;

  std::vector<DriverState> drivers_, full_drivers_;
  // The free drivers' states for drivers_at, formed once: they do not depend on t, and their sines
  // and cosines, formed at every evaluation, were 4 % of a four-bar's run.
  std::vector<DriverState> free_states_;
  std::vector<double> jacobian_values_, full_values_;
  bool square_ = false;  // as many rows as coordinates: the gate's LU exists
  SparseLU full_lu_;     // every row's square Jacobian, for the gate
  Eigen::MatrixXd first_order_, second_order_;
  Eigen::VectorXd all_rows_, residual_, time_derivative_, gamma_, product_, loads_, applied_loads_, zero_force_,
      energy_product_;
  std::vector<double> gate_values_;  // the drivers' values at the gate's q
  std::vector<double> row_lengths_;  // the gate's rows' lengths, then their reciprocals
  // The last gate, at gate_q_ with the drivers at gate_time_; drivers_ are at drivers_time_.
  bool gate_known_ = false;
  Gate gate_;
  Eigen::VectorXd gate_q_;
  double gate_time_ = 0.0, drivers_time_ = 0.0;
  Eigen::VectorXd lambda_, projection_lambda_, correction_;
  Rates rates_;
};

// The Dormand-Prince 5(4) pair (Dormand & Prince 1980; Hairer, Norsett & Wanner, Solving ODEs I,
// II.5) with its continuous extension of order 4.
namespace dopri {
constexpr double c2 = 1.0 / 5, c3 = 3.0 / 10, c4 = 4.0 / 5, c5 = 8.0 / 9;
constexpr double a21 = 1.0 / 5;
constexpr double a31 = 3.0 / 40, a32 = 9.0 / 40;
constexpr double a41 = 44.0 / 45, a42 = -56.0 / 15, a43 = 32.0 / 9;
constexpr double a51 = 19372.0 / 6561, a52 = -25360.0 / 2187, a53 = 64448.0 / 6561, a54 = -212.0 / 729;
constexpr double a61 = 9017.0 / 3168, a62 = -355.0 / 33, a63 = 46732.0 / 5247, a64 = 49.0 / 176, a65 = -5103.0 / 18656;
constexpr double a71 = 35.0 / 384, a73 = 500.0 / 1113, a74 = 125.0 / 192, a75 = -2187.0 / 6784, a76 = 11.0 / 84;
constexpr double e1 = 71.0 / 57600, e3 = -71.0 / 16695, e4 = 71.0 / 1920, e5 = -17253.0 / 339200, e6 = 22.0 / 525,
                 e7 = -1.0 / 40;
constexpr double d1 = -12715105075.0 / 11282082432, d3 = 87487479700.0 / 32700410799, d4 = -10690763975.0 / 1880347072,
                 d5 = 701980252875.0 / 199316789632, d6 = -1453857185.0 / 822651844, d7 = 69997945.0 / 29380423;
}  // namespace dopri

// The state integrated: q, q', and the dissipated and input work since t = 0.
class Integrator {
 public:
  Integrator(const Mechanism& mech, EquationsOfMotion& equations, const SimulationOptions& options)
      : mech_(mech), eq_(equations), options_(options), n_(equations.coordinates()) {}

  Eigen::VectorXd derivative(double t, const Eigen::VectorXd& y) {
    Eigen::VectorXd f;
    derivative(t, y, f);
    return f;
  }
  // The same into f (sized once: nothing allocated on a step).
  void derivative(double t, const Eigen::VectorXd& y, Eigen::VectorXd& f) {
    ++evaluations_;
    evaluated_q_ = y.head(n_);
    evaluated_qd_ = y.segment(n_, n_);
    store_rates(eq_.evaluate(t, evaluated_q_, evaluated_qd_, kStage), evaluated_qd_, f);
  }

  // Moves q onto Phi = 0 and q' onto Phi_q q' = -Phi_t at t by the smallest corrections in the
  // mass's metric; false when Newton fails. The augmented matrix is factorised once, at the first
  // q: the corrections are small, and each solve satisfies the Jacobian at the present q, which
  // is left there for the accelerations (evaluate_factorised). With `exact` (an output row) the
  // positions end at rounding, so that a row's residual does not depend on where the iteration
  // happened to stop (which rounding of another platform moves): Newton converges quadratically,
  // and the residual after a correction d is of the order of d^2 / length. After a correction
  // below kRoundingMove of the drawing (an output row's, from a step's interpolant, is typically
  // 1e-9 of it) it is at rounding; otherwise one more Newton step follows the one that reached
  // the tolerance (from |Phi| within 1e-12 of the size it lands at rounding). The residuals a row
  // reports are those at the final q.
  bool project(double t, Eigen::VectorXd& y, bool exact = false) {
    q_ = y.head(n_);
    const double tolerance = mech_.tolerance();
    bool converged = false;
    double moved = 0.0;  // the last correction's largest change of a coordinate
    for (int iteration = 0; iteration < 12; ++iteration) {
      const Eigen::VectorXd& phi =
          iteration > 0 ? eq_.update_jacobian_and_residuals(q_, moved) : eq_.factorise_with_residuals(t, q_);
      if (!phi.allFinite()) return false;
      if (phi.size() == 0 || phi.lpNorm<Eigen::Infinity>() <= tolerance) {
        converged = true;
        break;
      }
      moved = correct_positions(phi);
    }
    if (!converged) return false;
    const bool at_rounding = moved > 0.0 && moved <= kRoundingMove * mech_.drawing_size();
    if (exact && eq_.kept_rows() > 0 && !at_rounding) {
      moved = correct_positions(eq_.last_residuals());
      if (!eq_.update_jacobian_and_residuals(q_, moved).allFinite()) return false;
    }
    qd_ = y.segment(n_, n_);
    velocity_error_ = eq_.jacobian_times(qd_) + eq_.time_derivative(q_);
    qd_ -= eq_.correction(velocity_error_);
    y.head(n_) = q_;
    y.segment(n_, n_) = qd_;
    return y.allFinite();
  }

  // The derivative at the state project() returned last, at its time: the Jacobian and the
  // factorisation it left are used as they are (one evaluation of the Jacobian and one forming of
  // the Schur complement fewer than derivative()). False, with f untouched, where the accelerations
  // are not determined there (a toggle): derivative() then says so when it is asked.
  bool derivative_after_projection(double t, Eigen::VectorXd& f) {
    try {
      store_rates(eq_.evaluate_factorised(t, q_, qd_, kStage), qd_, f);
      ++evaluations_;
      return true;
    } catch (const SimulationStop&) {
      return false;
    }
  }

  // Weighted RMS norm of the q and q' parts (the work integrals are quadratures of the same steps
  // and do not steer the step size).
  double error_norm(const Eigen::VectorXd& error, const Eigen::VectorXd& y0, const Eigen::VectorXd& y1) const {
    double sum = 0.0;
    for (int i = 0; i < 2 * n_; ++i) {
      const double scale = error_scale(i, y0, y1);
      sum += (error(i) / scale) * (error(i) / scale);
    }
    return n_ > 0 ? std::sqrt(sum / (2 * n_)) : 0.0;
  }

  // What an error in coordinate i of a step from y0 to y1 is measured against: rtol times the
  // whole drawing's size (riding points included: every coordinate is integrated, and the steps
  // were chosen so before the linkage's own size set the position tolerance) and its value's.
  double error_scale(int i, const Eigen::VectorXd& y0, const Eigen::VectorXd& y1) const {
    const double rtol = options_.relative_tolerance;
    return rtol * mech_.drawing_size() + rtol * std::max(std::abs(y0(i)), std::abs(y1(i)));
  }

  // The step's error by Hairer's norm for DOP853: the fifth-order estimate e5 damped where the
  // third-order one e3 is much larger (err = |e5|^2 / sqrt(|e5|^2 + 0.01 |e3|^2), each weighted by
  // error_scale), so that the error is of the eighth-order result's order.
  template <class Stage>
  double step_error(double h, const Stage& stage, const Eigen::VectorXd& y0, const Eigen::VectorXd& y1) const {
    using namespace dop853;
    double fifth = 0.0, third = 0.0;
    for (int i = 0; i < 2 * n_; ++i) {
      double e5 = 0.0, e3 = 0.0;
      for (int j = 0; j < kStages; ++j) {
        const double k = stage(j)(i);
        e5 += e5_weights[j] * k;
        e3 += e3_weights[j] * k;
      }
      const double scale = error_scale(i, y0, y1);
      fifth += (h * e5 / scale) * (h * e5 / scale);
      third += (h * e3 / scale) * (h * e3 / scale);
    }
    if (fifth == 0.0 && third == 0.0) return 0.0;
    return fifth / std::sqrt((fifth + 0.01 * third) * (2 * n_));
  }

  // Hairer's starting step: from the sizes of y, f and an estimate of f's change.
  double initial_step(double t, const Eigen::VectorXd& y, const Eigen::VectorXd& f, double span) {
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(y.size());
    const double d0 = error_norm(y, y, zero) * options_.relative_tolerance;
    const double d1 = error_norm(f, y, zero) * options_.relative_tolerance;
    double h0 = (d0 < 1e-5 || d1 < 1e-5) ? 1e-6 : 0.01 * d0 / d1;
    h0 = std::min(h0, span);
    const Eigen::VectorXd f1 = derivative(t + h0, y + h0 * f);
    const double d2 = error_norm(f1 - f, y, zero) * options_.relative_tolerance / h0;
    const double largest = std::max(d1, d2);
    const double h1 = largest <= 1e-15 ? std::max(1e-6, 1e-3 * h0) : std::pow(0.01 / largest, 1.0 / 5);
    return std::min({100 * h0, h1, span});
  }

  // The two Runge-Kutta pairs: Dormand and Prince's 8(5,3) (DOP853) where the motion is away from
  // toggles, their 5(4) next to one (where the accelerations carry the near-singular solve's
  // rounding, which DOP853's error estimate, of large weights, magnifies into rejected and
  // ever shorter steps: a parallelogram bouncing on its change point took 480 steps at rtol 1e-8
  // and lost 2e-6 s a bounce, where the 5(4) pair takes 56 and loses 3e-9).
  enum class Pair { dopri5, dop853 };
  // A pair's step-size controller: the exponent 1 / (the error estimate's order + 1) and the
  // bounds on a step's shrinking and growth (Hairer's).
  struct Controller {
    double exponent, least, largest;
  };
  static constexpr Controller kDopri5{1.0 / 5, 0.2, 5.0}, kDop853{1.0 / 8, 0.333, 6.0};

  struct Step {
    Eigen::VectorXd y1;
    double error = 0.0;
    Pair pair = Pair::dop853;  // the pair that made it
    const Controller& controller() const { return pair == Pair::dop853 ? kDop853 : kDopri5; }
    // The continuous extension on [t, t + h] (extend): y(t + theta h) = y0 + theta (r[0] +
    // (1 - theta) (r[1] + theta (r[2] + ...))), the factors alternating (the 5(4) pair's last
    // three are zero).
    std::array<Eigen::VectorXd, dop853::kExtension> r;
  };

  // The step [t, t + h] from y, whose derivative is k1: its end and its error into s, the stages
  // kept for extend().
  void step(double t, const Eigen::VectorXd& y, const Eigen::VectorXd& k1, double h, Pair pair, Step& s) {
    s.pair = pair;
    if (pair == Pair::dop853)
      step_dop853(t, y, k1, h, s);
    else
      step_dopri5(t, y, k1, h, s);
  }

  // The continuous extension of the step step() took last, once it is accepted (a rejected step
  // needs none: DOP853's four further stages were a twentieth of a four-bar's evaluations).
  // `end`: the derivative at the step's end projected onto the constraints, where the caller has
  // it, which DOP853's extension then takes for its stage at the end (Hairer's at the end
  // unprojected): they differ by the projection's correction, of the order of the step's error,
  // whose effect on the extension the step's length makes smaller still, and the rows are
  // projected anyway. An evaluation fewer on every accepted step.
  void extend(double t, const Eigen::VectorXd& y, const Eigen::VectorXd& k1, double h, Step& s,
              const Eigen::VectorXd* end) {
    if (s.pair == Pair::dop853)
      extend_dop853(t, y, k1, h, s, end);
    else
      extend_dopri5(y, k1, h, s);
  }

  // One step of the 5(4) pair into s, its stages in vectors sized once (the arithmetic of each as
  // written out).
  void step_dopri5(double t, const Eigen::VectorXd& y, const Eigen::VectorXd& k1, double h, Step& s) {
    using namespace dopri;
    Eigen::VectorXd &k2 = k_[1], &k3 = k_[2], &k4 = k_[3], &k5 = k_[4], &k6 = k_[5], &k7 = k_[6];
    stage_ = y + h * a21 * k1;
    derivative(t + c2 * h, stage_, k2);
    stage_ = y + h * (a31 * k1 + a32 * k2);
    derivative(t + c3 * h, stage_, k3);
    stage_ = y + h * (a41 * k1 + a42 * k2 + a43 * k3);
    derivative(t + c4 * h, stage_, k4);
    stage_ = y + h * (a51 * k1 + a52 * k2 + a53 * k3 + a54 * k4);
    derivative(t + c5 * h, stage_, k5);
    stage_ = y + h * (a61 * k1 + a62 * k2 + a63 * k3 + a64 * k4 + a65 * k5);
    derivative(t + h, stage_, k6);
    s.y1 = y + h * (a71 * k1 + a73 * k3 + a74 * k4 + a75 * k5 + a76 * k6);
    derivative(t + h, s.y1, k7);
    stage_ = h * (e1 * k1 + e3 * k3 + e4 * k4 + e5 * k5 + e6 * k6 + e7 * k7);
    s.error = error_norm(stage_, y, s.y1);
  }
  void extend_dopri5(const Eigen::VectorXd& y, const Eigen::VectorXd& k1, double h, Step& s) {
    using namespace dopri;
    const Eigen::VectorXd &k3 = k_[2], &k4 = k_[3], &k5 = k_[4], &k6 = k_[5], &k7 = k_[6];
    s.r[0] = s.y1 - y;
    s.r[1] = h * k1 - s.r[0];
    s.r[2] = s.r[0] - h * k7 - s.r[1];
    s.r[3] = h * (d1 * k1 + d3 * k3 + d4 * k4 + d5 * k5 + d6 * k6 + d7 * k7);
    for (std::size_t i = 4; i < s.r.size(); ++i) s.r[i].setZero(y.size());
  }

  // One step of DOP853 into s: the twelve stages and the error of the step, in vectors sized once
  // (the stage at the end has no weight in the error estimates: extend_dop853 takes it).
  void step_dop853(double t, const Eigen::VectorXd& y, const Eigen::VectorXd& k1, double h, Step& s) {
    using namespace dop853;
    const auto stage = [&](int j) -> const Eigen::VectorXd& { return dop853_stage(j, k1); };
    for (int i = 1; i < kStages; ++i) {
      dop853_stage_state(i, y, k1, h, stage_);
      derivative(t + c[i] * h, stage_, k_[i]);
    }
    dop853_stage_state(kStages, y, k1, h, s.y1);  // a[12] holds the eighth-order weights
    s.error = step_error(h, stage, y, s.y1);
  }
  // The stage at the end (`end`, or evaluated at the end unprojected), the three further stages
  // and the continuous extension's coefficient vectors.
  void extend_dop853(double t, const Eigen::VectorXd& y, const Eigen::VectorXd& k1, double h, Step& s,
                     const Eigen::VectorXd* end) {
    using namespace dop853;
    if (end)
      k_[kStages] = *end;
    else
      derivative(t + h, s.y1, k_[kStages]);
    for (int i = kStagesWithEnd; i < kStagesExtended; ++i) {
      dop853_stage_state(i, y, k1, h, stage_);
      derivative(t + c[i] * h, stage_, k_[i]);
    }
    s.r[0] = s.y1 - y;
    s.r[1] = h * k1 - s.r[0];
    s.r[2] = 2 * s.r[0] - h * (k_[kStages] + k1);
    for (int i = 0; i < kExtension - 3; ++i) {
      Eigen::VectorXd& r = s.r[3 + i];
      r.setZero(y.size());
      for (int j = 0; j < kStagesExtended; ++j)
        if (d[i][j] != 0.0) r += (h * d[i][j]) * dop853_stage(j, k1);
    }
  }

  // DOP853's state of stage i: y + h (a[i][0] k_0 + ... + a[i][i-1] k_{i-1}), the zero weights
  // skipped, into out.
  void dop853_stage_state(int i, const Eigen::VectorXd& y, const Eigen::VectorXd& k1, double h,
                          Eigen::VectorXd& out) const {
    using namespace dop853;
    out = y;
    for (int j = 0; j < i; ++j)
      if (a[i][j] != 0.0) out += (h * a[i][j]) * dop853_stage(j, k1);
  }
  // DOP853's stage j of the present step (the first is given).
  const Eigen::VectorXd& dop853_stage(int j, const Eigen::VectorXd& k1) const { return j == 0 ? k1 : k_[j]; }

  static Eigen::VectorXd interpolate(const Eigen::VectorXd& y0, const Step& s, double theta) {
    Eigen::VectorXd out;
    interpolate(y0, s, theta, out);
    return out;
  }
  // The same into `out`: a row's state in storage kept.
  static void interpolate(const Eigen::VectorXd& y0, const Step& s, double theta, Eigen::VectorXd& out) {
    const Eigen::Index size = y0.size();
    out.resize(size);
    interpolate(
        y0.data(), [&](int k) { return s.r[k].data(); }, size, theta, out.data());
  }
  // The continuous extension at theta from y0 and the coefficient vectors part(k), of `size`
  // numbers each, into `out`.
  template <class Part>
  static void interpolate(const double* y0, const Part& part, Eigen::Index size, double theta, double* out) {
    const double rest = 1.0 - theta;
    for (Eigen::Index i = 0; i < size; ++i) {
      double sum = 0.0;
      for (int k = dop853::kExtension - 1; k >= 0; --k) sum = (k % 2 == 0 ? theta : rest) * (part(k)[i] + sum);
      out[i] = y0[i] + sum;
    }
  }

  long evaluations() const { return evaluations_; }

 private:
  static constexpr double kRoundingMove = 1e-8;
  // The stages' accelerations: their error need only be well below the tolerance's.
  static constexpr AugmentedSystem::Rounds kStage = AugmentedSystem::Rounds::as_needed;

  // f = (q', q'', the dissipated and the input power): the state's derivative.
  void store_rates(const EquationsOfMotion::Rates& r, const Eigen::VectorXd& qd, Eigen::VectorXd& f) const {
    f.resize(2 * n_ + 2);
    f.head(n_) = qd;
    f.segment(n_, n_) = r.acceleration;
    f(2 * n_) = r.dissipated;
    f(2 * n_ + 1) = r.work_in;
  }

  // q_ -= the correction of the residuals phi; returns its largest change of a coordinate.
  double correct_positions(const Eigen::VectorXd& phi) {
    const Eigen::VectorXd& dq = eq_.correction(phi);
    q_ -= dq;
    return dq.lpNorm<Eigen::Infinity>();
  }

  const Mechanism& mech_;
  EquationsOfMotion& eq_;
  const SimulationOptions& options_;
  int n_;
  long evaluations_ = 0;
  Eigen::VectorXd q_, qd_, velocity_error_;                 // the projection's
  Eigen::VectorXd evaluated_q_, evaluated_qd_, stage_;      // a step's
  std::array<Eigen::VectorXd, dop853::kStagesExtended> k_;  // a step's stages (the first is given)
};

// The last accepted steps with their continuous extensions: the state at a time some steps back.
// A toggle's row and the rows mirrored past it need it, because the steps shrink towards a
// toggle (to nanoseconds at rtol 1e-12) while its regular state lies some 1e-4 of the drawing back.
class RecentSteps {
 public:
  // Keeps a copy of the step [t, t + h] from y0, forgetting the oldest when capacity_ are kept.
  void keep(double t, double h, const Eigen::VectorXd& y0, const Integrator::Step& s) {
    if (stride_ == 0) {
      size_ = static_cast<std::size_t>(y0.size());
      stride_ = 2 + (1 + dop853::kExtension) * size_;
      capacity_ = std::clamp<std::size_t>(kDoublesKept / stride_, 64, 4096);
      newest_ = capacity_ - 1;
    }
    newest_ = (newest_ + 1) % capacity_;
    if (count_ < capacity_) data_.resize(++count_ * stride_);  // grows geometrically
    double* kept = data_.data() + newest_ * stride_;
    kept[0] = t;
    kept[1] = h;
    double* at = kept + 2;
    at = std::copy(y0.data(), y0.data() + size_, at);
    for (const Eigen::VectorXd& r : s.r) at = std::copy(r.data(), r.data() + size_, at);
  }
  // The state at `time`, on the newest step that starts at or before it (the oldest kept
  // step's start for an earlier time).
  Eigen::VectorXd state_at(double time) const {
    for (std::size_t i = 0; i < count_; ++i) {
      const double* kept = data_.data() + ((newest_ + capacity_ - i) % capacity_) * stride_;
      if (kept[0] > time && i + 1 < count_) continue;
      return interpolated(kept, std::clamp((time - kept[0]) / kept[1], 0.0, 1.0));
    }
    return {};
  }
  // The largest distance (infinity norm) from q of the positions on the kept steps, looked at at
  // their starts, middles and ends.
  double farthest_from(const Eigen::VectorXd& q) const {
    double most = 0.0;
    for (std::size_t i = 0; i < count_; ++i)
      for (const double theta : {0.0, 0.5, 1.0})
        most = std::max(most,
                        (interpolated(data_.data() + i * stride_, theta).head(q.size()) - q).lpNorm<Eigen::Infinity>());
    return most;
  }
  // Forgets every step: the motion after a reversal has a history of its own.
  void clear() {
    count_ = 0;
    newest_ = capacity_ - 1;
  }
  bool empty() const { return count_ == 0; }
  // The start of the newest step kept.
  double newest_start() const { return data_[newest_ * stride_]; }
  // The start of the oldest step kept.
  double earliest() const { return data_[(count_ < capacity_ ? 0 : (newest_ + 1) % capacity_) * stride_]; }

 private:
  // As many steps as fit in about 8 MB, from 64 to 4096: a toggle's approach takes hundreds of
  // steps at tight tolerances.
  static constexpr std::size_t kDoublesKept = 1 << 20;
  // The continuous extension of the step kept at `kept` at theta in [0, 1].
  Eigen::VectorXd interpolated(const double* kept, double theta) const {
    Eigen::VectorXd out(static_cast<Eigen::Index>(size_));
    const double* y0 = kept + 2;
    Integrator::interpolate(
        y0, [&](int k) { return y0 + (k + 1) * size_; }, static_cast<Eigen::Index>(size_), theta, out.data());
    return out;
  }
  std::size_t size_ = 0, stride_ = 0, capacity_ = 0, count_ = 0, newest_ = 0;
  std::vector<double> data_;  // per step: t, h, y0 and the continuous extension's vectors
};

// A body's direction at q: atan2's angle (rad) of its first two points.
double body_angle(const Mechanism& mech, const Eigen::VectorXd& q, int body) {
  const std::vector<int>& points = mech.model().bodies[body].points;
  const Eigen::Vector2d u = mech.point_position(points[1], q) - mech.point_position(points[0], q);
  return std::atan2(u.y(), u.x());
}

// Each body's body_angle at q (bodies of fewer than two points: 0), into `out`.
void raw_body_angles(const Mechanism& mech, const Eigen::VectorXd& q, std::vector<double>& out) {
  const Model& m = mech.model();
  out.resize(m.bodies.size());
  for (std::size_t b = 0; b < m.bodies.size(); ++b)
    out[b] = m.bodies[b].points.size() < 2 ? 0.0 : body_angle(mech, q, static_cast<int>(b));
}

// An angle moved by whole turns to the one nearest `reference`. Within half a turn of it (every
// row but the rare fast wheel) round() would give zero: its call is spared.
double unwrapped(double angle, double reference) {
  const double gap = reference - angle;
  if (std::abs(gap) < M_PI) return angle;
  return angle + 2 * M_PI * std::round(gap / (2 * M_PI));
}

// Each driver's value at q (SI) into `out`, angles unwrapped against `previous`; `bodies`, where
// given: the bodies' raw_body_angles at q, which the angle drivers' are then made of (an atan2
// fewer for each), else those drivers' bodies' angles are formed here.
void driver_values_at(const Mechanism& mech, const Eigen::VectorXd& q, const std::vector<double>* bodies,
                      const std::vector<double>& previous, std::vector<double>& out) {
  const Model& m = mech.model();
  const auto at = [&](int p) { return mech.point_position(p, q); };
  const auto angle_of = [&](int body) { return bodies ? (*bodies)[body] : body_angle(mech, q, body); };
  out.resize(m.drivers.size());
  for (std::size_t d = 0; d < m.drivers.size(); ++d) {
    const Driver& drv = m.drivers[d];
    switch (drv.kind) {
      case DriverKind::Angle:
        out[d] = unwrapped(angle_of(drv.body) - (drv.relative_to >= 0 ? angle_of(drv.relative_to) : 0.0), previous[d]);
        break;
      case DriverKind::Distance: out[d] = (at(drv.points[1]) - at(drv.points[0])).norm(); break;
      case DriverKind::Slide: {
        const Slider& s = m.sliders[drv.slider];
        const Eigen::Vector2d guide = at(s.along[1]) - at(s.along[0]);
        out[d] = (at(s.point) - at(s.along[0])).dot(guide) / guide.norm();
        break;
      }
    }
  }
}

// Each body's angle (raw_body_angles) unwrapped against `reference`, into `out` (which may be
// `reference`).
void unwrapped(const std::vector<double>& raw, const std::vector<double>& reference, std::vector<double>& out) {
  out.resize(raw.size());
  for (std::size_t b = 0; b < raw.size(); ++b) out[b] = unwrapped(raw[b], reference[b]);
}

// Each driver's value and each body's angle at q, unwrapped against `reference`'s (which they may
// be), with `raw` as work space.
void angles_at(const Mechanism& mech, const Eigen::VectorXd& q, const std::vector<double>& driver_reference,
               const std::vector<double>& body_reference, std::vector<double>& raw, std::vector<double>& drivers,
               std::vector<double>& bodies) {
  raw_body_angles(mech, q, raw);
  driver_values_at(mech, q, &raw, driver_reference, drivers);
  unwrapped(raw, body_reference, bodies);
}

// A row at an output time and what it says about the run, not yet kept.
struct Row {
  Sample sample;
  SimulationEnergy energy;
  ConstraintDrift drift;
};

// What a row is made against: each driver's value and each body's angle at the state kept last
// (the start, a step's end, an event), which its angles are unwrapped against, not against the
// row before, so that rows far apart (a fast wheel, a large --dt) lose no whole turn (a step
// turns a body far less than half a turn: its error control follows the positions' sines); and
// the energy stored at the start, which its balance is measured from.
struct RowReference {
  std::vector<double> drivers, bodies;
  double energy = 0.0;
};

// Makes rows with its own equations of motion and projection: each thread that makes rows has
// one (the projection leaves its factorisation, the solves their warm starts).
class RowMaker {
 public:
  RowMaker(const Mechanism& mech, EquationsOfMotion& eq, Integrator& integrator)
      : mech_(mech), eq_(eq), integrator_(integrator), n_(mech.coordinate_count()) {}

  // The row at `at`: y projected, q'' evaluated there, the energies and the drift.
  Row make(double at, const Eigen::VectorXd& y_given, const RowReference& reference) {
    Eigen::VectorXd& y = y_;  // the row's vectors in storage kept: nothing allocated but the row
    y = y_given;
    if (!integrator_.project(at, y, true))
      throw SimulationStop{"the positions could not be brought back onto the constraints at " + time_text(at),
                           eq_.driver_to_blame()};
    Eigen::VectorXd &q = q_, &qd = qd_;
    q = y.head(n_);
    qd = y.segment(n_, n_);
    const EquationsOfMotion::Rates& rates = eq_.evaluate_factorised(at, q, qd);
    ConstraintDrift drift;
    if (eq_.kept_rows()) {
      // |Phi| at q as the projection left it, |Phi_q q'' - gamma| as the accelerations' solve left
      // it (computed there with the q'' it returns), and |Phi_q q' + Phi_t| of the q' corrected
      // (not the correction's own residual, which leaves out the rounding of q' - dq': 1e-21
      // where the speeds hold 1e-13).
      drift.acceleration = eq_.last_solve_residual();
      drift.position = eq_.last_residuals().lpNorm<Eigen::Infinity>();
      drift.velocity = (eq_.jacobian_times(qd) + eq_.last_time_derivative()).lpNorm<Eigen::Infinity>();
    }
    return filled(at, y, rates.acceleration, drift, reference);
  }

  // The row at `at` of the state y (q, q' and the work integrals) with its accelerations.
  Row filled(double at, const Eigen::VectorXd& y, const Eigen::VectorXd& acceleration, const ConstraintDrift& drift,
             const RowReference& reference) {
    Row row;
    row.drift = drift;
    Eigen::VectorXd &q = q_, &qd = qd_;  // in storage kept: blocks passed on became vectors allocated
    q = y.head(n_);
    qd = y.segment(n_, n_);
    Sample& sample = row.sample;
    sample.time = at;
    angles_at(mech_, q, reference.drivers, reference.bodies, raw_angles_, sample.driver_values, sample.body_angles);
    sample.taylor.resize(n_, 3);
    sample.taylor.col(0) = q;
    sample.taylor.col(1) = qd;
    sample.taylor.col(2) = 0.5 * acceleration;
    sample.residual = drift.position;
    SimulationEnergy& e = row.energy;
    eq_.stored_energy(q, qd, e);
    e.dissipated = y(2 * n_);
    e.work_in = y(2 * n_ + 1);
    e.balance = e.kinetic + e.gravity + e.spring + e.dissipated - e.work_in - reference.energy;
    return row;
  }

 private:
  const Mechanism& mech_;
  EquationsOfMotion& eq_;
  Integrator& integrator_;
  int n_ = 0;
  Eigen::VectorXd y_, q_, qd_;
  std::vector<double> raw_angles_;
};

// What the output rows are made with (equations of motion and a projection of their own), and
// what they said. Allocated by the thread that makes them, at its first job, so that nothing it
// writes shares a cache line with what the steps write: made with the run, its small vectors lay
// between the steps' and the two threads ran each other half again as slow. A job's rows do not
// depend on the jobs made before it (the run's scales, no warm start from them), so the row
// thread and the steps' thread, each with its own, make the same rows.
struct OutputRows {
  OutputRows(const Mechanism& mech, const std::vector<double>& start, const SimulationOptions& options,
             const AugmentedSystem::Scales& scales)
      : eq(mech, start), integrator(mech, eq, options), maker(mech, eq, integrator) {
    eq.take_scales(scales);
  }
  EquationsOfMotion eq;
  Integrator integrator;
  RowMaker maker;
  Eigen::VectorXd state;  // the interpolated state of a row
  ConstraintDrift drift;  // the worst of the rows made
  double energy_error = 0.0;
  std::optional<SimulationStatistics> statistics_at_stop;  // the steps' when a row stopped the run
};

// The bracket [a, b] where f changes sign (f(a) = fa and f(b) = fb have opposite signs),
// narrowed until b - a <= tolerance: regula falsi with the Illinois halving, and a
// bisection whenever a step fails to halve the bracket, so that it converges in both ends.
std::pair<double, double> bracket_sign_change(const std::function<double(double)>& f, double a, double b, double fa,
                                              double fb, double tolerance) {
  int kept_end = 0;  // which end the last two steps kept: -1 a, +1 b
  bool bisect = false;
  for (int iteration = 0; iteration < 200 && b - a > tolerance; ++iteration) {
    const double width = b - a;
    double c = bisect ? 0.5 * (a + b) : (a * fb - b * fa) / (fb - fa);
    if (!std::isfinite(c)) c = 0.5 * (a + b);
    c = std::clamp(c, a + 0.25 * tolerance, b - 0.25 * tolerance);
    const double fc = f(c);
    if (fc == 0.0) return {c, c};
    if ((fc > 0) == (fb > 0)) {
      b = c, fb = fc;
      if (kept_end == -1) fa *= 0.5;
      kept_end = -1;
    } else {
      a = c, fa = fc;
      if (kept_end == 1) fb *= 0.5;
      kept_end = 1;
    }
    bisect = b - a > 0.5 * width;
  }
  return {a, b};
}

// The stop condition's column is not in the table: say which columns are, the nearest first (one
// sharing the name's point or body before the point) so that a typo shows its fix.
std::string unknown_column(const StopCondition& condition, const std::vector<std::string>& names) {
  const std::string owner = condition.column.substr(0, condition.column.find('.'));
  std::vector<std::string> listed;
  for (const std::string& name : names)
    if (name.substr(0, name.find('.')) == owner) listed.push_back(name);
  const bool same_owner = !listed.empty();
  if (!same_owner) listed = names;
  std::string list;
  constexpr std::size_t kShown = 12;
  for (std::size_t i = 0; i < listed.size() && i < kShown; ++i) list += (i ? ", " : "") + listed[i];
  if (listed.size() > kShown) list += " and " + std::to_string(listed.size() - kShown) + " more";
  return "the stop condition '" + condition.text + "' names no column '" + condition.column + "'; " +
         (same_owner ? "the columns of " + owner + " are " : "the simulation's table has ") + list;
}

// One column of simulation_table at a state not yet kept as a row, for a stop condition: the
// same names and units, angles unwrapped from the last state kept.
class ColumnProbe {
 public:
  ColumnProbe(const Mechanism& mech, const StopCondition& condition) : rows_(mech, 2), condition_(condition) {
    std::vector<std::string> names, units;
    rows_.name_columns(names, units);
    kinematic_ = names.size();
    for (const char* name : {"kinetic", "potential", "spring", "dissipated", "work", "balance"})
      names.push_back(std::string("energy.") + name);
    const auto found = std::find(names.begin(), names.end(), condition.column);
    if (found == names.end()) throw Error(ErrorKind::BadInput, unknown_column(condition, names));
    // A row's number is no quantity of the motion: between rows it has no value to cross.
    if (condition.column == "step")
      throw Error(ErrorKind::BadInput, "the stop condition '" + condition.text +
                                           "' watches `step`, the row's number, which does not change between rows "
                                           "as the motion does: watch the time instead ('t > ...')");
    index_ = static_cast<std::size_t>(found - names.begin());
    row_.resize(names.size());
  }

  // How far the condition is from holding: > 0 where it holds.
  double distance(const Sample& sample, const SimulationEnergy& energy, bool keep) {
    double value = 0.0;
    if (index_ < kinematic_) {
      if (keep) {
        rows_.fill(sample, row_.data());
      } else {
        KinematicRows trial = rows_;  // unwraps from the last kept state, which a trial leaves as it is
        trial.fill(sample, row_.data());
      }
      value = row_[index_];
    } else {
      const double energies[] = {energy.kinetic, energy.gravity + energy.spring,
                                 energy.spring,  energy.dissipated,
                                 energy.work_in, energy.balance};
      value = energies[index_ - kinematic_];
    }
    return condition_.above ? value - condition_.value : condition_.value - value;
  }

 private:
  KinematicRows rows_;
  StopCondition condition_;
  std::size_t kinematic_ = 0, index_ = 0;
  std::vector<double> row_;
};

// One run: the start, the steps, a row at every output time, and the events on the way.
class Run {
  // The output rows of one step, as the row thread makes them.
  struct RowJob {
    double t = 0.0, h = 0.0;
    Eigen::VectorXd y0;
    Integrator::Step step;  // its continuous extension (r)
    long first = 0, end = 0;
    RowReference reference;
    SimulationStatistics statistics;
    AugmentedSystem::Scales scales;  // the run's, for the equations that make the rows
    // The rows made on the steps' thread, when it did (made_here), and what one of them threw.
    bool made_here = false;
    std::vector<Row> made;
    std::exception_ptr failure;
  };

 public:
  Run(const Mechanism& mech, const SimulationOptions& options, const RunControl& control)
      : mech_(mech),
        options_(options),
        control_(control),
        start_(sweep_path(mech, 2).from),
        eq_(mech, start_),
        integrator_(mech, eq_, options_),
        rows_(mech, eq_, integrator_),
        output_worker_([this](RowJob& job) { make_output_rows(job); }, rows_on_second_thread(options),
                       row_jobs_ahead(mech)) {
    n_ = mech.coordinate_count();
    if (options.stop_when) probe_.emplace(mech, *options.stop_when);
    const double step = options.output_step > 0 ? options.output_step : options.end_time / 100;
    const long whole = static_cast<long>(std::floor(options.end_time / step * (1 + 1e-12)));
    for (long i = 0; i <= whole; ++i)
      output_times_.push_back(std::min(static_cast<double>(i) * step, options.end_time));
    if (output_times_.back() < options.end_time * (1 - 1e-12))
      output_times_.push_back(options.end_time);  // the end too
    outputs_ = static_cast<long>(output_times_.size()) - 1;
    // Every row is kept (events add a few): growing the vectors moved the rows already made.
    out_.samples.reserve(output_times_.size() + 4);
    out_.energies.reserve(output_times_.size() + 4);
  }

  Simulation run() {
    start();
    double t = 0.0;
    long next_output = 1;
    Eigen::VectorXd k1 = integrator_.derivative(t, y_);
    double h = integrator_.initial_step(t, y_, k1, options_.end_time);
    try {
      if (probe_ && condition_ > 0) {
        add_event(SimulationEvent::Kind::stop_when, 0.0,
                  "the stop condition '" + options_.stop_when->text + "' holds at the start, " + time_text(0.0));
        next_output = outputs_ + 1;  // nothing more to do
      }
      // The row thread starts while the first steps are taken, not at their first rows (where
      // the steps would wait for its creation); a run that ends at its start has none.
      if (next_output <= outputs_) output_worker_.start_early();
      while (next_output <= outputs_) {
        if (control_.should_stop("simulate", next_output, outputs_)) {
          drain_output_rows();
          throw cancellation();
        }
        const std::optional<double> step = next_step_size(t, h);
        if (!step) {  // the steps collapsed at a toggle they cannot get nearer: it is reached at t
          if (!go_on_after_event(SimulationEvent::Kind::toggle, t, recent_.newest_start(), next_output, t, k1)) break;
          h = integrator_.initial_step(t, y_, k1, options_.end_time - t);
          continue;
        }
        h = *step;
        Integrator::Step& s = step_;
        integrator_.step(t, y_, k1, h, away_from_toggles() ? Integrator::Pair::dop853 : Integrator::Pair::dopri5, s);
        if (!s.y1.allFinite() || !(s.error <= 1.0)) {
          h = after_rejected(s, h);
          continue;
        }
        const double t1 = t + h;
        const bool next_k1_ready = end_accepted_step(t, h, k1, s);
        const Eigen::VectorXd& y1 = y1_;
        std::optional<Found> event;
        try {
          event = first_event(t, h, s, y1);
        } catch (const SimulationStop&) {
          // The events' search met a stop inside the step (a fully driven linkage at its dead
          // centre): the rows before where it did are kept.
          hand_over_rows_to(t, h, s, next_output, t + search_stopped_at_ * h, true);
          throw;
        }
        recent_.keep(t, h, y_, s);
        const double reached = event ? t + event->theta * h : t1;
        // The event's own row stands for it: the rows before it only.
        next_output = hand_over_rows_to(t, h, s, next_output, reached, event.has_value());
        accept(h);
        if (event) {
          if (!go_on_after_event(event->kind, reached, t, next_output, t, k1)) break;
          continue;
        }
        y_ = y1;
        t = t1;
        if (next_k1_ready)
          k1.swap(next_k1_);
        else
          integrator_.derivative(t, y_, k1);
        keep_step_start(t);
        if (probe_) condition_ = condition_at(t, y_, true);
        h = after_accepted(s, h);
      }
      drain_output_rows();
    } catch (const SimulationStop& stop) {
      stopped(stop);
    }
    out_.statistics.evaluations = integrator_.evaluations();
    if (output_ && output_->statistics_at_stop) steps_as_at_row_stop(*output_->statistics_at_stop);
    return std::move(out_);
  }

 private:
  // The run ended early by `stop`, or by an output row's stop handed over before it, which came
  // first.
  void stopped(const SimulationStop& stop) {
    const SimulationStop first = earlier_output_row_stop().value_or(stop);
    out_.complete = false;
    out_.stop_reason = first.reason;
    out_.stop_where = first.where;
    out_.cancelled = first.cancelled;
  }

  // The steps' statistics as they were when the step of the output row that stopped the run was
  // taken: as on one thread, which stopped there.
  void steps_as_at_row_stop(const SimulationStatistics& then) {
    SimulationStatistics& now = out_.statistics;
    now.accepted_steps = then.accepted_steps;
    now.rejected_steps = then.rejected_steps;
    now.evaluations = then.evaluations;
    now.smallest_step = then.smallest_step;
    now.largest_step = then.largest_step;
  }

  // The event at `at` on the step from `step_start` handled (handle_event); where the motion goes
  // on (a reversal), its rows next to the toggle recorded and the integration restarted there
  // (t, k1 and the state kept). False where the run ends there.
  bool go_on_after_event(SimulationEvent::Kind kind, double at, double step_start, long& next_output, double& t,
                         Eigen::VectorXd& k1) {
    drain_output_rows();  // an event's rows take their places among them
    const std::optional<Reversal> reversal = handle_event(kind, at, step_start);
    if (!reversal) return false;
    record_window(reversal->regular_row, at, reversal->time, next_output);
    t = reversal->time;
    y_ = reversal->y;
    recent_.clear();
    reversal_restart_ = t;
    integrator_.derivative(t, y_, k1);
    keep_step_start(t);
    if (probe_) condition_ = condition_at(t, y_, true);
    return true;
  }

  // Whether the kept rows are within kChangePointDip of dependent at the state kept last: steps
  // that collapse there have reached a toggle they cannot get nearer (a near kite of a 1 mm crank
  // on 1 m links at rtol 1e-12 stopped with "the step size fell" 3e-15 s from it). Not while the
  // run still leaves a toggle at its start (no scale yet), nor before a step is kept since the
  // start or a reversal (the toggle's regular state is looked for on the steps kept).
  bool rows_at_toggle() {
    if (gate_scale_ == 0.0 || recent_.empty()) return false;
    dense_toggle_reference();
    eq_.factorise(step_start_time_, step_start_q_);
    return toggle_.least_singular_value(eq_.dense_jacobian()) <= kChangePointDip;
  }

  // The gate at the step's start is closed (its Jacobian square and its conditioning at least
  // kGateNear of the start's): the higher-order pair may take the step.
  bool away_from_toggles() const {
    return gate_start_.square && gate_scale_ > 0.0 && gate_start_.sign != 0 &&
           gate_start_.conditioning >= kGateNear * gate_scale_;
  }

  // The step size to try after the step s of size h was rejected (its error above the
  // tolerance, or not a number).
  double after_rejected(const Integrator::Step& s, double h) {
    ++out_.statistics.rejected_steps;
    just_rejected_ = true;
    const Integrator::Controller& c = s.controller();
    return h * (s.y1.allFinite() && std::isfinite(s.error) ? std::max(c.least, 0.9 * std::pow(s.error, -c.exponent))
                                                           : c.least);
  }

  // The step size after the accepted step s of size h. As Hairer's codes, the step after a
  // rejected one does not grow (the double crank of the benchmark: 137 steps rejected where 171
  // were, 3 % fewer evaluations).
  double after_accepted(const Integrator::Step& s, double h) {
    const Integrator::Controller& c = s.controller();
    const double factor =
        std::clamp(0.9 * std::pow(std::max(s.error, 1e-10), -c.exponent), c.least, just_rejected_ ? 1.0 : c.largest);
    just_rejected_ = false;
    return h * factor;
  }

  // The accepted step [t, t + h] from y_ (its first stage k1): its end projected onto the
  // constraints into y1_, the next step's first stage into next_k1_ while the projection's
  // factorisation is at y1_ (the rows and the events' search move it; false where the
  // accelerations are not determined there, and an event's step computes it again where it
  // ends), and the step's continuous extension. Throws where the end cannot be projected.
  bool end_accepted_step(double t, double h, const Eigen::VectorXd& k1, Integrator::Step& s) {
    const double t1 = t + h;
    y1_ = s.y1;
    if (!integrator_.project(t1, y1_))
      throw SimulationStop{"the positions could not be brought back onto the constraints at " + time_text(t1) +
                               " (the mechanism may have reached a limit of its motion)",
                           eq_.driver_to_blame()};
    const bool next_k1_ready = integrator_.derivative_after_projection(t1, next_k1_);
    integrator_.extend(t, y_, k1, h, s, next_k1_ready ? &next_k1_ : nullptr);
    return next_k1_ready;
  }

  // The step to take from t, h cut to the time left; a stop where the steps are too many (with a
  // row at t) or too short; nothing where they collapsed at a toggle (rows_at_toggle).
  std::optional<double> next_step_size(double t, double h) {
    const double remaining = options_.end_time - t;
    if (h >= remaining * (1 - 1e-12)) h = remaining;
    const bool near_toggle =
        gate_start_.square && gate_scale_ > 0.0 && gate_start_.conditioning < kStalledConditioning * gate_scale_;
    if (!near_toggle) stalled_steps_ = 0;
    if (near_toggle && h < kStalledStep * options_.end_time && ++stalled_steps_ >= kStalledSteps)
      throw stalled_next_to_a_toggle(t, h);
    if (out_.statistics.accepted_steps + out_.statistics.rejected_steps >= options_.max_steps) {
      // A row where the run got to, which the message names (the last output row is before it).
      drain_output_rows();
      if (t > out_.samples.back().time) record(t, y_);
      throw SimulationStop{"the simulation took more than " + std::to_string(options_.max_steps) + " steps before " +
                               time_text(options_.end_time) + " (stopped at " + time_text(t) + ")",
                           eq_.driver_to_blame()};
    }
    // A step to the end may be as short as the time left (a run of 1e-14 s); any other must
    // still move the time by more than its rounding.
    const bool to_the_end = h == remaining && h > 0.0;
    if (!(h > 1e-14 * std::max(1.0, std::abs(t))) && !to_the_end) {
      const std::string collapsed =
          "the step size fell to " + seconds_text(h) + " at " + time_text(t) + ", below the time's rounding: ";
      if (const std::optional<SimulationStop> law = eq_.law_to_blame(t))
        throw SimulationStop{collapsed + law->reason + " (a pole or a jump the motion cannot follow)", law->where};
      if (rows_at_toggle()) return std::nullopt;
      throw SimulationStop{collapsed + "the motion is too fast or not smooth there for the tolerance asked",
                           eq_.driver_to_blame()};
    }
    return h;
  }

  // Steps shrunk next to a nearly singular Jacobian: the motion approaches a toggle it does not
  // reach, where the accelerations grow without bound. A prescribed motion that pushes the
  // mechanism there (a five-bar's driven link into the stretched pose) ground on for 10 million
  // steps, 3.5 minutes, then stopped at the free driver.
  SimulationStop stalled_next_to_a_toggle(double t, double h) const {
    const std::string stalled = "the steps shrank to " + seconds_text(h) + " at " + time_text(t) +
                                " next to a singular position (a toggle the motion approaches but does not reach, "
                                "where its accelerations grow without bound)";
    const auto& drivers = mech_.model().drivers;
    for (std::size_t d = 0; d < drivers.size(); ++d)
      if (!drivers[d].free)
        return {stalled + ": the prescribed motion of driver '" + drivers[d].name +
                    "' pushes the mechanism into it, which no finite force can follow",
                {EntityRef::Kind::Driver, static_cast<int>(d), -1}};
    return {stalled, eq_.driver_to_blame()};
  }

  // An event on a step: its kind and where on the step, theta in [0, 1].
  struct Found {
    SimulationEvent::Kind kind;
    double theta;
  };

  double output_time(long i) const { return output_times_[i]; }

  // A cancel or a passed deadline ends the run as a stop does, so that the rows so far are kept
  // (an interrupted `nbar simulate -o run.csv` still writes them).
  SimulationStop cancellation() const {
    const std::string reached = time_text(out_.samples.back().time);
    return {control_.token.deadline_passed() ? "cancelled: the time budget ran out at " + reached
                                             : "cancelled at " + reached,
            {},
            true};
  }

  // y projected onto the constraints at `at`.
  Eigen::VectorXd projected(double at, Eigen::VectorXd y) {
    if (!integrator_.project(at, y))
      throw SimulationStop{"the positions could not be brought back onto the constraints at " + time_text(at),
                           eq_.driver_to_blame()};
    return y;
  }

  // The earliest event on the accepted step [t, t + h] whose projected end is y1 (the
  // constraints factorised there), located on the continuous output to 1e-12 s: where the
  // toggle measure changes sign (theta on the side the step started), or where the stop
  // condition comes to hold (theta on the side where it holds).
  std::optional<Found> first_event(double t, double h, const Integrator::Step& s, const Eigen::VectorXd& y1) {
    search_stopped_at_ = 1.0;
    const double tolerance = std::min(0.5, 1e-12 / h);
    std::optional<Found> found;
    if (const std::optional<double> theta = toggle_on_step(t, h, s, y1, tolerance))
      found = Found{SimulationEvent::Kind::toggle, *theta};
    if (probe_) {
      const double at_end = condition_at(t + h, y1, false);
      if (at_end > 0) {
        const auto distance_at = [&](double theta) {
          const double at = t + theta * h;
          return searched(theta, [&] { return condition_at(at, Integrator::interpolate(y_, s, theta), false); });
        };
        const double held = bracket_sign_change(distance_at, 0.0, 1.0, condition_, at_end, tolerance).second;
        if (!found || held < found->theta) found = Found{SimulationEvent::Kind::stop_when, held};
      }
    }
    return found;
  }

  // `look()`, a look at the point theta of the step an event's search makes; where it throws a stop,
  // the earliest such point is kept in search_stopped_at_ (the rows before it stand).
  template <class Look>
  auto searched(double theta, const Look& look) -> decltype(look()) {
    try {
      return look();
    } catch (const SimulationStop&) {
      search_stopped_at_ = std::min(search_stopped_at_, theta);
      throw;
    }
  }

  // Where on the step the constraints lose rank, if they do: the toggle measure changes sign, or
  // (where the step passes a change point and goes on along the other branch, so that the
  // measure only touches zero) dips to nothing. The ends are enough while the measure is well
  // away from zero; near zero, three inner points find a crossing or a dip within the step. The
  // measure is dense; the sparse gate at the step's ends decides whether it is needed at all.
  std::optional<double> toggle_on_step(double t, double h, const Integrator::Step& s, const Eigen::VectorXd& y1,
                                       double tolerance) {
    if (gate_scale_ == 0.0) return std::nullopt;  // still leaving a toggle at the start: no scale yet
    const EquationsOfMotion::Gate end = eq_.gate_at(t + h, y1.head(n_));
    if (end.square && gate_start_.square && end.sign != 0 && end.sign == gate_start_.sign &&
        std::min(end.conditioning, gate_start_.conditioning) >= kGateNear * gate_scale_)
      return std::nullopt;
    dense_toggle_reference();
    // A point of the step that cannot be brought onto the constraints is next to the toggle (a
    // near kite at rtol 1e-6: Newton fails where the branches nearly meet), taken as at it.
    const auto measure_at = [&](double theta) {
      Eigen::VectorXd y = Integrator::interpolate(y_, s, theta);
      if (!searched(theta, [&] { return integrator_.project(t + theta * h, y); })) return 0.0;
      return toggle_.measure(eq_.dense_jacobian());
    };
    std::vector<double> theta = {0.0, 1.0}, measure = {toggle_at_start_, measure_at(1.0)};
    // Near zero against the measure's size at the start, or, for a run started next to a toggle
    // (a size of nearly nothing), by the rows' dependence at the step's end (the last projected;
    // an SVD on every step the gate opened cost a four-bar's run 2.4 %).
    const bool near_zero = std::min(std::abs(measure[0]), std::abs(measure[1])) < 0.05 * toggle_scale_ ||
                           (toggle_scale_ < kSmallMeasure && toggle_.least_singular_value(eq_.dense_jacobian()) < 0.05);
    if (near_zero) {
      theta = {0.0, 0.25, 0.5, 0.75, 1.0};
      measure = {measure[0], measure_at(0.25), measure_at(0.5), measure_at(0.75), measure[1]};
    }
    for (std::size_t i = 1; i < theta.size(); ++i)
      if ((measure[i] > 0) != (measure[i - 1] > 0) || measure[i] == 0.0)
        return bracket_sign_change(measure_at, theta[i - 1], theta[i], measure[i - 1], measure[i], tolerance).first;
    if (!near_zero) return std::nullopt;
    return dip_on_step(theta, measure, measure_at, tolerance);
  }

  // Where |measure| falls until the rows are well within the blur of dependent on the step
  // (kToggleReached: the toggle, which the steps may not get nearer), or has a minimum where they
  // are within kChangePointDip of it, if it does: the motion passed a change point onto the other
  // branch. Judged by the rows' dependence itself, not by the measure against its size at the
  // start, which a run started next to a change point has nearly nothing of. The minimum may lie
  // at the step's start: over the tiny steps next to a change point each step sees the measure
  // only falling or only rising (a kite four-bar at rtol 1e-8: forty steps of 1e-7 s falling to
  // 2.3e-6 of its size and rising again), so a step still falling at its end leaves the minimum
  // to the next, which starts there.
  template <class Measure>
  std::optional<double> dip_on_step(const std::vector<double>& theta, const std::vector<double>& measure,
                                    const Measure& measure_at, double tolerance) {
    const std::size_t last = theta.size() - 1;
    std::size_t lowest = 0;
    for (std::size_t i = 1; i <= last; ++i)
      if (std::abs(measure[i]) < std::abs(measure[lowest])) lowest = i;
    const double at = golden_minimum([&](double x) { return std::abs(measure_at(x)); },
                                     theta[lowest > 0 ? lowest - 1 : 0], theta[std::min(lowest + 1, last)], tolerance);
    const double least = std::abs(measure_at(at));
    if (least == 0.0) return at;  // not brought onto the constraints there: at the toggle (measure_at)
    const bool still_falling = lowest == last && !(least < std::abs(measure[last]));
    const double dependence = toggle_.least_singular_value(eq_.dense_jacobian());  // at `at`, projected last
    if (!(dependence <= (still_falling ? kToggleReached : kChangePointDip))) return std::nullopt;
    return at;
  }

  // The stop condition's distance (> 0: it holds) at a state, kept as the last state when `keep`.
  double condition_at(double at, const Eigen::VectorXd& y, bool keep) {
    const Row row = rows_.make(at, y, reference_);
    return probe_->distance(row.sample, row.energy, keep);
  }

  // Where a reversal at a toggle goes on from.
  struct Reversal {
    double time;
    Eigen::VectorXd y;
    std::size_t regular_row;  // the toggle's row, the last regular state before it
  };

  // The row and report of an event at `at` on the step from `step_start` (kept in recent_); the
  // reversal to go on from at a toggle with AtToggle::reverse, nothing where the run ends there.
  std::optional<Reversal> handle_event(SimulationEvent::Kind kind, double at, double step_start) {
    if (kind == SimulationEvent::Kind::stop_when) {
      record(at, recent_.state_at(at));  // projected there by the row, to rounding
      add_event(kind, at, "the stop condition '" + options_.stop_when->text + "' was met at " + time_text(at));
      return std::nullopt;
    }
    // At the toggle itself neither the speeds' projection onto the constraints nor the
    // accelerations are determined (a row there said a crank turned backwards at half its speed),
    // so the toggle's row is the last regular state before it, in its place among the rows.
    if (coming_to_rest(at)) {
      const std::string rest = "the mechanism came back to the toggle at " + time_text(at) +
                               " without getting 3e-4 of the drawing away from it since it reversed there (going on "
                               "at " +
                               time_text(reversal_restart_) +
                               "): bounces this small are below what a reversal can follow (the motion may be coming "
                               "to rest against the toggle)";
      add_event(kind, at, rest);
      throw SimulationStop{rest, eq_.driver_to_blame()};
    }
    const double regular = regular_time(at, step_start);
    const Eigen::VectorXd y = projected(regular, recent_.state_at(regular));
    const std::size_t row = row_at(regular, y);
    const std::string where = "the mechanism reached a toggle at " + time_text(at) +
                              ": its constraints became singular (a dead centre or change point), where the loads "
                              "no longer determine its motion";
    if (options_.at_toggle == AtToggle::stop) {
      // Rows nearer the toggle than its row are not kept: their speeds' projection is not reliable.
      out_.samples.resize(row + 1);
      out_.energies.resize(row + 1);
      add_event(kind, at, where);
      throw SimulationStop{where, eq_.driver_to_blame()};
    }
    add_event(kind, at, where + "; every speed reversed there", row);
    // A state reversed at the toggle went on along either branch, or met the toggle again at
    // once. So the motion is mirrored about the toggle at t*: the regular state at t* - delta with
    // every speed reversed is the state at t* + delta. That is exact where the motion is
    // reversible in time (gravity, springs, loads of the positions); damping and friction lose on
    // the way back what they lost on the way in (mirrored, below), and loads of the time or the
    // speed are off by delta's share of their work, which the energy balance shows.
    return Reversal{2 * at - regular, mirrored(y, at), row};
  }

  // Back at the toggle with every step since the reversal there within kRestDistance of it: the
  // bounces are too small for reversals mirrored from 1e-4 of the drawing, and shrink towards a
  // rest against the toggle where the motion is damped (2537 reversals in 20 s, ever shorter).
  bool coming_to_rest(double toggle) const {
    if (reversal_restart_ < 0.0 || recent_.earliest() != reversal_restart_) return false;
    const Eigen::VectorXd at_toggle = recent_.state_at(toggle).head(n_);
    return recent_.farthest_from(at_toggle) < kRestDistance * mech_.drawing_size();
  }

  // A state before the toggle at `toggle`, mirrored about it: every speed reversed. The loads'
  // work is the state's (their work on the way back undoes that on the way in, exact for loads of
  // the positions). The way back loses to damping and friction what the way in lost: that is
  // counted as dissipated and taken from the kinetic energy (the speeds scaled), so that the
  // balance holds (with viscous friction at a parallelogram's pivot, 61 reversals were 0.006 J off).
  Eigen::VectorXd mirrored(Eigen::VectorXd y, double toggle) {
    const double lost = recent_.state_at(toggle)(2 * n_) - y(2 * n_);
    SimulationEnergy energy;
    eq_.stored_energy(y.head(n_), y.segment(n_, n_), energy);
    const double kept = energy.kinetic > 0.0 ? std::sqrt(std::max(0.0, 1.0 - 2.0 * lost / energy.kinetic)) : 1.0;
    y.segment(n_, n_) *= -kept;
    y(2 * n_) += 2.0 * lost;
    return y;
  }

  // The index of the row at `time`: the row kept there already (the start's), else y's, placed.
  std::size_t row_at(double time, const Eigen::VectorXd& y) {
    for (std::size_t i = out_.samples.size(); i-- > 0 && out_.samples[i].time >= time;)
      if (out_.samples[i].time == time) return i;
    return record_in_place(time, y);
  }

  // When before the toggle at `toggle` (on the step from `step_start`) the positions are
  // kRegularDistance of the drawing from the toggle's: searched backwards from a linear guess,
  // doubling; else the oldest state kept (the run's start, the last reversal's), nearer.
  double regular_time(double toggle, double step_start) const {
    const Eigen::VectorXd at_toggle = recent_.state_at(toggle).head(n_);
    const double wanted = kRegularDistance * mech_.drawing_size();
    const double travelled = (at_toggle - recent_.state_at(step_start).head(n_)).lpNorm<Eigen::Infinity>();
    double back = toggle - step_start;
    if (travelled > wanted) back *= wanted / travelled;
    back = std::max(back, 1e-15 * std::max(1.0, std::abs(toggle)));
    for (;;) {
      const double at = toggle - back;
      if (at <= recent_.earliest()) return recent_.earliest();
      if ((recent_.state_at(at).head(n_) - at_toggle).lpNorm<Eigen::Infinity>() >= wanted) return at;
      back *= 2;
    }
  }

  // The rows between the toggle's regular row (`row`) and the toggle at `toggle` (the output rows
  // there, kept already) and past it until the reversed motion goes on at `until` (the output rows
  // from `next` on, as their mirror images): each from the window's own motion (window_row).
  void record_window(std::size_t row, double toggle, double until, long& next) {
    const Sample regular = out_.samples[row];
    const Eigen::VectorXd third = third_taylor_coefficient(regular, toggle);
    for (std::size_t i = row + 1; i < out_.samples.size(); ++i) {
      const double at = out_.samples[i].time;
      Row replaced = window_row(at, regular, third, toggle);
      replaced.sample.step = static_cast<int>(i);
      out_.samples[i] = std::move(replaced.sample);
      out_.energies[i] = replaced.energy;
    }
    for (; next <= outputs_ && output_time(next) <= until * (1 + 1e-13); ++next) {
      const double at = output_time(next);
      keep_row(window_row(at, regular, third, toggle), out_.samples.size());
    }
  }

  // The third Taylor coefficient of q in time (the jerk over 6) at the regular row: from its
  // accelerations and those of a row as far before it as the toggle is after it (regular, well
  // away from the toggle); zero where the steps kept do not reach back there (the start).
  Eigen::VectorXd third_taylor_coefficient(const Sample& regular, double toggle) {
    const double span = toggle - regular.time, back = regular.time - span;
    if (!(span > 0.0) || back < recent_.earliest()) return Eigen::VectorXd::Zero(n_);
    const Row earlier = rows_.make(back, recent_.state_at(back), reference_);
    return (regular.taylor.col(2) - earlier.sample.taylor.col(2)) / (3 * span);
  }

  // An event at `at` whose row is `row` (the last row kept if none is given).
  void add_event(SimulationEvent::Kind kind, double at, std::string message,
                 std::optional<std::size_t> row = std::nullopt) {
    out_.events.push_back({kind, at, static_cast<int>(row.value_or(out_.samples.size() - 1)), std::move(message)});
  }

  // The start's: as a sweep's table starts them, at their driver's value for the bodies an
  // absolute angle drives, in atan2's range for the others.
  void first_body_angles(const Eigen::VectorXd& q) {
    const Model& m = mech_.model();
    std::vector<double> raw, reference;
    raw_body_angles(mech_, q, raw);
    unwrapped(raw, std::vector<double>(raw.size(), 0.0), reference);  // atan2's range
    for (std::size_t d = 0; d < m.drivers.size(); ++d) {
      const Driver& drv = m.drivers[d];
      if (drv.kind == DriverKind::Angle && drv.relative_to < 0) reference[drv.body] = reference_.drivers[d];
    }
    unwrapped(raw, reference, reference_.bodies);
  }

  // The state just kept (the last derivative's factorisation is there) starts the next step: its
  // gate, the dense measure's reference (formed only if the step needs it), and the angles' turns.
  void keep_step_start(double t) {
    step_start_time_ = t;
    step_start_q_ = y_.head(n_);
    angles_at(mech_, step_start_q_, reference_.drivers, reference_.bodies, raw_angles_, reference_.drivers,
              reference_.bodies);
    gate_start_ = eq_.gate_at(t, step_start_q_);
    // The gate's and the measure's scales are their values at the first regular state: the start,
    // unless it is a toggle itself (then scales of nearly nothing kept every later toggle unseen).
    if (gate_scale_ == 0.0 && !(gate_start_.square && gate_start_.conditioning < kSingularStart)) {
      gate_scale_ = gate_start_.conditioning;
      scale_time_ = t;
      scale_q_ = step_start_q_;
    }
    toggle_reference_ready_ = false;
  }

  // The dense measure's reference at the step's start, and its scale at the run's start (where the
  // mechanism is assembled), each formed the first time it is needed.
  void dense_toggle_reference() {
    if (toggle_scale_ == 0.0) {
      eq_.factorise(scale_time_, scale_q_);
      const Eigen::MatrixXd jacobian = eq_.dense_jacobian();
      ToggleMeasure at_start;
      at_start.reference(jacobian);
      toggle_scale_ = std::abs(at_start.measure(jacobian));
    }
    if (toggle_reference_ready_) return;
    eq_.factorise(step_start_time_, step_start_q_);
    const Eigen::MatrixXd jacobian = eq_.dense_jacobian();
    toggle_.reference(jacobian);
    toggle_at_start_ = toggle_.measure(jacobian);
    toggle_reference_ready_ = true;
  }

  // Positions assembled at t = 0, velocities from every driver's speed (free ones: their initial
  // speed), on the full set of rows.
  void start() {
    try {
      start_at_rest_or_speed();
    } catch (const SimulationStop& stop) {  // before the run: the model cannot be simulated
      throw Error(ErrorKind::InvalidModel, stop.reason, stop.where);
    }
    for (std::size_t d = 0; d < mech_.model().drivers.size(); ++d)
      if (mech_.model().drivers[d].free) out_.free_drivers.push_back(static_cast<int>(d));
  }

  void start_at_rest_or_speed() {
    State state(mech_);
    const Sample at_start = assemble_at_time(mech_, state, 0.0, 0);
    Eigen::VectorXd q = at_start.positions();
    std::vector<DriverState> drivers;
    eq_.drivers_at(0.0, drivers);
    const Eigen::VectorXd qd = start_velocities(q, drivers);
    y_.setZero(2 * n_ + 2);
    y_.head(n_) = q;
    y_.segment(n_, n_) = qd;
    eq_.evaluate(0.0, q, qd);
    reference_.drivers = start_;
    first_body_angles(q);
    record(0.0, y_);
    SimulationEnergy& first = out_.energies.front();
    reference_.energy = first.kinetic + first.gravity + first.spring;
    first.balance = 0.0;
    out_.statistics.largest_energy_error = 0.0;
    eq_.factorise(0.0, q);
    keep_step_start(0.0);
    if (gate_scale_ == 0.0)
      out_.warnings.push_back({"start_at_toggle", 0,
                               "the run starts at a toggle: its constraints are singular there (a dead centre or "
                               "change point), where the loads do not determine the motion; it goes on as the "
                               "integration leaves it, and toggles are watched for from the first regular state"});
    if (probe_) condition_ = condition_at(0.0, y_, true);
  }

  // Every row, the free drivers' at their initial speeds, gives q' at the start: J q' = -Phi_t,
  // solved with the kinematics' own sparse LU (a rank-revealing least-squares solve where the
  // rows are redundant or the Jacobian singular there).
  // Velocities at the start. Up to kDenseStartCoordinates coordinates by an SVD that meets the
  // kept rows exactly and the free drivers' initial speeds as nearly as it can, a correction said
  // in the warnings (initial_velocity.hpp); above, where that SVD's cubic cost would outweigh the
  // run (a chain of a hundred loops, 400 coordinates, spent 69 % of its run in it), by the sparse solve alone, exact at
  // a regular start.
  static constexpr int kDenseStartCoordinates = 100;
  Eigen::VectorXd start_velocities(const Eigen::VectorXd& q, const std::vector<DriverState>& drivers) {
    std::vector<double> values;
    evaluate_jacobian(mech_, q, drivers, values);
    Eigen::MatrixXd coefficients = Eigen::MatrixXd::Zero(n_, 2);
    coefficients.col(0) = q;
    Eigen::VectorXd phi_t;
    evaluate_series_remainder(mech_, coefficients, 1, drivers, phi_t);
    if (n_ <= kDenseStartCoordinates) {
      Eigen::MatrixXd jacobian = Eigen::MatrixXd::Zero(mech_.row_count(), n_);
      const auto& pattern = mech_.equations().pattern;
      for (std::size_t i = 0; i < pattern.size(); ++i) jacobian(pattern[i].row, pattern[i].col) += values[i];
      return consistent_initial_velocity(mech_, jacobian, phi_t, out_.warnings);
    }
    const Eigen::VectorXd rhs = -phi_t;
    LinearSolver solver(mech_);
    Eigen::VectorXd qd;
    if (solver.factorize(values) || solver.method() == LinearSolver::Method::LeastSquares) {
      solver.solve(rhs, qd);
      return qd;
    }
    Eigen::MatrixXd jacobian = Eigen::MatrixXd::Zero(mech_.row_count(), n_);
    const auto& pattern = mech_.equations().pattern;
    for (std::size_t i = 0; i < pattern.size(); ++i) jacobian(pattern[i].row, pattern[i].col) += values[i];
    return jacobian.completeOrthogonalDecomposition().solve(rhs);
  }

  // A row next to a toggle (within its regular distance), where positions projected there and
  // the accelerations solved there are not reliable (a crank's acceleration -3475 deg/s^2 for
  // -6138 at 7e-7 s from the parallelogram's toggle). The motion there is the regular row's own
  // Taylor expansion to the third order (`third`, third_taylor_coefficient), at the time as far
  // before the toggle as `at` is from it; mirrored when `at` is past it. Over the window's 1e-4
  // of the drawing it is exact to the fourth order in its length (its accelerations to the
  // second), and it asks nothing of the state at the toggle, whose speeds the integrator keeps
  // poorly there (a cubic Hermite to them left a parallelogram's rows 21 % off its energy at rtol
  // 1e-12). Its drift says how near the constraints that is.
  Row window_row(double at, const Sample& regular, const Eigen::VectorXd& third, double toggle) {
    const double before = toggle - std::abs(at - toggle), tau = std::max(before - regular.time, 0.0);
    const auto q0 = regular.taylor.col(0), v0 = regular.taylor.col(1), c2 = regular.taylor.col(2);
    Eigen::VectorXd y = recent_.state_at(before);  // for its work integrals
    y.head(n_) = q0 + tau * (v0 + tau * (c2 + tau * third));
    y.segment(n_, n_) = v0 + tau * (2 * c2 + 3 * tau * third);
    const Eigen::VectorXd acceleration = 2 * c2 + 6 * tau * third;
    if (at > toggle) y = mirrored(std::move(y), toggle);
    ConstraintDrift drift;
    if (eq_.kept_rows()) {
      const Eigen::VectorXd q = y.head(n_), qd = y.segment(n_, n_);
      drift.position = eq_.factorise_with_residuals(at, q).lpNorm<Eigen::Infinity>();
      drift.velocity = (eq_.jacobian_times(qd) + eq_.time_derivative(q)).lpNorm<Eigen::Infinity>();
      drift.acceleration = (eq_.jacobian_times(acceleration) - eq_.gamma(q, qd)).lpNorm<Eigen::Infinity>();
    }
    return rows_.filled(at, y, acceleration, drift, reference_);
  }

  // Keeps the row at `at` in the answer, after the rows so far.
  void record(double at, const Eigen::VectorXd& y) { keep_row(rows_.make(at, y, reference_), out_.samples.size()); }

  // Keeps the row at `at` in its place by time among the rows so far; its index.
  std::size_t record_in_place(double at, const Eigen::VectorXd& y) {
    const auto later = std::upper_bound(out_.samples.begin(), out_.samples.end(), at,
                                        [](double time, const Sample& row) { return time < row.time; });
    const std::size_t place = static_cast<std::size_t>(later - out_.samples.begin());
    keep_row(rows_.make(at, y, reference_), place);
    for (std::size_t i = place; i < out_.samples.size(); ++i) out_.samples[i].step = static_cast<int>(i);
    for (SimulationEvent& e : out_.events)
      if (e.row >= static_cast<int>(place)) ++e.row;
    return place;
  }

  void keep_row(Row row, std::size_t place) {
    add_quality(row.drift, row.energy.balance, out_.statistics.drift, out_.statistics.largest_energy_error);
    row.sample.step = static_cast<int>(place);
    out_.samples.insert(out_.samples.begin() + static_cast<std::ptrdiff_t>(place), std::move(row.sample));
    out_.energies.insert(out_.energies.begin() + static_cast<std::ptrdiff_t>(place), row.energy);
  }

  // How many steps' rows may wait for the row thread: some 4 MB of them, from 8 to 1024 (a four-bar's
  // are 0.5 kB each, a chain of a thousand loops' 0.3 MB). Deep, so that where the two threads
  // share the cores with other processes this one can run ahead for a whole time slice.
  static std::size_t row_jobs_ahead(const Mechanism& mech) {
    const std::size_t doubles = (1 + dop853::kExtension) * (2 * static_cast<std::size_t>(mech.coordinate_count()) + 2) +
                                mech.model().bodies.size() + mech.model().drivers.size();
    return std::clamp<std::size_t>((std::size_t{4} << 20) / (doubles * sizeof(double) + sizeof(RowJob)), 8, 1024);
  }

  // The worst drift and energy error so far, with a row's.
  static void add_quality(const ConstraintDrift& drift, double balance, ConstraintDrift& worst, double& energy_error) {
    worst.position = std::max(worst.position, drift.position);
    worst.velocity = std::max(worst.velocity, drift.velocity);
    worst.acceleration = std::max(worst.acceleration, drift.acceleration);
    energy_error = std::max(energy_error, std::abs(balance));
  }

  // Hands the rows of the step [t, t + h] from `first` up to the time `reached` over (before it only
  // when `before`); returns the next row.
  long hand_over_rows_to(double t, double h, const Integrator::Step& s, long first, double reached, bool before) {
    long end = first;
    while (end <= outputs_ && output_time(end) <= reached * (1 + 1e-13) && !(before && output_time(end) >= reached))
      ++end;
    if (end > first) hand_over_rows(t, h, s, first, end);
    return end;
  }

  // The output rows on the step [t, t + h] from y_ (output times first to end - 1), handed over to
  // the row thread with the references they are made against and the statistics so far.
  void hand_over_rows(double t, double h, const Integrator::Step& s, long first, long end) {
    RowJob& job = output_worker_.next_slot();
    job.t = t;
    job.h = h;
    job.y0 = y_;
    job.step.r = s.r;
    job.first = first;
    job.end = end;
    job.reference = reference_;  // the vectors' storage kept from the slot's last job
    job.statistics = out_.statistics;
    job.statistics.evaluations = integrator_.evaluations();
    job.scales = eq_.scales();
    job.made_here = false;
    const bool alternate = g_rows_on_both_threads && ++jobs_handed_over_ % 2 == 0;
    if (output_worker_.threaded() && (output_worker_.waiting() >= kRowJobsBehind || alternate)) make_rows_here(job);
    output_worker_.submit();
  }

  // On the steps' thread, while the row thread is kRowJobsBehind jobs or more behind: the job's
  // rows, which the row thread then only keeps in their place. The rows are the same whichever
  // thread makes them (OutputRows), so the share each makes may follow the threads' speeds.
  void make_rows_here(RowJob& job) {
    job.made_here = true;
    job.made.clear();
    job.failure = nullptr;
    try {
      make_job_rows(job, rows_made_with(rows_here_, job), [&](Row&& row) { job.made.push_back(std::move(row)); });
    } catch (...) {
      job.failure = std::current_exception();  // thrown by the row thread, in its place
    }
  }

  // On the row thread: a job's rows, kept after the rows so far (this thread keeps no row while
  // jobs are out: it drains them first).
  void make_output_rows(RowJob& job) {
    OutputRows& o = rows_made_with(output_, job);
    const auto keep = [&](Row&& row) {
      add_quality(row.drift, row.energy.balance, o.drift, o.energy_error);
      row.sample.step = static_cast<int>(out_.samples.size());
      out_.samples.push_back(std::move(row.sample));
      out_.energies.push_back(row.energy);
    };
    try {
      if (!job.made_here) {
        make_job_rows(job, o, keep);
        return;
      }
      for (Row& row : job.made) keep(std::move(row));
      if (job.failure) std::rethrow_exception(job.failure);
    } catch (const SimulationStop&) {
      o.statistics_at_stop = job.statistics;
      throw;
    }
  }

  // The equations `rows` makes rows with, made at the first job (by the thread that makes them).
  OutputRows& rows_made_with(std::unique_ptr<OutputRows>& rows, const RowJob& job) {
    if (!rows) rows = std::make_unique<OutputRows>(mech_, start_, options_, job.scales);
    return *rows;
  }

  // The job's rows, each given to `keep` in order; a row's stop is thrown after the rows before it.
  // The first row's solves start without a warm start, the others' from the row before: a job's
  // rows are made by one thread, so they depend on the job alone.
  template <class Keep>
  void make_job_rows(const RowJob& job, OutputRows& o, const Keep& keep) {
    o.eq.forget_warm_start();
    for (long i = job.first; i < job.end; ++i) {
      const double at = output_time(i);
      Integrator::interpolate(job.y0, job.step, std::clamp((at - job.t) / job.h, 0.0, 1.0), o.state);
      keep(o.maker.make(at, o.state, job.reference));
    }
  }

  // Waits for the output rows handed over; throws the stop one of them met (the rows before it
  // kept). Their drift and energy error join the statistics either way.
  void drain_output_rows() {
    struct AddQuality {
      Run& run;
      ~AddQuality() {
        if (run.output_)
          add_quality(run.output_->drift, run.output_->energy_error, run.out_.statistics.drift,
                      run.out_.statistics.largest_energy_error);
      }
    } add{*this};
    output_worker_.drain();
  }

  // The stop an output row handed over met, if one did.
  std::optional<SimulationStop> earlier_output_row_stop() {
    try {
      drain_output_rows();
    } catch (const SimulationStop& stop) {
      return stop;
    }
    return std::nullopt;
  }

  void accept(double h) {
    SimulationStatistics& s = out_.statistics;
    s.smallest_step = s.accepted_steps == 0 ? h : std::min(s.smallest_step, h);
    s.largest_step = std::max(s.largest_step, h);
    ++s.accepted_steps;
  }

  const Mechanism& mech_;
  const SimulationOptions& options_;
  const RunControl& control_;
  std::vector<double> start_;
  EquationsOfMotion eq_;
  Integrator integrator_;
  int n_ = 0;
  std::vector<double> output_times_;  // the rows' times: 0, dt, 2 dt, ... and the end
  long outputs_ = 0;
  Eigen::VectorXd y_;
  // Work vectors, sized once: the step's projected end, a row's interpolated and projected state.
  Eigen::VectorXd y1_, next_k1_;
  Integrator::Step step_;           // the last step's, kept for its storage
  RecentSteps recent_;              // the last steps accepted
  RowReference reference_;          // at the state kept last
  std::vector<double> raw_angles_;  // work space of angles_at
  RowMaker rows_;                   // the rows this thread makes: at events, for the stop condition
  double toggle_at_start_ = 1.0;    // the toggle measure at the state kept last
  double toggle_scale_ = 0.0;       // its size at the start, where the mechanism is assembled
  ToggleMeasure toggle_;            // its reference, at the state kept last when toggle_reference_ready_
  bool toggle_reference_ready_ = false;
  double step_start_time_ = 0.0;
  Eigen::VectorXd step_start_q_;
  // The first regular state (the start, unless it is a toggle): the toggle measures' scales are there.
  double scale_time_ = 0.0;
  Eigen::VectorXd scale_q_;
  double reversal_restart_ = -1.0;  // where the motion went on after the last reversal
  double search_stopped_at_ = 1.0;  // the earliest point of a step (theta) where an event's search met a stop
  long stalled_steps_ = 0;
  bool just_rejected_ = false;  // the last step tried was rejected              // tiny steps since the motion came
                                // next to a toggle (next_step_size)
  EquationsOfMotion::Gate gate_start_;  // the gate at the state kept last
  double gate_scale_ = 0.0;             // its conditioning at the start
  std::optional<ColumnProbe> probe_;    // the stop condition's column
  double condition_ = -1.0;             // its distance at the state kept last (> 0: it holds)
  // The answer. While output rows are out on the row thread (OrderedWorker), that thread appends
  // them to samples and energies, which this one then leaves alone (it drains them first); the
  // steps' statistics it writes meanwhile lie on another cache line (alignas).
  alignas(64) Simulation out_;
  // The output rows, made on a second thread while the steps go on (OrderedWorker), each from its
  // step as handed over; what they say of the drift and the energy is added to the statistics
  // when the rows are drained.
  std::unique_ptr<OutputRows> output_;     // made by the row thread, at its first job
  std::unique_ptr<OutputRows> rows_here_;  // the steps' thread's, made at the first job it takes
  long jobs_handed_over_ = 0;
  OrderedWorker<RowJob> output_worker_;  // last: its thread stops before what it uses goes
};

}  // namespace

bool rows_on_second_thread(const SimulationOptions& options) {
  const double step = options.output_step > 0 ? options.output_step : options.end_time / 100;
  return kSecondThreadPossible && options.threads != 1 && usable_cores() > 1 && options.end_time / step >= 64;
}

namespace testing {
void make_every_other_job_on_the_steps_thread(bool every) { g_rows_on_both_threads = every; }
}  // namespace testing

Simulation simulate(const Mechanism& mechanism, const SimulationOptions& options, const RunControl& control) {
  if (!(options.end_time > 0.0) || !std::isfinite(options.end_time))
    throw Error(ErrorKind::BadInput, "the simulated time must be a positive number of seconds");
  if (options.output_step < 0.0 || !std::isfinite(options.output_step))
    throw Error(ErrorKind::BadInput, "the output step must be a positive number of seconds");
  if (!(options.relative_tolerance > 0.0 && options.relative_tolerance < 1.0))
    throw Error(ErrorKind::BadInput, "the relative tolerance must be between 0 and 1");
  Run run(mechanism, options, control);
  return run.run();
}

namespace {

// The state the simulation reaches at `time`: the last row of the run to it, or the start.
Sample simulated_state_at(const Mechanism& mechanism, double time, SimulationOptions options, const RunControl& control,
                          long& accepted_steps) {
  if (time == 0.0) {
    // The start is the first row, kept before the first step: a run cancelled before it.
    RunControl at_start;
    at_start.token.cancel();
    options.end_time = 1.0;
    options.output_step = 0.0;
    options.stop_when.reset();
    return simulate(mechanism, options, at_start).samples.front();
  }
  options.end_time = time;
  const Simulation run = simulate(mechanism, options, control);
  accepted_steps = run.statistics.accepted_steps;
  if (run.cancelled) control.throw_stopped("simulate");
  const std::string before = "the simulation did not reach " + time_text(time) + ": ";
  if (!run.complete) throw Error(ErrorKind::StoppedAtLimit, before + run.stop_reason, run.stop_where);
  if (run.time_reached() < time * (1 - 1e-12))
    throw Error(ErrorKind::StoppedAtLimit, before + (run.events.empty() ? "it ended at " + time_text(run.time_reached())
                                                                        : run.events.back().message));
  return run.samples.back();
}

// The system [M Phi_q^T; Phi_q 0] [q''; lambda] = [Q; gamma] solved densely, and its relative residual.
void solve_written_system(EquationsOfMotionAt& out) {
  const Eigen::Index n = out.mass.rows(), m = out.jacobian.rows();
  Eigen::MatrixXd system = Eigen::MatrixXd::Zero(n + m, n + m);
  system.topLeftCorner(n, n) = out.mass;
  system.topRightCorner(n, m) = out.jacobian.transpose();
  system.bottomLeftCorner(m, n) = out.jacobian;
  Eigen::VectorXd rhs(n + m);
  rhs << out.forces, out.gamma;
  const Eigen::VectorXd solution = system.completeOrthogonalDecomposition().solve(rhs);
  out.acceleration = solution.head(n);
  out.multipliers = solution.tail(m);
  const double scale = std::max(rhs.lpNorm<Eigen::Infinity>(), std::numeric_limits<double>::min());
  out.residual = (system * solution - rhs).lpNorm<Eigen::Infinity>() / scale;
}

}  // namespace

EquationsOfMotionAt equations_of_motion_at(const Mechanism& mechanism, double time, SimulationOptions options,
                                           const RunControl& control) {
  if (!std::isfinite(time) || time < 0.0)
    throw Error(ErrorKind::BadInput,
                "the time of the equations of motion must be a number of seconds from 0, not " + std::to_string(time));
  const Model& m = mechanism.model();
  EquationsOfMotionAt out;
  for (const Driver& d : m.drivers)
    if (d.free) out.free_drivers.push_back(d.name);
  if (out.free_drivers.empty())
    throw Error(ErrorKind::InvalidModel,
                "nothing is free to move under the loads: the equations of motion need a driver marked `free: true`",
                {EntityRef::Kind::Driver, 0, -1});
  const Sample state = simulated_state_at(mechanism, time, options, control, out.accepted_steps);
  out.time = time;
  out.q = state.taylor.col(0);
  out.velocity = state.taylor.col(1);
  out.simulated_acceleration = 2.0 * state.taylor.col(2);
  out.coordinates.resize(out.q.size());
  for (std::size_t p = 0; p < m.points.size(); ++p)
    if (const int col = mechanism.column_of(static_cast<int>(p)); col >= 0) {
      out.coordinates[col] = m.points[p].name + ".x";
      out.coordinates[col + 1] = m.points[p].name + ".y";
    }
  EquationsOfMotion eq(mechanism, sweep_path(mechanism, 2).from);
  try {
    eq.factorise(time, out.q);
    out.gamma = eq.gamma(out.q, out.velocity);
    const EquationsOfMotion::ForceParts parts = eq.force_parts(time, out.q, out.velocity);
    out.gravity = parts.gravity;
    out.applied = parts.applied;
    out.springs = parts.springs;
    out.friction = parts.friction;
  } catch (const SimulationStop& stop) {
    throw Error(ErrorKind::InvalidModel, stop.reason, stop.where);
  }
  out.forces = out.gravity + out.applied + out.springs + out.friction;
  out.mass = eq.dense_mass();
  out.jacobian = eq.dense_jacobian();
  out.rows = eq.kept();
  for (int row : out.rows) out.row_labels.push_back(mechanism.row_label(row));
  solve_written_system(out);
  return out;
}

}  // namespace nbar

namespace nbar {

std::optional<StopCondition> parse_stop_condition(const std::string& text) {
  const auto trimmed = [](const std::string& s) {
    const std::size_t first = s.find_first_not_of(" \t");
    return first == std::string::npos ? std::string() : s.substr(first, s.find_last_not_of(" \t") - first + 1);
  };
  const std::size_t op = text.find_first_of("<>");
  if (op == std::string::npos || text.find_first_of("<>", op + 1) != std::string::npos) return std::nullopt;
  StopCondition condition;
  condition.above = text[op] == '>';
  condition.column = trimmed(text.substr(0, op));
  // ">=" reads as ">": a crossing of a continuous quantity is the same either way.
  const std::size_t number_start = op + 1 < text.size() && text[op + 1] == '=' ? op + 2 : op + 1;
  const std::string number = trimmed(text.substr(number_start));
  if (condition.column.empty() || condition.column.find_first_of(" \t=") != std::string::npos || number.empty())
    return std::nullopt;
  char* end = nullptr;
  condition.value = std::strtod(number.c_str(), &end);
  if (end != number.c_str() + number.size() || !std::isfinite(condition.value)) return std::nullopt;
  condition.text = condition.column + (condition.above ? " > " : " < ") + number;
  return condition;
}

}  // namespace nbar
