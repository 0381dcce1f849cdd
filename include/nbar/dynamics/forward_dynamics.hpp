// Forward dynamics: how a mechanism moves under its loads when some (or all) of its drivers are
// released (`free: true` in the model).
//
// Formulation (docs/dynamics.md): the equations of motion in the natural coordinates q of the
// kinematics, M q'' + Phi_q^T lambda = Q(t, q, q'), with M constant (each body's mass and inertia
// expressed on its two frame points), Phi the constraint rows and the rows of the drivers that stay
// kinematic. Index 1: at every evaluation the accelerations solve that system with Phi_q q'' =
// gamma, through the sparse augmented matrix M + alpha Phi_q^T Phi_q (its pattern analysed once),
// conjugate gradients on the Schur complement and a round of refinement, so redundant
// constraints need no special treatment, a free motion without inertia is found and refused, and
// the cost is linear in the size of a chain. Integrated by the embedded Runge-Kutta pairs of
// Dormand and Prince, 8(5,3) (DOP853) and, next to a toggle, 5(4), with their continuous
// extensions for the output times; after every accepted step q is projected back onto Phi = 0
// and q' onto Phi_q q' = -Phi_t (corrections in the mass's metric), so the drift stays at the
// solver's tolerance on all three levels.
#pragma once

#include <Eigen/Core>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "nbar/kinematics/mechanism.hpp"
#include "nbar/kinematics/sweep.hpp"
#include "nbar/kinematics/table.hpp"
#include "nbar/model/diagnostics.hpp"
#include "nbar/model/run_control.hpp"

namespace nbar {

// The integration method, in words, as the outputs name it.
inline constexpr const char* kSimulationMethod =
    "Dormand-Prince 8(5,3) (DOP853), 5(4) next to toggles, projected onto the constraints after every step";

// Stop when a column of the simulation's table (`simulation_table`) crosses a value, in the
// column's unit (the model's units; J for the energies): "slider.x > 0.2".
struct StopCondition {
  std::string column;
  bool above = true;  // stop when the column becomes > value (else < value)
  double value = 0.0;
  std::string text;  // as the user wrote it, for the report
};

// What a run does where its constraints (the kept rows' Jacobian) lose rank: a toggle or change
// point, where the loads no longer determine the motion.
enum class AtToggle { stop, reverse };

struct SimulationOptions {
  double end_time = 1.0;             // s, > 0
  double output_step = 0.0;          // s between rows; 0: end_time / 100
  double relative_tolerance = 1e-8;  // of the Runge-Kutta error estimate
  long max_steps = 10'000'000;       // accepted and rejected steps together
  std::optional<StopCondition> stop_when;
  AtToggle at_toggle = AtToggle::stop;  // reverse: every speed reversed there (a rigid stop), the run goes on
  // 1: everything on the caller's thread; otherwise (0, the default, or 2) the output rows are
  // made on a second thread while the integration goes on, where rows_on_second_thread (below)
  // says. The answer is the same either way, to the last bit.
  unsigned threads = 0;
};

// Whether a run with these options makes its output rows on a second thread here: threads is
// not 1, this process may use two cores or more (its CPU affinity), there are threads (not in
// WebAssembly) and 64 rows or more. Where a thread cannot be had after all, the run goes on one.
bool rows_on_second_thread(const SimulationOptions& options);

// An event the run met, located by root-finding on the integrator's continuous output to 1e-12 s.
// It adds a row at its time (`row`).
struct SimulationEvent {
  enum class Kind { toggle, stop_when } kind = Kind::toggle;
  double time = 0.0;  // s
  int row = 0;
  std::string message;
};

// Energies at one output time, J. The balance is kinetic + potential (gravity and springs)
// + dissipated - work_in, minus its value at t = 0: zero up to the integration error.
struct SimulationEnergy {
  double kinetic = 0.0;
  double gravity = 0.0;
  double spring = 0.0;
  double dissipated = 0.0;  // by dampers, since t = 0
  double work_in = 0.0;     // by applied forces and torques and by the kinematic drivers, since t = 0
  double balance = 0.0;
};

// How far the rows are from the constraints: max |Phi| (m), max |Phi_q q' + Phi_t| (m/s),
// max |Phi_q q'' - gamma| (m/s^2), over every output row.
struct ConstraintDrift {
  double position = 0.0, velocity = 0.0, acceleration = 0.0;
};

struct SimulationStatistics {
  long accepted_steps = 0;
  long rejected_steps = 0;
  long evaluations = 0;                            // of the accelerations
  double smallest_step = 0.0, largest_step = 0.0;  // s, of the accepted steps
  double largest_energy_error = 0.0;               // max |balance| over the rows, J
  ConstraintDrift drift;
};

struct Simulation {
  // One sample per output time: step, time, driver values (from q, free drivers included) and the
  // Taylor coefficients [q, q', q''/2], as a sweep's samples are, so the kinematic columns of
  // `nbar solve` apply unchanged.
  std::vector<Sample> samples;
  std::vector<SimulationEnergy> energies;
  std::vector<int> free_drivers;
  SimulationStatistics statistics;
  std::vector<SimulationEvent> events;  // in time order; a stop_when event ends the run (complete)
  // Before the run: free drivers' initial speeds the constraints did not allow
  // ("initial_speed_projected", with the size of the correction).
  std::vector<Warning> warnings;
  bool complete = true;
  std::string stop_reason;  // when !complete: what stopped it, at which time
  EntityRef stop_where;     // the entity concerned, for the file position
  bool cancelled = false;   // stopped by the RunControl (a cancel, a deadline), not by the motion

  // The time of the last row, s: where a run that stopped early got to.
  double time_reached() const { return samples.empty() ? 0.0 : samples.back().time; }
};

// Runs the simulation from the model's start: positions assembled at t = 0 with every driver at
// its start, velocities from the kinematic drivers' speeds and the free drivers' `initial_speed`.
// A run that cannot continue (a singular position, a step size too small, a failed projection)
// returns the rows so far with complete = false. Throws Error before the run for a model that
// cannot be simulated (no mass where a free motion needs inertia, nothing free). A cancel from
// `control` (its token, its deadline, its progress callback answering false, checked before every
// integration step) ends the run the same way, with the rows so far, complete = false and
// cancelled = true; stop_reason says "cancelled at t = ..." with the last row's time. A toggle stops the run (complete
// = false) or, with AtToggle::reverse, reverses every speed there; a stop condition met ends it (complete = true); both
// are in `events`. A stop condition on a column the table does not have is Error(BadInput).
Simulation simulate(const Mechanism& mechanism, const SimulationOptions& options, const RunControl& control = {});

}  // namespace nbar

namespace nbar {

// The simulation as the table `nbar solve` writes (step, t, drivers, every point's x, y, vx, vy,
// ax, ay, every body's angle, omega, alpha, transmission angles), in the model's units, followed
// by the energies in J: energy.kinetic, energy.potential (gravity and springs, as in `solve
// --dynamics`), energy.spring, energy.dissipated, energy.work (done by the loads and the
// kinematic drivers) and energy.balance (kinetic + potential + dissipated - work, minus its start
// value: the integration error).
ResultTable simulation_table(const Mechanism& mechanism, const Simulation& simulation);

// The text "slider.x > 0.2" (or <, with any spaces) as a StopCondition; nullopt when it is not a
// column name, an operator and a number. The column is checked by `simulate`.
std::optional<StopCondition> parse_stop_condition(const std::string& text);

}  // namespace nbar
