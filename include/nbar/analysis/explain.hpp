// The method, step by step, for the model at hand: what a course on planar mechanisms writes
// out by hand (Gruebler-Kutzbach count, the vector q of natural coordinates, the constraint
// equations Phi and their Jacobian Phi_q, the Newton-Raphson iterations, the velocity and
// acceleration systems, the instant centres). Everything is derived from the constraint rows
// the solver itself uses, so what is printed is what is solved. `nbar
// explain`, Python's Model.explain() and the web app's step-by-step panel render it.
#pragma once

#include <Eigen/Core>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "nbar/kinematics/mechanism.hpp"
#include "nbar/kinematics/sweep.hpp"
#include "nbar/model/diagnostics.hpp"
#include "nbar/model/run_control.hpp"
#include "nbar/stress/link_stress.hpp"

namespace nbar {

struct ExplainOptions {
  int step = 0;              // the sample of the sweep to explain (0 = the start)
  std::optional<int> steps;  // samples of the sweep, as `nbar solve --steps`; unset: the model's
  int max_iterations = 50;   // of the Newton-Raphson iterations shown
  // The sweep to the step checks it between samples, the explanation between its parts
  // (stage "explain"): Error(ErrorKind::Cancelled) when it says stop.
  RunControl control;
  int max_steps = kDefaultMaxSweepSamples;  // a larger sweep (the model's or `steps`) is an error
  int sections = 200;  // cross-sections per shaped link for the stresses at the pose (as `nbar stress`)
};

// G = 3 (n - 1) - 2 PI - PII, with n the links including the ground.
struct GrueblerCount {
  int links = 0;         // n, the ground included
  int lower_pairs = 0;   // PI: revolute pairs (k - 1 at a point shared by k links) and sliders
  int higher_pairs = 0;  // PII: pins in slots (two freedoms each)
  int dof = 0;           // G
  int mobility = 0;      // the true degrees of freedom, from the rank of Phi_q
};

// One entry of q: a coordinate of a moving point (nbar's natural coordinates are the x and y
// of every moving point; drivers enter the equations as known functions of time).
struct Coordinate {
  std::string name;    // "A.x"
  std::string symbol;  // "x_A" (plain), the LaTeX form is "x_{A}"
  int point = -1;
  int axis = 0;  // 0 x, 1 y
};

// One row of Phi: a rigid-body distance, a rigid-body point, a pin on a line, an orientation,
// or a driver, written with the model's names and numbers in the model's units.
struct EquationRow {
  std::string label;  // as the solver names the row: "length of crank (O2-A)"
  std::string kind;   // "distance", "rigid_x", "rigid_y", "point_on_line", "orientation", "driver"
  std::string text;   // plain text: "(x_A - x_O2)^2 + (y_A - y_O2)^2 - 80^2 = 0"
  std::string latex;  // the same in LaTeX
  // The non-zero entries of this row of Phi_q, symbolically: column of q, plain and LaTeX.
  struct Derivative {
    int column = 0;
    std::string text, latex;
  };
  std::vector<Derivative> jacobian;
  EntityRef source;
  bool driver = false;
  double scale = 1.0;  // the solver scales the row by this so that its residual is a length:
                       // scale * (the left-hand side of `text`, in model units) is the row's
                       // residual in model length units; scale * each Derivative is Phi_q's entry
};

struct NewtonIteration {
  int iteration = 0;      // 0 = the starting guess
  Eigen::VectorXd q;      // model units
  double residual = 0.0;  // max |Phi| at q, model length units
  Eigen::VectorXd dq;     // the step taken from q (empty on the last, converged, row)
};

// A linear system A x = b and its solution.
struct LinearSystem {
  Eigen::MatrixXd matrix;
  Eigen::VectorXd rhs;
  Eigen::VectorXd solution;
};

// The instant centre of two links (the ground is link -1): a point where their velocities
// are equal, or a direction when it lies at infinity (the links translate relative to each
// other).
struct InstantCentre {
  int body_a = -1, body_b = -1;  // body indices, -1 for the ground; body_a < body_b
  std::string name;              // "I(ground,crank)", "I(crank,coupler)"
  bool at_infinity = false;
  Eigen::Vector2d position{0, 0};   // model length units, when finite
  Eigen::Vector2d direction{0, 0};  // unit vector, when at infinity
  bool at_joint = false;            // a primary centre: a revolute joint the two links share
  bool indeterminate = false;       // no relative motion at this instant: every point qualifies
};

struct Explanation {
  std::shared_ptr<const Mechanism> mechanism;
  int step = 0;
  double time = 0.0;                  // s
  std::vector<double> driver_values;  // model units
  GrueblerCount count;
  std::vector<Coordinate> coordinates;  // q, in order
  std::vector<EquationRow> equations;   // Phi, in the solver's row order (constraints, then drivers)
  std::vector<NewtonIteration> newton;  // from the starting guess to convergence
  bool converged = false;
  std::string start;                   // where Newton started: "the drawn pose", "step 3's pose"
  Eigen::MatrixXd jacobian;            // Phi_q at the solution (rows scaled as the solver scales them)
  Eigen::VectorXd q;                   // the solution, model length units
  LinearSystem velocity;               // Phi_q qdot = -Phi_t
  LinearSystem acceleration;           // Phi_q qddot = -(Phi_q qdot)_q qdot - 2 Phi_qt qdot - Phi_tt
  std::vector<InstantCentre> centres;  // every pair of links
  double residual = 0.0;               // max |Phi| at the solution
  // Whether Newton's solution is the sweep's sample (same branch), and by how much they differ
  // (max |q - q_sweep|, model length units). When they differ, q, Phi_q, the velocity and
  // acceleration systems and the centres are the sweep's sample, and `notes` says so.
  bool matches_sweep = true;
  double sweep_difference = 0.0;
  // The stresses at this pose: for each link with a shape (`shape:` or `bar:` with a thickness),
  // in body order, the largest von Mises stress over its cross-sections under this sample's
  // inverse dynamics (`at`: the section, Pa, position along the link in m, as `nbar stress`'s
  // beam model cuts it, ExplainOptions::sections of them), `step` this explanation's, and the
  // safety factor when its material has a yield strength. Empty when no link has a shape.
  std::vector<StressPeak> stresses;
  // Everything the reader should know that the numbers do not say: a start on another branch, a
  // least-squares (redundant) system, links without an angle that have no centres.
  std::vector<std::string> notes;
};

// Explains one sample of the sweep. Throws Error: BadInput for a step outside the sweep,
// CannotAssemble when the start cannot be assembled, StoppedAtLimit when the sweep stops
// before the step.
Explanation explain(std::shared_ptr<const Mechanism> mechanism, const ExplainOptions& options = {});

enum class ExplainFormat { Text, Markdown, Latex };

// The explanation as a document: plain text for terminals, Markdown with LaTeX maths for
// Jupyter and the web app, or a LaTeX fragment.
std::string render_explanation(const Explanation& explanation, ExplainFormat format);

}  // namespace nbar
