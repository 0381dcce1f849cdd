#include "path_follower.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "constraints.hpp"

namespace nbar {

namespace {

// A step whose tangent turns more than this (rad) may have cut across to another branch.
constexpr double kMaxTurn = 0.3;
// The first step and the longest, as fractions of the model's size (the sweep's span maps to it).
constexpr double kFirstStep = 0.01, kLongestStep = 0.05;
constexpr double kShortestStep = 1e-11;
constexpr int kMaxPathCorrections = 15;
constexpr int kMaxSteps = 200000;
constexpr int kLocateIterations = 200;
// Near a change point, or where the linkage is almost one (two limits a hair apart, a loop a
// hair from Grashof's equality), [Phi_q Phi_u] is nearly singular and branches pass close by: a
// long step there can land on the other one and skip both limits. Steps are kept below this
// multiple of its relative smallest singular value (of the model's size), down to kSlowest.
constexpr double kStepPerConditioning = 0.5;
constexpr double kSlowest = 1e-6;
// At a located limit, [Phi_q Phi_u]'s n-th singular value over its largest: a simple limit keeps
// it well away from zero (the path is a smooth curve there, Phi_u outside Phi_q's range: 3e-3 to
// 0.2 on the bundled examples' limits), a limit where branches also cross (Phi_q two short of full
// rank) has it at the location's error (5e-12 to 3e-7 on a parallelogram driven by its diagonal,
// 2e-9 on the scissor lift lying flat).
constexpr double kBranchesCrossAtLimit = 1e-5;

void fill_drivers(const Mechanism& mech, const std::vector<double>& values, std::vector<DriverState>& out) {
  out.resize(values.size());
  for (std::size_t d = 0; d < values.size(); ++d)
    out[d] = make_driver_state(Series(1, values[d]), mech.model().drivers[d].is_angular());
}

void to_dense(const Mechanism& mech, const std::vector<double>& values, Eigen::MatrixXd& out) {
  out.setZero(mech.row_count(), mech.coordinate_count());
  const auto& pattern = mech.equations().pattern;
  for (std::size_t e = 0; e < pattern.size(); ++e) out(pattern[e].row, pattern[e].col) += values[e];
}

}  // namespace

Eigen::MatrixXd dense_jacobian(const Mechanism& mech, const Eigen::VectorXd& q,
                               const std::vector<double>& driver_values) {
  std::vector<DriverState> drivers;
  fill_drivers(mech, driver_values, drivers);
  std::vector<double> values;
  evaluate_jacobian(mech, q, drivers, values);
  Eigen::MatrixXd out;
  to_dense(mech, values, out);
  return out;
}

PathFollower::PathFollower(const Mechanism& mech, DriverPath path, double span)
    : mech_(mech), path_(std::move(path)), n_(mech.coordinate_count()), state_(mech) {
  length_ = mech.characteristic_length();
  p_scale_ = span > 0.0 ? span / length_ : 1.0;
  tolerance_ = mech.tolerance();
  const std::vector<int>& redundant = mech.mobility().redundant;
  if (mech.row_count() - static_cast<int>(redundant.size()) == n_)
    for (int r = 0; r < mech.row_count(); ++r)
      if (std::find(redundant.begin(), redundant.end(), r) == redundant.end()) independent_rows_.push_back(r);
  coefficients_.setZero(n_, 2);
}

// The rows at y and the augmented Jacobian [Phi_q Phi_u]: Phi_u is the first Taylor coefficient
// of the rows along the path with q held (the drivers' rate times their rows' derivative).
void PathFollower::evaluate(const Eigen::VectorXd& y) {
  path_(parameter(y), 2, values_);
  set_drivers(mech_, state_, values_);
  const Eigen::VectorXd q = y.head(n_);
  evaluate_residuals(mech_, q, state_.drivers, phi_);
  evaluate_jacobian(mech_, q, state_.drivers, jacobian_values_);
  Eigen::MatrixXd jacobian;
  to_dense(mech_, jacobian_values_, jacobian);
  coefficients_.col(0) = q;
  evaluate_series_remainder(mech_, coefficients_, 1, state_.drivers, rate_);
  augmented_.resize(jacobian.rows(), n_ + 1);
  augmented_.leftCols(n_) = jacobian;
  augmented_.col(n_) = rate_ * p_scale_;
}

// The unit tangent at y: [A; border^T] t = e_last, so that t . border > 0.
bool PathFollower::tangent(const Eigen::VectorXd& y, const Eigen::VectorXd& border, Eigen::VectorXd& t) {
  evaluate(y);
  Eigen::MatrixXd bordered(augmented_.rows() + 1, n_ + 1);
  bordered << augmented_, border.transpose();
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(bordered.rows());
  rhs[rhs.size() - 1] = 1.0;
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(bordered);
  count_factorisation(bordered.rows());
  t = qr.solve(rhs);
  // The bordered matrix is regular at limits and singular where branches cross: its pivoted R's
  // smallest diagonal over its largest estimates how near the path passes such a place.
  const Eigen::VectorXd diagonal = qr.matrixR().diagonal().cwiseAbs();
  conditioning_ = diagonal.maxCoeff() > 0.0 ? diagonal.tail(1)[0] / diagonal.maxCoeff() : 0.0;
  const double size = t.norm();
  if (!(size > 0.0) || !std::isfinite(size)) return false;
  t /= size;
  return true;
}

// Newton on [Phi(y); border . (y - anchor)] = 0.
bool PathFollower::correct(Eigen::VectorXd& y, const Eigen::VectorXd& border, const Eigen::VectorXd& anchor) {
  double previous = HUGE_VAL;
  for (int it = 0; it < kMaxPathCorrections; ++it) {
    evaluate(y);
    const double residual = phi_.lpNorm<Eigen::Infinity>();
    if (!std::isfinite(residual)) return false;
    if (residual <= 1e-3 * tolerance_) return true;
    Eigen::MatrixXd bordered(augmented_.rows() + 1, n_ + 1);
    bordered << augmented_, border.transpose();
    Eigen::VectorXd rhs(bordered.rows());
    rhs << phi_, border.dot(y - anchor);
    const Eigen::VectorXd dy = bordered.colPivHouseholderQr().solve(rhs);
    count_factorisation(bordered.rows());
    const double size = dy.lpNorm<Eigen::Infinity>();
    if (!std::isfinite(size)) return false;
    // Rounding stops the contraction short of the target: what the tolerance allows is enough.
    if (size > 0.5 * previous) return residual <= tolerance_;
    previous = size;
    y -= dy;
  }
  evaluate(y);
  return phi_.lpNorm<Eigen::Infinity>() <= tolerance_;
}

int PathFollower::determinant_sign(const Eigen::VectorXd& y, const Eigen::VectorXd& t) {
  if (independent_rows_.empty()) return 0;
  evaluate(y);
  Eigen::MatrixXd square(n_ + 1, n_ + 1);
  for (Eigen::Index r = 0; r < n_; ++r) square.row(r) = augmented_.row(independent_rows_[r]);
  square.row(n_) = t.transpose();
  const double det = square.partialPivLu().determinant();
  count_factorisation(n_ + 1);
  return det > 0.0 ? 1 : det < 0.0 ? -1 : 0;
}

PathFollower::Step PathFollower::begin(const Eigen::VectorXd& y, int direction) {
  Step step;
  step.y = y;
  Eigen::VectorXd along_p = Eigen::VectorXd::Zero(n_ + 1);
  along_p[n_] = direction;
  if (!tangent(y, along_p, step.t)) step.t = along_p;
  step.h = kFirstStep * length_;
  step.det_sign = determinant_sign(y, step.t);
  return step;
}

bool PathFollower::point_at(const Step& from, double sigma, Eigen::VectorXd& y) {
  y = from.y + sigma * from.t;
  return correct(y, from.t, y);
}

PathSingularity PathFollower::singularity(const Eigen::VectorXd& y, PathSingularityKind kind) {
  PathSingularity s;
  s.kind = kind;
  s.parameter = parameter(y);
  s.q = y.head(n_);
  path_(s.parameter, 1, values_);
  for (const Series& v : values_) s.driver_values.push_back(v.value());
  return s;
}

// Regula falsi (Illinois) on the tangent's p component over the step [0, h]: p is quadratic in the
// arclength near a limit, so the arclength to 1e-8 of the model gives p to far below 1e-9.
std::optional<PathSingularity> PathFollower::locate_limit(const Step& from, double h, Eigen::VectorXd& y_limit) {
  double a = 0.0, b = h;
  double fa = from.t[n_];
  Eigen::VectorXd y, t;
  if (!point_at(from, b, y) || !tangent(y, from.t, t)) return std::nullopt;
  double fb = t[n_];
  int side = 0;
  Eigen::VectorXd best = y;
  double best_value = std::abs(fb);
  for (int it = 0; it < kLocateIterations && b - a > 1e-13 * length_; ++it) {
    if (over_budget()) return std::nullopt;
    const double c = fa != fb ? (a * fb - b * fa) / (fb - fa) : 0.5 * (a + b);
    const double sigma = c > a && c < b ? c : 0.5 * (a + b);
    if (!point_at(from, sigma, y) || !tangent(y, from.t, t)) return std::nullopt;
    const double fc = t[n_];
    if (std::abs(fc) < best_value) {
      best_value = std::abs(fc);
      best = y;
    }
    if (fc == 0.0) break;
    if ((fc > 0.0) == (fa > 0.0)) {
      a = sigma;
      fa = fc;
      if (side == -1) fb *= 0.5;
      side = -1;
    } else {
      b = sigma;
      fb = fc;
      if (side == 1) fa *= 0.5;
      side = 1;
    }
  }
  y_limit = best;
  return singularity(best, PathSingularityKind::Limit);
}

// Regula falsi on the bordered determinant's sign over [0, h], by bisection (its value's scale
// says nothing about the distance).
std::optional<PathSingularity> PathFollower::locate_change(const Step& from, double h) {
  double a = 0.0, b = h;
  const int sign_a = from.det_sign;
  Eigen::VectorXd y, t;
  for (int it = 0; it < kLocateIterations && b - a > 1e-12 * length_; ++it) {
    if (over_budget()) return std::nullopt;
    const double sigma = 0.5 * (a + b);
    if (!point_at(from, sigma, y) || !tangent(y, from.t, t)) return std::nullopt;
    if (determinant_sign(y, t) == sign_a)
      a = sigma;
    else
      b = sigma;
  }
  if (!point_at(from, 0.5 * (a + b), y)) return std::nullopt;
  return singularity(y, PathSingularityKind::ChangePoint);
}

PathFollower::Advance PathFollower::advance(Step& step) {
  Advance out;
  const auto fail = [&](std::string reason) {
    out.ok = false;
    out.reason = std::move(reason);
    return out;
  };
  for (int attempt = 0; attempt < kMaxSteps; ++attempt) {
    if (over_budget()) return fail(budget_reason());
    if (step.h < kShortestStep * length_)
      return fail("the path cannot be followed past this point (the corrections do not converge)");
    Eigen::VectorXd y = step.y + step.h * step.t, t;
    const Eigen::VectorXd anchor = y;
    if (!correct(y, step.t, anchor) || (y - anchor).norm() > 0.5 * step.h || !tangent(y, step.t, t) ||
        t.dot(step.t) < std::cos(kMaxTurn)) {
      step.h *= 0.5;
      continue;
    }
    if ((t[n_] > 0.0) != (step.t[n_] > 0.0) && step.t[n_] != 0.0) {
      Eigen::VectorXd y_limit;
      out.limit = locate_limit(step, step.h, y_limit);
      if (!out.limit) return fail(over_budget() ? budget_reason() : "a limit could not be located");
      if (branches_cross_at(y_limit)) {
        out.change_point = *out.limit;  // the same pose, told first: the input turns back where branches cross
        out.change_point->kind = PathSingularityKind::ChangePoint;
      }
      // On from the step's end, past the limit: at the limit itself the tangent's p component is
      // rounding, whose sign would announce the same limit again.
      step.y = y;
      step.t = t;
      step.det_sign = determinant_sign(y, t);
      return out;
    }
    const double allowed = std::max(kStepPerConditioning * conditioning_ * length_, kSlowest * length_);
    if (step.h > allowed && step.h > kSlowest * length_) {
      step.h = std::max(0.5 * step.h, allowed);
      continue;
    }
    const int sign = determinant_sign(y, t);
    if (sign != 0 && step.det_sign != 0 && sign != step.det_sign) {
      out.change_point = locate_change(step, step.h);
      if (!out.change_point && over_budget()) return fail(budget_reason());
    }
    step.y = y;
    step.t = t;
    step.det_sign = sign;
    // The next step also stays under what the conditioning here allows (with a margin for its
    // fall on the way), so that approaching a singular pose does not try every step twice.
    step.h = std::min({1.5 * step.h, kLongestStep * length_, std::max(0.9 * allowed, kSlowest * length_)});
    return out;
  }
  return fail("too many steps");
}

bool PathFollower::branches_cross_at(const Eigen::VectorXd& y) {
  evaluate(y);
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(augmented_);
  count_factorisation(augmented_.rows());
  const Eigen::VectorXd& sigma = svd.singularValues();
  if (sigma.size() < n_ || !(sigma[0] > 0.0)) return false;
  return sigma[n_ - 1] < kBranchesCrossAtLimit * sigma[0];
}

std::string PathFollower::budget_reason() const {
  std::ostringstream text;
  text.precision(3);
  text << "the path's search stopped at its work budget (" << work_budget_ << " flops on a model of " << n_
       << " coordinates) before it reached a limit or its end";
  return text.str();
}

bool PathFollower::solve_at_parameter(Eigen::VectorXd& y, double p) {
  y[n_] = scaled(p);
  Eigen::VectorXd border = Eigen::VectorXd::Zero(n_ + 1);
  border[n_] = 1.0;
  return correct(y, border, y);
}

}  // namespace nbar
