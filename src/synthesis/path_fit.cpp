// Best-fit path synthesis (path_fit.hpp). The fit works in the targets' own frame, centred on
// their centroid and scaled by their RMS radius, so that tolerances, step sizes and penalty
// weights mean the same for every task; starts and results are in the task's coordinates.
#include "nbar/synthesis/path_fit.hpp"

#include <fmt/format.h>
#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <random>
#include <stdexcept>

#include "nbar/model/diagnostics.hpp"
#include "nbar/synthesis/five_point.hpp"
#include "nbar/synthesis/nine_point.hpp"

namespace nbar::synthesis {

namespace {

using Eigen::MatrixXd;
using Eigen::Vector2d;
using Eigen::VectorXd;
constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr int kParameters = 9;  // o2 (2), o4 (2), input, coupler, output, point (2)

thread_local long evaluation_count = 0;

Vector2d perpendicular(const Vector2d& v) { return {-v.y(), v.x()}; }

// The targets' frame: centre and scale.
struct Frame {
  Vector2d centre{0, 0};
  double scale = 1;
  Vector2d to_unit(const Vector2d& p) const { return (p - centre) / scale; }
  Vector2d to_task(const Vector2d& p) const { return centre + scale * p; }
  FourBarDesign to_task(const FourBarDesign& d) const {
    FourBarDesign out = d;
    out.ground_a = to_task(d.ground_a);
    out.ground_b = to_task(d.ground_b);
    out.moving_a = to_task(d.moving_a);
    out.moving_b = to_task(d.moving_b);
    out.coupler_point = to_task(d.coupler_point);
    return out;
  }
  FourBarDesign to_unit(const FourBarDesign& d) const {
    FourBarDesign out = d;
    out.ground_a = to_unit(d.ground_a);
    out.ground_b = to_unit(d.ground_b);
    out.moving_a = to_unit(d.moving_a);
    out.moving_b = to_unit(d.moving_b);
    out.coupler_point = to_unit(d.coupler_point);
    return out;
  }
};

// Rejects what no fit can use, and gives the frame.
Frame frame_of(const std::vector<Vector2d>& targets) {
  if (targets.size() < 10)
    throw Error(ErrorKind::InvalidModel,
                fmt::format("a path fit needs at least 10 target points, not {}", targets.size()));
  Frame f;
  for (const Vector2d& t : targets) {
    if (!t.allFinite()) throw Error(ErrorKind::InvalidModel, "a target point is not finite");
    f.centre += t;
  }
  f.centre /= static_cast<double>(targets.size());
  Eigen::Matrix2d spread = Eigen::Matrix2d::Zero();
  for (const Vector2d& t : targets) spread += (t - f.centre) * (t - f.centre).transpose();
  spread /= static_cast<double>(targets.size());
  f.scale = std::sqrt(spread.trace());
  if (!(f.scale > 0) || !std::isfinite(f.scale)) throw Error(ErrorKind::InvalidModel, "the target points all coincide");
  const Eigen::Vector2d widths = Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(spread).eigenvalues();
  if (widths(0) <= 1e-12 * widths(1))
    throw Error(ErrorKind::InvalidModel,
                "the target points lie on one straight line: a four-bar's coupler curve is fitted to a curve");
  return f;
}

// The fit's parameters of a shape, and back.
VectorXd parameters_of(const FourBarShape& s) {
  VectorXd x(kParameters);
  x << s.ground_a.x(), s.ground_a.y(), s.ground_b.x(), s.ground_b.y(), s.input, s.coupler, s.output, s.point.x(),
      s.point.y();
  return x;
}
FourBarShape shape_from(const VectorXd& x, int branch) {
  FourBarShape s;
  s.ground_a = {x(0), x(1)};
  s.ground_b = {x(2), x(3)};
  s.input = x(4);
  s.coupler = x(5);
  s.output = x(6);
  s.point = {x(7), x(8)};
  s.branch = branch;
  return s;
}

// The constraints in the unit frame, tightened a little so that the penalties (which leave a
// small violation) meet the user's bounds.
struct UnitConstraints {
  bool region = false;
  Vector2d lo{0, 0}, hi{0, 0};
  bool crank = false;
  double crank_margin = 0;      // how far inside the crank's conditions
  double cos_transmission = 1;  // |cos mu| must stay below it
  double min_length = 0, max_length = kInfinity;
  int rows(int targets) const {
    return (region ? 8 : 0) + (min_length > 0 ? 4 : 0) + (std::isfinite(max_length) ? 4 : 0) + (crank ? 2 : 0) +
           (cos_transmission < 1 ? targets + (crank ? 2 : 0) : 0);
  }
};

UnitConstraints unit_constraints(const PathConstraints& c, const Frame& f, double margin) {
  UnitConstraints u;
  if (c.region_min && c.region_max) {
    u.region = true;
    u.lo = f.to_unit(*c.region_min) + Vector2d::Constant(margin);
    u.hi = f.to_unit(*c.region_max) - Vector2d::Constant(margin);
  }
  u.crank = c.crank;
  u.crank_margin = margin;
  if (c.min_transmission > 0) u.cos_transmission = std::cos(c.min_transmission + margin);
  if (c.min_length > 0) u.min_length = c.min_length / f.scale * (1 + margin);
  if (c.max_length > 0) u.max_length = c.max_length / f.scale * (1 - margin);
  return u;
}

// |cos mu| at input angle theta (mu between coupler and output), from the law of cosines.
double cos_transmission(const FourBarShape& s, double theta) {
  const Vector2d a = s.ground_a + s.input * Vector2d(std::cos(theta), std::sin(theta));
  const double f2 = (s.ground_b - a).squaredNorm();
  return std::abs((s.coupler * s.coupler + s.output * s.output - f2) / (2 * std::abs(s.coupler * s.output)));
}

// The penalty rows (each >= 0, 0 when the constraint holds) for a shape and its angles; the
// transmission rows come one per target, in target order, after the others.
void penalty_rows(const UnitConstraints& c, const FourBarShape& s, const double* angles, int targets, double* out) {
  const auto over = [](double v) { return std::max(0.0, v); };
  const double d = (s.ground_b - s.ground_a).norm(), a = std::abs(s.input), b = std::abs(s.coupler),
               o = std::abs(s.output);
  int k = 0;
  if (c.region)
    for (const Vector2d& p : {s.ground_a, s.ground_b})
      for (int axis = 0; axis < 2; ++axis) {
        out[k++] = over(c.lo(axis) - p(axis));
        out[k++] = over(p(axis) - c.hi(axis));
      }
  if (c.min_length > 0)
    for (double length : {d, a, b, o}) out[k++] = over(c.min_length - length);
  if (std::isfinite(c.max_length))
    for (double length : {d, a, b, o}) out[k++] = over(length - c.max_length);
  // The input turns fully when |A - O4|, which ranges over [|d - a|, d + a], stays within
  // [|b - o|, b + o]; the margin keeps it off the toggle.
  if (c.crank) {
    out[k++] = over(d + a - (b + o) + c.crank_margin);
    out[k++] = over(std::abs(b - o) - std::abs(d - a) + c.crank_margin);
  }
  if (c.cos_transmission < 1) {
    if (c.crank) {  // the extremes of a full turn: the input along the frame line
      const double along = std::atan2(s.ground_b.y() - s.ground_a.y(), s.ground_b.x() - s.ground_a.x());
      out[k++] = over(cos_transmission(s, along) - c.cos_transmission);
      out[k++] = over(cos_transmission(s, along + std::numbers::pi) - c.cos_transmission);
    }
    for (int i = 0; i < targets; ++i) out[k++] = over(cos_transmission(s, angles[i]) - c.cos_transmission);
  }
}

// Initial matched angles: for every target, the nearest of many poses on the shape's branch.
std::optional<std::vector<double>> nearest_angles(const FourBarShape& s, const std::vector<Vector2d>& targets) {
  constexpr int kSamples = 720;
  std::vector<std::pair<double, Vector2d>> curve;
  for (int k = 0; k < kSamples; ++k) {
    const double theta = kTwoPi * k / kSamples;
    if (const auto p = coupler_point_at(s, theta)) curve.emplace_back(theta, *p);
  }
  if (curve.size() < 8) return std::nullopt;
  std::vector<double> angles;
  for (const Vector2d& t : targets) {
    const auto best = std::min_element(curve.begin(), curve.end(), [&](const auto& x, const auto& y) {
      return (x.second - t).squaredNorm() < (y.second - t).squaredNorm();
    });
    angles.push_back(best->first);
  }
  return angles;
}

// Levenberg–Marquardt on [shape parameters, matched angles]. Each angle moves only its own
// target's two rows (and its transmission row), so the angles' block of the normal equations is
// diagonal and is eliminated (Schur complement): every step solves a 9 x 9 system.
class LocalFit {
 public:
  LocalFit(const std::vector<Vector2d>& targets, const UnitConstraints& constraints, int max_iterations)
      : targets_(targets),
        constraints_(constraints),
        n_(static_cast<int>(targets.size())),
        penalties_(constraints.rows(n_)),
        rows_(2 * n_ + penalties_),
        max_iterations_(max_iterations) {
    // Which angle each row depends on (-1: none).
    owner_.assign(rows_, -1);
    for (int i = 0; i < n_; ++i) owner_[2 * i] = owner_[2 * i + 1] = i;
    if (constraints.cos_transmission < 1)
      for (int i = 0; i < n_; ++i) owner_[rows_ - n_ + i] = i;
  }

  struct Result {
    VectorXd x;
    double cost = kInfinity;  // targets only
    int iterations = 0;
  };

  std::optional<Result> run(const FourBarShape& start, const std::vector<double>& angles) {
    branch_ = start.branch;
    VectorXd x(kParameters + n_);
    x.head(kParameters) = parameters_of(start);
    for (int i = 0; i < n_; ++i) x(kParameters + i) = angles[i];
    VectorXd r(rows_);
    int iterations = 0;
    // Penalties grow until the constraints hold (or three rounds have passed).
    const std::vector<double> weights = penalties_ > 0 ? std::vector<double>{10, 100, 1000} : std::vector<double>{0};
    for (double weight : weights) {
      weight_ = weight;
      if (!residuals(x, r)) return std::nullopt;
      iterations += minimise(x, r);
      if (penalties_ == 0 || r.tail(penalties_).squaredNorm() == 0) break;
    }
    return Result{x, r.head(2 * n_).squaredNorm(), iterations};
  }

 private:
  bool residuals(const VectorXd& x, VectorXd& r) const {
    const FourBarShape s = shape_from(x.head(kParameters), branch_);
    for (int i = 0; i < n_; ++i) {
      const auto p = coupler_point_at(s, x(kParameters + i));
      if (!p) return false;
      r.segment<2>(2 * i) = *p - targets_[i];
    }
    if (penalties_ > 0) {
      penalty_rows(constraints_, s, x.data() + kParameters, n_, r.data() + 2 * n_);
      r.tail(penalties_) *= weight_;
    }
    return true;
  }

  // Forward differences, stepping back where the linkage does not assemble ahead.
  bool jacobian(const VectorXd& x, const VectorXd& r, MatrixXd& jp, VectorXd& jt) const {
    constexpr double kStep = 1e-7;
    VectorXd moved = x, rm(rows_);
    for (int j = 0; j < kParameters; ++j) {
      double h = kStep * std::max(1.0, std::abs(x(j)));
      moved(j) = x(j) + h;
      if (!residuals(moved, rm)) {
        h = -h;
        moved(j) = x(j) + h;
        if (!residuals(moved, rm)) return false;
      }
      jp.col(j) = (rm - r) / h;
      moved(j) = x(j);
    }
    // Every angle at once: no row depends on two of them.
    for (double h : {kStep, -kStep}) {
      moved.tail(n_) = x.tail(n_).array() + h;
      if (!residuals(moved, rm)) continue;
      jt = (rm - r) / h;
      for (int row = 0; row < rows_; ++row)
        if (owner_[row] < 0) jt(row) = 0;
      return true;
    }
    return false;
  }

  // The damped Gauss-Newton step with the angles eliminated.
  VectorXd step(const MatrixXd& jp, const VectorXd& jt, const VectorXd& r, double lambda) const {
    Eigen::Matrix<double, kParameters, kParameters> hpp = jp.transpose() * jp;
    Eigen::Matrix<double, kParameters, 1> gp = -jp.transpose() * r;
    VectorXd htt = VectorXd::Zero(n_), gt = VectorXd::Zero(n_);
    MatrixXd hpt = MatrixXd::Zero(kParameters, n_);
    for (int row = 0; row < rows_; ++row) {
      const int i = owner_[row];
      if (i < 0) continue;
      htt(i) += jt(row) * jt(row);
      gt(i) -= jt(row) * r(row);
      hpt.col(i) += jp.row(row).transpose() * jt(row);
    }
    const double floor = 1e-12 * std::max(1.0, hpp.diagonal().maxCoeff());
    for (int j = 0; j < kParameters; ++j) hpp(j, j) += lambda * (hpp(j, j) + floor);
    for (int i = 0; i < n_; ++i) htt(i) += lambda * (htt(i) + floor) + floor;
    Eigen::Matrix<double, kParameters, kParameters> reduced = hpp;
    Eigen::Matrix<double, kParameters, 1> rhs = gp;
    for (int i = 0; i < n_; ++i) {
      reduced -= hpt.col(i) * hpt.col(i).transpose() / htt(i);
      rhs -= hpt.col(i) * gt(i) / htt(i);
    }
    VectorXd delta(kParameters + n_);
    delta.head(kParameters) = reduced.ldlt().solve(rhs);
    for (int i = 0; i < n_; ++i) delta(kParameters + i) = (gt(i) - hpt.col(i).dot(delta.head(kParameters))) / htt(i);
    return delta;
  }

  // Iterations made; x and r end at the best point found.
  int minimise(VectorXd& x, VectorXd& r) const {
    MatrixXd jp(rows_, kParameters);
    VectorXd jt(rows_), trial_r(rows_);
    double cost = r.squaredNorm(), lambda = 1e-3;
    int iteration = 0;
    for (; iteration < max_iterations_; ++iteration) {
      if (!jacobian(x, r, jp, jt)) break;
      bool accepted = false;
      double reduction = 0;
      while (lambda < 1e12) {
        const VectorXd delta = step(jp, jt, r, lambda);
        const VectorXd trial = x + delta;
        if (delta.allFinite() && residuals(trial, trial_r) && trial_r.squaredNorm() < cost) {
          reduction = cost - trial_r.squaredNorm();
          x = trial;
          r = trial_r;
          cost = r.squaredNorm();
          lambda = std::max(lambda / 3, 1e-12);
          accepted = true;
          break;
        }
        lambda *= 4;
      }
      if (!accepted || reduction <= 1e-13 * cost || cost < 1e-28) break;
    }
    return iteration;
  }

  const std::vector<Vector2d>& targets_;
  const UnitConstraints& constraints_;
  const int n_, penalties_, rows_, max_iterations_;
  std::vector<int> owner_;
  int branch_ = 1;
  double weight_ = 0;
};

// Whether a fitted design (unit frame) meets the user's constraints, tested on the design
// itself with the closed forms the design check uses.
bool meets_constraints(const UnitConstraints& c, const FourBarDesign& d, const std::vector<double>& angles) {
  const FourBarShape s = shape_of(d);
  std::vector<double> rows(static_cast<std::size_t>(c.rows(static_cast<int>(angles.size()))));
  UnitConstraints geometric = c;
  geometric.cos_transmission = 1;  // measured below over the whole motion instead
  penalty_rows(geometric, s, angles.data(), static_cast<int>(angles.size()), rows.data());
  if (std::any_of(rows.begin(), rows.end(), [](double v) { return v > 0; })) return false;
  if (c.cos_transmission < 1) {
    const auto [lo, hi] = std::minmax_element(angles.begin(), angles.end());
    const double mu = c.crank ? min_transmission_angle(d, 0, kTwoPi) : min_transmission_angle(d, *lo, *hi);
    if (std::cos(mu) > c.cos_transmission + 1e-12) return false;
  }
  return true;
}

// Random four-bars around the targets (unit frame), best first by the distance from every
// target to the nearest of 64 points of the curve (order and similarity ignored: a screen).
std::vector<FourBarShape> screened_shapes(const std::vector<Vector2d>& targets, const PathFitOptions& options,
                                          int keep) {
  std::mt19937_64 random(options.seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  double reach = 0;
  for (const Vector2d& t : targets) reach = std::max(reach, t.norm());
  const auto in = [&](double lo, double hi) { return lo + (hi - lo) * unit(random); };
  std::vector<std::pair<double, FourBarShape>> scored;
  constexpr int kCurve = 64;
  std::vector<Vector2d> curve;
  for (int k = 0; k < options.samples; ++k) {
    FourBarShape s;
    s.ground_a = {in(-2, 2) * reach, in(-2, 2) * reach};
    s.ground_b = {in(-2, 2) * reach, in(-2, 2) * reach};
    s.input = in(0.1, 1.5) * reach;
    s.coupler = in(0.3, 3) * reach;
    s.output = in(0.3, 3) * reach;
    s.point = {in(-2, 2) * reach, in(-2, 2) * reach};
    s.branch = unit(random) < 0.5 ? 1 : -1;
    curve.clear();
    for (int j = 0; j < kCurve; ++j)
      if (const auto p = coupler_point_at(s, kTwoPi * j / kCurve)) curve.push_back(*p);
    if (curve.size() < 8) continue;
    double cost = 0;
    for (const Vector2d& t : targets) {
      double nearest = kInfinity;
      for (const Vector2d& p : curve) nearest = std::min(nearest, (p - t).squaredNorm());
      cost += nearest;
    }
    scored.emplace_back(cost, s);
  }
  std::sort(scored.begin(), scored.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  std::vector<FourBarShape> out;
  for (int k = 0; k < std::min<int>(keep, static_cast<int>(scored.size())); ++k) out.push_back(scored[k].second);
  return out;
}

// The design of a shape in its first pose that assembles.
std::optional<FourBarDesign> some_pose(const FourBarShape& s) {
  FourBarDesign d;
  for (int k = 0; k < 360; ++k)
    if (coupler_point_at(s, kTwoPi * k / 360, &d)) return d;
  return std::nullopt;
}

}  // namespace

FourBarShape shape_of(const FourBarDesign& design) {
  FourBarShape s;
  s.ground_a = design.ground_a;
  s.ground_b = design.ground_b;
  s.input = (design.moving_a - design.ground_a).norm();
  s.coupler = (design.moving_b - design.moving_a).norm();
  s.output = (design.moving_b - design.ground_b).norm();
  const Vector2d u = s.coupler > 0 ? Vector2d((design.moving_b - design.moving_a) / s.coupler) : Vector2d(1, 0);
  const Vector2d p = design.coupler_point - design.moving_a;
  s.point = {p.dot(u), p.dot(perpendicular(u))};
  const Vector2d to_b = design.moving_b - design.moving_a, to_o4 = design.ground_b - design.moving_a;
  s.branch = to_o4.x() * to_b.y() - to_o4.y() * to_b.x() >= 0 ? 1 : -1;
  return s;
}

std::optional<Vector2d> coupler_point_at(const FourBarShape& s, double theta, FourBarDesign* design) {
  ++evaluation_count;
  const Vector2d a = s.ground_a + s.input * Vector2d(std::cos(theta), std::sin(theta));
  const Vector2d diagonal = s.ground_b - a;
  const double f = diagonal.norm();
  const double b2 = s.coupler * s.coupler;
  if (!(f > 0)) return std::nullopt;
  const double along = (b2 + f * f - s.output * s.output) / (2 * f);
  const double h2 = b2 - along * along;
  if (!(h2 >= 0)) return std::nullopt;
  const Vector2d e = diagonal / f;
  const Vector2d b = a + along * e + s.branch * std::sqrt(h2) * perpendicular(e);
  const double length = std::abs(s.coupler);
  if (!(length > 0)) return std::nullopt;
  const Vector2d u = (b - a) / length;
  const Vector2d p = a + s.point.x() * u + s.point.y() * perpendicular(u);
  if (design) {
    design->ground_a = s.ground_a;
    design->ground_b = s.ground_b;
    design->moving_a = a;
    design->moving_b = b;
    design->coupler_point = p;
    design->input_angle_offset = design->output_angle_offset = 0;
  }
  return p;
}

long coupler_point_evaluations() { return evaluation_count; }

double path_objective(const FourBarShape& shape, const std::vector<double>& angles,
                      const std::vector<Vector2d>& targets) {
  double sum = 0;
  for (std::size_t i = 0; i < targets.size(); ++i) {
    const auto p = coupler_point_at(shape, angles[i]);
    if (!p) return kInfinity;
    sum += (*p - targets[i]).squaredNorm();
  }
  return sum;
}

std::vector<PathStart> sampled_starts(const PathFitTask& task, const PathFitOptions& options) {
  const Frame frame = frame_of(task.targets);
  std::vector<Vector2d> unit;
  for (const Vector2d& t : task.targets) unit.push_back(frame.to_unit(t));
  std::vector<PathStart> out;
  for (const FourBarShape& s : screened_shapes(unit, options, options.sampled_fits))
    if (const auto d = some_pose(s)) out.push_back({frame.to_task(*d), "sampled"});
  return out;
}

// Five of the targets, spread along them, with the fixed pivots of the best screened random
// four-bars: every real five-point design passes exactly through those five.
std::vector<PathStart> five_point_starts(const PathFitTask& task, const PathFitOptions& options) {
  const Frame frame = frame_of(task.targets);
  std::vector<Vector2d> unit;
  for (const Vector2d& t : task.targets) unit.push_back(frame.to_unit(t));
  const int subsets = 2;
  const int pivot_pairs = std::max(1, options.five_point_solves / subsets);
  const std::vector<FourBarShape> guesses = screened_shapes(unit, options, pivot_pairs);
  const int n = static_cast<int>(unit.size());
  std::vector<PathStart> out;
  for (int subset = 0; subset < subsets; ++subset) {
    FivePointTask problem;
    for (int k = 0; k < 5; ++k) {
      // Subset 0 spans the targets end to end; subset 1 sits between its points.
      const double at = subset == 0 ? k * (n - 1) / 4.0 : (k + 0.5) * (n - 1) / 5.0;
      problem.points[k] = unit[static_cast<std::size_t>(std::lround(at))];
    }
    for (const FourBarShape& g : guesses) {
      if (options.stop && options.stop()) return out;
      problem.pivot_a = g.ground_a;
      problem.pivot_b = g.ground_b;
      try {
        SolverOptions solver;
        solver.seed = options.seed;
        solver.stop = options.stop;
        for (const FivePointSolution& s : solve_five_point(problem, solver).solutions)
          if (s.real) out.push_back({frame.to_task(s.design), "five-point"});
      } catch (const Error& e) {  // pivots too close for the solver: skip them
        if (e.kind() != ErrorKind::InvalidModel && e.kind() != ErrorKind::BadInput) throw;
      }
    }
  }
  return out;
}

std::vector<PathStart> nine_point_starts(const PathFitTask& task, const PathFitOptions& options) {
  const Frame frame = frame_of(task.targets);
  const int n = static_cast<int>(task.targets.size());
  std::vector<PathStart> out;
  for (int subset = 0; subset < options.nine_point_subsets; ++subset) {
    if (options.stop && options.stop()) break;
    // Subset 0 spans the targets end to end; the others are shifted along them.
    std::array<Vector2d, 9> points;
    const double shift = static_cast<double>(subset) / std::max(1, options.nine_point_subsets);
    for (int k = 0; k < 9; ++k) {
      const double at = subset == 0 ? k * (n - 1) / 8.0 : (k + shift) * (n - 1) / (8.0 + shift);
      points[static_cast<std::size_t>(k)] = frame.to_unit(task.targets[static_cast<std::size_t>(std::lround(at))]);
    }
    NinePointOptions solver;
    solver.seed = options.seed + static_cast<std::uint64_t>(subset);
    solver.stop = options.stop;
    try {
      for (const NinePointLinkage& linkage : solve_nine_point(points, solver).linkages)
        for (const FourBarDesign& d : linkage.designs) out.push_back({frame.to_task(d), "nine-point"});
    } catch (const Error&) {  // nine targets the solver refuses (on a line...), or stopped
    }
  }
  return out;
}

std::vector<StartProvider> default_start_providers() { return {sampled_starts, five_point_starts, nine_point_starts}; }

namespace {

// `options` with its stop also asked whether `share` of the time budget from `start` has run
// out, which it records in `spent`.
PathFitOptions with_budget(const PathFitOptions& options, std::chrono::steady_clock::time_point start, double share,
                           const std::shared_ptr<std::atomic<bool>>& spent) {
  if (!(options.time_budget > 0)) return options;
  PathFitOptions bounded = options;
  const auto deadline = start + std::chrono::duration_cast<std::chrono::nanoseconds>(
                                    std::chrono::duration<double>(share * options.time_budget));
  bounded.stop = [stop = options.stop, deadline, spent] {
    if (stop && stop()) return true;
    if (std::chrono::steady_clock::now() < deadline) return false;
    spent->store(true);
    return true;
  };
  return bounded;
}

// The distinct optima, best first, at most `most` of them: many starts fall into the same basin.
std::vector<PathFit> distinct_best(std::vector<PathFit> fits, double scale, int most) {
  std::stable_sort(fits.begin(), fits.end(),
                   [](const PathFit& x, const PathFit& y) { return x.rms_deviation < y.rms_deviation; });
  // Within a hundredth of the targets' size: starts that stop along one flat valley differ
  // by less and are the same design for a designer.
  const auto same = [tolerance = 1e-2 * scale](const PathFit& x, const PathFit& y) {
    return (x.design.ground_a - y.design.ground_a).norm() < tolerance &&
           (x.design.ground_b - y.design.ground_b).norm() < tolerance &&
           (x.design.moving_a - y.design.moving_a).norm() < tolerance &&
           (x.design.moving_b - y.design.moving_b).norm() < tolerance &&
           (x.design.coupler_point - y.design.coupler_point).norm() < tolerance;
  };
  std::vector<PathFit> out;
  for (const PathFit& f : fits) {
    if (static_cast<int>(out.size()) >= most) break;
    if (std::none_of(out.begin(), out.end(), [&](const PathFit& kept) { return same(kept, f); })) out.push_back(f);
  }
  return out;
}

}  // namespace

PathFitResult fit_path(const PathFitTask& task, const PathFitOptions& given) {
  if (!(given.time_budget >= 0) || !std::isfinite(given.time_budget))
    throw Error(ErrorKind::BadInput, "the path fit's time budget must be a finite number of seconds, 0 for none");
  // The starts get half the budget, so that the fits from the starts found by then have the
  // rest: a budget spent on five-point solves alone would list nothing.
  const auto spent = std::make_shared<std::atomic<bool>>(false);
  const auto begun = std::chrono::steady_clock::now();
  const PathFitOptions finding = with_budget(given, begun, 0.5, spent);
  const PathFitOptions options = with_budget(given, begun, 1.0, spent);
  const long evaluations_before = coupler_point_evaluations();
  const Frame frame = frame_of(task.targets);
  std::vector<Vector2d> unit;
  for (const Vector2d& t : task.targets) unit.push_back(frame.to_unit(t));
  constexpr double kMargin = 1e-3;
  const UnitConstraints tightened = unit_constraints(task.constraints, frame, kMargin);
  const UnitConstraints exact = unit_constraints(task.constraints, frame, 0);

  PathFitResult result;
  std::vector<PathStart> starts;
  for (const StartProvider& provider : options.providers.empty() ? default_start_providers() : options.providers) {
    std::vector<PathStart> more = provider(task, finding);
    if (!more.empty()) result.start_counts.push_back(fmt::format("{} {}", more.size(), more.front().origin));
    starts.insert(starts.end(), more.begin(), more.end());
  }

  LocalFit local(unit, tightened, options.max_iterations);
  std::vector<PathFit> fits;
  const int n = static_cast<int>(unit.size());
  for (const PathStart& start : starts) {
    // The budget lets the first start be fitted whatever it is: a few milliseconds, and an
    // answer that lists a design however slow the machine. A caller's own stop is obeyed at once.
    const auto& stop = result.starts == 0 ? given.stop : options.stop;
    if (stop && stop()) break;
    if (options.progress) options.progress(result.starts, static_cast<int>(starts.size()));
    ++result.starts;
    const FourBarShape shape = shape_of(frame.to_unit(start.design));
    const auto angles = nearest_angles(shape, unit);
    if (!angles) continue;
    const auto found = local.run(shape, *angles);
    if (!found) continue;
    PathFit fit;
    fit.origin = start.origin;
    fit.iterations = found->iterations;
    fit.input_angles.assign(found->x.data() + kParameters, found->x.data() + kParameters + n);
    const FourBarShape fitted = shape_from(found->x.head(kParameters), shape.branch);
    FourBarDesign at_first;
    if (!coupler_point_at(fitted, fit.input_angles[0], &at_first)) continue;
    if (!meets_constraints(exact, at_first, fit.input_angles)) {
      ++result.rejected;
      continue;
    }
    for (int i = 0; i < n; ++i) {
      const double miss = (*coupler_point_at(fitted, fit.input_angles[i]) - unit[i]).norm();
      fit.max_deviation = std::max(fit.max_deviation, miss * frame.scale);
    }
    fit.rms_deviation = std::sqrt(found->cost / n) * frame.scale;
    fit.design = frame.to_task(at_first);
    fits.push_back(std::move(fit));
  }
  if (options.progress) options.progress(result.starts, static_cast<int>(starts.size()));

  result.fits = distinct_best(std::move(fits), frame.scale, options.max_fits);
  result.evaluations = coupler_point_evaluations() - evaluations_before;
  result.budget_spent = spent->load();
  return result;
}

}  // namespace nbar::synthesis
