// The limits of a whole mechanism along the path its sweep follows: the curve Phi(q, p) = 0 in
// (q, p), p the sweep's parameter, followed by pseudo-arclength continuation so that it can be
// followed through the positions where the input turns back. A limit is where p turns back along
// the curve (the tangent's p component changes sign, Phi_q loses rank while [Phi_q Phi_p] keeps
// it); a change point is where branches cross ([Phi_q Phi_p] loses rank: the bordered Jacobian's
// determinant changes sign). Any number of loops: the whole constraint Jacobian decides, and the
// constraints whose rows make it rank-deficient say which loop or joints are involved.
#pragma once

#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

#include "nbar/kinematics/mechanism.hpp"
#include "nbar/kinematics/sweep.hpp"

namespace nbar {

enum class PathSingularityKind {
  Limit,        // the input turns back: the sweep cannot pass it (it may reverse there)
  ChangePoint,  // branches cross: the sweep passes it on the branch it came along
};

struct PathSingularity {
  PathSingularityKind kind = PathSingularityKind::Limit;
  double parameter = 0.0;             // the sweep's path parameter there
  std::vector<double> driver_values;  // SI
  Eigen::VectorXd q;                  // the pose there
  // The constraint rows whose combination loses rank there (the left null vector of Phi_q), and
  // the bodies those rows belong to, in the model's order.
  std::vector<int> rows;
  std::vector<int> bodies;
  int loop = -1;         // the four-bar loop (Mechanism::four_bar_loops) holding all those bodies, or -1
  std::string involved;  // for people: "link5 and link6 in line (loop ...)"
};

// The path from the sweep's start in one direction (+1: the way the sweep goes; -1: back).
struct PathReach {
  std::vector<PathSingularity> singularities;  // in the order met; a limit ends the list
  bool turns_fully = false;                    // a full turn of the first driver without a limit
  bool window_end = false;                     // searched to the end of its window without a limit
  std::string undecided;                       // the search could not decide (why, and where)
  // When undecided: the pose where the search stopped, its driver values and the bodies nearest a
  // singular position there (the Jacobian's weakest combination, as for a singularity found).
  std::optional<PathSingularity> undecided_at;
  // The first limit met, if any.
  const PathSingularity* limit() const;
};

struct PathLimits {
  bool searched = false;
  std::string not_searched;  // why not (no driver, a driver that does not move...)
  double start_parameter = 0.0, end_parameter = 0.0;
  int driver = -1;  // the first driver the sweep moves: the one limits are told in
  PathReach ahead, behind;
  // The limit met before the sweep's end, where the sweep will stop (ahead, inside its range).
  std::optional<PathSingularity> stop;
  double work = 0.0;  // what the search did, in LimitSearchOptions::work_budget's unit
};

// The default work budget of a search along a path (LimitSearchOptions::work_budget).
inline constexpr double kDefaultLimitSearchWork = 1e9;

struct LimitSearchOptions {
  // Beyond the sweep's end and behind its start, how far to look, as a multiple of the sweep's
  // span; for angle drivers at least one full turn of the first driver.
  double window_spans = 1.0;
  bool full_turn = true;
  // The work (about the flops of the dense factorisations) the search may do, both ways together:
  // past it the search says it could not decide, and where. The default is about a second on one
  // core (the bundled examples take at most 1/25 of it).
  double work_budget = kDefaultLimitSearchWork;
};

// Follows the sweep's own path from its start both ways. Throws what assembling the start throws.
PathLimits find_path_limits(const Mechanism& mech, const LimitSearchOptions& options = {});

// The involved rows and bodies of a singular pose, and the text that names them.
void describe_singularity(const Mechanism& mech, PathSingularity& s);

// A rocking motion (`at_limits: reverse`): the model's one driver moves from its start at its
// speed's size and turns back at every limit of the mechanism its path meets; the path goes on
// through each limit (the configuration moves on along the curve, onto the branch beyond it), so
// the motion is one closed circuit of the path when it comes back to its start.
struct RockingPlan {
  bool reverses = false;
  std::string never_reverses;  // when !reverses: why (a full turn, or no limit within reach)
  double start = 0.0;          // the driver's value at the start (SI)
  int direction = 1;           // the way it moves first: +1 (its value grows) or -1
  double speed = 0.0;          // its speed's size (SI per second)
  // The limits met in order from the start, where the input turns back: one circuit when closed,
  // else those met before the path turned fully without one (the motion then goes on that way).
  std::vector<PathSingularity> turns;
  bool closed = false;          // the path comes back to the start's pose: the turns repeat
  double circuit_travel = 0.0;  // when closed: the input's travel over one circuit (SI)
  Eigen::VectorXd start_pose;   // q at the start, assembled
  AssemblyReport assembly;
  std::vector<PathSingularity> change_points;  // passed on the way (branches cross; the input goes on)
};

// Follows the path from the start with the input turning back at each limit, until it comes back
// to the start (or turns fully). Throws Error(StoppedAtLimit) at the driver when a turn would be
// at a change point (branches cross there: the path does not say which way the input goes) or
// the path cannot be followed; what assembling the start throws.
RockingPlan plan_rocking(const Mechanism& mech, double work_budget = kDefaultLimitSearchWork);

// The pose where the rocking motion of `plan` (one that reverses) first has the driver at `value`
// (SI), reached from the start as its sweep reaches it (the turns passed on the way decide the
// branch), with its Taylor coefficients to `order` in time (the input moving the way it moves
// then; none but the pose on a turn) and the time it gets there. Throws Error(StoppedAtLimit) at
// the driver when the motion never has that value (outside the range it rocks over).
Sample rocking_sample_at(const Mechanism& mech, const RockingPlan& plan, double value, int order);

}  // namespace nbar
