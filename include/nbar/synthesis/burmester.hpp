// Burmester motion generation: four-bars whose coupler passes through given positions.
//
// A position of the moving body is a BodyPose. A dyad (fixed pivot `centre`, moving pivot
// `circle` on the body) can guide the body through the positions when the moving pivot keeps
// one distance from the fixed pivot in all of them; two such dyads make a four-bar.
//   3 positions: every circle point has one centre point (and back): choose two.
//   4 positions: the pairs form the centre-point and circle-point curves (circular cubics).
//   5 positions: at most 4 pairs (the Burmester points), 0, 2 or 4 of them real.
// Method, conventions and limits: docs/synthesis-classic.md.
//
// Every function throws Error(ErrorKind::InvalidModel), naming the problem, for non-finite input,
// coincident positions or a degenerate task; none returns NaN.
#pragma once

#include <Eigen/Core>

#include <array>
#include <span>
#include <vector>

#include "nbar/synthesis/fourbar_design.hpp"
#include "nbar/synthesis/polynomial.hpp"

namespace nbar::synthesis {

// A position of the moving body: where its reference point is and its orientation (rad,
// counter-clockwise). A point with body coordinates b is at point + R(angle) b.
struct BodyPose {
  Eigen::Vector2d point{0, 0};
  double angle = 0;
};

// A dyad: fixed pivot `centre` and moving pivot `circle`, the latter with the body in its
// first position (all coordinates in the frame of the poses).
struct BurmesterPair {
  Eigen::Vector2d centre{0, 0};
  Eigen::Vector2d circle{0, 0};
};

// ---- Three positions -------------------------------------------------------------------

// The centre of the circle through the three positions of the body point that is at `circle`
// in the first position. Throws when those positions are collinear or two coincide.
Eigen::Vector2d centre_point(const std::array<BodyPose, 3>& poses, const Eigen::Vector2d& circle);

// The body point (given in the first position) whose three positions lie on a circle about
// `centre`: a 2x2 linear system. Throws when `centre` is a pole of the motion (every point
// works for two of the positions) or the system is singular.
Eigen::Vector2d circle_point(const std::array<BodyPose, 3>& poses, const Eigen::Vector2d& centre);

// Which pivots the designer chooses; the other two follow.
enum class PivotChoice { Moving, Fixed };

// The four-bar with the given input and output pivots (moving pivots in the first position,
// or fixed pivots), the body's reference point as coupler point. Throws for coincident pivots
// or a link of zero length.
FourBarDesign three_position_design(const std::array<BodyPose, 3>& poses, PivotChoice given,
                                    const Eigen::Vector2d& input_pivot, const Eigen::Vector2d& output_pivot);

// ---- Four positions --------------------------------------------------------------------

struct CurveOptions {
  // Curves are traced inside a disc about the centroid of the reference points (the window).
  double radius = 0;  // 0: 1.5 times the farthest reference point or pole (poles farther
                      // than 20 times the spread of the reference points are ignored)
  double step = 0;    // distance between samples; 0: radius / 300
};

// The widest window four_position_curves accepts: 10^6 times the poses' size (the RMS
// distance of their reference points from the centroid; 1 when the points coincide). A wider
// window spaces the samples too far apart to follow the curves near the poses, and far enough
// out the curves' equation overflows, so that nothing at all is traced.
inline constexpr double kMaxWindowRadius = 1e6;
double largest_window_radius(std::span<const BodyPose> poses);
// The poses' size: the RMS distance of their reference points from their centroid (1 when the
// points coincide), the unit of length the curves are traced in.
double pose_scale(std::span<const BodyPose> poses);

struct BurmesterCurves {
  // Polylines, each sample a dyad valid for all four positions. centre_curve is traced along
  // the centre points (samples evenly spaced in `centre`), circle_curve along the circle
  // points. A polyline ends at the window's edge, and where its partner point leaves 10^6
  // times the task's size (that dyad is practically a slider); a closed oval repeats its
  // first sample at the end.
  std::vector<std::vector<BurmesterPair>> centre_curve;
  std::vector<std::vector<BurmesterPair>> circle_curve;
  Eigen::Vector2d window_centre{0, 0};
  double window_radius = 0;
};

BurmesterCurves four_position_curves(const std::array<BodyPose, 4>& poses, const CurveOptions& options = {});

// ---- Five positions --------------------------------------------------------------------

// A four-bar made of two Burmester pairs.
struct BurmesterDesign {
  FourBarDesign design;         // input dyad `input`, output dyad `output`, coupler point =
                                // the body's reference point in the first position
  int input = -1, output = -1;  // indices into FivePositionResult::points
  bool one_branch = false;      // all five positions on one assembly branch (see branch_signs)
};

struct FivePositionResult {
  std::vector<BurmesterPair> points;     // the real Burmester pairs: 0, 2 or 4 for generic data
  int complex_points = 0;                // finite solutions that are not real (conjugate pairs)
  std::vector<BurmesterDesign> designs;  // every pair of distinct points: up to 6
};

FivePositionResult five_position_burmester(const std::array<BodyPose, 5>& poses);

// The equations E_i(c, q) = (|D_i q + d_i − c|² − |q − c|²) / 2 (i = 1..4; D_i, d_i the
// displacement from position 0 to position i) in the variables (c_x, c_y, q_x, q_y): fixed
// pivot c and moving pivot q in the first position, in the poses' coordinates. Bilinear in
// {c} and {q}: 6 solutions in P² x P², 4 finite and 2 at infinity (the circular points).
// For cross-checks with the homotopy solvers.
PolynomialSystem five_position_system(const std::array<BodyPose, 5>& poses);

// ---- Helpers ---------------------------------------------------------------------------

FourBarDesign design_from_pairs(const BurmesterPair& input, const BurmesterPair& output,
                                const Eigen::Vector2d& coupler_point);

// For each pose (poses[0] being the design's first position): +1 or −1 as the output's
// moving pivot lies left or right of the line from the input's moving pivot to the output's
// fixed pivot (0 when on it). Equal signs: the linkage reaches all poses without changing
// assembly branch (the order of the positions along the input's motion is not checked).
std::vector<int> branch_signs(const FourBarDesign& design, std::span<const BodyPose> poses);

}  // namespace nbar::synthesis
