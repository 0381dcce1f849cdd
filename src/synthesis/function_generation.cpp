#include "nbar/synthesis/function_generation.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>

#include "nbar/model/diagnostics.hpp"

namespace nbar::synthesis {
namespace {

using Vec2 = Eigen::Vector2d;

constexpr double kPi = 3.14159265358979323846;

template <class... Parts>
[[noreturn]] void fail(const Parts&... parts) {
  std::ostringstream message;
  message << "Freudenstein synthesis: ";
  (message << ... << parts);
  throw Error(ErrorKind::InvalidModel, message.str());
}

// Into (-pi, pi].
double wrap(double angle) {
  angle = std::remainder(angle, 2 * kPi);
  return angle <= -kPi ? angle + 2 * kPi : angle;
}

// A linkage from its signed lengths: a negative crank or output length turns that link by pi.
struct Linkage {
  double a = 0, b = 0, c = 0, d = 0;  // a, c signed; b = |coupler| > 0

  Vec2 crank_pin(double phi) const { return a * Vec2(std::cos(phi), std::sin(phi)); }
  // B on the given side of the line A -> O4, or none where the loop does not close.
  std::optional<Vec2> output_pin(double phi, int branch) const {
    const Vec2 pa = crank_pin(phi), o4(d, 0);
    const Vec2 diagonal = o4 - pa;
    const double l = diagonal.norm(), cc = std::abs(c);
    if (!(l > 0) || l > b + cc || l < std::abs(b - cc)) return std::nullopt;
    const double along = (b * b - cc * cc + l * l) / (2 * l);
    const double h = std::sqrt(std::max(0.0, b * b - along * along));
    const Vec2 n(-diagonal.y() / l, diagonal.x() / l);
    return Vec2(pa + along * diagonal / l + branch * h * n);
  }
  double output_angle(const Vec2& pb) const {
    const Vec2 v = (pb - Vec2(d, 0)) / c;  // e^(i psi), sign of c included
    return std::atan2(v.y(), v.x());
  }
};

struct Mapping {
  const FunctionTask& task;
  double y_start, y_end;
  double phi(double x) const {
    return task.input_start + task.input_range * (x - task.x_start) / (task.x_end - task.x_start);
  }
  double psi(double y) const { return task.output_start + task.output_range * (y - y_start) / (y_end - y_start); }
  // y units per radian of output.
  double value_per_angle() const { return (y_end - y_start) / task.output_range; }
};

double evaluate(const FunctionTask& task, double x) {
  const double y = task.f(x);
  if (!std::isfinite(y)) fail("f(", x, ") is not finite");
  return y;
}

void check_task(const FunctionTask& task) {
  if (!task.f) fail("no function given");
  for (double v : {task.x_start, task.x_end, task.input_start, task.input_range, task.output_start, task.output_range,
                   task.frame_length})
    if (!std::isfinite(v)) fail("the task has a non-finite number");
  if (task.x_start == task.x_end) fail("the range of x is empty (x_start equals x_end)");
  if (task.input_range == 0) fail("the input angle range is zero");
  if (task.output_range == 0) fail("the output angle range is zero");
  if (!(task.frame_length > 0)) fail("the frame length must be positive");
  if (task.samples < 2) fail("at least 2 samples are needed over the range");
}

void check_precision_points(const std::vector<double>& xs, const Mapping& map) {
  if (xs.size() < 3) fail("at least 3 precision points are needed (got ", xs.size(), ")");
  for (std::size_t i = 0; i < xs.size(); ++i)
    if (!std::isfinite(xs[i])) fail("precision point ", i + 1, " is not finite");
  const double span = std::abs(map.task.x_end - map.task.x_start);
  for (std::size_t i = 0; i < xs.size(); ++i)
    for (std::size_t j = i + 1; j < xs.size(); ++j) {
      if (std::abs(xs[i] - xs[j]) <= 1e-12 * span) fail("precision points ", i + 1, " and ", j + 1, " coincide");
      if (std::abs(std::sin(0.5 * (map.phi(xs[i]) - map.phi(xs[j])))) <= 1e-9)
        fail("precision points ", i + 1, " and ", j + 1,
             " give the same crank position (input angles differ by a multiple of 2 pi)");
    }
}

// K1, K2, K3 from the linear Freudenstein equations: exact for 3 rows, least squares above.
std::array<double, 3> solve_k(const std::vector<double>& phi, const std::vector<double>& psi) {
  const auto n = static_cast<Eigen::Index>(phi.size());
  Eigen::Matrix<double, Eigen::Dynamic, 3> m(n, 3);
  Eigen::VectorXd rhs(n);
  for (Eigen::Index j = 0; j < n; ++j) {
    m.row(j) << std::cos(psi[j]), -std::cos(phi[j]), 1.0;
    rhs[j] = std::cos(phi[j] - psi[j]);
  }
  // QR for the solve; the singular values of R (those of m) for an honest condition number.
  const Eigen::ColPivHouseholderQR<Eigen::Matrix<double, Eigen::Dynamic, 3>> qr(m);
  const Eigen::Matrix3d r = qr.matrixR().topLeftCorner<3, 3>().triangularView<Eigen::Upper>();
  const Eigen::Vector3d s = Eigen::JacobiSVD<Eigen::Matrix3d>(r).singularValues();
  if (!(s[2] > 1e-10 * s[0]))
    fail("the precision points give a singular Freudenstein system (condition ", s[0] / s[2],
         "); spread them or change the angle ranges");
  const Eigen::Vector3d k = qr.solve(rhs);
  return {k[0], k[1], k[2]};
}

Linkage linkage_from_k(const std::array<double, 3>& k, double d) {
  if (std::abs(k[0]) <= 1e-12) fail("K1 is zero: the input crank would be infinitely long");
  if (std::abs(k[1]) <= 1e-12) fail("K2 is zero: the output link would be infinitely long");
  Linkage l;
  l.d = d;
  l.a = d / k[0];
  l.c = d / k[1];
  const double b2 = l.a * l.a + l.c * l.c + d * d - 2 * l.a * l.c * k[2];
  if (!(b2 > 1e-24 * d * d))
    fail("no real four-bar fits: the coupler length squared comes out as ", b2,
         "; change the angle ranges or the precision points");
  l.b = std::sqrt(b2);
  return l;
}

std::optional<double> simulate(const Linkage& l, double phi, int branch) {
  const std::optional<Vec2> pb = l.output_pin(phi, branch);
  if (!pb) return std::nullopt;
  return l.output_angle(*pb);
}

}  // namespace

std::vector<double> chebyshev_spacing(double x_start, double x_end, int n) {
  if (!std::isfinite(x_start) || !std::isfinite(x_end)) fail("the range for Chebyshev spacing is not finite");
  if (n < 1) fail("Chebyshev spacing needs at least 1 point");
  std::vector<double> x;
  for (int j = 1; j <= n; ++j)
    x.push_back(0.5 * (x_start + x_end) - 0.5 * (x_end - x_start) * std::cos((2 * j - 1) * kPi / (2 * n)));
  return x;
}

FunctionDesign freudenstein_design(const FunctionTask& task, const std::vector<double>& precision_x) {
  check_task(task);
  const double y_start = evaluate(task, task.x_start), y_end = evaluate(task, task.x_end);
  if (y_start == y_end) fail("f(x_start) equals f(x_end): the output range has nothing to scale");
  const Mapping map{task, y_start, y_end};
  check_precision_points(precision_x, map);

  std::vector<double> phi, psi;
  for (double x : precision_x) {
    phi.push_back(map.phi(x));
    psi.push_back(map.psi(evaluate(task, x)));
  }
  FunctionDesign out;
  out.k = solve_k(phi, psi);
  const Linkage l = linkage_from_k(out.k, task.frame_length);
  out.input = std::abs(l.a);
  out.coupler = l.b;
  out.output = std::abs(l.c);
  out.frame = l.d;

  // The assembly that meets the first precision point best; the linkage keeps it.
  double best = kPi + 1;
  for (int branch : {1, -1})
    if (const auto p = simulate(l, phi[0], branch); p && std::abs(wrap(*p - psi[0])) < best) {
      best = std::abs(wrap(*p - psi[0]));
      out.branch = branch;
    }
  if (out.branch == 0) fail("the four-bar cannot be assembled at the first precision point");
  out.design.ground_a = Vec2(0, 0);
  out.design.ground_b = Vec2(l.d, 0);
  out.design.moving_a = l.crank_pin(phi[0]);
  out.design.moving_b = *l.output_pin(phi[0], out.branch);
  out.design.coupler_point = out.design.moving_b;
  // A negative length points its link opposite to phi (psi): the task's angles are those of
  // the link turned by pi, in the turn the task gives them.
  const auto offset = [](double length, double wanted, double direction) {
    const double base = length < 0 ? kPi : 0.0;
    return base + 2 * kPi * std::round((wanted - direction - base) / (2 * kPi));
  };
  out.design.input_angle_offset = offset(l.a, phi[0], std::atan2(out.design.moving_a.y(), out.design.moving_a.x()));
  const Vec2 output_link = out.design.moving_b - out.design.ground_b;
  out.design.output_angle_offset = offset(l.c, psi[0], std::atan2(output_link.y(), output_link.x()));

  auto error_at = [&](double x) {
    const auto generated = simulate(l, map.phi(x), out.branch);
    if (!generated) return StructuralError{x, 0, 0, false};
    const double angle = wrap(*generated - map.psi(evaluate(task, x)));
    return StructuralError{x, angle, angle * map.value_per_angle(), true};
  };
  auto record = [&](const StructuralError& e) {
    if (!e.assembled && out.whole_range) {
      out.whole_range = false;
      out.fails_at_x = e.x;
    }
    if (e.assembled && std::abs(e.angle) >= std::abs(out.worst.angle)) out.worst = e;
  };
  for (int i = 0; i < task.samples; ++i)
    record(error_at(task.x_start + (task.x_end - task.x_start) * i / (task.samples - 1)));
  for (double x : precision_x) {
    out.precision.push_back(error_at(x));
    record(out.precision.back());
  }
  return out;
}

std::vector<RotationTarget> rotation_targets(const FunctionTask& task, const std::vector<double>& precision_x) {
  check_task(task);
  if (precision_x.empty()) fail("no precision points");
  const Mapping map{task, evaluate(task, task.x_start), evaluate(task, task.x_end)};
  const double phi0 = map.phi(precision_x[0]), psi0 = map.psi(evaluate(task, precision_x[0]));
  std::vector<RotationTarget> targets;
  for (double x : precision_x) targets.push_back({map.phi(x) - phi0, map.psi(evaluate(task, x)) - psi0});
  return targets;
}

}  // namespace nbar::synthesis
