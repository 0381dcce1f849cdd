// Arcs in a shape's outline and polygon holes, as the model file writes them: {bulge: b} or
// {through: [x, y]} on the vertex that starts the arc.
#include "io/model_file_support.hpp"
#include "nbar/io/model_file.hpp"
#include "nbar/model/geometry.hpp"
#include "test_constants.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

namespace nbar::io {
namespace {

using nbar::test_constants::kPi;
using test_support::fails_at;

// A crank in mm whose plate is given on line 8 onwards.
std::string crank(const std::string& shape_lines) {
  return "units: {length: mm}\n"                    // 1
         "points: {O: [0, 0], A: [100, 0]}\n"       // 2
         "ground: [O]\n"                            // 3
         "bodies:\n"                                // 4
         "  crank:\n"                               // 5
         "    points: [O, A]\n"                     // 6
         "    thickness: 5\n    material: steel\n"  // 7, 8
         "    shape:\n" +                           // 9
         shape_lines;                               // 10...
}

TEST(ModelFileArcs, SlotByBulges) {
  // The slot around O and A: 100 mm long, 20 mm wide, with a round hole at each end.
  const Model m =
      parse_model(crank("      outline: [[0, -10], [100, -10, {bulge: 1}], [100, 10], [0, 10, {bulge: 1}]]\n"
                        "      holes: [{at: O, radius: 4}, {at: A, radius: 4}]\n"),
                  "m.yaml")
          .model;
  const Region& r = *m.bodies[0].shape;
  ASSERT_EQ(r.outline_bulges.size(), 4u);
  const double mm2 = 1e-6;
  const AreaProperties a = area_properties(r);
  EXPECT_NEAR(a.area, (100 * 20 + kPi * 100 - 2 * kPi * 16) * mm2, 1e-12);
  EXPECT_NEAR(a.centroid.x(), 0.05, 1e-15);
  EXPECT_NEAR(a.centroid.y(), 0.0, 1e-15);
}

TEST(ModelFileArcs, QuarterDiscThroughAPointAndAnArcInAHole) {
  const Model m =
      parse_model(crank("      outline: [[-20, -20], [120, -20], [120, 0, {through: [114.1421356237, 14.1421356237]}], "
                        "[100, 20], "
                        "[-20, 20]]\n"
                        "      holes: [{polygon: [[40, -5], [60, -5, {bulge: 1}], [60, 5], [40, 5, {bulge: 1}]]}]\n"),
                  "m.yaml")
          .model;
  const Region& r = *m.bodies[0].shape;
  EXPECT_NEAR(r.outline_bulges[2], std::tan(kPi / 8), 1e-10);
  ASSERT_EQ(r.polygon_hole_bulges.size(), 1u);
  // 140 x 40 rectangle, minus the corner square 20 x 20 plus the quarter disc of radius 20
  // standing in for it, minus the slot 20 x 10 with half discs of radius 5.
  const double area = 140 * 40 - 400 + kPi * 400 / 4 - (20 * 10 + kPi * 25);
  EXPECT_NEAR(area_properties(r).area, area * 1e-6, 1e-12);
}

TEST(ModelFileArcs, ArcsByCentreRadiusAndAngles) {
  // The same slot as SlotByBulges, its round ends given by centre, radius and angles (degrees):
  // the right end from -90 to 90 about A, the left from 90 to 270 about O.
  const Model m = parse_model(crank("      outline: [{centre: [100, 0], radius: 10, angles: [-90, 90]},\n"
                                    "                {centre: [0, 0], radius: 10, angles: [90, 270]}]\n"
                                    "      holes: [{at: O, radius: 4}, {at: A, radius: 4}]\n"),
                              "m.yaml")
                      .model;
  const Region& r = *m.bodies[0].shape;
  ASSERT_EQ(r.outline.size(), 4u);  // the arcs' ends, each shared with nothing: four vertices
  EXPECT_NEAR(r.outline_bulges[0], 1.0, 1e-12);
  EXPECT_NEAR(r.outline_bulges[2], 1.0, 1e-12);
  const AreaProperties a = area_properties(r);
  EXPECT_NEAR(a.area, (100 * 20 + kPi * 100 - 2 * kPi * 16) * 1e-6, 1e-12);
  EXPECT_NEAR(a.centroid.x(), 0.05, 1e-15);
  // A quarter disc: the arc from the x axis to the y axis closes back at the centre, in radians.
  std::string quarter =
      crank("      outline: [[0, 0], {centre: [0, 0], radius: 120, angles: [0, 1.5707963267948966]}]\n");
  quarter.replace(0, quarter.find('\n'), "units: {length: mm, angle: rad}");
  const Model q = parse_model(quarter, "q.yaml").model;
  EXPECT_NEAR(area_properties(*q.bodies[0].shape).area, kPi * 120 * 120 / 4 * 1e-6, 1e-12);
}

TEST(ModelFileArcs, Errors) {
  EXPECT_TRUE(fails_at(crank("      outline: [[0, 0], [10, 0, {bend: 1}], [0, 10]]\n"), "10:33",
                       "an arc on a vertex is {bulge: b} or {through: [x, y]}"));
  EXPECT_TRUE(fails_at(crank("      outline: [[0, 0], [10, 0, {through: [20, -10]}], [0, 10]]\n"), "10:43",
                       "on the line through the arc's ends but not between them"));
  EXPECT_TRUE(fails_at(crank("      outline: [[0, 0], [10, 0]]\n"), "10:16", "needs at least 3 vertices"));
  EXPECT_TRUE(fails_at(crank("      outline: [[0, 0], {centre: [0, 0], radius: 10, angles: [0, 360]}]\n"), "10:62",
                       "less than a full turn"));
  EXPECT_TRUE(fails_at(crank("      outline: [[0, 0], {centre: [0, 0], radius: -1, angles: [0, 90]}]\n"), "10:50",
                       "radius must be > 0"));
  EXPECT_TRUE(fails_at(crank("      outline: [[0, 0], [4, 0, {bulge: -1}], [4, 10], [0, 10]]\n"), "10:16",
                       "the outline intersects itself: edge 1-2 meets edge 3-0"));
}

}  // namespace
}  // namespace nbar::io
