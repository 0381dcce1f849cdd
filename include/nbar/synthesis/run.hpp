// Running a synthesis task, once for every front-end: the solver of the task's method, every
// real solution checked with the kinematics engine, and the ranking. The CLI prints the
// outcome; the web server and Python return it.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "nbar/model/run_control.hpp"
#include "nbar/synthesis/burmester.hpp"
#include "nbar/synthesis/fourbar_design.hpp"
#include "nbar/synthesis/nine_point.hpp"
#include "nbar/synthesis/task.hpp"

namespace nbar::synthesis {

// One solution: a real linkage with its check, or (five-point) a complex one.
struct DesignRow {
  bool real = true;
  FourBarDesign design;
  DesignCheck check;
  std::optional<InputMotion> motion;  // for an exported model, instead of check.motion
  double solver_residual = 0;
  double solver_condition = 0;             // five-point: the homotopy's condition number at the endpoint
  std::optional<double> structural_error;  // function generation: worst output error over the range (rad)
  std::optional<double> rms_error;         // path: RMS distance from the targets to the coupler point
  std::optional<double> fit_max_error;     // path: the fit's largest distance, at its own input angles
};

struct SynthesisOutcome {
  std::string method;
  std::vector<DesignRow> rows;
  std::vector<std::string> notes;
  bool angle_errors = false;              // errors are output angles (function generation), not lengths
  std::optional<BurmesterCurves> curves;  // burmester with 4 poses: the centre- and circle-point curves
  bool ranked = false;                    // rows are in rank order already (path: by RMS deviation)
};

struct SynthesisRunOptions {
  unsigned threads = 0;    // path tracking; 0: every hardware thread
  std::uint64_t seed = 1;  // of the homotopy
  // Cancellation, deadline and progress (stages "paths" and "checking"); on_progress may be
  // called from worker threads.
  RunControl control;
  // What a nine-point solve may take (s; 0: no limit): past it, the designs found by then, with a
  // note that says so (RunControl's deadline, by contrast, stops the run with nothing).
  double nine_point_budget = kDefaultNinePointBudget;
};

// Throws Error: InvalidModel (at task.file and task.where) when the solver rejects the task's
// data (coincident pivots...), Cancelled when `options.control` says so.
SynthesisOutcome run_synthesis(const SynthesisTask& task, const SynthesisRunOptions& options = {});

// The rows to show, best first: the real defect-free ones (with `all`, every real one, then the
// complex ones); at most `top` when top > 0.
std::vector<int> shown_rows(const SynthesisOutcome& outcome, bool all, int top);

}  // namespace nbar::synthesis
