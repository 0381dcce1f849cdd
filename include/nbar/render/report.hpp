// One self-contained HTML file that tells a mechanism's story: the model summary (degrees of
// freedom, Grashof class, mass properties), the animation, the paths of its coupler points,
// plots of the bodies' angles, angular velocities, accelerations and jerk, and, when the model
// has masses, loads and shapes, the joint forces, the driver efforts and the stresses with each
// link's largest von Mises stress marked on the drawing. No network access is needed to read
// it, and it reads on a phone.
#pragma once

#include <string>

#include "nbar/kinematics/sweep.hpp"

namespace nbar::render {

struct ReportOptions {
  std::string source;      // the model file's name, for the header
  int frames = 72;         // animation frames
  int sections = 200;      // stress sections per link
};

// The sweep must have order 3 or more (jerk plots) and its samples; forces and stresses are
// computed here when the model has what they need.
std::string html_report(const Mechanism& mech, const SweepResult& sweep, const ReportOptions& options);

}  // namespace nbar::render
