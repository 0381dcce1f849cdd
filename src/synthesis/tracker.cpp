#include "nbar/synthesis/tracker.hpp"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "linear_algebra.hpp"

namespace nbar::synthesis {
namespace {

// dx/dtau = -Hx^{-1} Ht dt/dtau.
bool velocity(const Homotopy& homotopy, const CVector& x, Complex t, Complex dt, CVector& v) {
  if (!homotopy.linear_solve(x, t, true, v)) return false;
  v *= -dt;
  return v.allFinite();
}

// Newton at fixed t. Fails when it does not converge within the iterations or when the steps
// do not shrink fast enough: a slow contraction means the prediction fell near another path.
bool correct(const Homotopy& homotopy, CVector& x, Complex t, const TrackSettings& s, CVector& dx, double& first_step) {
  double previous = std::numeric_limits<double>::infinity();
  for (int k = 0; k < s.corrector_iterations; ++k) {
    if (!homotopy.linear_solve(x, t, false, dx) || !dx.allFinite()) return false;
    const double step = dx.norm();
    x -= dx;
    if (k == 0) first_step = step / (1.0 + x.norm());
    if (k > 0 && step > s.contraction * previous) return false;
    if (step <= s.corrector_tolerance * (1.0 + x.norm())) return true;
    previous = step;
  }
  return false;
}

std::pair<Complex, Complex> on_segment(Complex from, Complex to, double tau) {
  return {from + tau * (to - from), to - from};
}

TPath segment(Complex from, Complex to) {
  return [from, to](double tau) { return on_segment(from, to, tau); };
}

}  // namespace

bool Homotopy::linear_solve(const CVector& x, Complex t, bool velocity, CVector& y) const {
  CVector h, ht;
  CMatrix hx;
  evaluate(x, t, h, &hx, velocity ? &ht : nullptr);
  const Eigen::PartialPivLU<CMatrix> lu(hx);
  y = lu.solve(velocity ? ht : h);
  return y.allFinite();
}

double condition_number(const CMatrix& m) {
  if (m.size() == 0) return 0.0;
  const Eigen::PartialPivLU<CMatrix> lu(m);
  const CMatrix inverse = lu.inverse();
  if (!inverse.allFinite()) return std::numeric_limits<double>::infinity();
  const double norm = m.cwiseAbs().colwise().sum().maxCoeff();
  const double inverse_norm = inverse.cwiseAbs().colwise().sum().maxCoeff();
  return norm * inverse_norm;
}

double refine(const Homotopy& homotopy, CVector& x, Complex t, int iterations, double tolerance) {
  CVector dx;
  double last = std::numeric_limits<double>::infinity();
  for (int k = 0; k < iterations; ++k) {
    if (!homotopy.linear_solve(x, t, false, dx) || !dx.allFinite()) break;
    const double step = dx.norm() / (1.0 + x.norm());
    if (step > 2 * last && last < 1e-6) break;  // diverging from a converged point: stop there
    x -= dx;
    last = step;
    if (step <= tolerance) break;
  }
  return last;
}

TrackResult track_segment(const Homotopy& homotopy, const CVector& start, const TPath& path, const TrackSettings& s) {
  TrackResult result;
  result.x = start;
  CVector k1, k2, k3, k4, stage, predicted, correction;
  double tau = 0.0, step = s.initial_step;
  int attempts = 0;
  double predictor_error = 0.0;
  while (tau < 1.0) {
    if (++attempts > s.max_steps) {
      result.failure = "too many steps";
      return result;
    }
    const bool last_step = tau + step >= 1.0;
    const double h = last_step ? 1.0 - tau : step;
    const auto [t0, d0] = path(tau);
    const auto [tm, dm] = path(tau + 0.5 * h);
    const auto [t1, d1] = path(last_step ? 1.0 : tau + h);
    bool ok = velocity(homotopy, result.x, t0, d0, k1);
    if (ok) {
      stage.noalias() = result.x + (0.5 * h) * k1;
      ok = velocity(homotopy, stage, tm, dm, k2);
    }
    if (ok) {
      stage.noalias() = result.x + (0.5 * h) * k2;
      ok = velocity(homotopy, stage, tm, dm, k3);
    }
    if (ok) {
      stage.noalias() = result.x + h * k3;
      ok = velocity(homotopy, stage, t1, d1, k4);
    }
    if (ok) {
      predicted.noalias() = result.x + (h / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
      ok = correct(homotopy, predicted, t1, s, correction, predictor_error);
    }
    if (ok) {
      result.x = predicted;
      tau = last_step ? 1.0 : tau + h;
      ++result.steps;
      // The first Newton correction measures the predictor's error, O(h^5) for RK4: aim the
      // next step at the error that lets Newton converge in about two iterations.
      const double ratio = s.predictor_target / std::max(predictor_error, 1e-300);
      step = std::min(h * std::clamp(0.9 * std::pow(ratio, 0.2), 0.5, 2.0), s.max_step);
    } else {
      step *= 0.5;
      if (step < s.min_step) {
        result.failure = "step size fell below its minimum";
        return result;
      }
    }
  }
  result.status = TrackStatus::Success;
  result.last_step = step;
  return result;
}

namespace {

// Cauchy's integral formula around |1 - t| = r: the endpoint is the mean of x over the
// circle, taken as many times round as it takes x to come back (the winding number).
TrackResult cauchy_endgame(const Homotopy& homotopy, CVector x, double r, const TrackSettings& s, int steps_so_far) {
  constexpr int samples = 8;
  const double dtheta = 2.0 * std::numbers::pi / samples;
  TrackResult result;
  result.steps = steps_so_far;
  CVector previous_estimate;
  double previous_difference = std::numeric_limits<double>::infinity();
  for (int level = 0; level < 16 && r > 1e-15; ++level) {
    const CVector loop_start = x;
    CVector y = x, sum = CVector::Zero(x.size());
    int loops = 0;
    bool closed = false;
    while (!closed && loops < s.max_winding) {
      ++loops;
      for (int k = 0; k < samples; ++k) {
        if (result.steps > s.max_steps) {
          result.failure = "endgame: the path's step budget is spent";
          result.x = y;
          return result;
        }
        sum += y;
        const double theta0 = k * dtheta;
        TPath arc = [r, theta0, dtheta](double tau) {
          const Complex e = std::polar(1.0, theta0 + tau * dtheta);
          return std::pair<Complex, Complex>{1.0 - r * e, -r * Complex(0.0, dtheta) * e};
        };
        TrackResult piece = track_segment(homotopy, y, arc, s);
        result.steps += piece.steps;
        if (piece.status != TrackStatus::Success) {
          result.failure = std::string("endgame: ").append(piece.failure);
          result.x = y;
          return result;
        }
        y = piece.x;
      }
      closed = (y - loop_start).norm() <= 1e-6 * (1.0 + loop_start.norm());
    }
    if (!closed) {
      result.failure = "endgame: the loop around t = 1 did not close";
      result.x = x;
      return result;
    }
    const CVector estimate = sum / static_cast<double>(samples * loops);
    result.winding = loops;
    if (previous_estimate.size() == estimate.size()) {
      const double difference = (estimate - previous_estimate).norm() / (1.0 + estimate.norm());
      if (difference < 1e-10 || (r < 1e-8 && difference < 1e-6) ||
          (difference < 1e-7 && difference > 0.5 * previous_difference)) {
        result.status = TrackStatus::Success;
        result.x = estimate;
        return result;
      }
      previous_difference = difference;
    }
    previous_estimate = estimate;
    // Move closer to t = 1 along the real line and try again.
    TrackResult inward = track_segment(homotopy, x, segment(1.0 - r, 1.0 - r / 4), s);
    result.steps += inward.steps;
    if (inward.status != TrackStatus::Success) {
      result.failure = std::string("endgame: ").append(inward.failure);
      result.x = x;
      return result;
    }
    x = inward.x;
    r /= 4;
  }
  if (previous_estimate.size() > 0 && previous_difference < 1e-6) {
    result.status = TrackStatus::Success;
    result.x = previous_estimate;
    return result;
  }
  result.failure = "endgame did not converge";
  result.x = x;
  return result;
}

}  // namespace

TrackResult track_path(const Homotopy& homotopy, const CVector& start, const TrackSettings& s) {
  const double r = s.endgame_radius;
  TrackResult first = track_segment(homotopy, start, segment(0.0, 1.0 - r), s);
  if (first.status != TrackStatus::Success) return first;

  TrackSettings going_on = s;
  // The step reached, rescaled from the first segment's parameter to the second's.
  going_on.initial_step = std::clamp(first.last_step * (1.0 - r) / r, s.initial_step, 1.0);
  TrackResult end = track_segment(homotopy, first.x, segment(1.0 - r, 1.0), going_on);
  if (end.status == TrackStatus::Success) {
    // A regular end: Newton converges quadratically there. At a multiple root it only
    // creeps (linear convergence), which sends the path to the endgame.
    const double last_step = refine(homotopy, end.x, 1.0, 4, s.final_tolerance);
    CVector h;
    CMatrix hx;
    homotopy.evaluate(end.x, 1.0, h, &hx, nullptr);
    end.condition = condition_number(hx);
    end.steps += first.steps;
    if (end.condition < s.singular_condition && last_step < 1e-9) return end;
  }
  // The endgame shares the path's budget of steps with the tracking that came before.
  TrackResult result = cauchy_endgame(homotopy, first.x, r, s, first.steps + end.steps);
  if (result.status == TrackStatus::Success) {
    CVector h;
    CMatrix hx;
    homotopy.evaluate(result.x, 1.0, h, &hx, nullptr);
    result.condition = condition_number(hx);
    if (result.winding == 1 && result.condition < s.singular_condition)
      refine(homotopy, result.x, 1.0, 3, s.final_tolerance);
  }
  return result;
}

}  // namespace nbar::synthesis
