// Path tracking for homotopies H(x, t) = 0 with complex t: an adaptive fourth-order
// Runge–Kutta predictor on the Davidenko equation Hx dx/dt = -Ht, a Newton corrector, and a
// Cauchy endgame for paths that end singular.
#pragma once

#include <functional>
#include <string>

#include "nbar/synthesis/polynomial.hpp"

namespace nbar::synthesis {

class Homotopy {
 public:
  virtual ~Homotopy() = default;
  virtual int size() const = 0;  // variables = equations
  // h = H(x, t); hx = dH/dx and ht = dH/dt when not null.
  virtual void evaluate(const CVector& x, Complex t, CVector& h, CMatrix* hx, CVector* ht) const = 0;
  // y = Hx^{-1} Ht (velocity) or Hx^{-1} H (Newton) at (x, t); false when Hx is singular.
  // The default evaluates and factors densely; structured homotopies do better.
  virtual bool linear_solve(const CVector& x, Complex t, bool velocity, CVector& y) const;
};

struct TrackSettings {
  double initial_step = 0.05;  // in the path parameter, which runs over [0, 1]
  double max_step = 0.25;
  double min_step = 1e-13;
  double corrector_tolerance = 1e-6;  // relative Newton step accepted while tracking
  int corrector_iterations = 3;
  double predictor_target = 3e-3;  // relative predictor error the step size aims at
  double contraction = 0.5;        // required ratio of successive Newton steps (guards jumps)
  double final_tolerance = 1e-12;  // relative, when refining at t = 1
  int max_steps = 3000;            // per path: accepted steps, endgame included; attempts per segment
  double endgame_radius = 0.05;    // |1 - t| where a singular end switches to the Cauchy endgame
  double singular_condition = 1e13;
  int max_winding = 12;
};

enum class TrackStatus { Success, Failed };

struct TrackResult {
  TrackStatus status = TrackStatus::Failed;
  CVector x;
  int steps = 0;
  double last_step = 0;  // the step size reached, to continue with
  int winding = 1;
  double condition = 0;  // 1-norm condition number of Hx at the end
  std::string failure;
};

// Tracks x from t = path(0) to t = path(1), where path(tau) gives (t, dt/dtau).
using TPath = std::function<std::pair<Complex, Complex>(double tau)>;
TrackResult track_segment(const Homotopy& h, const CVector& start, const TPath& path, const TrackSettings& settings);

// Tracks from t = 0 to t = 1 along the real segment, with the Cauchy endgame when the end
// is singular.
TrackResult track_path(const Homotopy& h, const CVector& start, const TrackSettings& settings);

// Newton's method on H(., t) from x: returns the last step's relative size.
double refine(const Homotopy& h, CVector& x, Complex t, int iterations, double tolerance);

// 1-norm condition number ||A||_1 ||A^-1||_1 of a square matrix (infinite when singular).
double condition_number(const CMatrix& m);

}  // namespace nbar::synthesis
