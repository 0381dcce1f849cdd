// /api/outline: a model being built, read as written, with the mobility of its joints and what
// still keeps it from being solved (the web app's drawing tools draw it). The counts are checked
// against the Gruebler-Kutzbach formula worked by hand for each model.
#include "web/web_support.hpp"

namespace nbar::web_test {
namespace {

Json outline(const std::string& model) {
  const ApiResponse r = post("/api/outline", {{"model", model}});
  EXPECT_EQ(r.status, 200) << r.body;
  return Json::parse(r.body);
}

// A ground pivot, a crank to (60, 80) and a rod to (200, 0), in mm, and two ground points on the
// x axis: built so far by the tools (drawn in a general pose: a crank drawn upright would put the
// rod-slider pose in a toggle, where the rank counts an instantaneous freedom).
const std::string kCrankAndRod = R"(name: "New model"
units: {length: mm, angle: deg}
points:
  P1: [0, 0]
  P2: [60, 80]
  P3: [200, 0]
  G1: [100, 0]
  G2: [300, 0]
ground: [P1, G1, G2]
bodies:
  link1: [P1, P2]
  link2: [P2, P3]
)";

TEST(WebOutline, AnEmptyModelIsReadWithItsUnits) {
  const Json j = outline("units: {length: mm, angle: deg}\npoints:\n");
  EXPECT_EQ(j["units"]["length"], "mm");
  EXPECT_TRUE(j["points"].empty());
  EXPECT_EQ(j["mobility"]["gruebler"], 0);  // 3 (1 - 1) - 0
  EXPECT_TRUE(j["mobility"]["dof"].is_null());
  EXPECT_TRUE(j["immobile"].is_null());
  EXPECT_FALSE(j["problem"].is_null());
}

TEST(WebOutline, PointsAreInTheModelsUnitAndAModelWithoutUnitsIsInMetres) {
  const Json mm = outline("units: {length: mm}\npoints: {A: [100, 20]}\n");
  EXPECT_EQ(mm["units"]["length"], "mm");
  EXPECT_DOUBLE_EQ(mm["points"][0]["x"].get<double>(), 100.0);
  EXPECT_DOUBLE_EQ(mm["points"][0]["y"].get<double>(), 20.0);
  // A point on no body: validate()'s complaint, at the point's line.
  EXPECT_EQ(mm["problem"]["line"], 2);
  const Json m = outline("points: {A: [100, 20]}\n");
  EXPECT_EQ(m["units"]["length"], "m");
  EXPECT_DOUBLE_EQ(m["points"][0]["x"].get<double>(), 100.0);
}

TEST(WebOutline, AnUnderConstrainedLinkageIsDrawnWithItsMobility) {
  const Json j = outline(kCrankAndRod);
  ASSERT_EQ(j["points"].size(), 5u);
  EXPECT_EQ(j["points"][0]["ground"], true);
  EXPECT_EQ(j["points"][1]["ground"], false);
  EXPECT_EQ(j["bodies"][1]["name"], "link2");
  EXPECT_EQ(j["bodies"][1]["points"], Json({"P2", "P3"}));
  EXPECT_EQ(j["joints"], Json({"revolute P1 (ground/link1)", "revolute P2 (link1/link2)"}));
  // n = 3 links (ground included), 2 revolute pairs: G = 3 (3 - 1) - 2 x 2 = 2, and the rank's
  // count agrees: 4 coordinates (P2, P3) less 2 independent lengths.
  EXPECT_EQ(j["mobility"]["gruebler"], 2);
  EXPECT_EQ(j["mobility"]["dof"], 2);
  EXPECT_EQ(j["mobility"]["drivers"], 0);
  EXPECT_EQ(j["problem"]["message"],
            "the mechanism has 2 degrees of freedom (Gruebler-Kutzbach count: 2) but 0 drivers are given; add one "
            "driver per free input");
  EXPECT_TRUE(j["immobile"].is_null());
}

TEST(WebOutline, ASliderOnTheConnectingRodLeavesNothingFree) {
  const Json j = outline(kCrankAndRod + "sliders:\n  - {body: link2, point: P3, along: [G1, G2]}\n");
  // The prismatic pair takes 2 more freedoms: G = 6 - 2 x 3 = 0; the rank: 4 coordinates, 4 rows.
  EXPECT_EQ(j["mobility"]["gruebler"], 0);
  EXPECT_EQ(j["mobility"]["dof"], 0);
  EXPECT_EQ(j["immobile"],
            "the joints leave no freedom: 0 degrees of freedom (Gruebler-Kutzbach count 0), so nothing can move");
  ASSERT_EQ(j["guides"].size(), 1u);
  EXPECT_EQ(j["guides"][0]["line"], Json({100.0, 0.0, 300.0, 0.0}));
}

TEST(WebOutline, ABlockOnItsOwnBodyMakesTheSliderCrank) {
  const Json j = outline(kCrankAndRod + "  block1: [P3]\nsliders:\n  - {body: block1, point: P3, along: [G1, G2]}\n");
  // n = 4, pairs: P1, P2, P3 (rod/block) and the slider: G = 9 - 2 x 4 = 1.
  EXPECT_EQ(j["mobility"]["gruebler"], 1);
  EXPECT_EQ(j["mobility"]["dof"], 1);
  EXPECT_TRUE(j["immobile"].is_null());
  EXPECT_EQ(j["joints"].back(), "slider block1 at P3 along G1-G2");
  // With a driver it is a model like any other: nothing keeps it from solving.
  const Json driven = outline(kCrankAndRod +
                              "  block1: [P3]\nsliders:\n  - {body: block1, point: P3, along: [G1, G2]}\n"
                              "drivers:\n  - {angle: link1, from: 0, to: 360}\n");
  EXPECT_TRUE(driven["problem"].is_null()) << driven.dump();
}

TEST(WebOutline, WhatCannotBeReadIsAnErrorAtItsLine) {
  const ApiResponse r = post("/api/outline", {{"model", "points: {A: [1, 2]}\nbodies: {b: [A, Q]}\n"}});
  EXPECT_EQ(r.status, 422) << r.body;
  const Json j = Json::parse(r.body);
  EXPECT_EQ(j["error"]["line"], 2);
}

}  // namespace
}  // namespace nbar::web_test
