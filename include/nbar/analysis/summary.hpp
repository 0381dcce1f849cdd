// What `nbar check` says about a model and what the report's summary shows, computed once:
// points, bodies, joints, degrees of freedom counted two ways, redundant constraints, drivers,
// mass properties and loads, the assembly at the start and every four-bar loop there.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "nbar/dynamics/inverse_dynamics.hpp"
#include "nbar/kinematics/limits.hpp"
#include "nbar/kinematics/loops.hpp"
#include "nbar/kinematics/mechanism.hpp"
#include "nbar/model/diagnostics.hpp"

namespace nbar {

struct BodySummary {
  std::string name;
  std::vector<std::string> points;
  std::optional<double> length;  // m, for bodies of two or more points (first to second)
  bool length_given = false;     // from `lengths:` rather than the drawing
  MassProperties mass;
  std::string mass_source;  // "given", the material's name, "shape, no material" or "none"
};

// A crank-rocker on the ground whose crank has its own angle driver (the input turns fully,
// the output only rocks): the rocker's
// limits, where the crank and the coupler lie in line, stretched and folded, and the time ratio
// of its two strokes at a constant crank speed.
struct RockerSwing {
  double crank_stretched = 0, crank_folded = 0;    // rad, the crank's input angle (as slider-cranks')
  double rocker_stretched = 0, rocker_folded = 0;  // rad, the output's angle (its first point to its second)
  double swing = 0;                                // rad, |rocker_stretched - rocker_folded|
  // Crank turn (rad, in its sense of rotation) from the folded to the stretched limit and back;
  // time_ratio = the longer over the shorter.
  double turn_to_stretched = 0, turn_to_folded = 0, time_ratio = 1;
  std::string description;
};

struct LoopSummary {
  FourBarLoop loop;
  GrashofReport grashof;
  std::string description;          // loops.hpp describe(): class, lengths, which links turn fully
  std::string branch;               // "open" or "crossed" at the start
  double transmission_angle = 0.0;  // rad, at the start
  // A loop on the ground whose input turns fully: mu over that full turn (rad), closed form.
  std::optional<TransmissionOverTurn> transmission_over_turn;
  // When the input cannot turn fully (the loop on the ground): the input angles of its two
  // toggle positions, rad, on the start's part of the range, in the input's measure (its
  // driver's, or the direction of the input from its first point to its second, from +x).
  std::optional<double> toggle_from, toggle_to;
  std::optional<RockerSwing> rocker;  // a crank-rocker on the ground, its crank driven
};

// A slider-crank: a crank on a ground pivot, a rod, and a block sliding on a fixed guide.
// Angles are the crank's input angle (its angle driver's measure, or its direction from its
// first point to its second, from +x), rad, in [from, from + 2 pi) of its driver (else [0, 2 pi)).
struct SliderCrankSummary {
  std::string crank, rod, slider;                       // body names
  double crank_length = 0, rod_length = 0, offset = 0;  // m; offset: the crank pivot from the guide line
  bool crank_turns_fully = false;                       // rod - crank > |offset|
  double stroke = 0;                                    // m, between the dead centres
  double outer_dead_centre = 0, inner_dead_centre = 0;  // rad: crank and rod in line, stretched and folded
  // Crank turn (rad, in its sense of rotation) from the inner to the outer dead centre (the
  // outstroke) and back; time_ratio = the longer over the shorter (1 for an in-line one).
  double outstroke_turn = 0, return_turn = 0, time_ratio = 1;
  std::string description;
};

// A quick-return (slotted lever, crank-shaper): a crank whose pin slides along an arm pivoted on
// the ground. When the crank is shorter than the distance between the pivots the arm swings:
// limit positions where the crank is perpendicular to the arm.
struct QuickReturnSummary {
  std::string crank, arm;                               // body names
  double crank_length = 0, pivot_distance = 0;          // m
  bool arm_turns_fully = false;                         // crank longer than the pivot distance (Whitworth)
  double swing = 0;                                     // rad, the arm's angle between its limits
  double limit_from = 0, limit_to = 0;                  // rad, the crank's input angles at the arm's limits
  double slow_turn = 0, fast_turn = 0, time_ratio = 1;  // rad of crank turn per stroke; slow / fast
  std::string description;
};

struct AssemblySummary {
  std::vector<double> driver_values;  // SI, each driver's value at the start of the sweep
  double residual = 0.0;              // m
  bool passed_singularity = false;    // reaching the start from the drawn pose crossed a singular position
};

struct ModelSummary {
  std::vector<std::string> ground_points, moving_points;
  std::vector<BodySummary> bodies;
  std::vector<std::string> joints;  // "revolute A (crank/coupler)", "slider ... along ...", "slot ..."
  MobilityReport mobility;
  std::vector<std::string> redundant;  // labels of the redundant constraint rows
  std::vector<std::string> drivers;    // one line per driver: what it drives and how it moves

  bool has_masses = false;     // some body has a mass
  bool has_mass_data = false;  // some body has mass properties given or a shape (even without a material)
  bool has_shapes = false;     // some body has a plate outline
  bool has_loads = false;      // gravity, forces, torques or springs
  // Whether inverse dynamics has anything to compute: masses or loads.
  bool has_kinetics() const { return has_masses || has_loads; }
  // Whether the stress stage has a link to cut: a shape with a thickness on a body of two or more points.
  bool has_stress_links = false;

  // At the start of the sweep: the assembly, or why it failed; the loops when it succeeded.
  std::optional<AssemblySummary> assembly;
  std::optional<Error> assembly_error;
  // The first law (of a driver, a force or a torque) that has no value at a time the sweep
  // reaches, at that driver, force or torque; `nbar check` reports it as an error.
  std::optional<Error> law_error;
  std::vector<LoopSummary> loops;
  // The limits and change points of the whole mechanism on the sweep's own path (limits.hpp), from
  // the start both ways, when the start assembles; `limits_error` when the search failed.
  std::optional<PathLimits> limits;
  std::optional<std::string> limits_error;
  // A rocking driver (`at_limits: reverse`): where it turns back over one cycle, or that it never
  // does (then also a never_reverses warning), or why it cannot rock.
  std::optional<std::string> rocking;
  // From the geometry alone (the model's lengths), whether or not the start assembles.
  std::vector<SliderCrankSummary> slider_cranks;
  std::vector<QuickReturnSummary> quick_returns;

  // What the sweep asks that it will not get, or may not mean, said before it runs:
  // "input_limited" (the sweep's path meets a limit of the whole mechanism before its end) and
  // "many_turns" (an angle driver asked to turn more than 4 times, a likely unit mistake) and
  // "rod_leaves_barrel" (a cylinder's rod would leave its barrel over the sweep, cylinders.hpp).
  std::vector<Warning> warnings;
};

// What every command that solves checks before its sweep runs, from the model's numbers alone:
// returns the warnings that need no solving ("many_turns"), and throws the error of a law that
// has no value at a time the sweep reaches (UndefinedLaw, at the law's driver, force or torque).
std::vector<Warning> check_before_sweep(const Mechanism& mechanism);

// The joints as `nbar check` lists them (ModelSummary::joints) for any model the reader has read,
// valid or not: "revolute A (crank/rod)", "slider piston at C along Y1-Y2", "slot ...".
std::vector<std::string> joint_descriptions(const Model& model);

// Never throws for a compiled mechanism: an assembly failure is kept in assembly_error (also a
// model sweep of more than `max_steps` samples, as every command that sweeps refuses it).
// `limit_search_work` bounds the search for the mechanism's limits and a rocking driver's turns
// (LimitSearchOptions::work_budget); past it the summary says the search could not decide.
ModelSummary summarize(const Mechanism& mechanism, int max_steps = kDefaultMaxSweepSamples,
                       double limit_search_work = kDefaultLimitSearchWork);

}  // namespace nbar
