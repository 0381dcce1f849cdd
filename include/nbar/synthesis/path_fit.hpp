// Best-fit path synthesis: four-bars whose coupler curve passes closest to many target points
// (ten or more), meeting them in order. The objective is the sum of squared distances from each
// target to the coupler point at its own input angle, the angles being unknowns too; a dense
// Levenberg–Marquardt solver minimises it from many starting designs. Constraints (a pivot
// region, a crank that turns fully, a minimum transmission angle, link length bounds) enter as
// penalties that grow until they hold, and designs that still break one are dropped.
//
// Starting designs come from start providers (StartProvider): by default random four-bars
// screened against the targets, and five-point designs through five of the targets with pivots
// taken from the best of those. A provider of nine-point designs (exact through nine targets)
// plugs in the same way.
#pragma once

#include <Eigen/Core>

#include <atomic>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "nbar/synthesis/fourbar_design.hpp"

namespace nbar::synthesis {

// Lengths in the targets' unit, angles in radians.
struct PathConstraints {
  std::optional<Eigen::Vector2d> region_min, region_max;  // both fixed pivots inside this box
  bool crank = false;                                     // the input turns fully
  double min_transmission = 0;                            // over the motion through the targets (a crank's whole turn)
  double min_length = 0;                                  // every link: frame, input, coupler, output; 0 for none
  double max_length = 0;                                  // 0 for none
};

struct PathFitTask {
  std::vector<Eigen::Vector2d> targets;  // in the order the coupler point should meet them
  PathConstraints constraints;
};

// A four-bar as the fit moves it: fixed pivots, link lengths, the coupler point in the
// coupler's frame (along A->B, and to its left) and the assembly branch (loops.hpp
// branch_sign: the side of the line A->O4 where B lies, +1 or -1).
struct FourBarShape {
  Eigen::Vector2d ground_a{0, 0}, ground_b{1, 0};
  double input = 1, coupler = 1, output = 1;
  Eigen::Vector2d point{0, 0};
  int branch = 1;
};

FourBarShape shape_of(const FourBarDesign& design);
// The coupler point with the input at angle theta (the direction ground_a -> A), if the
// linkage assembles there; `design` receives the whole pose.
std::optional<Eigen::Vector2d> coupler_point_at(const FourBarShape& shape, double theta,
                                                FourBarDesign* design = nullptr);

struct PathStart {
  FourBarDesign design;  // any pose; its branch is kept
  std::string origin;    // "sampled", "five-point", "nine-point"...
};

struct PathFitOptions;
// Starting designs for the fit, in the targets' coordinates.
using StartProvider = std::function<std::vector<PathStart>(const PathFitTask&, const PathFitOptions&)>;

// The default time budget of a fit, seconds.
inline constexpr double kDefaultPathFitBudget = 30.0;

struct PathFitOptions {
  std::uint64_t seed = 1;
  int samples = 4000;          // random four-bars screened by sampled_starts
  int sampled_fits = 40;       // the best of them fitted
  int five_point_solves = 8;   // five-point problems solved by five_point_starts
  int nine_point_subsets = 0;  // nine-target subsets solved by nine_point_starts (0: none)
  int max_iterations = 200;    // Levenberg–Marquardt, per start
  int max_fits = 30;           // distinct optima kept, best first
  // Empty: default_start_providers().
  std::vector<StartProvider> providers;
  // Asked between starts, between the five-point solves' paths and between the nine-point
  // subsets; true stops (the fits so far are kept). From worker threads too: thread-safe.
  std::function<bool()> stop;
  // Seconds of wall-clock time for the whole fit (0: no limit). When it runs out the fit stops
  // as `stop` would, keeps what it found and sets PathFitResult::budget_spent: ten points on a
  // nearly straight line kept the five-point solves of the starts busy for minutes, where a
  // usual task takes about a second (docs/synthesis-path.md).
  double time_budget = kDefaultPathFitBudget;
  std::function<void(int, int)> progress;  // (starts fitted, starts)
};

// sampled_starts and five_point_starts, and nine_point_starts when nine_point_subsets > 0
// (each subset costs a whole nine-point solve: seconds to minutes, where the rest takes about one).
std::vector<StartProvider> default_start_providers();
std::vector<PathStart> sampled_starts(const PathFitTask& task, const PathFitOptions& options);
std::vector<PathStart> five_point_starts(const PathFitTask& task, const PathFitOptions& options);
// Every real four-bar (with its two cognates) through nine of the targets, spread along them,
// for `nine_point_subsets` such subsets (nine_point.hpp's solver).
std::vector<PathStart> nine_point_starts(const PathFitTask& task, const PathFitOptions& options);

// One local optimum.
struct PathFit {
  FourBarDesign design;              // in the pose that meets the first target
  std::vector<double> input_angles;  // the matched input angle of every target (rad)
  double rms_deviation = 0;          // sqrt(mean squared distance), targets to matched points
  double max_deviation = 0;
  std::string origin;  // of its start
  int iterations = 0;
};

struct PathFitResult {
  std::vector<PathFit> fits;              // distinct local optima meeting the constraints, smallest RMS first
  int starts = 0;                         // starting designs fitted
  int rejected = 0;                       // optima dropped because they break a constraint
  long evaluations = 0;                   // coupler-point evaluations in all (screening included)
  std::vector<std::string> start_counts;  // "40 sampled", "93 five-point"
  bool budget_spent = false;              // the time budget ran out: the fits are the best found by then
};

// Throws Error(ErrorKind::InvalidModel) for fewer than 10 targets, non-finite ones, or targets that all
// coincide or lie on one line (no four-bar's curve is fitted to a line this way).
PathFitResult fit_path(const PathFitTask& task, const PathFitOptions& options = {});

// The fit's objective for one design and its matched angles, with the evaluations counted:
// what a global search (the differential evolution of bench/path_fit_compare.cpp) minimises.
// Infinity when the linkage does not assemble at one of the angles.
double path_objective(const FourBarShape& shape, const std::vector<double>& angles,
                      const std::vector<Eigen::Vector2d>& targets);
// coupler_point_at calls made by this thread so far: the evaluation budget both searches are
// measured in.
long coupler_point_evaluations();

}  // namespace nbar::synthesis
