#include "nbar/kinematics/continuation.hpp"

#include <cmath>
#include <numbers>
#include <sstream>

#include "nbar/kinematics/loop_closure.hpp"

namespace nbar {

namespace {

constexpr int kMaxCorrections = 8;
// A correction larger than this fraction of the predicted motion looks like a jump to
// another branch: the step is retried shorter.
constexpr double kMaxCorrectionRatio = 0.1;
// Below this fraction of the interval a sign change of det(Phi_q) is taken as a genuine
// crossing of a singular position rather than a jump.
constexpr double kCrossingStep = 1e-4;

void predict(const Eigen::MatrixXd& series, double h, Eigen::VectorXd& q) {
  q = series.col(series.cols() - 1);
  for (Eigen::Index k = series.cols() - 2; k >= 0; --k) q = series.col(k) + h * q;
}

// Simplified Newton with the factorisation of the last accepted point; it never destroys
// that factorisation, so a failed step can be retried shorter. On success `residual` is the
// largest |Phi| at the point found.
bool correct(const Mechanism& mech, State& state, const Eigen::VectorXd& q_old, const Eigen::VectorXd& q_pred,
             double& residual) {
  const double tol = mech.tolerance();
  const double motion = (q_pred - q_old).lpNorm<Eigen::Infinity>();
  const double allowed = std::max(kMaxCorrectionRatio * motion, 100.0 * tol);
  double previous = std::numeric_limits<double>::infinity();
  for (int it = 0; it <= kMaxCorrections; ++it) {
    residual = max_residual(mech, state);
    if (residual <= tol) return true;
    if (it == kMaxCorrections) return false;
    state.rhs = -state.phi;
    state.solver().solve(state.rhs, state.dq);
    const double size = state.dq.lpNorm<Eigen::Infinity>();
    if (!std::isfinite(size) || size > 0.5 * previous) return false;
    previous = size;
    state.q += state.dq;
    if ((state.q - q_pred).lpNorm<Eigen::Infinity>() > allowed) return false;
  }
  return false;
}

}  // namespace

TrackReport track(const Mechanism& mech, State& state, const DriverPath& path, double p_end,
                  const TrackOptions& options) {
  TrackReport report;
  const double span = p_end - state.parameter;
  const double h_min = std::abs(span) * options.min_step;
  double h = span;
  std::vector<Series>& values = state.driver_values;
  Eigen::VectorXd& q_old = state.q_accepted;
  Eigen::VectorXd& q_pred = state.q_predicted;
  q_old = state.q;
  int sign_old = state.solver().determinant_sign();
  // The residual at the last accepted point, as correct() found it there (with the drivers
  // where they are now): computing it again at the end would give the same number.
  double residual = 0.0;
  bool residual_known = false;

  while (true) {
    const double remaining = p_end - state.parameter;
    if (std::abs(remaining) <= 1e-13 * std::max(std::abs(span), std::abs(p_end))) break;
    if (std::abs(h) > std::abs(remaining)) h = remaining;

    predict(state.series, h, q_pred);
    path(state.parameter + h, options.terms, values);
    set_drivers(mech, state, values);
    state.q = q_pred;
    double trial_residual = 0.0;
    bool ok = correct(mech, state, q_old, q_pred, trial_residual) &&
              factorize_jacobian(mech, state, state.spare_solver());
    bool crossing = false;
    if (ok) {
      const int sign_new = state.spare_solver().determinant_sign();
      if (sign_old != 0 && sign_new != 0 && sign_new != sign_old) {
        crossing = true;
        if (std::abs(h) > kCrossingStep * std::abs(span)) ok = false;
      }
    }
    if (ok) {
      state.parameter += h;
      state.swap_solvers();
      compute_series(mech, state, options.terms);
      sign_old = state.solver().determinant_sign();
      q_old = state.q;
      residual = trial_residual;
      residual_known = true;
      ++report.steps;
      if (crossing) {
        report.passed_singularity = true;
        report.singular_parameter = state.parameter - 0.5 * h;
      }
      h *= 2.0;
      continue;
    }
    // Reject: back to the last accepted point, shorter step.
    state.q = q_old;
    path(state.parameter, options.terms, values);
    set_drivers(mech, state, values);
    h *= 0.5;
    if (std::abs(h) < h_min) {
      report.limit_parameter = state.parameter;
      report.reciprocal_condition = state.solver().reciprocal_condition();
      std::ostringstream why;
      why << "the constraints cannot be followed past this point: a singular position, either a limit (toggle) "
             "that the input cannot pass or a change point where two branches cross (reciprocal condition of the "
             "Jacobian "
          << report.reciprocal_condition << ")";
      report.reason = why.str();
      state.residual = max_residual(mech, state);
      return report;
    }
  }
  state.residual = residual_known ? residual : max_residual(mech, state);
  report.reached = true;
  return report;
}

namespace {

double wrap_angle(double a) {
  return a - 2.0 * std::numbers::pi * std::round(a / (2.0 * std::numbers::pi));
}

std::string worst_constraint_message(const Mechanism& mech, State& state) {
  int worst = -1;
  const double r = max_residual(mech, state, &worst);
  if (worst < 0) return "";
  const Model& m = mech.model();
  std::ostringstream s;
  s << "constraint '" << mech.rows()[worst].label << "' cannot be met (off by " << r / m.units.length_scale << " "
    << m.units.length << ")";
  return s.str();
}

}  // namespace

std::string format_driver_value(const Model& m, int d, double si) {
  std::ostringstream s;
  if (m.drivers[d].is_angular())
    s << si / m.units.angle_scale << " " << m.units.angle;
  else
    s << si / m.units.length_scale << " " << m.units.length;
  return s.str();
}

AssemblyReport assemble(const Mechanism& mech, State& state, const std::vector<double>& start) {
  const Model& m = mech.model();
  const int nd = static_cast<int>(m.drivers.size());
  const std::vector<double>& drawn = mech.drawn_driver_values();
  TrackOptions options;
  AssemblyReport report;

  // Angles are reached the short way round first; when that meets a limit, the long way.
  std::vector<double> delta(nd), other_way(nd);
  bool has_other_way = false;
  for (int d = 0; d < nd; ++d) {
    delta[d] = other_way[d] = start[d] - drawn[d];
    if (m.drivers[d].is_angular()) {
      delta[d] = wrap_angle(delta[d]);
      if (delta[d] != 0.0) {
        other_way[d] = delta[d] - std::copysign(2.0 * std::numbers::pi, delta[d]);
        has_other_way = true;
      }
    }
  }
  const std::vector<double>* active = &delta;
  const DriverPath path = [&](double p, int terms, std::vector<Series>& out) {
    out.resize(nd);
    for (int d = 0; d < nd; ++d) {
      out[d] = Series(terms, drawn[d] + p * (*active)[d]);
      if (terms > 1) out[d][1] = (*active)[d];
    }
  };

  auto start_from_drawing = [&] {
    state.q = mech.drawn_coordinates();
    state.parameter = 0.0;
    std::vector<Series> values;
    path(0.0, options.terms, values);
    set_drivers(mech, state, values);
    const NewtonReport newton = solve_position(mech, state);
    report.newton_iterations = newton.iterations;
    if (!newton.converged) {
      int worst = -1;
      max_residual(mech, state, &worst);
      const std::string open_loop = loop_closure_failure(mech.model(), mech.four_bar_loops());
      throw AssemblyError("cannot assemble the drawn pose with the given lengths: " +
                              (open_loop.empty() ? worst_constraint_message(mech, state) : open_loop),
                          worst, worst >= 0 ? mech.rows()[worst].source : EntityRef{});
    }
    compute_series(mech, state, options.terms);
  };

  start_from_drawing();
  TrackReport tracked = track(mech, state, path, 1.0, options);
  if (!tracked.reached && has_other_way) {
    const TrackReport first = tracked;
    const Eigen::VectorXd q_first = state.q;
    active = &other_way;
    start_from_drawing();
    tracked = track(mech, state, path, 1.0, options);
    if (!tracked.reached) {  // report the short way's limit, the one users expect
      active = &delta;
      tracked = first;
      state.q = q_first;
    }
  }
  if (!tracked.reached) {
    std::ostringstream s;
    s << "cannot reach the drivers' starting values from the drawn pose on its branch";
    for (int d = 0; d < nd; ++d) {
      if ((*active)[d] == 0.0) continue;
      s << "; driver '" << m.drivers[d].name << "' stops at "
        << format_driver_value(m, d, drawn[d] + tracked.limit_parameter * (*active)[d]) << " (drawn "
        << format_driver_value(m, d, drawn[d]) << ", wanted " << format_driver_value(m, d, start[d]) << ")";
      if (m.drivers[d].is_angular() && has_other_way) s << " either way round";
    }
    std::vector<Series> values;
    path(1.0, options.terms, values);
    set_drivers(mech, state, values);
    int worst = -1;
    if (solve_position(mech, state, 20).converged) {
      s << "; the wanted values can only be assembled on another branch: draw the mechanism on that branch";
    } else {
      const double r = max_residual(mech, state, &worst);
      s << "; at the wanted values constraint '" << mech.rows()[worst].label
        << "' cannot be met (the closest pose found leaves it off by " << r / m.units.length_scale << " "
        << m.units.length << ")";
    }
    throw AssemblyError(s.str(), worst, worst >= 0 ? mech.rows()[worst].source : EntityRef{});
  }
  report.passed_singularity = tracked.passed_singularity;
  report.residual = state.residual;
  return report;
}

}  // namespace nbar
