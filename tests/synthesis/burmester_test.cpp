// Burmester motion generation against a known four-bar: positions of its coupler, taken from
// a closed-form position analysis written here, must give back its pivots; and every design
// returned must carry its coupler through every precision position, checked with the same
// independent closed form (link lengths and input angle only). The five-position solutions
// are cross-checked with the homotopy solver.
#include "nbar/synthesis/burmester.hpp"
#include "nbar/model/diagnostics.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <Eigen/LU>

#include <cmath>
#include <limits>
#include <random>

#include "nbar/synthesis/solve.hpp"

namespace nbar::synthesis {
namespace {

using ::testing::HasSubstr;
using Vec2 = Eigen::Vector2d;

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180;

Vec2 polar(double r, double angle) { return r * Vec2(std::cos(angle), std::sin(angle)); }
Eigen::Matrix2d rotation(double a) {
  Eigen::Matrix2d r;
  r << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
  return r;
}

// The point B at distance ab from A and bo from O, left (+1) or right (-1) of the line A->O;
// none when the loop does not close.
std::optional<Vec2> circle_intersection(const Vec2& a, double ab, const Vec2& o, double bo, int side) {
  const Vec2 diag = o - a;
  const double l = diag.norm();
  if (l > ab + bo || l < std::abs(ab - bo)) return std::nullopt;
  const double along = (ab * ab - bo * bo + l * l) / (2 * l);
  const double h = std::sqrt(std::max(0.0, ab * ab - along * along));
  return Vec2(a + along * diag / l + side * h * Vec2(-diag.y(), diag.x()) / l);
}

// A four-bar with its coupler point given in the coupler's frame (x along A->B).
struct KnownFourBar {
  Vec2 o2{0.3, -0.2}, o4{4.1, 0.4};
  double crank = 1.2, coupler = 3.5, rocker = 2.8;
  Vec2 point_in_coupler{1.4, 0.9};
  int side = 1;

  Vec2 a(double theta) const { return o2 + polar(crank, theta); }
  Vec2 b(double theta) const { return *circle_intersection(a(theta), coupler, o4, rocker, side); }
  BodyPose pose(double theta) const {
    const Vec2 pa = a(theta), pb = b(theta);
    const double angle = std::atan2(pb.y() - pa.y(), pb.x() - pa.x());
    return {pa + rotation(angle) * point_in_coupler, angle};
  }
};

template <std::size_t N>
std::array<BodyPose, N> poses_at(const KnownFourBar& f, const std::array<double, N>& degrees) {
  std::array<BodyPose, N> out;
  for (std::size_t i = 0; i < N; ++i) out[i] = f.pose(degrees[i] * kDeg);
  return out;
}

// Where a body point given in the first position is in position i.
Vec2 moved(const Vec2& x, std::span<const BodyPose> poses, std::size_t i) {
  return rotation(poses[i].angle - poses[0].angle) * (x - poses[0].point) + poses[i].point;
}

double angle_difference(double a, double b) { return std::abs(std::remainder(a - b, 2 * kPi)); }

// Independent check: the design, given only its link lengths and the input angle of each
// position, puts its coupler at every pose, on some assembly branch. Returns the branch used
// at each pose (+1/-1).
std::vector<int> check_reaches(const FourBarDesign& d, std::span<const BodyPose> poses, double tolerance) {
  const double size = 1 + (d.ground_b - d.ground_a).norm();
  const double crank = (d.moving_a - d.ground_a).norm(), coupler = (d.moving_b - d.moving_a).norm();
  const double rocker = (d.moving_b - d.ground_b).norm();
  const double coupler_angle0 = std::atan2(d.moving_b.y() - d.moving_a.y(), d.moving_b.x() - d.moving_a.x());
  std::vector<int> branches;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const Vec2 a_expected = moved(d.moving_a, poses, i);
    // The dyad condition itself: the moving pivot stays on its circle.
    EXPECT_NEAR((a_expected - d.ground_a).norm(), crank, tolerance * size) << "input dyad, position " << i + 1;
    const double theta = std::atan2(a_expected.y() - d.ground_a.y(), a_expected.x() - d.ground_a.x());
    const Vec2 pa = d.ground_a + polar(crank, theta);
    int used = 0;
    for (int side : {1, -1}) {
      const auto pb = circle_intersection(pa, coupler, d.ground_b, rocker, side);
      if (!pb) continue;
      const double turn = std::atan2(pb->y() - pa.y(), pb->x() - pa.x()) - coupler_angle0;
      const Vec2 point = pa + rotation(turn) * (d.coupler_point - d.moving_a);
      if ((point - poses[i].point).norm() <= tolerance * size &&
          angle_difference(poses[0].angle + turn, poses[i].angle) <= tolerance) {
        used = side;
        break;
      }
    }
    EXPECT_NE(used, 0) << "the coupler misses position " << i + 1;
    branches.push_back(used);
  }
  return branches;
}

bool same_pair(const BurmesterPair& p, const Vec2& centre, const Vec2& circle, double tolerance) {
  return (p.centre - centre).norm() <= tolerance && (p.circle - circle).norm() <= tolerance;
}

// ---- Three positions ----------------------------------------------------------------------

TEST(BurmesterThreePositions, CentreAndCirclePointsRecoverTheKnownPivots) {
  const KnownFourBar f;
  const auto poses = poses_at<3>(f, {20, 75, 140});
  const Vec2 a0 = f.a(20 * kDeg), b0 = f.b(20 * kDeg);
  EXPECT_LT((centre_point(poses, a0) - f.o2).norm(), 1e-10);
  EXPECT_LT((centre_point(poses, b0) - f.o4).norm(), 1e-10);
  EXPECT_LT((circle_point(poses, f.o2) - a0).norm(), 1e-10);
  EXPECT_LT((circle_point(poses, f.o4) - b0).norm(), 1e-10);
}

TEST(BurmesterThreePositions, DesignsFromMovingOrFixedPivotsReachEveryPosition) {
  const KnownFourBar f;
  const auto poses = poses_at<3>(f, {20, 75, 140});
  const Vec2 a0 = f.a(20 * kDeg), b0 = f.b(20 * kDeg);

  const FourBarDesign from_moving = three_position_design(poses, PivotChoice::Moving, a0, b0);
  EXPECT_LT((from_moving.ground_a - f.o2).norm(), 1e-10);
  EXPECT_LT((from_moving.ground_b - f.o4).norm(), 1e-10);
  EXPECT_LT((from_moving.coupler_point - poses[0].point).norm(), 1e-15);
  EXPECT_EQ(check_reaches(from_moving, poses, 1e-9), std::vector<int>(3, 1));

  const FourBarDesign from_fixed = three_position_design(poses, PivotChoice::Fixed, f.o2, f.o4);
  EXPECT_LT((from_fixed.moving_a - a0).norm(), 1e-10);
  EXPECT_LT((from_fixed.moving_b - b0).norm(), 1e-10);
  EXPECT_EQ(branch_signs(from_fixed, poses), std::vector<int>(3, 1));

  // Any other choice is a new linkage through the same three positions.
  for (const auto& [p, q] : {std::pair{Vec2(1, 2), Vec2(3, -1)}, std::pair{Vec2(-2, 0.5), Vec2(6, 3)}}) {
    SCOPED_TRACE(testing::Message() << "pivots " << p.transpose() << ", " << q.transpose());
    check_reaches(three_position_design(poses, PivotChoice::Moving, p, q), poses, 1e-9);
    check_reaches(three_position_design(poses, PivotChoice::Fixed, p, q), poses, 1e-9);
  }
}

TEST(BurmesterThreePositions, LargeCoordinatesKeepTheirDigits) {
  // The same task 10^6 units away from the origin, in millimetres.
  KnownFourBar f;
  f.o2 = Vec2(1e6 + 300, -2e6 - 200);
  f.o4 = f.o2 + Vec2(3800, 600);
  f.crank = 1200, f.coupler = 3500, f.rocker = 2800, f.point_in_coupler = {1400, 900};
  const auto poses = poses_at<3>(f, {20, 75, 140});
  EXPECT_LT((centre_point(poses, f.a(20 * kDeg)) - f.o2).norm(), 1e-6);
  EXPECT_LT((circle_point(poses, f.o4) - f.b(20 * kDeg)).norm(), 1e-6);
}

TEST(BurmesterThreePositions, BadInputIsRefusedByName) {
  const KnownFourBar f;
  auto poses = poses_at<3>(f, {20, 75, 140});
  auto expect_error = [](auto&& call, const std::string& text) {
    try {
      call();
      ADD_FAILURE() << "no exception; expected one saying: " << text;
    } catch (const nbar::Error& e) {
      EXPECT_THAT(e.what(), HasSubstr(text));
    }
  };
  auto same = poses;
  same[2] = same[0];
  same[2].angle += 2 * kPi;  // one position, whatever the turn count
  expect_error([&] { centre_point(same, Vec2(1, 1)); }, "positions 1 and 3 coincide");
  auto nan = poses;
  nan[1].angle = std::numeric_limits<double>::quiet_NaN();
  expect_error([&] { circle_point(nan, Vec2(1, 1)); }, "position 2 is not finite");
  const Vec2 infinite(std::numeric_limits<double>::infinity(), 0);
  expect_error([&] { centre_point(poses, infinite); }, "circle point is not finite");

  // A body point moving along a line has no centre point.
  const std::array<BodyPose, 3> sliding{BodyPose{{0, 0}, 0}, BodyPose{{1, 0}, 0.3}, BodyPose{{3, 0}, 0.5}};
  expect_error([&] { centre_point(sliding, Vec2(0, 0)); }, "collinear");
  // The pole of positions 1 and 2 is at one place in both: no centre point.
  const Vec2 body = (rotation(poses[0].angle) - rotation(poses[1].angle)).inverse() * (poses[1].point - poses[0].point);
  const Vec2 pole12 = rotation(poses[0].angle) * body + poses[0].point;
  expect_error([&] { centre_point(poses, pole12); }, "positions 1 and 2");
  // ... and as a fixed pivot, no unique circle point.
  expect_error([&] { circle_point(poses, pole12); }, "positions 1 and 2");

  expect_error([&] { three_position_design(poses, PivotChoice::Moving, Vec2(1, 1), Vec2(1, 1)); },
               "two given moving pivots coincide");
  expect_error([&] { three_position_design(poses, PivotChoice::Fixed, f.o2, f.o2); },
               "two given fixed pivots coincide");
}

// ---- Four positions -------------------------------------------------------------------------

double distance_to_polylines(const std::vector<std::vector<BurmesterPair>>& lines, const Vec2& x, bool centre) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& line : lines)
    for (std::size_t k = 0; k + 1 < line.size(); ++k) {
      const Vec2 p = centre ? line[k].centre : line[k].circle, q = centre ? line[k + 1].centre : line[k + 1].circle;
      const double t = std::clamp((x - p).dot(q - p) / (q - p).squaredNorm(), 0.0, 1.0);
      best = std::min(best, (p + t * (q - p) - x).norm());
    }
  return best;
}

TEST(BurmesterFourPositions, EverySampleGuidesTheBodyThroughAllFourPositions) {
  const KnownFourBar f;
  const auto poses = poses_at<4>(f, {20, 75, 140, 210});
  const BurmesterCurves curves = four_position_curves(poses);
  ASSERT_FALSE(curves.centre_curve.empty());
  ASSERT_FALSE(curves.circle_curve.empty());
  int samples = 0;
  double worst = 0;
  for (const auto* family : {&curves.centre_curve, &curves.circle_curve})
    for (const auto& line : *family)
      for (const BurmesterPair& p : line) {
        const double r0 = (p.circle - p.centre).norm();
        for (std::size_t i = 1; i < 4; ++i)
          worst = std::max(worst, std::abs((moved(p.circle, poses, i) - p.centre).norm() - r0) / r0);
        // Each curve is clipped to the window; its partner points may lie anywhere.
        const Vec2& traced = family == &curves.centre_curve ? p.centre : p.circle;
        EXPECT_LE((traced - curves.window_centre).norm(), curves.window_radius * (1 + 1e-12));
        ++samples;
      }
  EXPECT_LT(worst, 1e-9);
  EXPECT_GT(samples, 300);
  std::printf("four positions: %zu centre and %zu circle polylines, %d samples, worst relative radius change %.2e\n",
              curves.centre_curve.size(), curves.circle_curve.size(), samples, worst);
}

TEST(BurmesterFourPositions, CurvesPassThroughTheKnownPivotsAndThePoles) {
  const KnownFourBar f;
  const auto poses = poses_at<4>(f, {20, 75, 140, 210});
  CurveOptions options;
  options.radius = 8;
  options.step = 0.02;
  const BurmesterCurves curves = four_position_curves(poses, options);
  EXPECT_NEAR(curves.window_radius, 8, 1e-12);
  // Chords of a smooth curve sampled every 0.02 stay within ~1e-4 of it.
  EXPECT_LT(distance_to_polylines(curves.centre_curve, f.o2, true), 1e-3);
  EXPECT_LT(distance_to_polylines(curves.centre_curve, f.o4, true), 1e-3);
  EXPECT_LT(distance_to_polylines(curves.circle_curve, f.a(20 * kDeg), false), 1e-3);
  EXPECT_LT(distance_to_polylines(curves.circle_curve, f.b(20 * kDeg), false), 1e-3);
  // Every pole of two positions is a centre point (any body point keeps its distance to it).
  for (std::size_t i = 0; i < 4; ++i)
    for (std::size_t j = i + 1; j < 4; ++j) {
      const Eigen::Matrix2d difference = rotation(poses[i].angle) - rotation(poses[j].angle);
      const Vec2 body = difference.inverse() * (poses[j].point - poses[i].point);
      const Vec2 pole = rotation(poses[i].angle) * body + poses[i].point;
      if ((pole - curves.window_centre).norm() < 0.9 * curves.window_radius) {
        EXPECT_LT(distance_to_polylines(curves.centre_curve, pole, true), 1e-3) << "pole " << i + 1 << j + 1;
      }
    }
  // The known dyads' partners: the samples nearest the known fixed pivots carry the known
  // moving pivots.
  for (const auto& [centre, circle] : {std::pair{f.o2, f.a(20 * kDeg)}, std::pair{f.o4, f.b(20 * kDeg)}}) {
    const BurmesterPair* nearest = nullptr;
    for (const auto& line : curves.centre_curve)
      for (const BurmesterPair& p : line)
        if (!nearest || (p.centre - centre).norm() < (nearest->centre - centre).norm()) nearest = &p;
    ASSERT_NE(nearest, nullptr);
    EXPECT_LT((nearest->circle - circle).norm(), 0.1);
  }
}

TEST(BurmesterFourPositions, DegenerateMotionsAreRefused) {
  auto expect_error = [](const std::array<BodyPose, 4>& poses, const CurveOptions& o, const std::string& text) {
    try {
      four_position_curves(poses, o);
      ADD_FAILURE() << "no exception; expected one saying: " << text;
    } catch (const nbar::Error& e) {
      EXPECT_THAT(e.what(), HasSubstr(text));
    }
  };
  const std::array<BodyPose, 4> translation{BodyPose{{0, 0}, 0.2}, BodyPose{{1, 0}, 0.2}, BodyPose{{1, 1}, 0.2},
                                            BodyPose{{0, 2}, 0.2}};
  expect_error(translation, {}, "does not turn");
  std::array<BodyPose, 4> turning;
  for (int i = 0; i < 4; ++i) turning[i] = {Vec2(2, 1) + rotation(0.4 * i) * Vec2(1, 0), 0.4 * i};
  expect_error(turning, {}, "only turns about one point");
  const KnownFourBar f;
  const auto poses = poses_at<4>(f, {20, 75, 140, 210});
  CurveOptions bad;
  bad.step = -1;
  expect_error(poses, bad, "step");
  bad.step = 0;
  bad.radius = std::numeric_limits<double>::quiet_NaN();
  expect_error(poses, bad, "radius");
  // So wide a window that the curves' equation overflows: nothing would be traced.
  bad.radius = 1e300;
  expect_error(poses, bad, "the window radius 1e+300 is more than 10^6 times the size of the poses");
  bad.radius = 0.99 * largest_window_radius(poses);
  EXPECT_NO_THROW(four_position_curves(poses, bad));
  auto same = poses;
  same[3] = same[1];
  expect_error(same, {}, "positions 2 and 4 coincide");
}

// ---- Five positions -------------------------------------------------------------------------

struct Found {
  int real = 0, complex = 0;
  std::vector<Eigen::Vector4d> points;  // (c, q)
};

// Every solution of the bilinear system by the homotopy solver (6 paths).
Found by_homotopy(const std::array<BodyPose, 5>& poses) {
  SolverOptions options;
  options.threads = 1;
  const SolveResult r = solve_linear_product(five_position_system(poses), {{0, 1}, {2, 3}}, options);
  EXPECT_EQ(r.endpoints.size(), 6u);
  EXPECT_EQ(r.count(EndpointKind::AtInfinity), 2);
  Found out;
  for (const CVector& x : r.solutions()) {
    if (x.imag().cwiseAbs().maxCoeff() <= 1e-8 * (1 + x.norm())) {
      ++out.real;
      out.points.push_back(x.real());
    } else {
      ++out.complex;
    }
  }
  return out;
}

void expect_agrees_with_homotopy(const std::array<BodyPose, 5>& poses, const FivePositionResult& r) {
  const Found h = by_homotopy(poses);
  EXPECT_EQ(h.real + h.complex, 4);
  EXPECT_EQ(static_cast<int>(r.points.size()), h.real);
  EXPECT_EQ(r.complex_points, h.complex);
  for (const Eigen::Vector4d& x : h.points) {
    bool matched = false;
    for (const BurmesterPair& p : r.points) matched = matched || same_pair(p, x.head<2>(), x.tail<2>(), 1e-8);
    EXPECT_TRUE(matched) << "homotopy solution " << x.transpose() << " missing";
  }
}

TEST(BurmesterFivePositions, RecoversTheKnownFourBarAndEveryDesignReachesAllPositions) {
  const KnownFourBar f;
  const auto poses = poses_at<5>(f, {20, 75, 140, 210, 300});
  const FivePositionResult r = five_position_burmester(poses);
  ASSERT_GE(r.points.size(), 2u);
  EXPECT_EQ(r.points.size() + static_cast<std::size_t>(r.complex_points), 4u);
  EXPECT_EQ(r.designs.size(), r.points.size() * (r.points.size() - 1) / 2);
  int input = -1, output = -1;
  for (int k = 0; k < static_cast<int>(r.points.size()); ++k) {
    if (same_pair(r.points[k], f.o2, f.a(20 * kDeg), 1e-8)) input = k;
    if (same_pair(r.points[k], f.o4, f.b(20 * kDeg), 1e-8)) output = k;
  }
  ASSERT_GE(input, 0) << "the crank's dyad is not among the Burmester points";
  ASSERT_GE(output, 0) << "the rocker's dyad is not among the Burmester points";
  for (const BurmesterDesign& d : r.designs) {
    SCOPED_TRACE(testing::Message() << "design " << d.input << "-" << d.output);
    const std::vector<int> branches = check_reaches(d.design, poses, 1e-9);
    EXPECT_EQ(d.one_branch, std::all_of(branches.begin(), branches.end(), [&](int b) { return b == branches[0]; }));
    if (d.input == std::min(input, output) && d.output == std::max(input, output)) {
      EXPECT_TRUE(d.one_branch);
    }
  }
  expect_agrees_with_homotopy(poses, r);
  std::printf("five positions: %zu real Burmester points, %d complex, %zu designs\n", r.points.size(), r.complex_points,
              r.designs.size());
}

TEST(BurmesterFivePositions, AgreesWithTheHomotopySolverOnRandomTasks) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coordinate(-3, 3), angle(-kPi, kPi);
  int totals[5] = {0, 0, 0, 0, 0};
  for (int task = 0; task < 12; ++task) {
    SCOPED_TRACE(testing::Message() << "task " << task);
    std::array<BodyPose, 5> poses;
    for (BodyPose& p : poses) p = {Vec2(coordinate(rng), coordinate(rng)), angle(rng)};
    const FivePositionResult r = five_position_burmester(poses);
    expect_agrees_with_homotopy(poses, r);
    ++totals[r.points.size()];
    for (const BurmesterDesign& d : r.designs) check_reaches(d.design, poses, 1e-8);
  }
  std::printf("random tasks with 0/2/4 real Burmester points: %d/%d/%d\n", totals[0], totals[2], totals[4]);
  EXPECT_EQ(totals[1] + totals[3], 0);
}

TEST(BurmesterFivePositions, TheFirstPositionCanBeAnyOfThem) {
  // Same task, positions listed from another one: the fixed pivots stay, the moving pivots
  // are given in the new first position.
  const KnownFourBar f;
  const auto poses = poses_at<5>(f, {20, 75, 140, 210, 300});
  const auto rotated = poses_at<5>(f, {140, 210, 300, 20, 75});
  const FivePositionResult a = five_position_burmester(poses), b = five_position_burmester(rotated);
  ASSERT_EQ(a.points.size(), b.points.size());
  for (const BurmesterPair& p : a.points) {
    bool matched = false;
    for (const BurmesterPair& q : b.points)
      matched = matched || same_pair(q, p.centre, moved(p.circle, poses, 2), 1e-8);
    EXPECT_TRUE(matched);
  }
}

TEST(BurmesterFivePositions, DegenerateTasksAreRefused) {
  const KnownFourBar f;
  auto poses = poses_at<5>(f, {20, 75, 140, 210, 300});
  auto expect_error = [](const std::array<BodyPose, 5>& p, const std::string& text) {
    try {
      five_position_burmester(p);
      ADD_FAILURE() << "no exception; expected one saying: " << text;
    } catch (const nbar::Error& e) {
      EXPECT_THAT(e.what(), HasSubstr(text));
    }
  };
  auto same = poses;
  same[4] = same[0];
  expect_error(same, "positions 1 and 5 coincide");
  auto two_angles = poses;
  for (int i = 0; i < 5; ++i) two_angles[i].angle = i % 2 ? 0.5 : 0.1;
  expect_error(two_angles, "three whose angles all differ");
  auto inf = poses;
  inf[3].point.x() = std::numeric_limits<double>::infinity();
  expect_error(inf, "position 4 is not finite");
}

}  // namespace
}  // namespace nbar::synthesis
