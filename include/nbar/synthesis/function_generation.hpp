// Freudenstein function generation: a four-bar whose output angle is a given function of its
// input angle, exactly at 3 precision points or by least squares at more.
//
// Convention (Norton, Design of Machinery): fixed pivots O2 = (0, 0) and O4 = (d, 0); input
// crank O2A of length a at angle phi, coupler AB of length b, output O4B of length c at
// angle psi, both angles counter-clockwise from the frame line O2 -> O4. Closing the loop
// a e^(i phi) + b e^(i theta3) = d + c e^(i psi) and eliminating theta3 gives
//     K1 cos(psi) - K2 cos(phi) + K3 = cos(phi - psi),
//     K1 = d / a,  K2 = d / c,  K3 = (a² - b² + c² + d²) / (2 a c),
// linear in K1, K2, K3. The task maps x in [x_start, x_end] linearly onto phi and
// y = f(x) (from f(x_start) to f(x_end)) linearly onto psi. docs/synthesis-classic.md.
//
// Throws Error(ErrorKind::InvalidModel), naming the problem, for bad input (too few or coincident
// precision points, non-finite numbers, empty ranges) and when no real four-bar results.
#pragma once

#include <array>
#include <functional>
#include <vector>

#include "nbar/synthesis/fourbar_design.hpp"

namespace nbar::synthesis {

// Chebyshev spacing of n precision points on [x_start, x_end]:
// x_j = (a + b)/2 - (b - a)/2 cos((2j - 1) pi / (2n)), j = 1..n (ascending when a < b).
std::vector<double> chebyshev_spacing(double x_start, double x_end, int n);

struct FunctionTask {
  std::function<double(double)> f;  // the function to generate, y = f(x)
  double x_start = 0, x_end = 1;    // the range of x
  double input_start = 0;           // phi at x_start (rad)
  double input_range = 0;           // phi(x_end) - phi(x_start) (rad, either sign)
  double output_start = 0;          // psi at y = f(x_start) (rad)
  double output_range = 0;          // psi at f(x_end) minus psi at f(x_start) (rad, either sign)
  double frame_length = 1;          // d: sets the size of the linkage
  int samples = 1001;               // evenly spaced x for the structural error over the range
};

// The generated output against the wanted one at x: output angle error in rad and the same
// error in y units (generated minus wanted). When the linkage cannot be assembled at x on
// its branch, `assembled` is false and both errors are 0.
struct StructuralError {
  double x = 0;
  double angle = 0;
  double value = 0;
  bool assembled = true;
};

struct FunctionDesign {
  // O2 at the origin, O4 at (d, 0), moving pivots with the crank at the first precision
  // point (in the order given), the coupler point on the output's moving pivot.
  FourBarDesign design;
  double input = 0, coupler = 0, output = 0, frame = 0;  // link lengths a, b, c, d (> 0)
  std::array<double, 3> k{};                             // K1, K2, K3; a negative K1 (K2) means the crank (output
                                                         // link) points opposite to phi (psi): the design has it right
  int branch = 0;  // +1/-1: side of B from the line A -> O4 (as branch_signs in burmester.hpp),
                   // the assembly that best meets the first precision point; kept over the range
  std::vector<StructuralError> precision;  // at each precision point, simulated
  StructuralError worst;                   // largest |angle error| over the range's samples and the precision points
  bool whole_range = true;                 // the linkage assembles on its branch at every sample and precision point
  double fails_at_x = 0;  // when not: the first such x (samples from x_start on, then precision points)
};

// The precision points as check_design's targets: the input's and the output's rotations from
// the first precision point, as the task maps x onto phi and f(x) onto psi.
std::vector<RotationTarget> rotation_targets(const FunctionTask& task, const std::vector<double>& precision_x);

// precision_x: 3 points (solved exactly) or more (least squares on the Freudenstein
// equation's residuals; the structural error is then nonzero at every point).
FunctionDesign freudenstein_design(const FunctionTask& task, const std::vector<double>& precision_x);

}  // namespace nbar::synthesis
