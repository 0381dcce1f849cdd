#include "nbar/kinematics/continuation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

#include "constraints.hpp"
#include "nbar/kinematics/loop_closure.hpp"
#include "sized.hpp"
#include "workspace.hpp"

namespace nbar {

namespace {

constexpr int kMaxCorrections = 8;
// The corrections go on until the pose is known to its rounding, not only to the tolerance: a
// pose's residual r leaves it off by about r / sigma_min, and its velocities and accelerations by
// that over sigma_min and sigma_min^2, so that near a limit a pose merely within the tolerance
// (1e-12 of the linkage's size) gave accelerations off by 5e-8 of L w^2 0.3 deg from a six-bar's
// limit (tests/kinematics/near_limit_test.cpp). They stop when the correction just solved, or the
// next one as the contraction of the last two predicts it, is below this many units in the last
// place of every point's coordinates (of the linkage's size for a point nearer the origin than
// that): what is left is rounding, which further corrections would only stir. A correction found
// to be rounding is not applied, so that the Jacobian evaluated with the residuals is the point's
// own. A correction that does not contract by half ends them too: the factorisation they reuse
// is too far from the point (near a singular position), and the point gets a Newton step with
// its own Jacobian (polish) if the tolerance is met.
constexpr double kRoundingUlps = 8.0;
// A correction larger than this fraction of the predicted motion looks like a jump to
// another branch: the step is retried shorter.
constexpr double kMaxCorrectionRatio = 0.1;
// Below this fraction of the interval a sign change of det(Phi_q) is taken as a genuine
// crossing of a singular position rather than a jump.
constexpr double kCrossingStep = 1e-4;
constexpr double kContinuedCorrection = 1e-6;
// Below this reciprocal condition a point is too near a singular position for its own Jacobian
// to give its series: they would carry about 1/rcond times the rounding error, and the next
// prediction would start off towards either of the branches that cross there.
constexpr double kCoastRcond = 1e-8;
// Below this reciprocal condition an end point lies on a singular position: a pose converged to
// the tolerance lies about sqrt(tolerance) from the singular one, where the condition is about
// 1e-6; its series come from a regular point beside it (coast_to_singular_end).
constexpr double kSingularEndRcond = 1e-5;
// The series re-centred onto a singular end point: as many terms as a Series holds.
constexpr int kCoastSeriesTerms = Series::kCapacity;
// Positions, velocities and accelerations there are checked, to 1e-6 (the sweep reports how
// well they are known); higher derivatives, whose rounding grows as a power of the distance
// from the singular position, are not.
constexpr int kCoastCheckedTerms = 3;
constexpr double kCoastMaxError = 1e-6;
// Below this reciprocal condition at the current point the predictor does not use the past one.
constexpr double kHistoryRcond = 1e-4;
// Without the past point, the predictor is the current point's series with this many terms.
constexpr int kTaylorPredictorTerms = 4;
// A step whose end is this much worse conditioned than its start, and singular, landed on a
// singular position; it is retried this much shorter.
constexpr double kSuddenRcondDrop = 1e-2;
constexpr double kOffSingularShrink = 0.7;

void predict(const Eigen::MatrixXd& series, double h, Eigen::VectorXd& q) {
  q = series.col(series.cols() - 1);
  for (Eigen::Index k = series.cols() - 2; k >= 0; --k) q = series.col(k) + h * q;
}

// max(largest, |x|), NaN if either is: the loops below run every step on a few coordinates,
// where Eigen's expression set-up costs more than the arithmetic.
void grow(double& largest, double x) {
  const double size = std::abs(x);
  if (!(size <= largest) && !std::isnan(largest)) largest = size;
}

// A step's work on the coordinates, for N of them known when compiled (sized.hpp:
// the loops unroll, which is most of a small mechanism's step) or, with N = 0, as many as the
// vectors hold.
template <int N>
Eigen::Index coordinates(const Eigen::VectorXd& q) {
  if constexpr (N > 0) {
    return N;
  } else {
    return q.size();
  }
}

template <int N>
void copy_coordinates(const Eigen::VectorXd& from, Eigen::VectorXd& to) {
  if constexpr (N > 0) {
    if (to.size() != N) to.resize(N);
    copy_numbers<N>(from.data(), N, to.data());
  } else {
    to = from;
  }
}

// x = J^-1 b with a solver's factors.
template <int N>
void solve_with(LinearSolver& solver, const double* b, double* x) {
  if constexpr (N > 0) {
    solver.solve_dense<N>(b, x);
  } else {
    solver.solve(b, x);
  }
}

template <int N>
double largest_difference(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  double largest = 0.0;
  for (Eigen::Index i = 0; i < coordinates<N>(a); ++i) grow(largest, a[i] - b[i]);
  return largest;
}

// A correction's size in units of its points' own scale: the largest |dq| of a point over the
// larger of its distance from the origin (the larger coordinate) and the linkage's size. A point
// is known to about the rounding of its coordinates, so that a point riding along far out (a
// centre of mass drawn as a point 470 m from a 5 m linkage, its correction the coupler's times
// its lever) does not stop the joints' corrections at its own rounding.
template <int N>
double relative_size(const Eigen::VectorXd& dq, const Eigen::VectorXd& q, double length) {
  double largest = 0.0;
  for (Eigen::Index i = 0; i + 1 < coordinates<N>(q); i += 2) {
    const double scale = std::max({std::abs(q[i]), std::abs(q[i + 1]), length});
    grow(largest, std::max(std::abs(dq[i]), std::abs(dq[i + 1])) / scale);
  }
  return largest;
}

// Simplified Newton with the factorisation of the last accepted point; it never destroys
// that factorisation, so a failed step can be retried shorter. On success `residual` is the
// largest |Phi| at the point found (the workspace's phi holds its rows) and the point is known to
// its rounding (kRoundingUlps), or, with `short_of_rounding` set, the corrections stopped
// contracting first (within the tolerance): the caller finishes with the point's own Jacobian
// (polish). The predicted point is corrected at least once even when it already meets the
// tolerance. On success the workspace's jacobian holds the Jacobian's values at the point found.
template <int N>
bool correct(const Mechanism& mech, State& state, const Eigen::VectorXd& q_old, const Eigen::VectorXd& q_pred,
             double& residual, bool& short_of_rounding) {
  State::Workspace& work = state.workspace();
  const double tol = mech.tolerance();
  const double rounding = kRoundingUlps * std::numeric_limits<double>::epsilon();
  const double length = mech.characteristic_length();
  const double motion = largest_difference<N>(q_pred, q_old);
  const double allowed = std::max(kMaxCorrectionRatio * motion, 100.0 * tol);
  double previous = std::numeric_limits<double>::infinity();
  double next = previous;  // the next correction's size, from the contraction of the last two
  const Eigen::Index n = coordinates<N>(state.q);
  short_of_rounding = false;
  // The Jacobian is evaluated with the residuals only where the point is expected to be the last
  // (the next correction predicted to be rounding), else once the corrections end: a step's
  // corrections before its last need only the residuals.
  bool jacobian_here = false;
  const auto done = [&](bool ok) {
    if (ok && !jacobian_here) evaluate_jacobian(mech, state.q, state.drivers, work.jacobian);
    return ok;
  };
  const auto stop_within_tolerance = [&](int it) {
    short_of_rounding = it > 0 && residual <= tol;
    return done(short_of_rounding);
  };
  for (int it = 0; it <= kMaxCorrections; ++it) {
    jacobian_here = it > 0 && next <= rounding;
    residual = jacobian_here ? evaluate_residuals_and_jacobian(mech, state.q, state.drivers, work.phi, work.jacobian)
                             : evaluate_residuals(mech, state.q, state.drivers, work.phi);
    if (jacobian_here) return residual <= tol;
    if (it == kMaxCorrections) return stop_within_tolerance(it);
    // Phi_q dq = -Phi: solved for -dq, which is subtracted.
    if (work.dq.size() != n) work.dq.resize(n);
    solve_with<N>(work.solver(), work.phi.data(), work.dq.data());
    const double size = relative_size<N>(work.dq, state.q, length);
    // Rounding already: left unapplied, so that the Jacobian is the point's.
    if (it > 0 && size <= rounding) return done(residual <= tol);
    if (!std::isfinite(size) || size > 0.5 * previous) return stop_within_tolerance(it);
    if (it > 0) next = size * (size / previous);
    previous = size;
    double moved = 0.0;
    for (Eigen::Index i = 0; i < n; ++i) {
      state.q[i] -= work.dq[i];
      grow(moved, state.q[i] - q_pred[i]);
    }
    // Written so that a NaN fails it.
    if (!(moved <= allowed)) return false;
  }
  return false;
}

// A point the simplified Newton left short of its rounding, with `solver` factorised at it
// and the workspace's phi its residuals: one Newton correction with that Jacobian, then the
// Jacobian factorised again at the corrected point, so that the series come from the point they
// are for.
// Returns false when that Jacobian is singular.
bool polish(const Mechanism& mech, State& state, LinearSolver& solver, double& residual) {
  State::Workspace& work = state.workspace();
  const Eigen::Index n = state.q.size();
  work.dq.resize(n);
  solver.solve(work.phi.data(), work.dq.data());
  for (Eigen::Index i = 0; i < n; ++i) state.q[i] -= work.dq[i];
  residual = max_residual(mech, state);
  return factorize_jacobian(mech, state, solver);
}

// Re-centres a Taylor polynomial (coefficients in columns) from p to p + d: synthetic division.
void shift_series(Eigen::MatrixXd& c, double d) {
  const Eigen::Index terms = c.cols();
  for (Eigen::Index i = 0; i + 1 < terms; ++i)
    for (Eigen::Index k = terms - 2; k >= i; --k) c.col(k) += d * c.col(k + 1);
}

double binomial(int n, int k) {
  double b = 1.0;
  for (int i = 1; i <= k; ++i) b = b * (n - k + i) / i;
  return b;
}

// How far the series at a point, re-centred by d, may be off in their first `checked`
// coefficients, relative to each: the last term's share of it. That share is truncation far
// from the singular position and rounding near it (the k-th coefficient computed at a distance
// d from a singular Jacobian carries about 1e-16 / d^k), so it bounds both.
double shift_error(const Eigen::MatrixXd& series, const Eigen::MatrixXd& shifted, double d, int checked) {
  const int last = static_cast<int>(series.cols()) - 1;
  const double tail = series.col(last).lpNorm<Eigen::Infinity>();
  double worst = 0.0;
  for (int j = 0; j < checked && j < last; ++j) {
    const double share = binomial(last, j) * std::pow(std::abs(d), last - j) * tail;
    const double size = shifted.col(j).lpNorm<Eigen::Infinity>();
    worst = std::max(worst, size > 0.0 ? share / size : (share > 0.0 ? HUGE_VAL : 0.0));
  }
  return std::isfinite(worst) ? worst : HUGE_VAL;
}

// Back at the start of the track: q_track_start at p_start, factorised, its series computed.
bool restart(const Mechanism& mech, State& state, const DriverPath& path, double p_start, int terms) {
  State::Workspace& work = state.workspace();
  state.q = work.q_track_start;
  state.parameter = p_start;
  path(p_start, terms, work.driver_values);
  set_drivers(mech, state, work.driver_values);
  if (!factorize_jacobian(mech, state)) return false;
  // The series whatever the condition, so that a failed restart still leaves the start's own.
  compute_series(mech, state, terms);
  return work.solver().reciprocal_condition() >= kCoastRcond;
}

// The series at p_end from those at a regular point p_end - distance (before it, or beyond it
// when distance < 0), tracked to from the start. Positions at p_end are polished with that
// point's factorisation. Returns the estimated relative error, or infinity when the point
// cannot be reached or p_end turns out to be regular after all.
double series_from(const Mechanism& mech, State& state, const DriverPath& path, double p_start, double p_end,
                   double distance, const TrackOptions& options) {
  State::Workspace& work = state.workspace();
  TrackOptions plain = options;
  plain.coast_terms = 0;
  const double p_b = p_end - distance;
  try {
    if (!restart(mech, state, path, p_start, options.terms)) return HUGE_VAL;
    const TrackReport reach = track(mech, state, path, p_b, plain);
    // Before p_end the way there must stay on one side of the singular position.
    if (!reach.reached || (distance > 0.0 && reach.passed_singularity)) return HUGE_VAL;
    if (work.solver().reciprocal_condition() < kCoastRcond) return HUGE_VAL;
    path(p_b, kCoastSeriesTerms, work.driver_values);
  } catch (const Error&) {  // beyond the end of the sweep a law may be undefined
    return HUGE_VAL;
  }
  set_drivers(mech, state, work.driver_values);
  compute_series(mech, state, kCoastSeriesTerms);
  Eigen::MatrixXd shifted = state.series;
  shift_series(shifted, distance);
  const double error = shift_error(state.series, shifted, distance, std::min(options.coast_terms, kCoastCheckedTerms));
  if (!(error <= kCoastMaxError)) return HUGE_VAL;
  const Eigen::VectorXd q_b = state.q;
  path(p_end, kCoastSeriesTerms, work.driver_values);
  set_drivers(mech, state, work.driver_values);
  state.q = shifted.col(0);
  double residual = 0.0;
  bool short_of_rounding = false;
  if (!correct<0>(mech, state, q_b, shifted.col(0), residual, short_of_rounding)) return HUGE_VAL;
  const bool singular = !factorize_jacobian(mech, state, work.spare_solver()) ||
                        work.spare_solver().reciprocal_condition() < kSingularEndRcond;
  if (!singular) return HUGE_VAL;
  state.series = std::move(shifted);
  state.series.col(0) = state.q;
  state.parameter = p_end;
  state.residual = residual;
  return error;
}

// p_end lies on a singular position, or may (the path was about to be given up there): the
// series at p_end are taken from a regular point near it on the branch followed, re-centred at
// p_end, and the solver keeps that point's factorisation. Near the singular position rounding
// spoils the series, far from it truncation does: the point is tried half a step before p_end,
// then alternately further beyond it (fine sweeps) and nearer before it (coarse ones). On entry
// the workspace's q_track_start solved the constraints at p_start. False, with state back at the
// start, when p_end is not singular or no point gives its series.
bool coast_to_singular_end(const Mechanism& mech, State& state, const DriverPath& path, double p_start, double p_end,
                           const TrackOptions& options, double* accuracy) {
  const double half_step = 0.5 * (p_end - p_start);
  const double distances[] = {half_step,          -half_step,        0.25 * half_step,     -4.0 * half_step,
                              0.0625 * half_step, -16.0 * half_step, 0.015625 * half_step, -64.0 * half_step};
  for (double distance : distances) {
    const double error = series_from(mech, state, path, p_start, p_end, distance, options);
    if (error <= kCoastMaxError) {
      *accuracy = error;
      return true;
    }
  }
  restart(mech, state, path, p_start, options.terms);
  return false;
}

}  // namespace

namespace {

// track(), for N coordinates (0: any number).
// Left long (138 lines) on purpose: this is the sweep's inner loop, one pass a step, and its
// state (the step h, the accepted point's q and determinant sign, the residual known there,
// whether the coast was tried) is read and written by the predictor, the corrector, the tests
// that accept or reject a step and the coast alike. Split into functions, that state would be
// passed by reference through each call of the hot path whose cost a step the benchmarks track
// (bench/kinematics_bench.cpp, docs/benchmarks.md); the comments mark its stages instead.
template <int N>
TrackReport track_sized(const Mechanism& mech, State& state, const DriverPath& path, double p_end,
                        const TrackOptions& options) {
  State::Workspace& work = state.workspace();
  TrackReport report;
  const double span = p_end - state.parameter;
  const double h_min = std::abs(span) * options.min_step;
  double h = span;
  std::vector<Series>& values = work.driver_values;
  Eigen::VectorXd& q_old = work.q_accepted;
  Eigen::VectorXd& q_pred = work.q_predicted;
  copy_coordinates<N>(state.q, q_old);
  const double p_start = state.parameter;
  if (options.coast_terms > 0) copy_coordinates<N>(state.q, work.q_track_start);
  int sign_old = work.solver().determinant_sign();
  // The residual at the last accepted point, as correct() found it there (with the drivers
  // where they are now): computing it again at the end would give the same number.
  double residual = 0.0;
  bool residual_known = false;
  bool coast_tried = false;
  // Once per track: true when p_end was reached on a singular position; else state is at an
  // accepted point, perhaps nearer p_end, to go on from as usual.
  const auto coast = [&] {
    coast_tried = true;
    residual_known = false;
    if (coast_to_singular_end(mech, state, path, p_start, p_end, options, &report.singular_end_accuracy)) {
      report.singular_end = true;
      ++report.steps;
      return true;
    }
    q_old = state.q;
    sign_old = work.solver().determinant_sign();
    h = p_end - state.parameter;
    return false;
  };

  while (true) {
    const double remaining = p_end - state.parameter;
    if (std::abs(remaining) <= 1e-13 * std::max(std::abs(span), std::abs(p_end))) break;
    if (std::abs(h) > std::abs(remaining)) h = remaining;

    const bool final_step = h == remaining;
    // Near a singular position the series carry about 1/rcond times the rounding error, which
    // an extrapolation through the past point would multiply further: there, and where there is
    // no past point, the current point's series alone predict, with at least four terms.
    const bool regular = work.solver().reciprocal_condition() >= kHistoryRcond;
    if (!regular || !work.history.predict<N>(state.parameter, state.series, h, q_pred)) {
      if (state.series.cols() < kTaylorPredictorTerms) {
        path(state.parameter, kTaylorPredictorTerms, values);
        set_drivers(mech, state, values);
        compute_series(mech, state, kTaylorPredictorTerms);
      }
      predict(state.series, h, q_pred);
    }
    path(state.parameter + h, options.terms, values);
    set_drivers(mech, state, values);
    copy_coordinates<N>(q_pred, state.q);
    double trial_residual = 0.0;
    bool short_of_rounding = false;
    const bool converged = correct<N>(mech, state, q_old, q_pred, trial_residual, short_of_rounding);
    bool ok = converged && work.spare_solver().factorize(work.jacobian);
    // On a singular position the point's own Jacobian would amplify the correction instead: the
    // point stays as the tolerance left it (a sample there takes its series from beside it).
    if (ok && short_of_rounding && work.spare_solver().reciprocal_condition() >= kHistoryRcond)
      ok = polish(mech, state, work.spare_solver(), trial_residual) && trial_residual <= mech.tolerance();
    if (converged && final_step && options.coast_terms > 0 && !coast_tried &&
        (!ok || work.spare_solver().reciprocal_condition() < kSingularEndRcond)) {
      if (coast()) break;
      continue;
    }
    bool crossing = false;
    if (ok) {
      const int sign_new = work.spare_solver().determinant_sign();
      if (sign_old != 0 && sign_new != 0 && sign_new != sign_old) {
        crossing = true;
        // A step that Newton hardly had to correct stayed on the branch the series continue,
        // however long: the branches through a change point part linearly, the series' error
        // is of the order of h^terms.
        const double motion = (q_pred - q_old).lpNorm<Eigen::Infinity>();
        const bool continued = (state.q - q_pred).lpNorm<Eigen::Infinity>() <= kContinuedCorrection * motion;
        if (std::abs(h) > kCrossingStep * std::abs(span) && !continued) ok = false;
      }
    }
    // A step that lands on a singular position (its condition far below the last point's) is no
    // place to stop between samples: the series there would carry 1/rcond times the rounding
    // error into the next prediction. It is retried shorter, by a factor that does not land on
    // the same place again (halving can: a quarter step of a sweep may be a change point).
    const double rcond_new = ok ? work.spare_solver().reciprocal_condition() : 1.0;
    const bool onto_singular = ok && !final_step && rcond_new < kSingularEndRcond &&
                               rcond_new < kSuddenRcondDrop * work.solver().reciprocal_condition();
    if (onto_singular) ok = false;
    if (ok) {
      // The history takes the accepted point's series; the new point's are written over what it
      // gives back.
      work.history.take(state.parameter, state.series);
      state.parameter += h;
      work.swap_solvers();
      compute_series(mech, state, options.terms);
      work.history.mark_current<N>(state.parameter, state.series);
      sign_old = work.solver().determinant_sign();
      copy_coordinates<N>(state.q, q_old);
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
    copy_coordinates<N>(q_old, state.q);
    path(state.parameter, options.terms, values);
    set_drivers(mech, state, values);
    h *= onto_singular ? kOffSingularShrink : 0.5;
    if (std::abs(h) < h_min && options.coast_terms > 0 && !coast_tried) {
      // Given up short of p_end: perhaps p_end is a change point, where Newton converges too
      // slowly to be trusted.
      if (coast()) break;
      continue;
    }
    if (std::abs(h) < h_min) {
      report.limit_parameter = state.parameter;
      report.reciprocal_condition = work.solver().reciprocal_condition();
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

}  // namespace

TrackReport track(const Mechanism& mech, State& state, const DriverPath& path, double p_end,
                  const TrackOptions& options) {
  // Sized only for the dense LU's solves (least squares reads its size at run time).
  const bool lu = state.workspace().solver().method() == LinearSolver::Method::LU;
  return with_coordinate_count(lu ? mech.coordinate_count() : 0, [&](auto n) {
    return track_sized<decltype(n)::value>(mech, state, path, p_end, options);
  });
}

namespace {

double wrap_angle(double a) { return a - 2.0 * std::numbers::pi * std::round(a / (2.0 * std::numbers::pi)); }

std::string worst_constraint_message(const Mechanism& mech, State& state) {
  int worst = -1;
  const double r = max_residual(mech, state, &worst);
  if (worst < 0) return "";
  const Model& m = mech.model();
  std::ostringstream s;
  s << "constraint '" << mech.equations().rows[worst].label << "' cannot be met (off by " << r / m.units.length_scale
    << " " << m.units.length << ")";
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

namespace {

// Each driver's offset from its drawn value to `start` (`delta`), angles the short way round,
// and the long way round (`other_way`); whether any angle has a long way.
bool offsets_to_start(const Model& m, const std::vector<double>& start, const std::vector<double>& drawn,
                      std::vector<double>& delta, std::vector<double>& other_way) {
  const int nd = static_cast<int>(m.drivers.size());
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
  return has_other_way;
}

// The start was not reached along `active` (the offsets tracked): says where each driver
// stopped, and whether the wanted values assemble at all.
[[noreturn]] void refuse_unreached_start(const Mechanism& mech, State& state, const DriverPath& path,
                                         const std::vector<double>& active, const std::vector<double>& start,
                                         const TrackReport& tracked, bool has_other_way, int terms) {
  const Model& m = mech.model();
  const int nd = static_cast<int>(m.drivers.size());
  const std::vector<double>& drawn = mech.drawn_driver_values();
  std::ostringstream s;
  s << "cannot reach the drivers' starting values from the drawn pose on its branch";
  for (int d = 0; d < nd; ++d) {
    if (active[d] == 0.0) continue;
    s << "; driver '" << m.drivers[d].name << "' stops at "
      << format_driver_value(m, d, drawn[d] + tracked.limit_parameter * active[d]) << " (drawn "
      << format_driver_value(m, d, drawn[d]) << ", wanted " << format_driver_value(m, d, start[d]) << ")";
    if (m.drivers[d].is_angular() && has_other_way) s << " either way round";
  }
  std::vector<Series> values;
  path(1.0, terms, values);
  set_drivers(mech, state, values);
  int worst = -1;
  if (solve_position(mech, state, 20).converged) {
    s << "; the wanted values can only be assembled on another branch: draw the mechanism on that branch";
  } else {
    const double r = max_residual(mech, state, &worst);
    s << "; at the wanted values constraint '" << mech.equations().rows[worst].label
      << "' cannot be met (the closest pose found leaves it off by " << r / m.units.length_scale << " "
      << m.units.length << ")";
  }
  throw AssemblyError(s.str(), worst, worst >= 0 ? mech.equations().rows[worst].source : EntityRef{});
}

}  // namespace

AssemblyReport assemble(const Mechanism& mech, State& state, const std::vector<double>& start) {
  const Model& m = mech.model();
  const int nd = static_cast<int>(m.drivers.size());
  const std::vector<double>& drawn = mech.drawn_driver_values();
  TrackOptions options;
  AssemblyReport report;

  // Angles are reached the short way round first; when that meets a limit, the long way.
  std::vector<double> delta(nd), other_way(nd);
  const bool has_other_way = offsets_to_start(m, start, drawn, delta, other_way);
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
                          worst, worst >= 0 ? mech.equations().rows[worst].source : EntityRef{});
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
  if (!tracked.reached)
    refuse_unreached_start(mech, state, path, *active, start, tracked, has_other_way, options.terms);
  report.passed_singularity = tracked.passed_singularity;
  report.residual = state.residual;
  return report;
}

}  // namespace nbar
