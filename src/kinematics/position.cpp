#include "nbar/kinematics/position.hpp"

#include "nbar/kinematics/sized.hpp"

#include <algorithm>
#include <cmath>

namespace nbar {

State::State(const Mechanism& mech) : solvers_{LinearSolver(mech), LinearSolver(mech)} {
  q = mech.drawn_coordinates();
  drivers.resize(mech.model().drivers.size());
  for (std::size_t d = 0; d < drivers.size(); ++d)
    drivers[d] = make_driver_state(Series(1, mech.drawn_driver_values()[d]), mech.model().drivers[d].is_angular());
  series = q;
  phi.resize(mech.row_count());
  rhs.resize(mech.row_count());
  dq.resize(mech.coordinate_count());
}

void set_drivers(const Mechanism& mech, State& state, const std::vector<Series>& values) {
  const auto& drivers = mech.model().drivers;
  for (std::size_t d = 0; d < drivers.size(); ++d)
    set_driver_state(state.drivers[d], values[d], drivers[d].is_angular());
}

bool factorize_jacobian(const Mechanism& mech, State& state, LinearSolver& solver) {
  evaluate_jacobian(mech, state.q, state.drivers, state.jacobian);
  return solver.factorize(state.jacobian);
}

bool factorize_jacobian(const Mechanism& mech, State& state) { return factorize_jacobian(mech, state, state.solver()); }

double max_residual(const Mechanism& mech, State& state, int* worst_row) {
  const double largest = evaluate_residuals(mech, state.q, state.drivers, state.phi);
  if (worst_row && state.phi.size() > 0) {
    // The first row of the largest size, or the first NaN.
    const double* phi = state.phi.data();
    Eigen::Index worst = 0;
    for (Eigen::Index i = 0; i < state.phi.size(); ++i) {
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
  const double tol = mech.tolerance();
  double r = max_residual(mech, state, &report.worst_row);
  double merit = state.phi.squaredNorm();
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
      merit = state.phi.squaredNorm();
      if (trace) {
        trace->iterates.back().dq = state.q - q_before;
        trace->iterates.back().nudged = true;
        trace->iterates.push_back({state.q, r, {}, 1.0, false});
      }
      continue;
    }
    state.rhs = -state.phi;
    state.solver().solve(state.rhs, state.dq);
    // Backtracking on |Phi|^2 keeps a far starting guess from overshooting into another branch.
    const Eigen::VectorXd q0 = state.q;
    double step = 1.0;
    bool improved = false;
    for (int halving = 0; halving < 30; ++halving) {
      state.q = q0 + step * state.dq;
      r = max_residual(mech, state, &report.worst_row);
      const double trial = state.phi.squaredNorm();
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

// compute_series for N coordinates known when compiled (nbar/kinematics/sized.hpp), or with
// N = 0 any number.
template <int N>
void series_sized(const Mechanism& mech, State& state, const std::vector<DriverState>& drivers, int terms,
                  Eigen::MatrixXd& out) {
  const int n = N > 0 ? N : mech.coordinate_count();
  if (out.rows() != n || out.cols() != terms) out.resize(n, terms);
  copy_numbers<N>(state.q.data(), n, out.data());
  for (int k = 1; k < terms; ++k) {
    // Phi_q q_k = -R_k, solved for -q_k and turned round (exactly) in place.
    evaluate_series_remainder(mech, out, k, drivers, state.rhs);
    double* column = out.col(k).data();
    if constexpr (N > 0) {
      state.solver().solve_dense<N>(state.rhs.data(), column);
    } else {
      state.solver().solve(state.rhs.data(), column);
    }
    for (int i = 0; i < n; ++i) column[i] = -column[i];
  }
}

}  // namespace

void compute_series(const Mechanism& mech, State& state, const std::vector<DriverState>& drivers, int terms,
                    Eigen::MatrixXd& out) {
  const bool lu = state.solver().method() == LinearSolver::Method::LU;
  with_coordinate_count(lu ? mech.coordinate_count() : 0,
                        [&](auto n) { series_sized<decltype(n)::value>(mech, state, drivers, terms, out); });
}

void compute_series(const Mechanism& mech, State& state, int terms) {
  compute_series(mech, state, state.drivers, terms, state.series);
}

}  // namespace nbar
