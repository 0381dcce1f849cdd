#include "rocking.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <utility>

#include "constraints.hpp"
#include "path_follower.hpp"
#include "workspace.hpp"

namespace nbar {

namespace {

constexpr int kMaxTurns = 64;         // limits in one circuit
constexpr int kMaxAdvances = 400000;  // path steps to plan a circuit, or between two samples
// A circuit closes when the path passes the start's value again, going the start's way, this close
// to the start's pose (of the model's size): another branch through the same value is far from it.
constexpr double kSamePose = 1e-6;
// A change point this close to a limit (of the model's size) is where the input would turn back.
constexpr double kTurnAtChangePoint = 1e-6;

EntityRef the_driver() { return EntityRef{EntityRef::Kind::Driver, 0}; }

// The path parameter is the driver's value less its start.
DriverPath input_path(double start) {
  return [start](double p, int terms, std::vector<Series>& out) {
    out.resize(1);
    out[0].set_line(terms, start, 1.0, p);
  };
}

// The input's length the follower scales to the model's size: a radian, or the model's size.
double input_span(const Mechanism& mech) {
  return mech.model().drivers[0].is_angular() ? 1.0 : mech.characteristic_length();
}

// How far the input goes without a limit before it is taken to turn fully (or never to meet one).
double open_window(const Mechanism& mech) {
  return mech.model().drivers[0].is_angular() ? 2.0 * std::numbers::pi * 1.0000001
                                              : 10.0 * mech.characteristic_length();
}

std::string value_text(const Mechanism& mech, double si) { return format_driver_value(mech.model(), 0, si); }

[[noreturn]] void cannot_rock(const Mechanism& mech, const std::string& why) {
  throw Error(ErrorKind::StoppedAtLimit, "driver '" + mech.model().drivers[0].name + "' cannot rock: " + why,
              the_driver());
}

bool same_place(const Mechanism& mech, const PathSingularity& a, const PathSingularity& b) {
  return (a.q - b.q).norm() <= kTurnAtChangePoint * mech.characteristic_length();
}

// Where the input would turn back, branches cross: the path does not say which way it goes on.
void refuse_turn_at_change_point(const Mechanism& mech, const PathSingularity& change) {
  cannot_rock(mech, "its path turns back at " + value_text(mech, change.driver_values[0]) +
                        ", which is a change point (branches cross there: " + change.involved +
                        "), not a limit where the input alone turns back: the sweep stops there");
}

// The start, assembled, as a point of the follower's path.
Eigen::VectorXd start_point(const PathFollower& follower, const Eigen::VectorXd& q) {
  Eigen::VectorXd y(q.size() + 1);
  y << q, follower.scaled(0.0);
  return y;
}

// Follows the path from the start until it comes back there going the same way (a closed
// circuit), turns fully without a limit, or meets too many limits.
void follow_circuit(const Mechanism& mech, double work_budget, RockingPlan& plan) {
  PathFollower follower(mech, input_path(plan.start), input_span(mech));
  follower.set_work_budget(work_budget);
  const Eigen::Index n = plan.start_pose.size();
  PathFollower::Step step = follower.begin(start_point(follower, plan.start_pose), plan.direction);
  const double window = open_window(mech);
  double leg_from = 0.0, travel = 0.0;
  int way = plan.direction;
  for (int advances = 0; advances < kMaxAdvances; ++advances) {
    const Eigen::VectorXd before = step.y;
    PathFollower::Advance a = follower.advance(step);
    if (!a.ok)
      cannot_rock(mech, a.reason + " (near " + value_text(mech, plan.start + follower.parameter(step.y)) + ")");
    if (a.change_point) {
      describe_singularity(mech, *a.change_point);
      if (!plan.turns.empty() && same_place(mech, plan.turns.back(), *a.change_point))
        refuse_turn_at_change_point(mech, *a.change_point);
      plan.change_points.push_back(*a.change_point);
    }
    if (a.limit) {
      describe_singularity(mech, *a.limit);
      if (!plan.change_points.empty() && same_place(mech, plan.change_points.back(), *a.limit))
        refuse_turn_at_change_point(mech, plan.change_points.back());
      travel += std::abs(a.limit->parameter - leg_from);
      leg_from = a.limit->parameter;
      way = -way;
      plan.turns.push_back(std::move(*a.limit));
      if (static_cast<int>(plan.turns.size()) > kMaxTurns)
        cannot_rock(mech, "its path meets more than " + std::to_string(kMaxTurns) +
                              " limits before it comes back to its start");
      continue;
    }
    const double p = follower.parameter(step.y), p_before = follower.parameter(before);
    if (!plan.turns.empty() && way == plan.direction && p_before * way < 0.0 && p * way >= 0.0) {
      Eigen::VectorXd y = before;
      if (follower.solve_at_parameter(y, 0.0) &&
          (y.head(n) - plan.start_pose).norm() <= kSamePose * mech.characteristic_length()) {
        plan.closed = true;
        plan.circuit_travel = travel + std::abs(leg_from);
        return;
      }
    }
    if (std::abs(p - leg_from) > window) return;
  }
  cannot_rock(mech, "its path takes too many steps to follow");
}

// The input's place after travelling `s` from the start: the turns passed and its value.
class Schedule {
 public:
  explicit Schedule(const RockingPlan& plan) : plan_(plan) {
    double at = plan.start, travelled = 0.0;
    for (const PathSingularity& turn : plan.turns) {
      travelled += std::abs(turn.driver_values[0] - at);
      at = turn.driver_values[0];
      turn_travel_.push_back(travelled);
    }
  }

  struct Place {
    long leg = 0;  // the turns passed (a turn the sample lies on among them)
    double value = 0.0;
    int way = 1;           // the way it moves
    bool on_turn = false;  // the sample lies on the last turn passed, to rounding
  };

  Place at(double s) const {
    const long m = static_cast<long>(turn_travel_.size());
    long cycles = 0;
    double rest = s;
    if (plan_.closed) {
      cycles = static_cast<long>(std::floor(s / plan_.circuit_travel));
      rest = s - static_cast<double>(cycles) * plan_.circuit_travel;
      if (rest < 0.0) {  // s a hair below a whole number of circuits
        rest += plan_.circuit_travel;
        --cycles;
      }
    }
    // A sample within rounding of a turn (a symmetric cycle sampled evenly lands on its turns) is
    // taken on it: a hair before it the input's value would have no pose on the path.
    const double rounding = 1e-12 * (plan_.closed ? plan_.circuit_travel : turn_travel_.back());
    const long j = std::upper_bound(turn_travel_.begin(), turn_travel_.end(), rest + rounding) - turn_travel_.begin();
    Place place;
    place.leg = cycles * m + j;
    place.way = j % 2 == 0 ? plan_.direction : -plan_.direction;
    place.on_turn = j > 0 && rest - turn_travel_[j - 1] <= rounding;
    if (place.on_turn)
      place.value = plan_.turns[j - 1].driver_values[0];
    else
      place.value = j == 0 ? plan_.start + place.way * rest
                           : plan_.turns[j - 1].driver_values[0] + place.way * (rest - turn_travel_[j - 1]);
    return place;
  }

  // The travel to the `leg`-th turn (counted from 0), and the turn.
  double travel_to(long leg) const {
    const long m = static_cast<long>(turn_travel_.size());
    return plan_.closed ? static_cast<double>(leg / m) * plan_.circuit_travel + turn_travel_[leg % m]
                        : turn_travel_[leg];
  }
  const PathSingularity& turn(long leg) const {
    return plan_.turns[static_cast<std::size_t>(leg % static_cast<long>(plan_.turns.size()))];
  }

 private:
  const RockingPlan& plan_;
  std::vector<double> turn_travel_;  // from the start to each turn of the first circuit
};

// Walks the path from the start, as the plan did, to each sample's place: the pose on the path
// at the sample's value after as many turns as the schedule says.
class Walk {
 public:
  Walk(const Mechanism& mech, const RockingPlan& plan)
      : mech_(mech), follower_(mech, input_path(plan.start), input_span(mech)), start_(plan.start) {
    // The samples asked for bound the walk (as many steps as the plan took per cycle), not the
    // search's budget: a long run of many cycles is as much work as it asks for.
    follower_.set_work_budget(HUGE_VAL);
    before_ = start_point(follower_, plan.start_pose);
    step_ = follower_.begin(before_, plan.direction);
  }

  Eigen::VectorXd pose(const Schedule::Place& place) {
    const double p = place.value - start_;
    for (int advances = 0; !reached(place.leg, place.way, p); ++advances) {
      if (advances == kMaxAdvances) cannot_rock(mech_, "its path takes too many steps to follow");
      before_ = step_.y;
      turns_before_ = turns_;
      const PathFollower::Advance a = follower_.advance(step_);
      if (!a.ok) cannot_rock(mech_, a.reason + " (near " + value_text(mech_, place.value) + ")");
      if (a.limit) ++turns_;
    }
    Eigen::VectorXd y;
    if (turns_before_ == place.leg && turns_ == place.leg) {
      const double pa = follower_.parameter(before_), pb = follower_.parameter(step_.y);
      y = pb != pa ? Eigen::VectorXd(before_ + ((p - pa) / (pb - pa)) * (step_.y - before_)) : step_.y;
    } else if (turns_before_ == place.leg) {
      y = before_;  // between the point before and the limit after it
    } else if (turns_ == place.leg) {
      y = step_.y;  // between the limit and the point after it
    } else {
      cannot_rock(mech_, "two of its limits lie too close together to sample between them (near " +
                             value_text(mech_, place.value) + ")");
    }
    if (!follower_.solve_at_parameter(y, p))
      cannot_rock(mech_, "no pose on its path at " + value_text(mech_, place.value) +
                             " (a sample too close to a limit: ask for another number of steps)");
    return y;
  }

 private:
  bool reached(long leg, int way, double p) const {
    return turns_ > leg || (turns_ == leg && way * (follower_.parameter(step_.y) - p) >= 0.0);
  }

  const Mechanism& mech_;
  PathFollower follower_;
  double start_ = 0.0;
  PathFollower::Step step_;
  Eigen::VectorXd before_;
  long turns_ = 0, turns_before_ = 0;
};

// The input's total travel: the cycles asked for, or |to - from|.
double rocking_travel(const Mechanism& mech, const RockingPlan& plan) {
  const Driver& d = mech.model().drivers[0];
  const bool range = d.to && *d.to != plan.start;
  if (d.cycles || !range) {
    if (!plan.closed)
      cannot_rock(mech, "its path does not come back to its start (after its limit at " +
                            value_text(mech, plan.turns.back().driver_values[0]) +
                            " it turns fully), so it has no cycles to repeat: give `to` for the input's travel");
    return d.cycles.value_or(1) * plan.circuit_travel;
  }
  return std::abs(*d.to - plan.start);
}

// A sample on a turn: the limit's pose (located to rounding when the plan was made). The input
// arrives at full speed and leaves at full speed the other way, while the linkage is at its limit:
// its velocities and every higher derivative there are unbounded, so they are not numbers.
void take_turn_sample(const Mechanism& mech, const PathSingularity& turn, State& state, int terms, Sample& sample) {
  state.q = turn.q;
  sample.taylor.setConstant(state.q.size(), terms, std::numeric_limits<double>::quiet_NaN());
  sample.taylor.col(0) = turn.q;
  sample.residual = max_residual(mech, state);
}

Warning turn_sample_warning(const Mechanism& mech, const std::vector<long>& steps) {
  std::string list;
  for (std::size_t k = 0; k < steps.size() && k < 8; ++k) list += (k ? ", " : "") + std::to_string(steps[k]);
  if (steps.size() > 8) list += " and " + std::to_string(steps.size() - 8) + " more";
  return {"sample_on_turn", static_cast<int>(steps.front()),
          "step" + std::string(steps.size() > 1 ? "s " : " ") + list + " of driver '" + mech.model().drivers[0].name +
              "' lie on a turn (a limit of the mechanism), where the input " +
              "arrives and leaves at full speed while the linkage is at its limit: those rows give the pose, and " +
              "their velocities, accelerations and higher derivatives are unbounded there (nan, null in JSON); " +
              "another number of steps moves the samples off the turns"};
}

}  // namespace

namespace {

// The input's travel from the start to where the rocking motion first has `value`: along the legs
// between the turns of one circuit, then on past the last turn when the path does not close (it
// turns fully there and goes on). Empty when the motion never has that value.
std::optional<double> travel_to_value(const RockingPlan& plan, double value) {
  double at = plan.start, travelled = 0.0;
  int way = plan.direction;
  for (const PathSingularity& turn : plan.turns) {
    const double end = turn.driver_values[0];
    if (way * (value - at) >= 0.0 && way * (end - value) >= 0.0) return travelled + std::abs(value - at);
    travelled += std::abs(end - at);
    at = end;
    way = -way;
  }
  if (way * (value - at) >= 0.0 && (!plan.closed || way * (plan.start - value) >= 0.0))
    return travelled + std::abs(value - at);
  return std::nullopt;
}

// The driver at `place`: its value, and its speed with the sign of the way the motion goes there.
std::vector<DriverState> drivers_at(const Mechanism& mech, const RockingPlan& plan, const Schedule::Place& place,
                                    int terms) {
  Series series(terms, place.value);
  if (terms > 1) series[1] = place.way * plan.speed;
  return {make_driver_state(series, mech.model().drivers[0].is_angular())};
}

// The pose and motion at `place` into `sample`, with `state.drivers` set there: a turn's own, or the
// walk's pose there solved. False when that pose does not solve (the caller says where).
bool place_sample(const Mechanism& mech, const Schedule& schedule, Walk& walk, const Schedule::Place& place,
                  State& state, int terms, Sample& sample) {
  if (place.on_turn) {
    take_turn_sample(mech, schedule.turn(place.leg - 1), state, terms, sample);
    return true;
  }
  state.q = walk.pose(place).head(state.q.size());
  if (!solve_position(mech, state).converged) return false;
  compute_series(mech, state, state.drivers, terms, sample.taylor);
  sample.residual = state.residual;
  return true;
}

// The smallest and largest values the rocking input takes in one circuit.
std::pair<double, double> rocking_range(const RockingPlan& plan) {
  double low = plan.start, high = plan.start;
  for (const PathSingularity& turn : plan.turns) {
    low = std::min(low, turn.driver_values[0]);
    high = std::max(high, turn.driver_values[0]);
  }
  return {low, high};
}

}  // namespace

Sample rocking_sample_at(const Mechanism& mech, const RockingPlan& plan, double value, int order) {
  const std::optional<double> travel = travel_to_value(plan, value);
  if (!travel) {
    const auto [low, high] = rocking_range(plan);
    throw Error(ErrorKind::StoppedAtLimit,
                "driver '" + mech.model().drivers[0].name + "' rocks between " + value_text(mech, low) + " and " +
                    value_text(mech, high) + " (`at_limits: reverse`): it never reaches " + value_text(mech, value),
                the_driver());
  }
  const Schedule schedule(plan);
  const Schedule::Place place = schedule.at(*travel);
  const int terms = order + 1;
  State state(mech);
  state.drivers = drivers_at(mech, plan, place, terms);
  Walk walk(mech, plan);
  Sample sample;
  if (!place_sample(mech, schedule, walk, place, state, terms, sample))
    cannot_rock(mech, "no pose at " + value_text(mech, value) + " (too close to a limit)");
  sample.time = *travel / plan.speed;
  sample.driver_values.assign(1, value);
  sample.reversals = static_cast<int>(place.leg);
  return sample;
}

bool sweep_rocks(const Model& m) { return m.drivers.size() == 1 && m.drivers[0].at_limits == AtLimits::Reverse; }

RockingPlan plan_rocking(const Mechanism& mech, double work_budget) {
  const Model& m = mech.model();
  if (!sweep_rocks(m)) throw Error(ErrorKind::BadInput, "the model has no rocking driver (`at_limits: reverse`)");
  const Driver& d = m.drivers[0];
  RockingPlan plan;
  plan.start = d.from.value_or(mech.drawn_driver_values()[0]);
  plan.direction = d.to && *d.to != plan.start ? (*d.to > plan.start ? 1 : -1) : (d.speed > 0.0 ? 1 : -1);
  plan.speed = std::abs(d.speed);
  State state(mech);
  plan.assembly = assemble(mech, state, {plan.start});
  plan.start_pose = state.q;
  follow_circuit(mech, work_budget, plan);
  plan.reverses = !plan.turns.empty();
  if (!plan.reverses)
    plan.never_reverses = d.is_angular() ? "its path turns fully (a whole turn from its start without a limit)"
                                         : "its path meets no limit within ten times the mechanism's size";
  return plan;
}

// Left long (85 lines) on purpose: one loop over the samples shares the schedule, the walk along
// the path, the state solved at each sample and the reversals passed between samples.
SweepResult run_rocking_sweep(const Mechanism& mech, const RockingPlan& plan, const SweepOptions& options,
                              const RunControl& control, const SampleSink& sink) {
  const Model& m = mech.model();
  check_sample_count(m, options.steps, options.max_steps);
  const long samples = options.steps.value_or(m.sweep.steps);
  const double travel = rocking_travel(mech, plan);
  control.checkpoint("sweep", 0, samples);
  SweepResult result;
  result.order = options.order;
  result.assembly = plan.assembly;
  const int terms = options.order + 1;
  for (const PathSingularity& change : plan.change_points)
    result.warnings.push_back({"change_point_passed", -1,
                               "the rocking path passes a singular (change-point) position at " +
                                   value_text(mech, change.driver_values[0]) + " (" + change.involved +
                                   "): the assembly branch may change there"});
  const Schedule schedule(plan);
  Walk walk(mech, plan);
  State state(mech);
  Sample streamed;
  long reversals = 0;
  std::vector<long> on_turns;  // the samples that lie on a turn
  for (long i = 0; i < samples; ++i) {
    if (i % 16 == 0) control.checkpoint("sweep", i, samples);
    const double s = samples > 1 ? travel * (static_cast<double>(i) / static_cast<double>(samples - 1)) : 0.0;
    const Schedule::Place place = schedule.at(s);
    state.drivers = drivers_at(mech, plan, place, terms);
    Sample& sample = sink ? streamed : result.samples.emplace_back();
    if (!place_sample(mech, schedule, walk, place, state, terms, sample))
      cannot_rock(mech, "no pose at " + value_text(mech, place.value) + " at step " + std::to_string(i) +
                            " (a sample too close to a limit: ask for another number of steps)");
    if (place.on_turn) {
      on_turns.push_back(i);
      if (options.condition) sample.reciprocal_condition = 0.0;  // a limit: Phi_q is singular there
    } else {
      if (options.condition) sample.reciprocal_condition = sample_condition(state);
      if (!sample.taylor.allFinite())
        cannot_rock(mech, "its motion at step " + std::to_string(i) + " (" + value_text(mech, place.value) +
                              ") is not finite: a sample too close to a limit (ask for another number of steps)");
    }
    for (; reversals < place.leg; ++reversals) {
      const PathSingularity& turn = schedule.turn(reversals);
      const bool here = place.on_turn && reversals + 1 == place.leg;
      result.reversals.push_back({static_cast<int>(here ? i : i - 1), schedule.travel_to(reversals) / plan.speed,
                                  turn.driver_values[0], turn.involved, here});
    }
    sample.reversals = static_cast<int>(reversals);
    sample.step = static_cast<int>(i);
    sample.time = s / plan.speed;
    sample.driver_values.assign(1, place.value);
    result.max_residual = std::max(result.max_residual, sample.residual);
    ++result.solved;
    if (sink) sink(sample);
  }
  if (!on_turns.empty()) result.warnings.push_back(turn_sample_warning(mech, on_turns));
  return result;
}

}  // namespace nbar
