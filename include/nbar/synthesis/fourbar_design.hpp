// A four-bar found by synthesis, as pivots in the first precision position, and what the
// kinematics engine says about it.
// (Owner of the implementation: fourbar_design.cpp. The struct is shared by every method.)
#pragma once

#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

#include "nbar/kinematics/loops.hpp"
#include "nbar/model/model.hpp"

namespace nbar::synthesis {

// Positions with the coupler in its first precision position.
struct FourBarDesign {
  Eigen::Vector2d ground_a{0, 0};  // fixed pivot of the input link
  Eigen::Vector2d ground_b{0, 0};  // fixed pivot of the output link
  Eigen::Vector2d moving_a{0, 0};  // coupler-input joint
  Eigen::Vector2d moving_b{0, 0};  // coupler-output joint
  Eigen::Vector2d coupler_point{0, 0};
  // Where the design's input and output angles are measured from (rad): the input angle is
  // the direction ground_a -> moving_a plus input_angle_offset, the output angle the direction
  // ground_b -> moving_b plus output_angle_offset. 0 but for function generation, where a
  // negative Freudenstein length points a link opposite to its angle (an offset of pi): the
  // task's angles are those of a pointer on the link. make_fourbar_model then adds that
  // pointer, and check_design reports input angles and motions in the design's angles.
  double input_angle_offset = 0;
  double output_angle_offset = 0;
};

// ---- Checking a design with the kinematics engine (fourbar_design.cpp) -------------------
//
// Lengths are in whatever unit the design is written in (the check never converts); angles
// are in radians, counter-clockwise. The input is the link ground_a-moving_a, driven by its
// angle; the output is ground_b-moving_b.

// A precision position: where the coupler point should be and, for motion generation, the
// coupler's rotation from the first position. targets[0] is the first position itself.
struct Target {
  Eigen::Vector2d point{0, 0};
  std::optional<double> rotation;  // rad, relative to the first position
};

// A precision point of function generation: the input's and the output's rotations from the
// first position (rad, counter-clockwise), which the linkage should couple.
struct RotationTarget {
  double input = 0;
  double output = 0;
};

// How an exported model moves its input: the design's input angles (rad; the direction of the
// input link from +x, plus FourBarDesign::input_angle_offset).
struct InputMotion {
  double from = 0;
  double to = 0;
  int steps = 361;
};

// What happens at one target.
struct TargetCheck {
  double input_angle = 0;     // input angle at the target, unwrapped along the motion (rad)
  int branch = 0;             // +1 or -1: side of the line moving_a -> ground_b where moving_b
                              // lies (loops.hpp branch_sign), in the pose found at the target
  bool on_branch = false;     // on the first target's assembly branch
  bool reached = false;       // the engine got there from the first target on that branch
  double error = 0;           // distance from the coupler point to the target (angle targets:
                              // |output rotation - wanted|, rad), as simulated when reached
  double rotation_error = 0;  // motion targets: |coupler rotation - wanted| (rad)
};

struct DesignCheck {
  std::string invalid;  // why the design is not a linkage (a link of zero length...); empty if it is
  double frame = 0, input = 0, coupler = 0, output = 0;  // link lengths
  GrashofReport grashof;
  bool input_turns_fully = false;

  std::vector<TargetCheck> targets;
  // A target lies off the first target's branch: the input cannot reach it by turning...
  bool branch_defect = false;
  bool circuit_defect = false;  // ...because it lies on the other circuit (take the linkage apart)
  bool toggle_between = false;  // ...because a toggle (the input's limit) lies between them
  // Every target is on the branch, but turning the input one way does not meet them in order.
  bool order_defect = false;

  int direction = 0;                 // +1 counter-clockwise, -1 clockwise: how the input turns through the targets
  double travel = 0;                 // input rotation from the first to the last target along that motion (rad)
  double min_transmission = 0;       // min over that motion of min(mu, pi - mu), rad
  double min_transmission_full = 0;  // the same over the branch's whole range (0 for a rocker input)
  double max_error = 0;              // worst `error` over the reached targets
  double max_rotation_error = 0;     // worst `rotation_error`
  InputMotion motion;                // a sweep for an exported model: through the targets, or a full turn of a crank

  bool defect_free() const { return invalid.empty() && !branch_defect && !order_defect && !unreached(); }
  // Some target on the branch was not reached by the simulation, or no pose of the linkage
  // meets a target at all (its input angle is out of reach: function generation).
  bool unreached() const;
};

struct CheckOptions {
  // A path target counts as on the coupler curve within this distance, relative to the
  // linkage's size; farther, the nearest pose is used and the miss is reported.
  double match_tolerance = 1e-6;
};

// Path generation (targets without rotation) and motion generation (with rotation).
DesignCheck check_design(const FourBarDesign& design, const std::vector<Target>& targets,
                         const CheckOptions& options = {});
// Function generation: targets[0] should be {0, 0}, the first position.
DesignCheck check_design(const FourBarDesign& design, const std::vector<RotationTarget>& targets,
                         const CheckOptions& options = {});

// min(mu, pi - mu) over the input angles from..to (rad, either order; a full turn or more
// covers every angle), mu being the angle between coupler and output. Closed form.
double min_transmission_angle(const FourBarDesign& design, double from, double to);

// Indices of `checks` from best to worst: valid and defect-free first, then fewer kinds of
// defect, larger min_transmission, smaller max_error. Stable for ties.
std::vector<int> rank_designs(const std::vector<DesignCheck>& checks);

// A text for the defects: "none", or e.g. "circuit, order".
std::string describe_defects(const DesignCheck& check);

// The four-bar as a model: ground points O2 (ground_a) and O4 (ground_b); bodies input
// [O2, A], coupler [A, B, P], output [O4, B]; an angle driver on the input moving as
// `motion` says (a static pose at the drawn angle without it). A link whose angle offset is
// not a multiple of 2 pi gets a pointer, so that its body angle (first to second point) is the
// design's angle: the input becomes [O2, Ip, A] and the output [O4, Op, B], Ip and Op being A
// and B turned by the offset about the link's fixed pivot (points appended after P). Coordinates are in `units`
// (converted to SI in the model); `motion` is in rad.
Model make_fourbar_model(const FourBarDesign& design, const std::string& name, const Units& units = {},
                         const std::optional<InputMotion>& motion = std::nullopt);

}  // namespace nbar::synthesis
