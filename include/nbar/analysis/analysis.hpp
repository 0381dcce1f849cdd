// One analysis pipeline, in the order the physics flows (like MuJoCo's forward pipeline in
// fixed stages): the sweep of the drivers, then the inverse dynamics of every sample, solved
// once and kept, then the stresses along every link, taken from the kept dynamics. Front-ends
// (the CLI, the web server, Python) ask for the stages they need and render the Analysis; none
// of them solves anything itself.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "nbar/dynamics/inverse_dynamics.hpp"
#include "nbar/kinematics/mechanism.hpp"
#include "nbar/kinematics/sweep.hpp"
#include "nbar/kinematics/table.hpp"
#include "nbar/model/diagnostics.hpp"
#include "nbar/model/run_control.hpp"
#include "nbar/stress/link_fe.hpp"
#include "nbar/stress/link_stress.hpp"

namespace nbar {

// How stresses are computed: beam theory on cross-sections (quick; slender links between
// joints), or plane-stress finite elements on each link's plate (the peaks at pin holes,
// fillets and in plates).
enum class StressMethod { beam, fe };

// Cross-sections per link for the beam stresses: fewer miss the peaks, more only cost time and
// memory (the command line, the web server and Python take the same range).
inline constexpr int kMinSectionsPerLink = 10;
inline constexpr int kMaxSectionsPerLink = 100'000;

struct AnalysisOptions {
  std::optional<int> steps;  // samples of the sweep, ends included; unset: the model's
  int order = 2;             // highest time derivative, 0 to 5; raised to 2 for dynamics and stress
  bool dynamics = false;     // joint forces, driver efforts, energies at every sample
  bool stress = false;       // the largest von Mises stress of every link with a shape (implies dynamics)
  StressMethod stress_method = StressMethod::beam;
  int sections = 200;                       // stress, beam: cross-sections per link, at least (10 to 100 000)
  FeOptions fe;                             // stress, fe: mesh size and threads
  int max_steps = kDefaultMaxSweepSamples;  // a larger sweep (the model's or `steps`) is an error
  RunControl control;                       // cancellation, deadline and progress for every stage
  // Overrides of the model's first driver's `at_limits` and `cycles` (`--at-limits reverse`): the
  // analysis then runs on the model with them (with_sweep_options).
  std::optional<AtLimits> at_limits;
  std::optional<int> cycles;
  // Each sample's condition estimate (Sample::reciprocal_condition), for the `cond` column: a few
  // solves per sample with the factors the sweep kept, so only when asked.
  bool condition = false;
};

// The mechanism the options' sweep runs on: `mechanism` itself, or, when the options override
// what its first driver does at a limit, the model with that override, compiled (a ModelError at
// the driver when the model cannot rock so).
std::shared_ptr<const Mechanism> with_sweep_options(std::shared_ptr<const Mechanism> mechanism,
                                                    const AnalysisOptions& options);

// The inverse dynamics of every sample, solved once.
struct DynamicsStage {
  std::shared_ptr<const InverseDynamics> solver;  // the structure (unknowns, joints, masses)
  std::vector<DynamicsResult> samples;            // one per sample of the sweep, in order
  bool unique = true;                             // false: redundant constraints, minimum-norm forces
  double max_residual = 0.0;                      // of the Newton-Euler equations, N or N m
  std::vector<Warning> warnings;                  // forces that are not unique
};

// The stresses in every link that has a shape, from the kept dynamics: by the beam model
// (`links` and `peaks`) or by finite elements (`fe` and `fe_peaks`), as the options chose.
struct StressStage {
  StressMethod method = StressMethod::beam;
  std::shared_ptr<const LinkStress> links;  // beam
  std::vector<StressPeak> peaks;            // beam: one per analysed body
  std::shared_ptr<const LinkFe> fe;         // fe: every link's plate model, factorised
  std::vector<FePeak> fe_peaks;             // fe: one per analysed body
};

// What analyse() keeps, field by field: the stage that fills it, its units and its shape (like
// MuJoCo's mjData). N is the number of samples solved (sweep.samples.size()), n the coordinate
// count (2 per moving point: mechanism->coordinate_count()), B the model's bodies.
struct Analysis {
  // Given to analyse() and shared, never copied: the model (SI units inside), its constraint rows
  // and mobility. Set before any stage runs.
  std::shared_ptr<const Mechanism> mechanism;
  // Stage 1, always: the assembly at the start, then N samples along the drawn branch, each with
  // its time (s), driver values (SI: rad or m) and an n x (order + 1) matrix of Taylor
  // coefficients of q in time (column k is q^(k) / k!; m, m/s, ...). A sweep stopped at a limit
  // position keeps what it solved (complete false, stop_reason says why).
  SweepResult sweep;
  // Stage 2, when options.dynamics or options.stress: N DynamicsResult in sample order, each with
  // the pin forces (N, one per InverseDynamics::joint_links() entry), slider and slot forces (N,
  // N m), driver efforts (N m or N, one per driver) and energies (J). Empty optional otherwise.
  std::optional<DynamicsStage> dynamics;
  // Stage 3, when options.stress: one peak per shaped body, the largest von Mises stress over the
  // N samples (Pa), where (the cross-section, or the plate's point in m) and at which step, with
  // the safety factor when the material has a yield strength; by the beam model (peaks) or by
  // finite elements (fe_peaks). Empty optional otherwise.
  std::optional<StressStage> stress;

  const Model& model() const { return mechanism->model(); }
  bool complete() const { return sweep.complete; }
  // The warnings of every stage that ran, in stage order.
  std::vector<Warning> warnings() const;
};

// Runs the stages the options ask for. Throws Error: CannotAssemble when the start cannot be
// assembled, BadInput for options out of range, UndefinedLaw when a law has no value where it
// is needed, InvalidModel when stresses are asked of a model with no shaped link (or, by finite
// elements, of a link whose material has no elastic constants), Cancelled.
// A sweep stopped at a limit position is not an error: complete() is false, the samples solved
// so far are kept (and analysed by the later stages) and sweep.stop_reason says why.
Analysis analyse(std::shared_ptr<const Mechanism> mechanism, const AnalysisOptions& options = {});

// The sweep as a table in the model's units: the kinematic columns, then the dynamics columns
// when that stage ran (kinematics/table.hpp and dynamics/dynamics_table.hpp name them), with
// numerical noise made exact 0 (zero_numerical_noise); so is section_profile_table's.
// `extra`, the columns on request (columns_on_request), come after the kinematic ones.
ResultTable result_table(const Analysis& analysis, const ColumnsOnRequest& extra = {});
// The same columns stored column by column, for front-ends that hand columns out whole.
ColumnTable result_columns(const Analysis& analysis, const ColumnsOnRequest& extra = {});

// Every cross-section of one link at one sample: x, area, N, V, M, sigma at both fibres, tau
// and von Mises. Needs the stress stage by the beam method; throws Error(BadInput) for a body without a shape or a
// step that was not solved.
ResultTable section_profile_table(const Analysis& analysis, int body, int step);

// A four-bar loop's transmission angle mu over the sweep (rad), each extreme with the sample
// where it occurs: the smallest and largest mu, and the design value, the smallest of
// min(mu, pi - mu) over the sweep (how near the loop comes to a dead point, whichever side of
// 90 deg mu swings to). From the core, so that no front-end computes it. Empty without samples.
struct TransmissionExtremes {
  std::string loop;
  double min = 0.0, max = 0.0, design = 0.0;  // rad
  int min_step = -1, max_step = -1, design_step = -1;
};
std::vector<TransmissionExtremes> transmission_extremes(const Analysis& analysis);

}  // namespace nbar
