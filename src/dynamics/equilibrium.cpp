#include "nbar/dynamics/equilibrium.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>

#include "dynamics/golden_section.hpp"
#include "kinematics/rocking.hpp"
#include "kinematics/workspace.hpp"
#include "nbar/dynamics/inverse_dynamics.hpp"
#include "nbar/kinematics/position.hpp"

namespace nbar {

const char* to_string(Stability stability) {
  switch (stability) {
    case Stability::stable: return "stable";
    case Stability::unstable: return "unstable";
    case Stability::neutral: return "neutral";
  }
  return "stable";
}

namespace {

std::string number_text(double value) {
  std::ostringstream s;
  s.precision(6);
  s << value;
  return s.str();
}

// The free drivers' efforts at rest as functions of their values, every other driver held at
// its start: the equations the equilibrium zeroes, and their poses.
class HoldingEfforts {
 public:
  HoldingEfforts(const Mechanism& mech, const RunControl& control)
      : mech_(mech),
        control_(control),
        // The solver only borrows the mechanism for the call: no ownership to share.
        dynamics_(std::shared_ptr<const Mechanism>(&mech, [](const Mechanism*) {})),
        state_(mech),
        start_state_(mech) {
    const Model& m = mech.model();
    for (std::size_t d = 0; d < m.drivers.size(); ++d)
      if (m.drivers[d].free) free_.push_back(static_cast<int>(d));
    if (free_.empty())
      throw Error(ErrorKind::InvalidModel,
                  "nothing is free to find an equilibrium for: mark the drivers the loads should move with "
                  "`free: true`",
                  {EntityRef::Kind::Driver, 0, -1});
    start_ = assemble_at_time(mech, state_, 0.0, 0).driver_values;
    start_state_ = state_;
    // Steps of the finite differences and the largest Newton step, per free driver.
    const double size = mech.drawing_size();
    for (int d : free_) {
      const bool angular = m.drivers[d].is_angular();
      scale_.push_back(angular ? 1.0 : size);
    }
  }

  const std::vector<int>& free_drivers() const { return free_; }
  double scale(int i) const { return scale_[i]; }
  EntityRef where() const { return {EntityRef::Kind::Driver, free_.front(), -1}; }
  Eigen::VectorXd start() const {
    Eigen::VectorXd x(free_.size());
    for (std::size_t i = 0; i < free_.size(); ++i) x(static_cast<Eigen::Index>(i)) = start_[free_[i]];
    return x;
  }

  // Assembles the pose at x from the last pose found (the branch followed); false when there is none.
  bool assemble(const Eigen::VectorXd& x) {
    control_.checkpoint("equilibrium", 0, 0);
    State trial = state_;
    std::vector<Series> values;
    for (double v : start_) values.emplace_back(1, v);
    for (std::size_t i = 0; i < free_.size(); ++i) values[free_[i]] = Series(1, x(static_cast<Eigen::Index>(i)));
    set_drivers(mech_, trial, values);
    const NewtonReport report = solve_position(mech_, trial);
    if (!report.converged || !trial.q.allFinite()) return false;
    state_ = std::move(trial);
    values_ = start_;
    for (std::size_t i = 0; i < free_.size(); ++i) values_[free_[i]] = x(static_cast<Eigen::Index>(i));
    return true;
  }

  // The reciprocal condition and the determinant's sign (0 where not square or singular) of the
  // Jacobian of every row at the pose assembled last, the free drivers' rows at their values.
  std::pair<double, int> jacobian_at_pose() {
    if (!factorize_jacobian(mech_, state_)) return {0.0, 0};
    const bool square = mech_.row_count() == mech_.coordinate_count();
    return {sample_condition(state_), square ? state_.workspace().solver().determinant_sign() : 0};
  }

  // The least reciprocal condition of the Jacobian along the straight path of the free drivers'
  // values from the start to x, each pose assembled from the one before (the drawn branch
  // followed), its minima refined by golden section (next to a change point it falls as the
  // square root of the distance: the samples alone pass it at 0.07); 0 where the path cannot be
  // assembled. The pose assembled last is left as it was.
  double least_condition_on_the_way_to(const Eigen::VectorXd& x) {
    const State kept = state_;
    const std::vector<double> kept_values = values_;
    state_ = start_state_;
    const Eigen::VectorXd from = this->start();
    const auto condition_at = [&](double s) {
      return assemble(from + s * (x - from)) ? jacobian_at_pose().first : 0.0;
    };
    constexpr int kSamples = 64;
    std::vector<double> condition(kSamples + 1);
    std::vector<State> poses;
    for (int i = 0; i <= kSamples; ++i) {
      condition[i] = condition_at(static_cast<double>(i) / kSamples);
      poses.push_back(state_);
    }
    double least = *std::min_element(condition.begin(), condition.end());
    for (int i = 0; i <= kSamples && least > 0.0; ++i) {  // the ends too: a change point just past x
      const int before = std::max(i - 1, 0), after = std::min(i + 1, kSamples);
      if (!(condition[i] <= condition[before] && condition[i] <= condition[after])) continue;
      const auto from_sample_before = [&](double s) {  // each pose assembled from the sample before
        state_ = poses[before];
        return condition_at(s);
      };
      const double nearest = golden_minimum(from_sample_before, static_cast<double>(before) / kSamples,
                                            static_cast<double>(after) / kSamples, 1e-12);
      least = std::min(least, from_sample_before(nearest));
    }
    state_ = kept;
    values_ = kept_values;
    return least;
  }

  // The free drivers' holding efforts at the pose assembled last.
  Eigen::VectorXd efforts() const {
    const Sample sample = pose(2);
    const DynamicsResult result = dynamics_.solve(sample);
    Eigen::VectorXd out(free_.size());
    for (std::size_t i = 0; i < free_.size(); ++i) out(static_cast<Eigen::Index>(i)) = result.driver_effort[free_[i]];
    return out;
  }

  // The pose assembled last, at rest: [q, 0, ...] to `order`.
  Sample pose(int order) const {
    Sample sample;
    sample.time = 0.0;
    sample.driver_values = values_;
    sample.taylor = Eigen::MatrixXd::Zero(mech_.coordinate_count(), order + 1);
    sample.taylor.col(0) = state_.q;
    sample.residual = state_.residual;
    return sample;
  }

  // d(effort)/dx by central differences about x (assembled last, and again on return).
  Eigen::MatrixXd stiffness(const Eigen::VectorXd& x) {
    const Eigen::Index n = x.size();
    Eigen::MatrixXd k(n, n);
    const State at_x = state_;
    const std::vector<double> values_at_x = values_;
    for (Eigen::Index j = 0; j < n; ++j) {
      const double h = 1e-6 * scale_[j];
      Eigen::VectorXd side[2];
      for (int s = 0; s < 2; ++s) {
        Eigen::VectorXd moved = x;
        moved(j) += s == 0 ? h : -h;
        if (!assemble(moved))
          throw Error(ErrorKind::CannotAssemble,
                      "no equilibrium found: the mechanism cannot be assembled next to " + values_text(x) +
                          " (a limit of its motion)",
                      where());
        side[s] = efforts();
        state_ = at_x;
      }
      k.col(j) = (side[0] - side[1]) / (2 * h);
    }
    state_ = at_x;
    values_ = values_at_x;
    return k;
  }

  // "crank = 31.2 deg, slider = 120 mm": the free drivers' values in the model's units.
  std::string values_text(const Eigen::VectorXd& x) const {
    const Model& m = mech_.model();
    std::string out;
    for (std::size_t i = 0; i < free_.size(); ++i) {
      const Driver& d = m.drivers[free_[i]];
      const double v = x(static_cast<Eigen::Index>(i));
      out += (i ? ", " : "") + d.name + " = " +
             (d.is_angular() ? number_text(v / m.units.angle_scale) + " " + m.units.angle
                             : number_text(v / m.units.length_scale) + " " + m.units.length);
    }
    return out;
  }

 private:
  const Mechanism& mech_;
  const RunControl& control_;
  InverseDynamics dynamics_;
  State state_;
  State start_state_;  // the start's pose, where the path to the equilibrium is followed from
  std::vector<int> free_;
  std::vector<double> start_, values_, scale_;
};

// The stiffness's eigenvalues, smallest first, and what their signs say. An eigenvalue is taken
// as zero below 1e-8 of the largest, or of the loads' own scale when every one is that small.
void classify(Equilibrium& e, double load_scale) {
  const Eigen::MatrixXd symmetric = 0.5 * (e.stiffness + e.stiffness.transpose());
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(symmetric, Eigen::EigenvaluesOnly);
  e.eigenvalues.assign(solver.eigenvalues().data(), solver.eigenvalues().data() + solver.eigenvalues().size());
  double largest = load_scale;
  for (double v : e.eigenvalues) largest = std::max(largest, std::abs(v));
  const double zero = 1e-8 * largest;
  e.stability = Stability::stable;
  for (double v : e.eigenvalues)
    if (std::abs(v) <= zero && e.stability == Stability::stable) e.stability = Stability::neutral;
  for (double v : e.eigenvalues)
    if (v < -zero) e.stability = Stability::unstable;
}

// The largest |force_i| weighted by driver i's scale (N m for angles, N x size for lengths): the
// size Newton's line search compares.
double weighted_norm(const Eigen::VectorXd& force, const HoldingEfforts& h) {
  double worst = 0.0;
  for (Eigen::Index i = 0; i < force.size(); ++i)
    worst = std::max(worst, std::abs(force(i)) * h.scale(static_cast<int>(i)));
  return worst;
}

// A pose whose Jacobian's reciprocal condition is below this is at a toggle: the positions'
// tolerance (1e-12 of the size) blurs a change point's to about sqrt(1e-12) = 1e-6 (a
// parallelogram's equilibrium at its change point: 6e-7), and next to a dead centre it is about
// the angle from it.
constexpr double kToggleCondition = 1e-5;

// The equilibrium's warnings: at a toggle, or past one (the start's Jacobian given as at_start,
// the least condition on the straight way from the start as on_the_way).
std::vector<Warning> toggle_warnings(const std::pair<double, int>& at_start, const std::pair<double, int>& at_pose,
                                     double on_the_way, const std::string& where) {
  std::vector<Warning> out;
  if (at_pose.first < kToggleCondition)
    out.push_back(
        {"equilibrium_at_toggle", 0,
         "the equilibrium at " + where + " is at a toggle or change point (the constraint Jacobian is " +
             (at_pose.first > 0 ? "near singular there, its condition number " + number_text(1 / at_pose.first)
                                : "singular there") +
             "): the loads do not determine the motion there, and the stability is that of the start's "
             "branch only"});
  else if ((at_start.second != 0 && at_pose.second != 0 && at_start.second != at_pose.second) ||
           on_the_way < kToggleCondition)
    out.push_back({"equilibrium_past_toggle", 0,
                   "between the start and the equilibrium at " + where +
                       " the mechanism passed a toggle or change point (the constraint Jacobian's determinant changed "
                       "sign, or it became singular on the way): the equilibrium may be on another branch than the "
                       "drawn one"});
  return out;
}

}  // namespace

// Newton on the holding efforts, each step limited (half a radian, half the drawing's size) and
// halved until the efforts shrink, so that a start far off still converges to the nearest
// equilibrium on the start's branch. Converged when the step is below 1e-12 of the drivers'
// scale: the error of x is then of that order (quadratic convergence), well below the
// simulation's.
Equilibrium find_equilibrium(const Mechanism& mechanism, const EquilibriumOptions& options, const RunControl& control) {
  HoldingEfforts h(mechanism, control);
  Eigen::VectorXd x = h.start();
  if (!h.assemble(x))
    throw Error(ErrorKind::CannotAssemble, "the start cannot be assembled at " + h.values_text(x), h.where());
  Eigen::VectorXd force = h.efforts();
  const double start_scale = weighted_norm(force, h);
  const std::pair<double, int> jacobian_at_start = h.jacobian_at_pose();
  Equilibrium out;
  out.free_drivers = h.free_drivers();
  bool converged = false;
  for (int iteration = 0; iteration < options.max_iterations && !converged; ++iteration) {
    out.iterations = iteration + 1;
    const Eigen::MatrixXd k = h.stiffness(x);
    const Eigen::FullPivLU<Eigen::MatrixXd> lu(k);
    if (lu.rank() < k.rows() || lu.rcond() < 1e-13) {
      if (weighted_norm(force, h) <= 1e-12 * std::max(start_scale, 1e-300)) break;  // at rest already
      throw Error(ErrorKind::InvalidModel,
                  "there is no equilibrium near " + h.values_text(x) +
                      ": the loads on the free drivers are not balanced and do not change with their position "
                      "(the stiffness is zero), e.g. a constant torque that nothing resists",
                  h.where());
    }
    Eigen::VectorXd step = -lu.solve(force);
    double largest = 0.0;
    for (Eigen::Index i = 0; i < step.size(); ++i)
      largest = std::max(largest, std::abs(step(i)) / (0.5 * h.scale(static_cast<int>(i))));
    if (largest > 1.0) step /= largest;
    const double before = weighted_norm(force, h);
    bool moved = false;
    for (int halving = 0; halving < 30 && !moved; ++halving, step *= 0.5) {
      double size = 0.0;  // of the step, relative to the drivers' scale
      for (Eigen::Index i = 0; i < step.size(); ++i)
        size = std::max(size, std::abs(step(i)) / h.scale(static_cast<int>(i)));
      const Eigen::VectorXd trial = x + step;
      if (!h.assemble(trial)) continue;
      const Eigen::VectorXd trial_force = h.efforts();
      // Near the root rounding stops the decrease: a step that small is taken as it is.
      if (!(weighted_norm(trial_force, h) < before) && size > 1e-10) continue;
      x = trial;
      force = trial_force;
      moved = true;
      converged = size <= 1e-12;
    }
    if (!moved) break;
  }
  if (!h.assemble(x)) throw Error(ErrorKind::CannotAssemble, "the equilibrium's pose cannot be assembled", h.where());
  force = h.efforts();
  out.pose = h.pose(0);
  out.forces.resize(force.size());
  for (Eigen::Index i = 0; i < force.size(); ++i) out.forces[i] = -force(i);
  out.residual = force.cwiseAbs().maxCoeff();
  out.stiffness = h.stiffness(x);
  if (!converged) {
    // The step stalled: accept only a point where the force is at rounding level.
    const double tolerance = 1e-9 * std::max(start_scale, out.stiffness.cwiseAbs().maxCoeff());
    if (!(weighted_norm(force, h) <= tolerance))
      throw Error(ErrorKind::InvalidModel,
                  "no equilibrium found: after " + std::to_string(out.iterations) +
                      " Newton iterations the generalised force on the free drivers is still " +
                      number_text(out.residual) + " (N m or N) at " + h.values_text(x),
                  h.where());
  }
  classify(out, 1e-12 * start_scale);
  out.warnings =
      toggle_warnings(jacobian_at_start, h.jacobian_at_pose(), h.least_condition_on_the_way_to(x), h.values_text(x));
  return out;
}

ResultTable equilibrium_table(const Mechanism& mechanism, const Equilibrium& equilibrium) {
  ResultTable table;
  KinematicRows rows(mechanism, 0);
  rows.name_columns(table.columns, table.units);
  std::vector<double> row(table.columns.size());
  rows.fill(equilibrium.pose, row.data());
  table.rows.push_back(std::move(row));
  return table;
}

}  // namespace nbar
