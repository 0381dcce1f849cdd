// What a four-bar should do: the input of every synthesis method, as a task file says it
// (io/synthesis_task.hpp reads them) or as a front-end builds it.
#pragma once

#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

#include "nbar/model/diagnostics.hpp"
#include "nbar/model/law.hpp"
#include "nbar/model/units.hpp"
#include "nbar/synthesis/burmester.hpp"
#include "nbar/synthesis/path_fit.hpp"

namespace nbar::synthesis {

enum class SynthesisKind {
  FivePoint,
  Burmester,
  Function,
  NinePoint,
  Path,
};

// "five-point", "burmester", "function", "nine-point", "path".
std::string to_string(SynthesisKind kind);

// Lengths are in the task's length unit (the solvers work in it and exported models keep
// it); angles are in radians.
struct SynthesisTask {
  SynthesisKind kind = SynthesisKind::FivePoint;
  std::string file;  // for messages
  std::string name;  // the task's title; exported models are named after it
  Units units;
  SourceMark where;  // the section the solver's own complaints are reported at

  // five-point: both fixed pivots and the coupler point's five positions, in order.
  // nine-point: the coupler point's nine positions, in order (no pivots).
  Eigen::Vector2d pivot_a{0, 0}, pivot_b{0, 0};
  std::vector<Eigen::Vector2d> points;

  // burmester: 3, 4 or 5 poses of the coupler (point, angle).
  std::vector<synthesis::BodyPose> poses;
  // 3 poses: the two pivots the designer chooses, fixed or moving (in the first pose).
  synthesis::PivotChoice given = synthesis::PivotChoice::Fixed;
  Eigen::Vector2d given_a{0, 0}, given_b{0, 0};
  // 4 poses: how the Burmester curves are traced, and how many dyads along them are paired
  // into four-bars.
  synthesis::CurveOptions curves;
  int samples = 24;

  // function: y = f(x) for x in [x_start, x_end] mapped onto the input's and output's angles.
  std::string function_text;
  std::optional<Law> function;  // in x (read as the law's t)
  double x_start = 0, x_end = 1;
  double input_from = 0, input_to = 0;    // input angle at x_start and x_end (rad)
  double output_from = 0, output_to = 0;  // output angle at f(x_start) and f(x_end)
  int precision_points = 3;
  bool chebyshev = true;  // else evenly spaced, ends included
  double frame = 1;       // length of the frame link (sets the size)

  // path: `points` holds the targets (10 or more, from the file or its `curve` CSV), and these
  // bound the designs.
  PathConstraints constraints;
  std::string curve_file;     // the CSV the targets came from, if any
  int nine_point_starts = 0;  // subsets of nine targets whose nine-point designs start fits too
};

}  // namespace nbar::synthesis
