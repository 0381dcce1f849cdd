#include "nbar/kinematics/position.hpp"

#include <algorithm>
#include <cmath>

#include "constraints.hpp"
#include "sized.hpp"
#include "workspace.hpp"

namespace nbar {

State::Workspace::Workspace(const Mechanism& mech) : solvers_{LinearSolver(mech), LinearSolver(mech)} {
  phi.resize(mech.row_count());
  rhs.resize(mech.row_count());
  dq.resize(mech.coordinate_count());
}

State::WorkspaceCopy::WorkspaceCopy(const Mechanism& mech) : owned_(std::make_unique<Workspace>(mech)) {}
State::WorkspaceCopy::WorkspaceCopy(const WorkspaceCopy& other) : owned_(std::make_unique<Workspace>(*other.owned_)) {}
State::WorkspaceCopy& State::WorkspaceCopy::operator=(const WorkspaceCopy& other) {
  if (this != &other) owned_ = std::make_unique<Workspace>(*other.owned_);
  return *this;
}
State::WorkspaceCopy::WorkspaceCopy(WorkspaceCopy&& other) noexcept = default;
State::WorkspaceCopy& State::WorkspaceCopy::operator=(WorkspaceCopy&& other) noexcept = default;
State::WorkspaceCopy::~WorkspaceCopy() = default;

State::State(const Mechanism& mech) : workspace_(mech) {
  q = mech.drawn_coordinates();
  drivers.resize(mech.model().drivers.size());
  for (std::size_t d = 0; d < drivers.size(); ++d)
    drivers[d] = make_driver_state(Series(1, mech.drawn_driver_values()[d]), mech.model().drivers[d].is_angular());
  series = q;
}

void set_drivers(const Mechanism& mech, State& state, const std::vector<Series>& values) {
  const auto& drivers = mech.model().drivers;
  for (std::size_t d = 0; d < drivers.size(); ++d)
    set_driver_state(state.drivers[d], values[d], drivers[d].is_angular());
}

bool factorize_jacobian(const Mechanism& mech, State& state, LinearSolver& solver) {
  std::vector<double>& jacobian = state.workspace().jacobian;
  evaluate_jacobian(mech, state.q, state.drivers, jacobian);
  return solver.factorize(jacobian);
}

bool factorize_jacobian(const Mechanism& mech, State& state) {
  return factorize_jacobian(mech, state, state.workspace().solver());
}

double max_residual(const Mechanism& mech, State& state, int* worst_row) {
  Eigen::VectorXd& residuals = state.workspace().phi;
  const double largest = evaluate_residuals(mech, state.q, state.drivers, residuals);
  if (worst_row && residuals.size() > 0) {
    // The first row of the largest size, or the first NaN.
    const double* phi = residuals.data();
    Eigen::Index worst = 0;
    for (Eigen::Index i = 0; i < residuals.size(); ++i) {
      if (std::isnan(phi[i])) {
        worst = i;
        break;
      }
      if (std::abs(phi[i]) > std::abs(phi[worst])) worst = i;
    }
    *worst_row = static_cast<int>(worst);
  }
  return largest;
}

NewtonReport solve_position(const Mechanism& mech, State& state, int max_iterations, NewtonTrace* trace) {
  NewtonReport report;
  State::Workspace& work = state.workspace();
  const double tol = mech.tolerance();
  double r = max_residual(mech, state, &report.worst_row);
  double merit = work.phi.squaredNorm();
  if (trace) trace->iterates.push_back({state.q, r, {}, 1.0, false});
  for (int it = 0; it < max_iterations; ++it) {
    report.iterations = it;
    if (r <= tol) break;
    if (!factorize_jacobian(mech, state)) {
      // A singular Jacobian away from the solution: nudge the pose off the singular set.
      const double eps = 1e-6 * mech.characteristic_length();
      const Eigen::VectorXd q_before = trace ? state.q : Eigen::VectorXd();
      for (Eigen::Index i = 0; i < state.q.size(); ++i) state.q[i] += eps * std::sin(1.0 + 7.0 * i);
      r = max_residual(mech, state, &report.worst_row);
      merit = work.phi.squaredNorm();
      if (trace) {
        trace->iterates.back().dq = state.q - q_before;
        trace->iterates.back().nudged = true;
        trace->iterates.push_back({state.q, r, {}, 1.0, false});
      }
      continue;
    }
    work.rhs = -work.phi;
    work.solver().solve(work.rhs, work.dq);
    // Backtracking on |Phi|^2 keeps a far starting guess from overshooting into another branch.
    const Eigen::VectorXd q0 = state.q;
    double step = 1.0;
    bool improved = false;
    for (int halving = 0; halving < 30; ++halving) {
      state.q = q0 + step * work.dq;
      r = max_residual(mech, state, &report.worst_row);
      const double trial = work.phi.squaredNorm();
      if (std::isfinite(trial) && trial < (1.0 - 1e-4 * step) * merit) {
        merit = trial;
        improved = true;
        break;
      }
      step *= 0.5;
    }
    if (!improved) {
      state.q = q0;
      r = max_residual(mech, state, &report.worst_row);
      break;
    }
    if (trace) {
      trace->iterates.back().dq = state.q - q0;
      trace->iterates.back().damping = step;
      trace->iterates.push_back({state.q, r, {}, 1.0, false});
    }
  }
  report.residual = r;
  report.converged = r <= tol;
  if (report.converged) report.converged = factorize_jacobian(mech, state);
  state.residual = r;
  state.iterations = report.iterations;
  return report;
}

namespace {

// compute_series for N coordinates known when compiled (kinematics/sized.hpp), or with
// N = 0 any number.
template <int N>
void series_sized(const Mechanism& mech, State& state, const std::vector<DriverState>& drivers, int terms,
                  Eigen::MatrixXd& out) {
  State::Workspace& work = state.workspace();
  const int n = N > 0 ? N : mech.coordinate_count();
  if (out.rows() != n || out.cols() != terms) out.resize(n, terms);
  copy_numbers<N>(state.q.data(), n, out.data());
  for (int k = 1; k < terms; ++k) {
    // Phi_q q_k = -R_k, solved for -q_k and turned round (exactly) in place.
    evaluate_series_remainder(mech, out, k, drivers, work.rhs);
    double* column = out.col(k).data();
    if constexpr (N > 0) {
      work.solver().solve_dense<N>(work.rhs.data(), column);
    } else {
      work.solver().solve(work.rhs.data(), column);
    }
    for (int i = 0; i < n; ++i) column[i] = -column[i];
  }
}

}  // namespace

void compute_series(const Mechanism& mech, State& state, const std::vector<DriverState>& drivers, int terms,
                    Eigen::MatrixXd& out) {
  const bool lu = state.workspace().solver().method() == LinearSolver::Method::LU;
  with_coordinate_count(lu ? mech.coordinate_count() : 0,
                        [&](auto n) { series_sized<decltype(n)::value>(mech, state, drivers, terms, out); });
}

void compute_series(const Mechanism& mech, State& state, int terms) {
  compute_series(mech, state, state.drivers, terms, state.series);
}

}  // namespace nbar
