// Four-bar loops found in a linkage's topology, Grashof's classification, transmission angle
// and assembly branch of each loop.
#pragma once

#include <Eigen/Core>

#include <string>
#include <vector>

#include "nbar/model/model.hpp"

namespace nbar {

// A closed chain of four links joined by four revolute joints. Links are body indices, or
// -1 for the ground. The frame is the ground when the loop contains it.
struct FourBarLoop {
  int frame = -1, input = -1, coupler = -1, output = -1;
  int o2 = -1;       // joint frame-input
  int a = -1;        // joint input-coupler
  int b = -1;        // joint coupler-output
  int o4 = -1;       // joint output-frame
  std::string name;  // "input-coupler-output" by body names
};

enum class GrashofClass {
  CrankRocker,   // Grashof, shortest link adjacent to the frame: it is the crank
  DoubleCrank,   // Grashof, shortest link is the frame (drag link)
  DoubleRocker,  // Grashof, shortest link is the coupler
  TripleRocker,  // not Grashof: no link turns fully (a non-Grashof double-rocker)
  ChangePoint,   // s + l = p + q: can switch branches at the flat positions
};

struct GrashofReport {
  GrashofClass kind = GrashofClass::TripleRocker;
  double frame = 0, input = 0, coupler = 0, output = 0;  // link lengths
  double margin = 0;                                     // (p + q) - (s + l); > 0 Grashof
  bool input_turns_fully = false;                        // relative to the frame
  bool output_turns_fully = false;
};

// Loops are found from the topology alone; their roles (input = the link next to the frame
// that carries a driver, when one does) use the drivers too.
std::vector<FourBarLoop> find_four_bar_loops(const Model& model);

// `tolerance` decides equality for the change-point case (absolute, in length units).
GrashofReport classify_grashof(double frame, double input, double coupler, double output, double tolerance);
GrashofReport classify_grashof(const FourBarLoop& loop, const std::vector<Eigen::Vector2d>& points, double tolerance);

// The one vocabulary of Grashof classes, as textbooks name them (Norton): "crank-rocker",
// "double-crank", "double-rocker", "triple-rocker", "change point"; a crank-rocker driven by
// its rocker (the input does not turn fully) is a "rocker-crank". Tables, JSON, exported
// files and `nbar check` all use these names.
std::string grashof_name(GrashofClass kind, bool input_turns_fully = true);
std::string to_string(GrashofClass kind);  // grashof_name(kind)
std::string describe(const GrashofReport& report, const FourBarLoop& loop, const Model& model);

// How far the input of a four-bar can turn relative to its frame, on the part of its range that
// holds the input angle `at` (rad, the direction o2 -> a, any turn). Closed form: the diagonal
// from a to o4 has length f, f^2 = input^2 + frame^2 - 2 input frame cos(at - frame_angle) (law
// of cosines), and the loop closes while |coupler - output| <= f <= coupler + output; the limits
// (toggles) are where f reaches either bound. `full` when the input turns fully (no limit);
// otherwise from <= at <= to, in the turn of `at`. `closes` is false when the loop cannot be
// closed at `at` at all (then from = to = at).
struct InputLimits {
  bool full = false;
  bool closes = true;
  double from = 0, to = 0;  // rad
};
InputLimits input_limits(double frame, double input, double coupler, double output, double frame_angle, double at);

// The transmission angle mu of a four-bar whose input turns fully, over that full turn (rad).
// Closed form: cos mu = (coupler^2 + output^2 - f^2) / (2 coupler output), f the diagonal from
// the input-coupler joint to the output-frame joint, so mu grows with f and its extremes are at
// f = |frame - input| and frame + input, the input along the frame line. `design` is the
// smallest of min(mu, pi - mu), how near the loop comes to a dead point: at one of the two
// extremes, since min(mu, pi - mu) has no minimum inside an interval of mu.
struct TransmissionOverTurn {
  double min = 0, max = 0, design = 0;
};
TransmissionOverTurn transmission_over_full_turn(double frame, double input, double coupler, double output);

// Angle between the coupler and the output link at their joint, in [0, pi].
double transmission_angle(const FourBarLoop& loop, const std::vector<Eigen::Vector2d>& points);

// +1 or -1: on which side of the diagonal from the input-coupler joint to the output-frame
// joint the coupler-output joint lies. Constant along a branch of the crank-driven loop; it
// changes only through a toggle of the output or a change point.
int branch_sign(const FourBarLoop& loop, const std::vector<Eigen::Vector2d>& points);
// "open" or "crossed" as the two roots of Norton's closed form (x axis from o2 to o4, angles
// counter-clockwise): open when the coupler-output joint lies to the left of the line from
// the input-coupler joint to o4. A mechanism drawn mirrored reads the other way round.
std::string branch_name(int branch_sign);

}  // namespace nbar
