// One self-contained HTML file that tells a mechanism's story: the model summary (degrees of
// freedom, Grashof class, mass properties), the animation, the paths of its coupler points,
// plots of the bodies' angles, angular velocities, accelerations and jerk, and, when the
// analysis has them, the joint forces, the driver efforts and the stresses with each link's
// largest von Mises stress marked on the drawing. No network access is needed to read it, and
// it reads on a phone. It renders an Analysis: it solves nothing itself.
#pragma once

#include <string>

#include "nbar/analysis/analysis.hpp"
#include "nbar/analysis/summary.hpp"
#include "nbar/dynamics/forward_dynamics.hpp"
#include "nbar/model/run_control.hpp"

namespace nbar::render {

// The report's animation has this many frames at least and at most (the command line, the web
// server and Python take the same range).
inline constexpr int kMinReportFrames = 2;
inline constexpr int kMaxReportFrames = 1000;

struct ReportOptions {
  std::string source;  // the model file's name, for the header
  int frames = 72;     // animation frames, kMinReportFrames to kMaxReportFrames
  // Checked between the report's sections (stage "report") and its animation's frames
  // ("frames"): Error(ErrorKind::Cancelled) when it says stop.
  RunControl control;
  // The report of a simulation (`nbar report --simulate`): the analysis is its motion
  // (request::simulated_analysis), plotted against t, and a section tells the run (its end, its
  // events, the integrator's steps and drift) and plots its energies. Not owned; null: a sweep.
  const Simulation* simulation = nullptr;
};

// The analysis's sweep should have order 3 (jerk is plotted; lower orders plot less). Forces
// are shown when it has the dynamics stage, stresses when it has the stress stage. Frames out of
// range are Error(ErrorKind::BadInput).
std::string html_report(const Analysis& analysis, const ModelSummary& summary, const ReportOptions& options);

// The stages a report of this model shows: order 3, dynamics when the model has masses or
// loads, stresses when it also has a shaped link.
AnalysisOptions report_analysis_options(const ModelSummary& summary);

}  // namespace nbar::render
