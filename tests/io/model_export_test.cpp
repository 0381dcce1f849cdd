// Writing models as model files: every kinematic example reads back to the same model, and a
// synthesised four-bar's file, solved, passes through its targets.
#include "test_constants.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>

#include "nbar/io/model_export.hpp"
#include "nbar/io/model_file.hpp"
#include "nbar/kinematics/mechanism.hpp"
#include "nbar/kinematics/sweep.hpp"
#include "nbar/model/diagnostics.hpp"
#include "nbar/synthesis/fourbar_design.hpp"

namespace {

namespace fs = std::filesystem;
using Eigen::Vector2d;
using nbar::test_constants::kPi;

bool has_kinetics(const nbar::Model& m) {
  for (const nbar::Body& b : m.bodies)
    if (b.shape || b.inertia || b.material) return true;
  return !m.gravity.isZero() || !m.point_loads.empty() || !m.torques.empty() || !m.springs.empty();
}

// Equal after a trip through text in the model's units: to a few units in the last place.
void expect_close(double a, double b) { EXPECT_NEAR(a, b, 4e-16 * std::max(1.0, std::abs(a))); }

TEST(ModelExport, EveryKinematicExampleReadsBackTheSame) {
  int kinematic = 0;
  for (const auto& entry : fs::directory_iterator(NBAR_EXAMPLES_DIR)) {
    if (entry.path().extension() != ".yaml") continue;
    SCOPED_TRACE(entry.path().string());
    const nbar::Model m = nbar::io::load_model_file(entry.path().string()).model;
    if (has_kinetics(m)) {
      EXPECT_THROW(nbar::io::model_yaml(m), nbar::Error);
      continue;
    }
    ++kinematic;
    const std::string text = nbar::io::model_yaml(m, {"a comment"});
    const nbar::Model back = nbar::io::parse_model(text, "exported.yaml").model;
    EXPECT_EQ(back.name, m.name);
    EXPECT_EQ(back.units.length, m.units.length);
    EXPECT_EQ(back.units.angle, m.units.angle);
    ASSERT_EQ(back.points.size(), m.points.size());
    for (std::size_t i = 0; i < m.points.size(); ++i) {
      EXPECT_EQ(back.points[i].name, m.points[i].name);
      EXPECT_EQ(back.points[i].ground, m.points[i].ground);
      expect_close(back.points[i].position.x(), m.points[i].position.x());
      expect_close(back.points[i].position.y(), m.points[i].position.y());
    }
    ASSERT_EQ(back.bodies.size(), m.bodies.size());
    for (std::size_t i = 0; i < m.bodies.size(); ++i) {
      EXPECT_EQ(back.bodies[i].name, m.bodies[i].name);
      EXPECT_EQ(back.bodies[i].points, m.bodies[i].points);
      EXPECT_EQ(back.bodies[i].length.has_value(), m.bodies[i].length.has_value());
      if (m.bodies[i].length) expect_close(*back.bodies[i].length, *m.bodies[i].length);
    }
    EXPECT_EQ(back.sliders.size(), m.sliders.size());
    EXPECT_EQ(back.slots.size(), m.slots.size());
    ASSERT_EQ(back.drivers.size(), m.drivers.size());
    for (std::size_t i = 0; i < m.drivers.size(); ++i) {
      const nbar::Driver &d = m.drivers[i], &e = back.drivers[i];
      EXPECT_EQ(e.name, d.name);
      EXPECT_EQ(e.kind, d.kind);
      EXPECT_EQ(e.body, d.body);
      EXPECT_EQ(e.relative_to, d.relative_to);
      EXPECT_EQ(e.points, d.points);
      EXPECT_EQ(e.slider, d.slider);
      EXPECT_EQ(e.from.has_value(), d.from.has_value());
      if (d.from) expect_close(*e.from, *d.from);
      if (d.to) expect_close(*e.to, *d.to);
      expect_close(e.speed, d.speed);
      expect_close(e.accel, d.accel);
      EXPECT_EQ(e.law.has_value(), d.law.has_value());
      if (d.law) {
        EXPECT_EQ(e.law->text(), d.law->text());
      }
    }
    EXPECT_EQ(back.sweep.steps, m.sweep.steps);
    EXPECT_EQ(back.sweep.duration, m.sweep.duration);
    EXPECT_EQ(back.sweep.time_step.has_value(), m.sweep.time_step.has_value());
  }
  EXPECT_GE(kinematic, 15);
}

TEST(ModelExport, NamesYamlWouldMisreadAreQuoted) {
  nbar::Model m;
  m.name = "a \"quoted\": name";
  m.points = {{"null", {0, 0}, true}, {"A: 1", {1, 0}, false}, {"#b", {1, 1}, false}, {"O-4", {0, 1}, true}};
  for (const auto& [name, points] :
       std::vector<std::pair<std::string, std::vector<int>>>{{"crank one", {0, 1}}, {"~", {1, 2}}, {"out", {3, 2}}}) {
    nbar::Body b;
    b.name = name;
    b.points = points;
    m.bodies.push_back(b);
  }
  nbar::Driver d;
  d.name = "my driver";
  d.body = 0;
  d.from = 0.25;
  d.to = 1.0;
  m.drivers.push_back(d);
  const std::string text = nbar::io::model_yaml(m);
  const nbar::Model back = nbar::io::parse_model(text).model;
  EXPECT_EQ(back.name, m.name);
  EXPECT_EQ(back.points[0].name, "null");
  EXPECT_EQ(back.points[1].name, "A: 1");
  EXPECT_EQ(back.points[2].name, "#b");
  EXPECT_EQ(back.points[3].name, "O-4");
  EXPECT_EQ(back.bodies[1].name, "~");
  EXPECT_EQ(back.drivers[0].name, "my driver");
  EXPECT_DOUBLE_EQ(*back.drivers[0].from, 0.25);
}

TEST(ModelExport, AnExportedDesignSolvesThroughItsTargets) {
  // A crank-rocker in millimetres (frame 200, crank 80, coupler 180, rocker 150), its coupler
  // point at five crank angles as the targets.
  const auto pose = [](double theta) {
    const Vector2d a = 80 * Vector2d(std::cos(theta), std::sin(theta));
    const Vector2d f = Vector2d(200, 0) - a;
    const double dist = f.norm(), l = (180 * 180 - 150 * 150 + dist * dist) / (2 * dist);
    const Vector2d b = a + (l / dist) * f + (std::sqrt(180 * 180 - l * l) / dist) * Vector2d(-f.y(), f.x());
    const Vector2d u = (b - a) / 180;
    return std::array<Vector2d, 3>{a, b, a + 60 * u + 110 * Vector2d(-u.y(), u.x())};
  };
  std::vector<nbar::synthesis::Target> targets;
  for (double deg : {-90.0, -20.0, 60.0, 150.0, 200.0}) targets.push_back({pose(deg * kPi / 180)[2], std::nullopt});
  const auto first = pose(-kPi / 2);
  const nbar::synthesis::FourBarDesign design{{0, 0}, {200, 0}, first[0], first[1], first[2]};
  const nbar::synthesis::DesignCheck check = nbar::synthesis::check_design(design, targets);
  ASSERT_TRUE(check.defect_free());

  const nbar::Units mm = *nbar::Units::make("mm", "deg");
  const std::string text = nbar::io::design_yaml(design, check, "crank-rocker design", mm, {"from a test"});
  EXPECT_NE(text.find("# from a test\n# Link lengths (mm): frame 200, input 80, coupler 180, output 150\n"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("# Grashof class: crank-rocker; the input turns fully"), std::string::npos);
  EXPECT_NE(text.find("# Defects: none"), std::string::npos);
  EXPECT_NE(text.find("# Input angle at the targets (deg): -90 -20 60 150 200"), std::string::npos);
  EXPECT_NE(text.find("drivers:\n  - {angle: input, from: -90, to: 270, speed: 360}"), std::string::npos) << text;
  const nbar::io::LoadedModel loaded = nbar::io::parse_model(text, "design.yaml");
  EXPECT_EQ(loaded.model.name, "crank-rocker design");

  // Its own sweep runs: a full turn.
  const nbar::Mechanism mech(loaded.model);
  const nbar::SweepResult sweep = nbar::run_sweep(mech);
  EXPECT_TRUE(sweep.complete) << sweep.stop_reason;
  EXPECT_EQ(sweep.samples.size(), 361u);
  // Swept to each target's input angle, the coupler point is on the target.
  const int p = loaded.model.find_point("P");
  for (std::size_t i = 0; i < targets.size(); ++i) {
    nbar::Model to_target = loaded.model;
    to_target.drivers[0].to = check.targets[i].input_angle;
    to_target.sweep.steps = 50;
    const nbar::Mechanism m(to_target);
    const nbar::SweepResult s = nbar::run_sweep(m, {.steps = std::nullopt, .order = 0});
    ASSERT_TRUE(s.complete) << s.stop_reason;
    const Vector2d at = nbar::point_positions(m, s.samples.back().taylor.col(0))[p] / 0.001;
    EXPECT_LT((at - targets[i].point).norm(), 1e-9) << i;
  }
}

}  // namespace

TEST(ModelExport, AUnitConversionsRoundingIsNotWrittenBack) {
  // 120 rpm is 720 deg/s; kept in rad/s it divides back to 719.9999999999999.
  const std::string text =
      "points: {O: [0, 0], A: [10, 0], B: [30, 20], C: [40, 0]}\nground: [O, C]\n"
      "bodies: {crank: [O, A], coupler: [A, B], rocker: [B, C]}\n"
      "drivers: [{angle: crank, from: 0, to: 360, speed: 120 rpm}]\n";
  const nbar::Model m = nbar::io::parse_model(text, "rpm.yaml").model;
  ASSERT_NE(m.drivers[0].speed / m.units.angle_scale, 720.0);  // else this test shows nothing
  const std::string out = nbar::io::model_yaml(m);
  EXPECT_NE(out.find("speed: 720}"), std::string::npos) << out;
  // A number with all 17 digits of its own keeps them.
  nbar::Model digits = m;
  digits.points[1].position.x() = 10.123456789012345 * m.units.length_scale;
  const nbar::Model back = nbar::io::parse_model(nbar::io::model_yaml(digits), "back.yaml").model;
  expect_close(back.points[1].position.x(), digits.points[1].position.x());
}
