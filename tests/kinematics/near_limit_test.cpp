// Exactness near a limit (issue 37, item 3): the bundled Watt I and Stephenson III six-bars swept
// to 0.3 deg from each limit of the mechanism, against a 60-digit solution of the same models
// written independently in mpmath (tests/kinematics/near_limit_reference.py, its numbers in
// tests/kinematics/data/near_limit_reference.txt). There the Jacobian is nearly singular and
// magnifies a position's residual into its velocities and accelerations: positions must be within
// 1e-14 of the linkage's size and accelerations within 1e-10 of L w^2 all the same.
#include <gtest/gtest.h>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "nbar/io/model_file.hpp"
#include "nbar/kinematics/limits.hpp"
#include "nbar/kinematics/mechanism.hpp"
#include "nbar/kinematics/sweep.hpp"

namespace nbar {
namespace {

struct ReferencePoint {
  std::string name;
  double x = 0, y = 0, vx = 0, vy = 0, ax = 0, ay = 0;
};

struct ReferenceCase {
  std::string example;
  int direction = 1;
  double limit = 0.0;  // rad
  double input = 0.0;  // rad, 0.3 deg inside the limit
  std::vector<ReferencePoint> points;
};

std::vector<ReferenceCase> read_references() {
  std::ifstream file(std::string(NBAR_SOURCE_DIR) + "/tests/kinematics/data/near_limit_reference.txt");
  std::vector<ReferenceCase> cases;
  std::string line;
  while (std::getline(file, line)) {
    std::istringstream words(line);
    std::string key;
    words >> key;
    if (key == "case") {
      cases.emplace_back();
      words >> cases.back().example >> cases.back().direction;
    } else if (key == "limit") {
      words >> cases.back().limit;
    } else if (key == "input") {
      words >> cases.back().input;
    } else if (key == "point") {
      ReferencePoint p;
      words >> p.name >> p.x >> p.y >> p.vx >> p.vy >> p.ax >> p.ay;
      cases.back().points.push_back(p);
    }
  }
  return cases;
}

// The diagonal of the drawing's bounding box: every point of these six-bars is a joint.
double drawing_size(const Model& m) {
  Eigen::Vector2d lo = m.points.front().position, hi = lo;
  for (const Point& p : m.points) {
    lo = lo.cwiseMin(p.position);
    hi = hi.cwiseMax(p.position);
  }
  return (hi - lo).norm();
}

int point_index(const Model& m, const std::string& name) {
  for (std::size_t i = 0; i < m.points.size(); ++i)
    if (m.points[i].name == name) return static_cast<int>(i);
  return -1;
}

// The example driven from its drawn pose (input at 0) to the reference's input angle at 1 rad/s.
Model driven_to(const ReferenceCase& c, int steps) {
  Model m = io::load_model_file(std::string(NBAR_EXAMPLES_DIR) + "/" + c.example).model;
  Driver& d = m.drivers.at(0);
  d.from = 0.0;
  d.to = c.input;
  d.speed = c.direction;
  d.accel = 0.0;
  m.sweep.steps = steps;
  return m;
}

TEST(NearLimit, ReferenceFileHasTheFourCases) {
  const std::vector<ReferenceCase> cases = read_references();
  ASSERT_EQ(cases.size(), 4u);
  for (const ReferenceCase& c : cases) EXPECT_GE(c.points.size(), 4u) << c.example;
}

// Positions within 1e-14 of the linkage's size, velocities within 1e-12 of L w and accelerations
// within 1e-10 of L w^2 at the sample 0.3 deg from the limit, for sweeps of several step counts (so
// that the track reaches the sample by steps of several lengths).
TEST(NearLimit, SixBarsMatchTheSixtyDigitSolution) {
  for (const ReferenceCase& c : read_references()) {
    for (int steps : {2, 16, 61}) {
      SCOPED_TRACE(c.example + (c.direction > 0 ? ", input growing" : ", input falling") + ", " +
                   std::to_string(steps) + " samples");
      const Mechanism mech(driven_to(c, steps));
      const double size = drawing_size(mech.model());
      SweepOptions options;
      options.order = 2;
      const SweepResult sweep = run_sweep(mech, options);
      ASSERT_TRUE(sweep.complete) << sweep.stop_reason;
      const Sample& last = sweep.samples.back();
      ASSERT_EQ(last.driver_values[0], c.input);
      const Eigen::VectorXd v = last.derivative(1), a = last.derivative(2);
      double position_error = 0, velocity_error = 0, acceleration_error = 0;
      for (const ReferencePoint& p : c.points) {
        const int col = mech.column_of(point_index(mech.model(), p.name));
        ASSERT_GE(col, 0) << p.name;
        position_error =
            std::max({position_error, std::abs(last.taylor(col, 0) - p.x), std::abs(last.taylor(col + 1, 0) - p.y)});
        // The reference turns the input at +1 rad/s; the sweep at `direction`.
        velocity_error = std::max(
            {velocity_error, std::abs(v[col] - c.direction * p.vx), std::abs(v[col + 1] - c.direction * p.vy)});
        acceleration_error = std::max({acceleration_error, std::abs(a[col] - p.ax), std::abs(a[col + 1] - p.ay)});
      }
      // w = 1 rad/s: L w = L, L w^2 = L.
      EXPECT_LE(position_error, 1e-14 * size);
      EXPECT_LE(velocity_error, 1e-12 * size);
      EXPECT_LE(acceleration_error, 1e-10 * size);
      std::printf("%s %+d %d samples: position %.2e, velocity %.2e, acceleration %.2e (of L, L w, L w^2)\n",
                  c.example.c_str(), c.direction, steps, position_error / size, velocity_error / size,
                  acceleration_error / size);
    }
  }
}

// The limit nbar finds on the sweep's path is the reference's to 1e-9 relative (item 1's promise).
TEST(NearLimit, LimitsAreTheReferences) {
  for (const ReferenceCase& c : read_references()) {
    SCOPED_TRACE(c.example + (c.direction > 0 ? ", input growing" : ", input falling"));
    const Mechanism mech(driven_to(c, 16));
    const PathLimits limits = find_path_limits(mech);
    const PathSingularity* limit = limits.ahead.limit();
    ASSERT_NE(limit, nullptr);
    EXPECT_NEAR(limit->driver_values[0], c.limit, 1e-9 * std::abs(c.limit));
  }
}

}  // namespace
}  // namespace nbar
