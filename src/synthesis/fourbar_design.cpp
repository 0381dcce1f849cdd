// Checking a synthesised four-bar. The closed form of the four-bar locates each target: the
// input angle and assembly branch of the pose that meets it, the input's toggle angles and
// so the branch and circuit each pose lies on, and the transmission angle's extremes. The
// kinematics engine then drives the model from the first target through the others, as
// `nbar solve` would, and measures how closely it meets them.
#include "nbar/synthesis/fourbar_design.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <tuple>
#include <utility>

#include "kinematics/workspace.hpp"
#include "model/triangle.hpp"
#include "nbar/kinematics/continuation.hpp"
#include "nbar/kinematics/mechanism.hpp"
#include "nbar/kinematics/sweep.hpp"
#include "nbar/model/diagnostics.hpp"

namespace nbar::synthesis {

namespace {

using Eigen::Vector2d;
constexpr double kPi = std::numbers::pi;
constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

double cross(const Vector2d& u, const Vector2d& v) { return u.x() * v.y() - u.y() * v.x(); }
double angle_of(const Vector2d& u) { return std::atan2(u.y(), u.x()); }
Vector2d rotate(const Vector2d& v, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return {c * v.x() - s * v.y(), s * v.x() + c * v.y()};
}
double wrap_positive(double a) {  // [0, 2 pi)
  const double r = std::fmod(a, kTwoPi);
  return r < 0.0 ? r + kTwoPi : r;
}
double wrap_signed(double a) { return a - kTwoPi * std::round(a / kTwoPi); }  // [-pi, pi]
// loops.hpp branch_sign, for the pose A, B with the output pivot o4.
int side(const Vector2d& o4, const Vector2d& a, const Vector2d& b) { return cross(o4 - a, b - a) >= 0 ? 1 : -1; }

// Point indices of make_fourbar_model.
enum PointIndex { kO2 = 0, kO4 = 1, kA = 2, kB = 3, kP = 4 };

// The four-bar in closed form.
struct FourBar {
  Vector2d o2, o4, a0, b0, p0;
  double a = 0, b = 0, c = 0, d = 0;  // input, coupler, output, frame
  double frame_angle = 0;
  double coupler_angle0 = 0;    // of the coupler, A to B, in the first position
  double size = 0;              // for tolerances
  std::vector<double> toggles;  // input angles in [0, 2 pi) where coupler and output fold in line

  explicit FourBar(const FourBarDesign& design)
      : o2(design.ground_a), o4(design.ground_b), a0(design.moving_a), b0(design.moving_b), p0(design.coupler_point) {
    a = (a0 - o2).norm();
    b = (b0 - a0).norm();
    c = (b0 - o4).norm();
    d = (o4 - o2).norm();
    frame_angle = angle_of(o4 - o2);
    coupler_angle0 = angle_of(b0 - a0);
    size = std::max({a, b, c, d, (p0 - a0).norm()});
    // |A - O4|^2 = a^2 + d^2 - 2ad cos(theta - frame_angle) reaches (b + c)^2 or (b - c)^2.
    for (double fold : {b + c, std::abs(b - c)}) {
      // never reached, only touched (a change point), or degenerate
      if (!(fold > std::abs(a - d) && fold < a + d)) continue;
      const double alpha = angle_opposite(fold, a, d);
      toggles.push_back(wrap_positive(frame_angle + alpha));
      toggles.push_back(wrap_positive(frame_angle - alpha));
    }
    std::sort(toggles.begin(), toggles.end());
  }

  bool crank() const { return toggles.empty(); }

  struct Pose {
    Vector2d a, b, p;
    double rotation = 0;  // of the coupler from the first position
  };
  // The pose at input angle theta on the branch of sign `sigma` (side()), if it assembles.
  std::optional<Pose> pose(double theta, int sigma) const {
    Pose pose;
    pose.a = o2 + a * Vector2d(std::cos(theta), std::sin(theta));
    const Vector2d diagonal = o4 - pose.a;
    const double f = diagonal.norm();
    if (f > b + c || f < std::abs(b - c) || f == 0.0) return std::nullopt;
    pose.b = pose.a + b * rotate(diagonal / f, sigma * angle_opposite(c, b, f));
    pose.rotation = angle_of(pose.b - pose.a) - coupler_angle0;
    pose.p = pose.a + rotate(p0 - a0, pose.rotation);
    return pose;
  }

  // min(mu, pi - mu) at input angle theta, mu being the angle between coupler and output.
  double transmission(double theta) const {
    const double f2 = a * a + d * d - 2.0 * a * d * std::cos(theta - frame_angle);
    const double mu = angle_opposite(std::sqrt(std::max(0.0, f2)), b, c);
    return std::min(mu, std::numbers::pi - mu);
  }
  // Its minimum over the input angles lo..hi (lo <= hi): |cos mu| grows with the distance of
  // |A - O4| from its middle value, so the extremes are at the ends or where the input lies
  // along the frame line.
  double min_transmission(double lo, double hi) const {
    double best = std::min(transmission(lo), transmission(hi));
    for (double along : {frame_angle, frame_angle + kPi}) {
      const double first = along + kTwoPi * std::ceil((lo - along) / kTwoPi);
      if (first < hi || hi - lo >= kTwoPi) best = std::min(best, transmission(first));
    }
    return best;
  }

  // The gap between toggles that holds theta (always 0 for a crank): poses of one branch
  // share it and their sign.
  int interval(double theta) const {
    const double t = wrap_positive(theta);
    const auto next = std::upper_bound(toggles.begin(), toggles.end(), t);
    return next == toggles.begin() ? static_cast<int>(toggles.size()) - 1
                                   : static_cast<int>(next - toggles.begin()) - 1;
  }
  // How far the input can turn from theta either way before a toggle (2 pi for a crank).
  double room(double theta, int direction) const {
    if (crank()) return kTwoPi;
    double best = kTwoPi;
    for (double t : toggles) best = std::min(best, wrap_positive(direction * (t - theta)));
    return best;
  }
};

// A pose that meets a target: input angle, branch sign, and the closed form's miss.
struct Placement {
  double theta = 0;
  int sigma = 1;
  double miss = kInfinity;
};

// Minimises f on [lo, hi] by golden sections (f may be infinite where the linkage does not
// assemble); the distance to a point on the coupler curve is V-shaped there, which golden
// sections handle to full precision.
std::pair<double, double> golden_minimum(const std::function<double(double)>& f, double lo, double hi) {
  const double ratio = (std::sqrt(5.0) - 1.0) / 2.0;
  double x1 = hi - ratio * (hi - lo), x2 = lo + ratio * (hi - lo);
  double f1 = f(x1), f2 = f(x2);
  for (int i = 0; i < 200 && hi - lo > 1e-15 * (1.0 + std::abs(lo)); ++i) {
    if (f1 <= f2) {
      hi = x2;
      x2 = x1;
      f2 = f1;
      x1 = hi - ratio * (hi - lo);
      f1 = f(x1);
    } else {
      lo = x1;
      x1 = x2;
      f1 = f2;
      x2 = lo + ratio * (hi - lo);
      f2 = f(x2);
    }
  }
  return f1 <= f2 ? std::pair{x1, f1} : std::pair{x2, f2};
}

// The coupler curve sampled once per design on both branches, a quarter degree apart (finer
// than any feature of a sane coupler curve), shared by every target's search.
struct CurveSamples {
  static constexpr int kSamples = 1440;
  explicit CurveSamples(const FourBar& fb) {
    for (int s = 0; s < 2; ++s) {
      points[s].resize(kSamples);
      assembles[s].resize(kSamples);
      for (int k = 0; k < kSamples; ++k) {
        const auto pose = fb.pose(kTwoPi * k / kSamples, s == 0 ? 1 : -1);
        assembles[s][k] = pose.has_value();
        if (pose) points[s][k] = pose->p;
      }
    }
  }
  std::array<std::vector<Vector2d>, 2> points;  // [0]: branch sigma = 1, [1]: sigma = -1
  std::array<std::vector<char>, 2> assembles;
};

// Every pose whose coupler point is on `target` (within `tolerance`), or the nearest one.
std::vector<Placement> path_placements(const FourBar& fb, const CurveSamples& curve, const Vector2d& target,
                                       double tolerance) {
  constexpr int kSamples = CurveSamples::kSamples;
  std::vector<Placement> found;
  std::vector<double> sampled(kSamples);
  for (int sigma : {1, -1}) {
    const auto distance = [&](double theta) {
      const auto pose = fb.pose(theta, sigma);
      return pose ? (pose->p - target).norm() : kInfinity;
    };
    const int s = sigma == 1 ? 0 : 1;
    for (int k = 0; k < kSamples; ++k)
      sampled[k] = curve.assembles[s][k] ? (curve.points[s][k] - target).norm() : kInfinity;
    for (int k = 0; k < kSamples; ++k) {
      const double here = sampled[k];
      if (!std::isfinite(here) || here > sampled[(k + kSamples - 1) % kSamples] || here > sampled[(k + 1) % kSamples])
        continue;
      const auto [theta, miss] = golden_minimum(distance, kTwoPi * (k - 1) / kSamples, kTwoPi * (k + 1) / kSamples);
      const double t = wrap_positive(theta);
      const bool duplicate = std::any_of(found.begin(), found.end(), [&](const Placement& p) {
        return p.sigma == sigma && std::abs(wrap_signed(p.theta - t)) < 1e-9;
      });
      if (!duplicate) found.push_back({t, sigma, miss});
    }
  }
  std::vector<Placement> on_curve;
  for (const Placement& p : found)
    if (p.miss <= tolerance) on_curve.push_back(p);
  if (on_curve.empty() && !found.empty())
    on_curve.push_back(*std::min_element(found.begin(), found.end(),
                                         [](const Placement& x, const Placement& y) { return x.miss < y.miss; }));
  return on_curve;
}

// The engine's view of a pose: the model's points, in the design's unit.
struct EnginePose {
  Vector2d a, b, p, o4;
  double rotation = 0;  // of the coupler from the first position, wrapped
};

// How to place and measure one kind of target.
struct TargetRules {
  int count = 0;
  // Candidate poses for target i >= 1.
  std::function<std::vector<Placement>(int)> place;
  // error and rotation error of target i in a pose.
  std::function<std::pair<double, double>(int, const EnginePose&)> measure;
};

std::vector<Placement> motion_placement(const FourBar& fb, const Vector2d& target, double rotation) {
  // The coupler's pose is given: its joints are where the rigid motion takes them.
  const Vector2d a = target + rotate(fb.a0 - fb.p0, rotation);
  const Vector2d b = target + rotate(fb.b0 - fb.p0, rotation);
  Placement p{angle_of(a - fb.o2), side(fb.o4, a, b), kInfinity};
  if (const auto pose = fb.pose(p.theta, p.sigma))
    p.miss = std::max((pose->p - target).norm(), fb.size * std::abs(wrap_signed(pose->rotation - rotation)));
  return {p};
}

// check_design, step by step, for any kind of target.
class Checker {
 public:
  Checker(const FourBarDesign& design, const TargetRules& rules) : design_(design), rules_(rules), fb_(design) {}

  DesignCheck run() {
    if (!valid_links()) return check_;
    check_.grashof = classify_grashof(fb_.d, fb_.a, fb_.b, fb_.c, 1e-9 * fb_.size);
    check_.input_turns_fully = fb_.crank();
    theta0_ = angle_of(fb_.a0 - fb_.o2);
    sigma0_ = side(fb_.o4, fb_.a0, fb_.b0);
    interval0_ = fb_.interval(theta0_);
    place_targets();
    classify_targets();
    unwrapped_.assign(rules_.count, theta0_);
    if (fb_.crank())
      unwrap_crank();
    else
      unwrap_rocker();
    if (check_.direction == 0) check_.direction = 1;
    for (int i : along_) check_.targets[i].input_angle = unwrapped_[i];
    motion_and_transmission();
    simulate();
    for (std::size_t i = 0; i < check_.targets.size(); ++i)
      if (!check_.targets[i].reached) check_.targets[i].error = placed_[i].miss;
    // Reported in the design's angles (the link's direction plus its offset).
    for (TargetCheck& t : check_.targets) t.input_angle += design_.input_angle_offset;
    check_.motion.from += design_.input_angle_offset;
    check_.motion.to += design_.input_angle_offset;
    return check_;
  }

 private:
  bool valid_links() {
    check_.frame = fb_.d;
    check_.input = fb_.a;
    check_.coupler = fb_.b;
    check_.output = fb_.c;
    const double tiny = 1e-9 * fb_.size;
    if (!(fb_.size > 0.0) || !std::isfinite(fb_.size)) {
      check_.invalid = "the points coincide or are not finite";
      return false;
    }
    if (fb_.d <= tiny)
      check_.invalid = "the fixed pivots coincide";
    else if (fb_.a <= tiny)
      check_.invalid = "the input link has zero length";
    else if (fb_.b <= tiny)
      check_.invalid = "the coupler has zero length";
    else if (fb_.c <= tiny)
      check_.invalid = "the output link has zero length";
    return check_.invalid.empty();
  }

  // A crank's circuits are its two branches; a rocker's circuit is a gap between toggles,
  // holding both branches.
  bool same_circuit(const Placement& p) const {
    return fb_.crank() ? p.sigma == sigma0_ : fb_.interval(p.theta) == interval0_;
  }
  bool on_branch(const Placement& p) const { return p.sigma == sigma0_ && fb_.interval(p.theta) == interval0_; }

  // Which pose meets each target: the first target's branch when possible, then its circuit.
  void place_targets() {
    placed_ = {{theta0_, sigma0_, 0.0}};
    for (int i = 1; i < rules_.count; ++i) {
      const std::vector<Placement> candidates = rules_.place(i);
      const auto rank = [&](const Placement& p) { return on_branch(p) ? 0 : same_circuit(p) ? 1 : 2; };
      const auto best =
          std::min_element(candidates.begin(), candidates.end(), [&](const Placement& x, const Placement& y) {
            return rank(x) != rank(y) ? rank(x) < rank(y) : x.miss < y.miss;
          });
      placed_.push_back(best == candidates.end() ? Placement{theta0_, -sigma0_, kInfinity} : *best);
    }
  }

  void classify_targets() {
    check_.targets.resize(rules_.count);
    for (int i = 0; i < rules_.count; ++i) {
      TargetCheck& t = check_.targets[i];
      t.branch = placed_[i].sigma;
      t.on_branch = std::isfinite(placed_[i].miss) && on_branch(placed_[i]);
      t.input_angle = placed_[i].theta;
      t.error = placed_[i].miss;
      if (t.on_branch) {
        along_.push_back(i);
      } else if (std::isfinite(placed_[i].miss)) {  // otherwise no pose meets it: unreached
        check_.branch_defect = true;
        (same_circuit(placed_[i]) ? check_.toggle_between : check_.circuit_defect) = true;
      }
    }
  }

  // Each step turns a crank onward by 0..2 pi; in order means less than a turn in all.
  void unwrap_crank() {
    double best_total = kInfinity;
    for (int direction : {1, -1}) {
      std::vector<double> u{theta0_};
      double total = 0.0;
      for (std::size_t k = 1; k < along_.size(); ++k) {
        double step = wrap_positive(direction * (placed_[along_[k]].theta - placed_[along_[k - 1]].theta));
        if (step > kTwoPi - 1e-12) step = 0.0;  // the same angle, within rounding
        total += step;
        u.push_back(theta0_ + direction * total);
      }
      if (total < best_total) {
        best_total = total;
        check_.direction = direction;
        for (std::size_t k = 0; k < along_.size(); ++k) unwrapped_[along_[k]] = u[k];
      }
    }
    check_.order_defect = best_total >= kTwoPi - 1e-12;
  }

  // Within a rocker's gap between toggles the angle is continuous: measure it from theta0 the
  // way that stays inside the gap.
  void unwrap_rocker() {
    const double forward = fb_.room(theta0_, 1);
    for (int i : along_) {
      const double ahead = wrap_positive(placed_[i].theta - theta0_);
      unwrapped_[i] = ahead <= forward ? theta0_ + ahead : theta0_ - (kTwoPi - ahead);
    }
    for (std::size_t k = 1; k < along_.size(); ++k) {
      const double step = unwrapped_[along_[k]] - unwrapped_[along_[k - 1]];
      if (std::abs(step) <= 1e-12) continue;
      const int direction = step > 0 ? 1 : -1;
      if (check_.direction == 0) check_.direction = direction;
      if (direction != check_.direction) check_.order_defect = true;
    }
  }

  // The motion, first to last target on the branch (the span of those met, when out of order),
  // its transmission angles, and the exported sweep: a crank's full turn from the first
  // target, a rocker's motion through the targets (when there is none, most of its branch).
  void motion_and_transmission() {
    double lo = theta0_, hi = theta0_;
    for (int i : along_) {
      lo = std::min(lo, unwrapped_[i]);
      hi = std::max(hi, unwrapped_[i]);
    }
    check_.travel = along_.empty() ? 0.0 : std::abs(unwrapped_[along_.back()] - theta0_);
    check_.min_transmission = fb_.min_transmission(lo, hi);
    check_.min_transmission_full =
        fb_.crank() ? fb_.min_transmission(0.0, kTwoPi)
                    : fb_.min_transmission(theta0_ - fb_.room(theta0_, -1), theta0_ + fb_.room(theta0_, 1));
    if (fb_.crank()) {
      check_.motion = {theta0_, theta0_ + check_.direction * kTwoPi, 361};
      return;
    }
    if (!check_.order_defect && !along_.empty() && unwrapped_[along_.back()] != theta0_) {
      check_.motion = {theta0_, unwrapped_[along_.back()], 0};
    } else if (hi > lo) {
      check_.motion = {check_.direction > 0 ? lo : hi, check_.direction > 0 ? hi : lo, 0};
    } else {
      check_.motion = {theta0_ - 0.9 * fb_.room(theta0_, -1), theta0_ + 0.9 * fb_.room(theta0_, 1), 0};
    }
    check_.motion.steps =
        std::max(2, static_cast<int>(std::ceil(std::abs(check_.motion.to - check_.motion.from) * 180.0 / kPi)) + 1);
  }

  // Drive the model from the first target through the others in turn, on the branch it was
  // drawn on, and measure each target where the engine reaches it.
  void simulate() {
    for (TargetCheck& t : check_.targets) t.error = kInfinity;
    try {
      FourBarDesign plain = design_;  // driven by the link's own direction
      plain.input_angle_offset = plain.output_angle_offset = 0.0;
      const Mechanism mech(make_fourbar_model(plain, "check", Units{}, InputMotion{theta0_, theta0_, 2}));
      State state(mech);
      assemble(mech, state, {theta0_});
      const DriverPath path = [](double p, int terms, std::vector<Series>& out) {
        out.assign(1, Series::variable(terms, p));
      };
      constexpr int kTerms = 4;
      std::vector<Series> values;
      state.parameter = theta0_;
      path(theta0_, kTerms, values);
      set_drivers(mech, state, values);
      compute_series(mech, state, kTerms);
      for (int i : along_) {
        if (unwrapped_[i] != state.parameter && !track(mech, state, path, unwrapped_[i]).reached) break;
        if (!measure_target(mech, state, i)) break;
      }
    } catch (const Error& e) {  // ModelError, AssemblyError: the design is not a linkage
      check_.invalid = e.what();
    }
  }

  // False when the engine cannot go on from this pose.
  bool measure_target(const Mechanism& mech, State& state, int i) {
    constexpr int kTerms = 4;
    // The tracker stops at its tolerance (1e-12 of the size); two more Newton steps give the
    // pose to rounding, so that the misses measure the design, not the tracker.
    State::Workspace& work = state.workspace();
    for (int k = 0; k < 2 && factorize_jacobian(mech, state); ++k) {
      max_residual(mech, state);
      work.rhs = -work.phi;
      work.solver().solve(work.rhs, work.dq);
      state.q += work.dq;
    }
    if (!factorize_jacobian(mech, state)) return false;
    compute_series(mech, state, kTerms);
    EnginePose pose;
    pose.a = mech.point_position(kA, state.q);
    pose.b = mech.point_position(kB, state.q);
    pose.p = mech.point_position(kP, state.q);
    pose.o4 = fb_.o4;
    pose.rotation = wrap_signed(angle_of(pose.b - pose.a) - angle_of(fb_.b0 - fb_.a0));
    if (side(pose.o4, pose.a, pose.b) != sigma0_) return false;  // never expected: the engine keeps its branch
    TargetCheck& t = check_.targets[i];
    t.reached = true;
    std::tie(t.error, t.rotation_error) = rules_.measure(i, pose);
    check_.max_error = std::max(check_.max_error, t.error);
    check_.max_rotation_error = std::max(check_.max_rotation_error, t.rotation_error);
    return true;
  }

  const FourBarDesign& design_;
  const TargetRules& rules_;
  const FourBar fb_;
  DesignCheck check_;
  double theta0_ = 0.0;
  int sigma0_ = 0, interval0_ = 0;
  std::vector<Placement> placed_;
  std::vector<int> along_;  // targets on the branch, in the given order
  std::vector<double> unwrapped_;
};

DesignCheck check_with(const FourBarDesign& design, const TargetRules& rules) { return Checker(design, rules).run(); }

}  // namespace

bool DesignCheck::unreached() const {
  return std::any_of(targets.begin(), targets.end(),
                     [](const TargetCheck& t) { return !t.reached && (t.on_branch || !std::isfinite(t.error)); });
}

DesignCheck check_design(const FourBarDesign& design, const std::vector<Target>& targets, const CheckOptions& options) {
  const FourBar fb(design);
  std::optional<CurveSamples> curve;  // sampled at the first target on the path
  TargetRules rules;
  rules.count = static_cast<int>(targets.size());
  rules.place = [&](int i) {
    const Target& t = targets[i];
    if (t.rotation) return motion_placement(fb, t.point, *t.rotation);
    if (!curve) curve.emplace(fb);
    return path_placements(fb, *curve, t.point, options.match_tolerance * fb.size);
  };
  rules.measure = [&](int i, const EnginePose& pose) {
    const Target& t = targets[i];
    const double rotation_error = t.rotation ? std::abs(wrap_signed(pose.rotation - *t.rotation)) : 0.0;
    return std::pair{(pose.p - t.point).norm(), rotation_error};
  };
  return check_with(design, rules);
}

DesignCheck check_design(const FourBarDesign& design, const std::vector<RotationTarget>& targets,
                         const CheckOptions& /*options*/) {
  const FourBar fb(design);
  const double theta0 = angle_of(fb.a0 - fb.o2);
  const double psi0 = angle_of(fb.b0 - fb.o4);
  const auto output_error = [&](int i, const Vector2d& b) {
    return std::abs(wrap_signed(angle_of(b - fb.o4) - psi0 - targets[i].output));
  };
  TargetRules rules;
  rules.count = static_cast<int>(targets.size());
  // The input angle is given; of the two poses there, the one with the output nearer its goal.
  rules.place = [&](int i) {
    std::vector<Placement> out;
    const double theta = theta0 + targets[i].input;
    for (int sigma : {1, -1})
      if (const auto pose = fb.pose(theta, sigma))
        out.push_back({wrap_positive(theta), sigma, output_error(i, pose->b)});
    std::sort(out.begin(), out.end(), [](const Placement& x, const Placement& y) { return x.miss < y.miss; });
    if (out.size() > 1) out.pop_back();
    return out;
  };
  rules.measure = [&](int i, const EnginePose& pose) { return std::pair{output_error(i, pose.b), 0.0}; };
  return check_with(design, rules);
}

double min_transmission_angle(const FourBarDesign& design, double from, double to) {
  from -= design.input_angle_offset;
  to -= design.input_angle_offset;
  return FourBar(design).min_transmission(std::min(from, to), std::max(from, to));
}

std::vector<int> rank_designs(const std::vector<DesignCheck>& checks) {
  const auto kinds = [](const DesignCheck& c) {
    return (c.circuit_defect ? 1 : 0) + (c.toggle_between ? 1 : 0) + (c.order_defect ? 1 : 0) + (c.unreached() ? 1 : 0);
  };
  std::vector<int> order(checks.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
  std::stable_sort(order.begin(), order.end(), [&](int i, int j) {
    const DesignCheck& x = checks[i];
    const DesignCheck& y = checks[j];
    if (x.invalid.empty() != y.invalid.empty()) return x.invalid.empty();
    if (x.defect_free() != y.defect_free()) return x.defect_free();
    if (kinds(x) != kinds(y)) return kinds(x) < kinds(y);
    if (x.min_transmission != y.min_transmission) return x.min_transmission > y.min_transmission;
    return x.max_error < y.max_error;
  });
  return order;
}

std::string describe_defects(const DesignCheck& check) {
  if (!check.invalid.empty()) return "invalid: " + check.invalid;
  std::string out;
  const auto add = [&](bool present, const char* name) {
    if (!present) return;
    if (!out.empty()) out += ", ";
    out += name;
  };
  add(check.circuit_defect, "circuit");
  add(check.toggle_between, "branch");
  add(check.order_defect, "order");
  add(check.unreached(), "unreached");
  return out.empty() ? "none" : out;
}

Model make_fourbar_model(const FourBarDesign& design, const std::string& name, const Units& units,
                         const std::optional<InputMotion>& motion) {
  Model m;
  m.name = name;
  m.units = units;
  const double scale = units.length_scale;
  const auto point = [&](const char* label, const Vector2d& at, bool ground) {
    m.points.push_back(Point{label, scale * at, ground});
  };
  // The order matches PointIndex.
  point("O2", design.ground_a, true);
  point("O4", design.ground_b, true);
  point("A", design.moving_a, false);
  point("B", design.moving_b, false);
  point("P", design.coupler_point, false);
  const auto body = [&](const char* label, std::vector<int> points) {
    Body b;
    b.name = label;
    b.points = std::move(points);
    m.bodies.push_back(std::move(b));
  };
  // A pointer where a link's angle is not its direction (offsets of pi: function generation).
  const auto turned = [](double offset) { return std::abs(wrap_signed(offset)) > 1e-12; };
  std::vector<int> input_points{kO2, kA}, output_points{kO4, kB};
  if (turned(design.input_angle_offset)) {
    point("Ip", design.ground_a + rotate(design.moving_a - design.ground_a, design.input_angle_offset), false);
    input_points = {kO2, static_cast<int>(m.points.size()) - 1, kA};
  }
  if (turned(design.output_angle_offset)) {
    point("Op", design.ground_b + rotate(design.moving_b - design.ground_b, design.output_angle_offset), false);
    output_points = {kO4, static_cast<int>(m.points.size()) - 1, kB};
  }
  body("input", input_points);
  body("coupler", {kA, kB, kP});
  body("output", output_points);
  Driver input;
  input.name = "input";
  input.kind = DriverKind::Angle;
  input.body = 0;
  const double drawn = angle_of(design.moving_a - design.ground_a) + design.input_angle_offset;
  input.from = motion ? motion->from : drawn;
  input.to = motion ? motion->to : drawn;
  // One turn a second, in the direction of the motion.
  input.speed = (motion && motion->to < motion->from ? -1.0 : 1.0) * kTwoPi;
  m.drivers.push_back(input);
  m.sweep.steps = motion ? std::max(2, motion->steps) : 2;
  return m;
}

}  // namespace nbar::synthesis
