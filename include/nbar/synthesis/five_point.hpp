// The five-point path-generation problem for four-bars (Morgan & Wampler, J. Mech. Design
// 112, 1990): given both fixed pivots and five positions of a coupler point, every four-bar
// whose coupler point passes through all five. 36 solutions for generic data.
//
// Solved in isotropic coordinates (t_i = e^{i theta_i}, x, y as complex numbers with their
// "conjugates" as independent unknowns) by a parameter homotopy from a stored generic complex
// instance whose 36 solutions the solver computed itself (monodromy); when paths fail or the
// count is not 36, by the 96-path linear-product homotopy on the (c_i, s_i, x, y) form.
#pragma once

#include <Eigen/Core>

#include <array>
#include <string>
#include <vector>

#include "nbar/synthesis/fourbar_design.hpp"
#include "nbar/synthesis/solve.hpp"

namespace nbar::synthesis {

struct FivePointTask {
  Eigen::Vector2d pivot_a{0, 0};          // fixed pivot of the first dyad
  Eigen::Vector2d pivot_b{1, 0};          // fixed pivot of the second dyad
  std::array<Eigen::Vector2d, 5> points;  // coupler point, in the order it should pass them
};

struct FivePointSolution {
  // Coupler rotations from position 0 to positions 1..4 (cos, sin; complex in general).
  std::array<Complex, 4> cos_rotation{}, sin_rotation{};
  // Moving pivots relative to the coupler point in position 0, in the task's frame.
  std::array<Complex, 2> moving_a{}, moving_b{};
  bool real = false;
  double residual = 0.0;   // max |equation| in the primer's (c, s, x, y) form, task units
  double condition = 0.0;  // 1-norm condition number of the solver's Jacobian at the endpoint
  FourBarDesign design;    // the linkage, when real
};

struct FivePointResult {
  std::vector<FivePointSolution> solutions;  // distinct finite solutions (36 generically)
  int paths = 0;                             // paths tracked in all
  bool used_fallback = false;                // the linear-product homotopy was needed
  std::string method;                        // "parameter homotopy (36 paths)" or the fallback's name
  int failed_paths = 0;                      // of the parameter homotopy, after re-tracking
  int retracked_paths = 0;
};

// Throws Error(ErrorKind::InvalidModel) for coincident pivots or non-finite input.
FivePointResult solve_five_point(const FivePointTask& task, const SolverOptions& options = {});

// The primer's twelve equations (c_i, s_i, x1, x2, y1, y2), pivots at 0 and (1, 0).
PolynomialSystem five_point_system(const std::array<Eigen::Vector2d, 5>& points);
VariableGroups five_point_groups();  // {c1,s1}...{c4,s4}{x1,x2}{y1,y2}: 96 paths

}  // namespace nbar::synthesis
