// The immutable description of a planar linkage: points, bodies, joints, drivers.
// Everything is stored in SI units (m, rad, s); `units` only records how the user
// wants to read and write numbers. Built by the model-file parser or by code
// (ModelBuilder); checked and compiled into a Mechanism by the kinematics stage.
#pragma once

#include <Eigen/Core>

#include <array>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "nbar/model/diagnostics.hpp"
#include "nbar/model/geometry.hpp"
#include "nbar/model/law.hpp"
#include "nbar/model/units.hpp"

namespace nbar {

struct Point {
  std::string name;
  Eigen::Vector2d position;  // in the starting pose, m
  bool ground = false;       // fixed to the frame
  // Made by the reader for a guide given by a point and an angle (`along: {point: C, angle: 30}`):
  // it only sets the guide's direction, so it has no columns and no label.
  bool guide_direction = false;
};

struct Material {
  std::string name;
  double density = 0.0;                  // kg/m^3
  std::optional<double> yield_strength;  // Pa
  // Elastic constants, for finite-element stresses (`nbar stress --method fe`); the beam model
  // and the dynamics need neither.
  std::optional<double> youngs_modulus;  // Pa, > 0
  std::optional<double> poisson_ratio;   // in [0, 0.5)
};

// Mass properties given directly instead of computed from a shape.
struct GivenInertia {
  double mass = 0.0;         // kg
  Eigen::Vector2d cg{0, 0};  // m, in the starting pose
  double inertia = 0.0;      // kg m^2 about the centre of mass
};

struct Body {
  std::string name;
  std::vector<int> points;              // indices into Model::points; the first two define its angle
  std::optional<double> length;         // exact length of a two-point body (m), overriding the drawing
  std::optional<Region> shape;          // the plate's outline minus holes, in the starting pose (m)
  double thickness = 0.0;               // m, with a shape
  std::optional<Material> material;     // with a shape: density and strength
  std::optional<GivenInertia> inertia;  // explicit mass properties (then the shape is only for stresses)
};

// Prismatic joint: `point` of `body` moves on the line through along[0], along[1], and `body`
// keeps its orientation relative to the guide (the body or ground that owns the along points).
struct Slider {
  int body = -1;
  int point = -1;
  std::array<int, 2> along{-1, -1};
};

// Pin in slot: `point` moves on the line through along[0], along[1] and may rotate freely.
struct Slot {
  int point = -1;
  std::array<int, 2> along{-1, -1};
};

enum class DriverKind {
  Angle,     // angle of `body` (from its 1st to its 2nd point), from +x or relative to `relative_to`
  Distance,  // distance between points[0] and points[1]
  Slide,     // position of slider `slider`'s point along its guide, from the guide's first point
};

// The most an angle driver may turn over a sweep (the model's check) or to reach a pose (pose_at):
// the work of following the motion grows with the travel.
inline constexpr double kMaxDriverTurns = 1000.0;

// What a from/to sweep does when its path meets a limit of the mechanism (where the input
// cannot go on and turns back): stop there (exit 4 on the command line), or turn back and rock
// between the limits (`at_limits: reverse`, one driver without a law or an acceleration).
enum class AtLimits { Stop, Reverse };
inline constexpr int kMaxRockingCycles = 10000;

// How a driver moves. Either a from/to sweep sampled at evenly spaced values (with the
// derivatives of the driver moving at `speed` with `accel` at every sample), or a law in time.
struct Driver {
  std::string name;  // column name in outputs
  DriverKind kind = DriverKind::Angle;
  int body = -1;                      // Angle
  int relative_to = -1;               // Angle: -1 means the +x axis of the frame
  std::array<int, 2> points{-1, -1};  // Distance
  int slider = -1;                    // Slide: index into Model::sliders

  std::optional<double> from;  // SI (rad or m); unset means "the value in the drawn pose"
  std::optional<double> to;
  double speed = 1.0;      // SI per second
  double accel = 0.0;      // SI per second squared
  std::optional<Law> law;  // value as a function of t, in SI
  // `nbar simulate` only: the input is left to the loads (its row is dropped) and starts at its
  // start value moving at `initial_speed` (SI per second). Kinematics ignores both.
  bool free = false;
  double initial_speed = 0.0;
  AtLimits at_limits = AtLimits::Stop;
  // With `at_limits: reverse`: full cycles of the rocking motion to run (each back to the start's
  // pose, going the start's way); unset: the input travels |to - from| in all, turning back at
  // each limit it meets.
  std::optional<int> cycles;

  bool is_angular() const { return kind == DriverKind::Angle; }
};

struct SweepSpec {
  int steps = 361;                  // from/to sweeps: number of samples, ends included
  double duration = 1.0;            // time-law sweeps, s
  std::optional<double> time_step;  // time-law sweeps, s; default duration/100
};

// A force on a point: on `body` there, or on the joint's pin when body is -1 (the pin passes it
// on to the bodies that meet there). Components are laws in t (a constant is a law too), N.
struct PointLoad {
  int point = -1;
  int body = -1;
  Law fx, fy;
};

// A torque on a body, N m, counter-clockwise positive.
struct BodyTorque {
  int body = -1;
  Law torque;
  // A motor's torque-speed line: the torque falls linearly from `torque` at rest to 0 at this
  // angular speed of the body (rad/s, non-zero, its sign the direction it drives).
  std::optional<double> no_load_speed;
};

// A linear spring and damper between two points: tension = stiffness (length - free_length)
// + damping d(length)/dt + preload, pulling the points together when positive.
struct Spring {
  std::string name;
  std::array<int, 2> points{-1, -1};
  double stiffness = 0.0;    // N/m
  double free_length = 0.0;  // m
  double damping = 0.0;      // N s/m
  double preload = 0.0;      // N, the tension at the free length
};

// Friction in a joint, read by `nbar simulate` (and `nbar equilibrium`, which ignores it: at rest
// a friction force is whatever holds). It resists the joint's relative motion: the relative
// rotation of two links at a pin, or the slide of a slider's or a slot's point along its guide.
// Viscous: -viscous x speed. Coulomb: a given constant torque or force, -coulomb x
// tanh(speed / creep_speed), smooth so that an explicit integrator can cross zero speed; a joint
// held by Coulomb friction creeps at a speed of the order of creep_speed.
struct JointFriction {
  enum class Joint { Revolute, Slider, Slot } joint = Joint::Revolute;
  int index = -1;  // Revolute: the pin's point; Slider: index into Model::sliders; Slot: into Model::slots
  std::array<int, 2> links{-1, -1};  // Revolute: the two links whose relative rotation it resists (-1: ground)
  double viscous = 0.0;              // N m s/rad (revolute) or N s/m (sliding)
  double coulomb = 0.0;              // N m (revolute) or N (sliding)
  double creep_speed = 0.0;          // rad/s or m/s, > 0 (the reader sets the default)
};

// The largest coefficient (stiffness N/m, damping N s/m, friction in SI) a model may give: past it
// the motion's time scale is below any step an integrator can take, so it is a typo.
inline constexpr double kMaxLoadCoefficient = 1e12;

// A simulation's settings given in the model file (`simulation:`); the command line's flags
// override each of them.
struct SimulationSpec {
  std::optional<double> end_time;            // s
  std::optional<double> output_step;         // s
  std::optional<double> relative_tolerance;  // of the integrator
  std::optional<std::string> stop_when;      // "slider.x > 200", checked by the reader's syntax
  std::optional<bool> reverse_at_toggle;     // at_toggle: reverse (true) or stop (false)
};

struct Model {
  std::string name;
  Units units;
  std::vector<Point> points;
  std::vector<Body> bodies;
  std::vector<Slider> sliders;
  std::vector<Slot> slots;
  std::vector<Driver> drivers;
  SweepSpec sweep;

  Eigen::Vector2d gravity{0, 0};  // m/s^2
  std::vector<PointLoad> point_loads;
  std::vector<BodyTorque> torques;
  std::vector<Spring> springs;
  std::vector<JointFriction> frictions;
  SimulationSpec simulation;

  int find_point(const std::string& name) const;  // -1 when absent
  int find_body(const std::string& name) const;
  bool has_time_law() const;
};

// Checks names, references and geometry that need no solving; throws ModelError.
void validate(const Model& model);

}  // namespace nbar
