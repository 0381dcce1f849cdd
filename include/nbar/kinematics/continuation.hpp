// Following one assembly branch while the drivers move: predict with the Taylor series of q
// in the path parameter, correct with Newton using the last factorisation, and shrink the
// step rather than ever jump to another branch. Also used to assemble the mechanism at the
// drivers' starting values, beginning from the drawn pose.
#pragma once

#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "nbar/kinematics/position.hpp"

namespace nbar {

// Each driver's value as a Taylor series (with `terms` coefficients) in the path parameter p.
using DriverPath = std::function<void(double p, int terms, std::vector<Series>& out)>;

struct TrackOptions {
  int terms = 4;           // coefficients of the predictor series (order + 1)
  double min_step = 1e-7;  // relative to the interval, below which the path is given up
  // When p_end lies on a singular position (a change point, where branches cross), take the
  // series there from a regular point just before it instead of from its singular Jacobian,
  // accurate in their first `coast_terms` coefficients; 0: never (the end is then accepted as
  // it comes, or the path given up).
  int coast_terms = 0;
};

struct TrackReport {
  bool reached = false;
  int steps = 0;
  bool passed_singularity = false;  // det(Phi_q) changed sign: a change point was crossed
  double singular_parameter = 0.0;
  // p_end lies on a singular position: state.series there were re-centred from a regular point
  // before it on the branch followed, and the state's workspace holds that point's
  // factorisation, so that the next step continues the same branch through the singular position.
  bool singular_end = false;
  double singular_end_accuracy = 0.0;  // an estimate of their relative error in q, q', q''
  double limit_parameter = 0.0;        // where the path was given up
  double reciprocal_condition = 0.0;
  std::string reason;
};

// Moves state from state.parameter to p_end along `path`. On entry state.q must solve the
// constraints at state.parameter with the Jacobian factorised and state.series holding at
// least options.terms coefficients; on exit the same holds at the point reached.
TrackReport track(const Mechanism& mech, State& state, const DriverPath& path, double p_end,
                  const TrackOptions& options = {});

class AssemblyError : public Error {
 public:
  // `where` is the model entity of the row, so that the message is located at it.
  AssemblyError(const std::string& message, int row, EntityRef where = {})
      : Error(ErrorKind::CannotAssemble, message, where), row_(row) {}
  int row() const { return row_; }  // the constraint that cannot be met, or -1

 private:
  int row_;
};

struct AssemblyReport {
  int newton_iterations = 0;
  double residual = 0.0;
  bool passed_singularity = false;
};

// Assembles the mechanism with the drivers at `start` (SI), starting from the drawn pose:
// first Newton with the drivers at their drawn values (only `lengths` overrides can make the
// drawing inconsistent), then continuation of the drivers to `start` on the drawn branch.
// Throws AssemblyError naming the constraint that cannot be met.
AssemblyReport assemble(const Mechanism& mech, State& state, const std::vector<double>& start);

// A driver value (SI) in the model's units, for messages: "23.4 deg".
std::string format_driver_value(const Model& model, int driver, double si);

}  // namespace nbar
