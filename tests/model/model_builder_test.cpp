// Models built in code: the same model as the file gives the same mechanism and motion, and
// mistakes name what is wrong.
#include <gtest/gtest.h>

#include <numbers>

#include "nbar/io/model_file.hpp"
#include "nbar/kinematics/sweep.hpp"
#include "nbar/model/model_builder.hpp"

namespace nbar {
namespace {

Model built_crank_rocker() {
  DriverMotion turn;
  turn.from = 0;
  turn.to = 360;
  turn.speed = 720;  // deg/s: 120 rpm
  return ModelBuilder("Crank-rocker four-bar")
      .units("mm", "deg")
      .ground("O2", 0, 0)
      .ground("O4", 200, 0)
      .point("A", 80, 0)
      .point("B", 181.25, 148.823511)
      .point("P", 77.81169, 121.227931)
      .body("crank", {"O2", "A"}, 80)
      .body("coupler", {"A", "B", "P"})
      .body("rocker", {"O4", "B"}, 150)
      .angle_driver("crank", "crank", turn)
      .steps(37)
      .build();
}

TEST(ModelBuilder, GivesTheModelTheFileGives) {
  Model from_file = io::load_model_file(std::string(NBAR_EXAMPLES_DIR) + "/fourbar-crank-rocker.yaml").model;
  from_file.sweep.steps = 37;
  const Mechanism built(built_crank_rocker()), read(from_file);
  ASSERT_EQ(built.coordinate_count(), read.coordinate_count());
  EXPECT_LT((built.drawn_coordinates() - read.drawn_coordinates()).norm(), 1e-15);
  EXPECT_NEAR(built.model().drivers[0].speed, 4 * std::numbers::pi, 1e-12);  // 120 rpm in rad/s

  SweepOptions options;
  options.order = 2;
  const SweepResult a = run_sweep(built, options), b = run_sweep(read, options);
  ASSERT_EQ(a.samples.size(), 37u);
  ASSERT_EQ(b.samples.size(), 37u);
  for (std::size_t i = 0; i < a.samples.size(); ++i) {
    const Sample &sa = a.samples[i], &sb = b.samples[i];
    const double scale = sb.taylor.cwiseAbs().maxCoeff();
    EXPECT_LT((sa.taylor - sb.taylor).cwiseAbs().maxCoeff(), 1e-12 * scale) << "sample " << i;
  }
}

TEST(ModelBuilder, KineticsInTheBuildersUnits) {
  const Model m = ModelBuilder("loaded")
                      .units("mm")
                      .ground("O", 0, 0)
                      .point("A", 100, 0)
                      .body("bar", {"O", "A"})
                      .angle_driver("bar", "bar")
                      .gravity(0, -9.81)
                      .mass("bar", 2.0, 50, 0, 0.01)
                      .force("A", 0, -5.5, "bar")
                      .torque("bar", 1.25)
                      .spring("s", "O", "A", 1000, 80)
                      .build();
  ASSERT_TRUE(m.bodies[0].inertia);
  EXPECT_DOUBLE_EQ(m.bodies[0].inertia->cg.x(), 0.05);
  EXPECT_DOUBLE_EQ(m.point_loads[0].fy.value(0.3), -5.5);
  EXPECT_DOUBLE_EQ(m.torques[0].torque.value(0.0), 1.25);
  EXPECT_DOUBLE_EQ(m.springs[0].free_length, 0.08);
  EXPECT_DOUBLE_EQ(m.points[1].position.x(), 0.1);
}

TEST(ModelBuilder, MistakesAreInvalidModelErrorsThatNameTheCulprit) {
  try {
    ModelBuilder().ground("O", 0, 0).point("A", 1, 0).body("crank", {"O", "B"});
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::InvalidModel);
    EXPECT_EQ(e.message(), "unknown point 'B'; the points are: O, A");
  }
  try {
    ModelBuilder().units("furlong");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::InvalidModel);
  }
  // validate() runs at build(): a zero-length body.
  try {
    ModelBuilder().ground("O", 0, 0).point("A", 0, 0).body("crank", {"O", "A"}).build();
    FAIL() << "no error";
  } catch (const ModelError& e) {
    EXPECT_EQ(e.where().kind, EntityRef::Kind::Body);
  }
  DriverMotion bad;
  bad.law = "sin(";
  EXPECT_THROW(ModelBuilder().ground("O", 0, 0).point("A", 1, 0).body("c", {"O", "A"}).angle_driver("c", "c", bad),
               ModelError);
}

}  // namespace
}  // namespace nbar
