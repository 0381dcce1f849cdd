// Freudenstein function generation. The reference is a known four-bar: its output angle,
// from a closed-form position analysis written here, is the function to generate, and
// three precision points must give its link lengths back. Designs for y = log10(x) are
// simulated here, independently of the library, at their precision points.
#include "nbar/synthesis/function_generation.hpp"
#include "nbar/model/diagnostics.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <optional>

namespace nbar::synthesis {
namespace {

using ::testing::HasSubstr;
using Vec2 = Eigen::Vector2d;

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180;

double wrap(double a) { return std::remainder(a, 2 * kPi); }
double angle_of(const Vec2& v) { return std::atan2(v.y(), v.x()); }

// B at distance ab from A and bo from O, left (+1) or right (-1) of the line A->O.
std::optional<Vec2> circle_intersection(const Vec2& a, double ab, const Vec2& o, double bo, int side) {
  const Vec2 diag = o - a;
  const double l = diag.norm();
  if (l > ab + bo || l < std::abs(ab - bo)) return std::nullopt;
  const double along = (ab * ab - bo * bo + l * l) / (2 * l);
  const double h = std::sqrt(std::max(0.0, ab * ab - along * along));
  return Vec2(a + along * diag / l + side * h * Vec2(-diag.y(), diag.x()) / l);
}

// Output angle of the four-bar a, b, c, d (O2 at 0, O4 at (d, 0)) at crank angle phi.
double output_angle(double a, double b, double c, double d, double phi) {
  const Vec2 pa = a * Vec2(std::cos(phi), std::sin(phi)), o4(d, 0);
  return angle_of(*circle_intersection(pa, b, o4, c, 1) - o4);
}

// The design turned by its crank from the first precision point: the output's rotation
// from the first precision point, on the branch it is drawn in.
double output_rotation(const FourBarDesign& d, double crank_turn) {
  const double crank = (d.moving_a - d.ground_a).norm(), coupler = (d.moving_b - d.moving_a).norm();
  const double rocker = (d.moving_b - d.ground_b).norm();
  const int side = (d.ground_b - d.moving_a).x() * (d.moving_b - d.moving_a).y() -
                               (d.ground_b - d.moving_a).y() * (d.moving_b - d.moving_a).x() >
                           0
                       ? 1
                       : -1;
  const double theta = angle_of(d.moving_a - d.ground_a) + crank_turn;
  const Vec2 pa = d.ground_a + crank * Vec2(std::cos(theta), std::sin(theta));
  const Vec2 pb = *circle_intersection(pa, coupler, d.ground_b, rocker, side);
  return wrap(angle_of(pb - d.ground_b) - angle_of(d.moving_b - d.ground_b));
}

template <class F>
void expect_invalid(F&& call, const std::string& text) {
  try {
    call();
    ADD_FAILURE() << "no exception; expected one saying: " << text;
  } catch (const nbar::Error& e) {
    EXPECT_THAT(e.what(), HasSubstr(text));
  }
}

TEST(FunctionGenerationChebyshev, SpacingMatchesTheFormula) {
  const std::vector<double> x = chebyshev_spacing(1, 2, 3);
  ASSERT_EQ(x.size(), 3u);
  EXPECT_NEAR(x[0], 1.0669872981077808, 1e-15);  // 1.5 - 0.5 cos(30 deg)
  EXPECT_NEAR(x[1], 1.5, 1e-15);
  EXPECT_NEAR(x[2], 1.9330127018922192, 1e-15);
  const std::vector<double> one = chebyshev_spacing(0, 4, 1);
  ASSERT_EQ(one.size(), 1u);
  EXPECT_NEAR(one[0], 2, 1e-15);
  const std::vector<double> four = chebyshev_spacing(-1, 1, 4);  // cos(pi/8), cos(3 pi/8)
  EXPECT_NEAR(four[0], -0.92387953251128674, 1e-15);
  EXPECT_NEAR(four[1], -0.38268343236508978, 1e-15);
  EXPECT_NEAR(four[3], 0.92387953251128674, 1e-15);
  expect_invalid([] { chebyshev_spacing(0, 1, 0); }, "at least 1 point");
  expect_invalid([] { chebyshev_spacing(0, std::numeric_limits<double>::infinity(), 3); }, "not finite");
}

// The crank-rocker a = 2, b = 4.5, c = 3.5, d = 5: K1 = d/a = 2.5, K2 = d/c = 10/7,
// K3 = (a² - b² + c² + d²)/(2ac) = 21/14 = 1.5.
FunctionTask known_four_bar_task() {
  FunctionTask t;
  t.f = [](double phi) { return output_angle(2, 4.5, 3.5, 5, phi); };
  t.x_start = 40 * kDeg;
  t.x_end = 130 * kDeg;
  t.input_start = t.x_start;
  t.input_range = t.x_end - t.x_start;
  t.output_start = t.f(t.x_start);
  t.output_range = t.f(t.x_end) - t.f(t.x_start);
  t.frame_length = 5;
  return t;
}

TEST(FunctionGenerationFreudenstein, ThreePointsGiveBackAKnownFourBar) {
  const FunctionTask task = known_four_bar_task();
  for (int n : {3, 9}) {
    SCOPED_TRACE(testing::Message() << n << " precision points");
    const FunctionDesign d = freudenstein_design(task, chebyshev_spacing(task.x_start, task.x_end, n));
    EXPECT_NEAR(d.k[0], 2.5, 1e-9);
    EXPECT_NEAR(d.k[1], 10.0 / 7, 1e-9);
    EXPECT_NEAR(d.k[2], 1.5, 1e-9);
    EXPECT_NEAR(d.input, 2, 1e-9);
    EXPECT_NEAR(d.coupler, 4.5, 1e-9);
    EXPECT_NEAR(d.output, 3.5, 1e-9);
    EXPECT_EQ(d.frame, 5);
    EXPECT_EQ(d.branch, 1);
    EXPECT_TRUE(d.whole_range);
    // The same linkage: no structural error anywhere.
    EXPECT_LT(std::abs(d.worst.angle), 1e-9);
    ASSERT_EQ(d.precision.size(), static_cast<std::size_t>(n));
    for (const StructuralError& e : d.precision) EXPECT_LT(std::abs(e.angle), 1e-9);
    const double phi1 = chebyshev_spacing(task.x_start, task.x_end, n)[0];
    EXPECT_LT((d.design.ground_b - Vec2(5, 0)).norm(), 1e-15);
    EXPECT_LT((d.design.moving_a - 2 * Vec2(std::cos(phi1), std::sin(phi1))).norm(), 1e-9);
    EXPECT_NEAR(angle_of(d.design.moving_b - d.design.ground_b), task.f(phi1), 1e-9);
    EXPECT_EQ(d.design.coupler_point, d.design.moving_b);
  }
}

FunctionTask log10_task() {
  FunctionTask t;
  t.f = [](double x) { return std::log10(x); };
  t.x_start = 1;
  t.x_end = 2;
  t.input_start = 45 * kDeg;
  t.input_range = 60 * kDeg;
  t.output_start = 90 * kDeg;
  t.output_range = 60 * kDeg;
  t.frame_length = 1;
  return t;
}

// Wanted output rotation from the first precision point.
double wanted_rotation(const FunctionTask& t, double x, double x1) {
  return t.output_range * (t.f(x) - t.f(x1)) / (t.f(t.x_end) - t.f(t.x_start));
}

TEST(FunctionGenerationFreudenstein, Log10HitsItsChebyshevPrecisionPointsExactly) {
  const FunctionTask task = log10_task();
  const std::vector<double> xs = chebyshev_spacing(1, 2, 3);
  const FunctionDesign d = freudenstein_design(task, xs);
  ASSERT_EQ(d.precision.size(), 3u);
  for (std::size_t j = 0; j < 3; ++j) {
    EXPECT_EQ(d.precision[j].x, xs[j]);
    EXPECT_TRUE(d.precision[j].assembled);
    EXPECT_LT(std::abs(d.precision[j].angle), 1e-9);
    // Our own simulation of the drawn linkage, turned by the crank's rotation.
    const double turn = task.input_range * (xs[j] - xs[0]);
    EXPECT_LT(std::abs(wrap(output_rotation(d.design, turn) - wanted_rotation(task, xs[j], xs[0]))), 1e-9);
  }
  // Between the precision points the linkage only approximates log10: the structural error
  // is some thousandths of a radian, and in y units scaled by log10(2) / 60 deg.
  EXPECT_TRUE(d.whole_range);
  EXPECT_GT(std::abs(d.worst.angle), 1e-4);
  EXPECT_LT(std::abs(d.worst.angle), 5e-3);
  EXPECT_NEAR(d.worst.value, d.worst.angle * std::log10(2.0) / (60 * kDeg), 1e-15);
  // The reported worst error is the one our simulation finds at its x.
  const double turn = task.input_range * (d.worst.x - xs[0]);
  EXPECT_NEAR(wrap(output_rotation(d.design, turn) - wanted_rotation(task, d.worst.x, xs[0])), d.worst.angle, 1e-9);
  // Regression values (docs/synthesis-classic.md quotes them).
  EXPECT_NEAR(d.input, 2.652351, 1e-6);
  EXPECT_NEAR(d.coupler, 1.394423, 1e-6);
  EXPECT_NEAR(d.output, 2.957884, 1e-6);
  EXPECT_NEAR(d.worst.x, 1.0, 1e-12);
  EXPECT_NEAR(std::abs(d.worst.angle), 1.226e-3, 1e-6);
  // The lengths close the Freudenstein relations.
  EXPECT_NEAR(d.k[0], d.frame / d.input * (d.k[0] > 0 ? 1 : -1), 1e-12);
  EXPECT_NEAR(d.k[1], d.frame / d.output * (d.k[1] > 0 ? 1 : -1), 1e-12);
  std::printf(
      "log10 on [1, 2], 3 Chebyshev points: a %.6f b %.6f c %.6f d %.6f; K %.6f %.6f %.6f; "
      "worst error %.3e rad at x = %.4f\n",
      d.input, d.coupler, d.output, d.frame, d.k[0], d.k[1], d.k[2], d.worst.angle, d.worst.x);
}

// Sum of squared Freudenstein residuals of K at the given x.
double equation_residual(const FunctionTask& t, const std::array<double, 3>& k, const std::vector<double>& xs) {
  double sum = 0;
  for (double x : xs) {
    const double phi = t.input_start + t.input_range * (x - t.x_start) / (t.x_end - t.x_start);
    const double psi = t.output_start + wanted_rotation(t, x, t.x_start);
    const double r = k[0] * std::cos(psi) - k[1] * std::cos(phi) + k[2] - std::cos(phi - psi);
    sum += r * r;
  }
  return sum;
}

// The design keeps the task's angles: where a length comes out negative its link points
// opposite to phi (psi), and the offset of pi says so; the check reports input angles as phi,
// and the model gets a pointer whose body angle is phi (psi).
TEST(FunctionGenerationFreudenstein, DesignUsesTheTasksAngles) {
  FunctionTask task = log10_task();
  task.input_start = 90 * kDeg;  // the example's task: both lengths come out negative
  task.output_start = 60 * kDeg;
  const std::vector<double> xs = chebyshev_spacing(1, 2, 3);
  const FunctionDesign d = freudenstein_design(task, xs);
  ASSERT_LT(d.k[0], 0);
  ASSERT_LT(d.k[1], 0);
  const double phi1 = task.input_start + task.input_range * (xs[0] - 1);
  const Vec2 input = d.design.moving_a - d.design.ground_a;
  EXPECT_NEAR(std::atan2(input.y(), input.x()) + d.design.input_angle_offset, phi1, 1e-12);
  EXPECT_NEAR(std::abs(wrap(d.design.input_angle_offset)), kPi, 1e-12);
  EXPECT_NEAR(std::abs(wrap(d.design.output_angle_offset)), kPi, 1e-12);

  const DesignCheck check = check_design(d.design, rotation_targets(task, xs));
  ASSERT_EQ(check.targets.size(), 3u);
  for (std::size_t j = 0; j < 3; ++j)
    EXPECT_NEAR(check.targets[j].input_angle, task.input_start + task.input_range * (xs[j] - 1), 1e-9);

  const Model m = make_fourbar_model(d.design, "log10", {}, check.motion);
  ASSERT_EQ(m.points.size(), 7u);  // O2, O4, A, B, P and the pointers Ip, Op
  const Body& in = m.bodies[0];
  const Body& out = m.bodies[2];
  ASSERT_EQ(in.points.size(), 3u);
  ASSERT_EQ(out.points.size(), 3u);
  const Vec2 pointer = m.points[in.points[1]].position - m.points[in.points[0]].position;
  EXPECT_NEAR(std::atan2(pointer.y(), pointer.x()), phi1, 1e-12);
  const Vec2 output = m.points[out.points[1]].position - m.points[out.points[0]].position;
  EXPECT_NEAR(std::atan2(output.y(), output.x()),
              task.output_start + task.output_range * std::log10(xs[0]) / std::log10(2.0), 1e-9);

  // Positive lengths (the 45 deg task above): no offsets, no pointers.
  const FunctionDesign plain = freudenstein_design(log10_task(), xs);
  ASSERT_GT(plain.k[0], 0);
  EXPECT_EQ(plain.design.input_angle_offset, 0.0);
  EXPECT_EQ(make_fourbar_model(plain.design, "plain").points.size(), 5u);
}

TEST(FunctionGenerationFreudenstein, LeastSquaresMinimisesTheEquationResiduals) {
  const FunctionTask task = log10_task();
  std::vector<double> many;
  for (int i = 0; i <= 100; ++i) many.push_back(1 + i / 100.0);
  const FunctionDesign three = freudenstein_design(task, chebyshev_spacing(1, 2, 3));
  const FunctionDesign fitted = freudenstein_design(task, many);
  ASSERT_EQ(fitted.precision.size(), 101u);
  const double r3 = equation_residual(task, three.k, many), rf = equation_residual(task, fitted.k, many);
  EXPECT_LT(rf, r3);
  // Nudging the fitted K any way makes it worse: it is the minimum.
  for (int i = 0; i < 3; ++i)
    for (double step : {1e-4, -1e-4}) {
      std::array<double, 3> k = fitted.k;
      k[static_cast<std::size_t>(i)] += step;
      EXPECT_GT(equation_residual(task, k, many), rf);
    }
  // Precision points now all miss a little, and the report says by how much: our own
  // simulation agrees with each reported error (relative to the first point's).
  double largest = 0;
  for (const StructuralError& e : fitted.precision) {
    const double turn = task.input_range * (e.x - many[0]);
    const double ours = wrap(output_rotation(fitted.design, turn) - wanted_rotation(task, e.x, many[0]));
    EXPECT_NEAR(ours, e.angle - fitted.precision[0].angle, 1e-9);
    largest = std::max(largest, std::abs(e.angle));
  }
  EXPECT_GT(largest, 1e-5);
  EXPECT_LE(largest, std::abs(fitted.worst.angle));
  // For this smooth function the fit also lowers the largest structural error (not a law:
  // least squares minimises the equation residuals, not the error in angle).
  EXPECT_LT(std::abs(fitted.worst.angle), std::abs(three.worst.angle));
  std::printf("log10: worst error %.3e rad with 3 Chebyshev points, %.3e rad with 101 points by least squares\n",
              three.worst.angle, fitted.worst.angle);
}

TEST(FunctionGenerationFreudenstein, BadInputIsRefusedByName) {
  const FunctionTask task = log10_task();
  const auto cheb = chebyshev_spacing(1, 2, 3);
  expect_invalid([&] { freudenstein_design(task, {1, 2}); }, "at least 3 precision points");
  expect_invalid([&] { freudenstein_design(task, {1, 1.5, 1.5}); }, "precision points 2 and 3 coincide");
  expect_invalid(
      [&] {
        freudenstein_design(task, {1, std::numeric_limits<double>::quiet_NaN(), 2});
      },
      "precision point 2 is not finite");
  auto t = task;
  t.f = nullptr;
  expect_invalid([&] { freudenstein_design(t, cheb); }, "no function given");
  t = task;
  t.input_range = 0;
  expect_invalid([&] { freudenstein_design(t, cheb); }, "input angle range is zero");
  t = task;
  t.output_range = 0;
  expect_invalid([&] { freudenstein_design(t, cheb); }, "output angle range is zero");
  t = task;
  t.x_end = t.x_start;
  expect_invalid([&] { freudenstein_design(t, cheb); }, "range of x is empty");
  t = task;
  t.frame_length = -1;
  expect_invalid([&] { freudenstein_design(t, cheb); }, "frame length must be positive");
  t = task;
  t.output_start = std::numeric_limits<double>::infinity();
  expect_invalid([&] { freudenstein_design(t, cheb); }, "non-finite");
  t = task;
  t.x_start = -1;  // log10(-1) is NaN
  expect_invalid([&] { freudenstein_design(t, {-0.5, 0.5, 1.5}); }, "f(-1) is not finite");
  t = task;
  t.f = [](double x) { return x * x; };
  t.x_start = -1;
  t.x_end = 1;
  expect_invalid([&] { freudenstein_design(t, {-0.5, 0.1, 0.5}); }, "f(x_start) equals f(x_end)");
  t = task;
  t.input_range = 2 * kPi;  // x_start and x_end put the crank at one place
  expect_invalid([&] { freudenstein_design(t, {1, 1.5, 2}); }, "same crank position");
  // Chebyshev points symmetric about phi = 180 deg for y = x^2 make K1 vanish: the input
  // would have to be a slider.
  t = task;
  t.f = [](double x) { return x * x; };
  t.x_start = 0;
  t.x_end = 1;
  t.input_start = 150 * kDeg;
  t.output_start = 30 * kDeg;
  expect_invalid([&] { freudenstein_design(t, chebyshev_spacing(0, 1, 3)); }, "infinitely long");
}

}  // namespace
}  // namespace nbar::synthesis
