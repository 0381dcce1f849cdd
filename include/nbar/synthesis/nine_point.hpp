// Alt's problem: every four-bar whose coupler point passes through nine given points
// (Wampler, Morgan & Sommese, J. Mech. Des. 114(1), 1992). A generic instance has 4326
// four-bars in 1442 triples of Roberts cognates; the isotropic formulation below (24
// equations in 24 unknowns, plus two patch equations for the homogenized dyads) counts each
// triple six times (cognates x the relabelling of the two dyads): 8652 solutions.
//
// Unknowns, in a frame with the first point at the origin: per dyad the fixed pivot a and the
// moving pivot x (relative to the first point, in the first position) with their isotropic
// "conjugates", homogenized per dyad on a random patch so that far pivots stay bounded; per
// position j = 1..8 the coupler rotation t_j = e^{i theta_j} and tb_j = 1 / t_j.
//   |delta_j + t_j x - a|^2 = |x - a|^2   (each dyad),   t_j tb_j = 1.
//
// New tasks are solved by a parameter homotopy from a stored generic complex instance with
// one representative of each of its 1442 orbits (nine_point_start.cpp); lost orbits are
// recovered by tracking again and, failing that, by monodromy at the task;
// generate_nine_point_start (nine_point_start.hpp) makes such an instance from scratch.
#pragma once

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "nbar/synthesis/fourbar_design.hpp"
#include "nbar/synthesis/polynomial.hpp"

namespace nbar::synthesis {

inline constexpr int kNinePointOrbits = 1442;     // generic number of cognate triples
inline constexpr int kNinePointSolutions = 8652;  // of the isotropic system (6 per orbit)
// What a nine-point run may take by default (s): a generic task takes 2 to 10 s here, a task whose
// points lie nearly on a conic can take minutes and gives no finite answer anyway.
inline constexpr double kDefaultNinePointBudget = 60.0;

struct NinePointOptions {
  unsigned threads = 0;    // 0: every hardware thread
  std::uint64_t seed = 1;  // random parameter nodes and gammas
  // Called with (stage, done, total), from worker threads: stage "paths" (parameter
  // homotopy) or "monodromy" (done = orbits known, total = 1442 as a guide, not a rule).
  std::function<void(const std::string&, int, int)> progress;
  // Asked between paths (thread-safe); true stops the run, which then throws
  // Error(ErrorKind::Cancelled, "cancelled").
  std::function<bool()> stop;
  // When the parameter homotopy loses orbits for good, monodromy at the task recovers them: a
  // graph of three parameter nodes, run until closed or until max_loops rounds of its six edges.
  int max_loops = 40;
  // Seconds the run may take (0: no limit). Past it no new path is started and the stages still
  // to come are skipped: the result holds what was found so far, with budget_spent set (where a
  // `stop` ends the run with Error(Cancelled) and nothing).
  double time_budget = 0.0;
  // Asked between paths, as `stop` is; solve_nine_point sets it from time_budget.
  std::function<bool()> out_of_time;
};

// One real four-bar through the nine points and its two Roberts cognates (same coupler curve).
struct NinePointLinkage {
  // designs[0] is the solution itself; designs[1], designs[2] its cognates. Positions with the
  // coupler point at points[0]. Link lengths: check_design or the pivots.
  std::array<FourBarDesign, 3> designs;
  double residual = 0;   // largest relative residual of the 24 equations (task units)
  double condition = 0;  // condition number of the solver's Jacobian at the endpoint
};

struct NinePointResult {
  std::vector<NinePointLinkage> linkages;  // one per real orbit (cognate triple)
  int orbits = 0;                          // distinct orbits found, real or complex (1442 generically)
  int real_orbits = 0;                     // = linkages.size()
  int paths = 0;                           // paths tracked in all (parameter homotopy and monodromy)
  int failed_paths = 0;                    // of the parameter homotopy from the stored instance
  int monodromy_loops = 0;                 // loops run to recover what the parameter homotopy lost
  // How complete the set is: complete when as many distinct orbits were reached as the stored
  // instance has (1442, closed under monodromy when it was made); the sentence says so or not.
  std::string certificate;
  bool complete = false;
  bool budget_spent = false;  // stopped at options.time_budget: what was found by then
  std::string method;
  // Every orbit representative, affine solver coordinates in the solver's frame (for tests).
  std::vector<CVector> representatives;
};

// The circle through all nine points when they lie on one, within 1e-9 of their spread. Such a
// task has infinitely many solutions: a crank of that radius about its centre, whose moving
// pivot is the coupler point, with any second dyad.
struct NinePointCircle {
  Eigen::Vector2d centre;
  double radius = 0;
};
std::optional<NinePointCircle> common_circle(const std::array<Eigen::Vector2d, 9>& points);

// Throws Error(ErrorKind::InvalidModel) for non-finite, repeated (within 1e-9 of the spread), collinear
// (a line is no coupler curve) or concyclic points (infinitely many four-bars).
NinePointResult solve_nine_point(const std::array<Eigen::Vector2d, 9>& points, const NinePointOptions& options = {});

}  // namespace nbar::synthesis
