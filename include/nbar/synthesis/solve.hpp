// Homotopy continuation for square polynomial systems: all isolated complex solutions.
//
//   F(x) = 0 is reached from a start system G whose solutions are known, along
//   H(x, t) = (1 - t) * gamma * G(x) + t * F(x),  t: 0 -> 1,
// with a random complex gamma (the gamma trick: no path meets a singularity before t = 1
// with probability one). Variables are homogenized, one extra coordinate per variable group
// on a random affine patch, so paths to infinity stay bounded and are recognised.
// Each path runs on its own; results are identical whatever the number of threads.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "nbar/synthesis/polynomial.hpp"

namespace nbar::synthesis {

// A partition of the variables, for multihomogeneous (linear-product) start systems.
using VariableGroups = std::vector<std::vector<int>>;

struct SolverOptions {
  unsigned threads = 0;              // 0: every hardware thread
  std::uint64_t seed = 1;            // gamma and patches; the answer depends on it, not on threads
  double tolerance = 1e-11;          // relative accuracy asked of the corrector near the end
  double singular_condition = 1e13;  // endpoints with a larger condition number are singular
  double infinity_threshold = 1e-8;  // |homogenizing coordinate| below this: at infinity
  int max_steps = 3000;              // per path (a regular path takes 20 to 200)
  // Track failed paths again with tighter settings: worth it when every path should arrive
  // (parameter homotopies, where solve_five_point asks for it), wasted on the many paths of
  // a total-degree or linear-product homotopy that end on a singular set at infinity.
  bool retrack_failures = false;
  // Called after each path with (finished paths, all paths); from worker threads.
  std::function<void(int, int)> progress;
  // Asked before each path (from worker threads, so thread-safe); true stops the run: the
  // paths not yet tracked end as Failed with failure "stopped", and none is tracked again.
  std::function<bool()> stop;
};

enum class EndpointKind { Finite, AtInfinity, Failed };

struct Endpoint {
  int path = -1;
  EndpointKind kind = EndpointKind::Failed;
  CVector x;               // affine coordinates (finite endpoints); the last point otherwise
  bool singular = false;   // condition above the threshold, or a winding number above 1
  bool real = false;       // every coordinate real to 1e-8 (relative)
  double residual = 0.0;   // max |F_i(x)| after Newton refinement
  double condition = 0.0;  // 1-norm condition number of the tracker's Jacobian at x
  int winding = 1;         // cycle number found by the endgame (1 = regular endpoint)
  int steps = 0;           // accepted predictor-corrector steps
  bool retracked = false;  // tracked again after it landed on another path's endpoint
  std::string failure;     // why, when kind == Failed
};

struct SolveResult {
  std::vector<Endpoint> endpoints;  // one per path, in path order
  int retracked = 0;                // paths re-tracked because two landed on one endpoint

  int count(EndpointKind kind) const;
  // Distinct finite, non-singular endpoints (duplicates merged), optionally only real ones.
  std::vector<CVector> solutions(bool real_only = false) const;
  std::vector<const Endpoint*> finite_regular() const;
};

// Number of paths each start system needs.
long total_degree_count(const PolynomialSystem& f);
long multihomogeneous_count(const PolynomialSystem& f, const VariableGroups& groups);

SolveResult solve_total_degree(const PolynomialSystem& f, const SolverOptions& options = {});
// Linear-product start system from the grouping: each equation becomes a product, over the
// groups, of deg_g random linear forms in that group's variables.
SolveResult solve_linear_product(const PolynomialSystem& f, const VariableGroups& groups,
                                 const SolverOptions& options = {});

// A family F(x; p) = 0 of square systems with parameters p. Implementations may work in
// homogenized coordinates (patch equations included) and say how to read them back.
class ParameterizedSystem {
 public:
  virtual ~ParameterizedSystem() = default;
  virtual int variables() const = 0;  // equal to the number of equations
  virtual int parameters() const = 0;
  // f = F(x; p); jx = dF/dx and jp = dF/dp when not null.
  virtual void evaluate(const CVector& x, const CVector& p, CVector& f, CMatrix* jx, CMatrix* jp) const = 0;
  // y = Fx^{-1} F (dp null: a Newton step) or Fx^{-1} (Fp dp) (a velocity) at (x; p); false
  // when Fx is singular. The default evaluates and factors densely.
  virtual bool linear_solve(const CVector& x, const CVector& p, const CVector* dp, CVector& y) const;
  // Smallest homogenizing coordinate relative to its group (1 when affine).
  virtual double infinity_measure(const CVector& /*x*/) const { return 1.0; }
  // Affine coordinates of a finite point (identity when affine).
  virtual CVector to_affine(const CVector& x) const { return x; }
  // Coordinates the tracker uses for an affine point (identity when affine).
  virtual CVector from_affine(const CVector& affine) const { return affine; }
  // Whether an affine point is real (default: every coordinate's imaginary part is small).
  virtual bool is_real(const CVector& affine) const;
};

// Moves the known solutions of F(x; from) to F(x; to) along the segment between the
// parameters (choose `from` generic complex so the segment avoids the discriminant).
SolveResult solve_parameter_homotopy(const ParameterizedSystem& f, const CVector& from,
                                     const std::vector<CVector>& from_solutions, const CVector& to,
                                     const SolverOptions& options = {});

struct MonodromyResult {
  std::vector<CVector> solutions;  // of F(x; p), tracker coordinates
  int loops = 0;
  bool stable = false;  // stopped because `stale_loops` loops found nothing new (or target met)
};
// Grows a set of solutions of F(x; p) from one seed solution by tracking around random
// triangles in parameter space. Stops at `target` solutions (when > 0) or after
// `stale_loops` loops in a row bring nothing new.
MonodromyResult monodromy_solve(const ParameterizedSystem& f, const CVector& p, const std::vector<CVector>& seeds,
                                int target, const SolverOptions& options = {}, int stale_loops = 5,
                                int max_loops = 200);

}  // namespace nbar::synthesis
