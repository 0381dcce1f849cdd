// The cutting DXF read back with a small reader written here: a well-formed file (group-code
// pairs, sections opened and closed, EOF last), one layer per plate, and every outline vertex,
// bulge and hole where the model puts it, as drawn and in a solved pose.
#include "nbar/io/dxf_writer.hpp"
#include "nbar/analysis/pose.hpp"
#include "nbar/io/model_file.hpp"
#include "nbar/kinematics/sweep.hpp"
#include "nbar/model/diagnostics.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

namespace nbar::io {
namespace {


struct Pair {
  int code;
  std::string value;
};

// Group codes and values on alternate lines; a code must be an integer.
std::vector<Pair> read_pairs(const std::string& text) {
  std::istringstream in(text);
  std::vector<Pair> pairs;
  std::string code, value;
  while (std::getline(in, code)) {
    EXPECT_TRUE(std::getline(in, value)) << "a group code without its value: " << code;
    std::size_t used = 0;
    const int c = std::stoi(code, &used);
    EXPECT_EQ(code.find_first_not_of(' ', used), std::string::npos) << "not a group code: '" << code << "'";
    pairs.push_back({c, value});
  }
  return pairs;
}

struct Entity {
  std::string type, layer;
  std::map<int, std::vector<double>> numbers;  // every value of a numeric group code, in order
  std::vector<Entity> vertices;                // a POLYLINE's VERTEXes
};

// The ENTITIES section, with POLYLINEs gathering their VERTEXes up to SEQEND; checks the
// sections' nesting and the EOF at the end on the way.
std::vector<Entity> read_entities(const std::vector<Pair>& pairs, std::vector<std::string>* layers) {
  std::vector<Entity> entities;
  std::string section;
  bool in_polyline = false;
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const Pair& p = pairs[i];
    if (p.code == 0 && p.value == "SECTION") {
      EXPECT_EQ(section, "") << "a SECTION inside " << section;
      EXPECT_EQ(pairs.at(i + 1).code, 2);
      section = pairs.at(i + 1).value;
      ++i;
      continue;
    }
    if (p.code == 0 && p.value == "ENDSEC") {
      EXPECT_NE(section, "") << "ENDSEC outside a section";
      EXPECT_FALSE(in_polyline) << "a POLYLINE without SEQEND";
      section.clear();
      continue;
    }
    if (p.code == 0 && p.value == "EOF") {
      EXPECT_EQ(i + 1, pairs.size()) << "EOF before the end";
      EXPECT_EQ(section, "") << "EOF inside a section";
      continue;
    }
    if (section == "TABLES" && p.code == 0 && p.value == "LAYER") layers->push_back(pairs.at(i + 1).value);
    if (section != "ENTITIES") continue;
    if (p.code == 0) {
      if (p.value == "SEQEND") {
        in_polyline = false;
        continue;
      }
      Entity e;
      e.type = p.value;
      if (p.value == "VERTEX") {
        EXPECT_TRUE(in_polyline) << "a VERTEX outside a POLYLINE";
        entities.back().vertices.push_back(e);
      } else {
        EXPECT_FALSE(in_polyline) << p.value << " inside a POLYLINE";
        in_polyline = p.value == "POLYLINE";
        entities.push_back(e);
      }
      continue;
    }
    Entity& e = in_polyline && !entities.back().vertices.empty() ? entities.back().vertices.back() : entities.back();
    if (p.code == 8) {
      e.layer = p.value;
    } else {
      e.numbers[p.code].push_back(std::stod(p.value));
    }
  }
  EXPECT_FALSE(pairs.empty());
  if (!pairs.empty()) {
    EXPECT_EQ(pairs.back().value, "EOF");
  }
  return entities;
}

// A crank O-A as a slot with a pin hole at each end and a polygon hole with an arc, and a
// rocker bar; lengths in mm.
const std::string kModel =
    "units: {length: mm}\n"
    "points: {O: [0, 0], A: [80, 0], B: [180, 150], C: [200, 0]}\n"
    "ground: [O, C]\n"
    "bodies:\n"
    "  crank:\n"
    "    points: [O, A]\n"
    "    shape:\n"
    "      outline: [[0, -10], [80, -10, {bulge: 1}], [80, 10], [0, 10, {bulge: 1}]]\n"
    "      holes: [{at: O, radius: 5}, {at: A, radius: 5}, {polygon: [[30, -4], [50, -4, {bulge: 0.5}], [50, 4], [30, 4]]}]\n"
    "    thickness: 8\n"
    "    material: steel\n"
    "  coupler: [A, B]\n"
    "  rocker point:\n"
    "    points: [C, B]\n"
    "    bar: {width: 20, margin: 12, hole: 5}\n"
    "    thickness: 8\n"
    "    material: steel\n"
    "drivers: [{angle: crank, from: 0, to: 360}]\n";

TEST(DxfWriter, WellFormedWithOneLayerPerPlate) {
  const Mechanism mech(parse_model(kModel, "m.yaml").model);
  std::vector<Eigen::Vector2d> drawn;
  for (const Point& p : mech.model().points) drawn.push_back(p.position);
  const std::string dxf = cutting_dxf(mech, drawn);
  std::vector<std::string> layers;
  const std::vector<Entity> entities = read_entities(read_pairs(dxf), &layers);
  EXPECT_THAT(layers, ::testing::ElementsAre("crank", "rocker_point"));  // the coupler has no plate
  EXPECT_THAT(dxf, ::testing::HasSubstr("$ACADVER\n  1\nAC1009\n"));
  EXPECT_THAT(dxf, ::testing::HasSubstr("$INSUNITS\n 70\n4\n"));  // millimetres

  // The crank: its outline and polygon hole as closed POLYLINEs with their bulges, two CIRCLEs.
  std::vector<const Entity*> crank;
  for (const Entity& e : entities)
    if (e.layer == "crank") crank.push_back(&e);
  ASSERT_EQ(crank.size(), 4u);
  const Entity& outline = *crank[0];
  EXPECT_EQ(outline.type, "POLYLINE");
  EXPECT_EQ(outline.numbers.at(70).front(), 1);  // closed
  ASSERT_EQ(outline.vertices.size(), 4u);
  const double xs[] = {0, 80, 80, 0}, ys[] = {-10, -10, 10, 10}, bulges[] = {0, 1, 0, 1};
  for (int i = 0; i < 4; ++i) {
    const Entity& v = outline.vertices[i];
    EXPECT_EQ(v.layer, "crank");
    EXPECT_DOUBLE_EQ(v.numbers.at(10).front(), xs[i]);
    EXPECT_DOUBLE_EQ(v.numbers.at(20).front(), ys[i]);
    EXPECT_DOUBLE_EQ(v.numbers.count(42) ? v.numbers.at(42).front() : 0.0, bulges[i]);
  }
  EXPECT_EQ(crank[1]->type, "POLYLINE");
  ASSERT_EQ(crank[1]->vertices.size(), 4u);
  EXPECT_DOUBLE_EQ(crank[1]->vertices[1].numbers.at(42).front(), 0.5);
  EXPECT_EQ(crank[2]->type, "CIRCLE");
  EXPECT_DOUBLE_EQ(crank[2]->numbers.at(10).front(), 0);
  EXPECT_DOUBLE_EQ(crank[2]->numbers.at(40).front(), 5);
  EXPECT_EQ(crank[3]->type, "CIRCLE");
  EXPECT_DOUBLE_EQ(crank[3]->numbers.at(10).front(), 80);

  // The rocker's bar: a rectangle 20 wide around C-B, 12 beyond each end, and its two holes.
  std::vector<const Entity*> rocker;
  for (const Entity& e : entities)
    if (e.layer == "rocker_point") rocker.push_back(&e);
  ASSERT_EQ(rocker.size(), 3u);
  const Eigen::Vector2d c(200, 0), b(180, 150), u = (b - c).normalized(), n(-u.y(), u.x());
  const Eigen::Vector2d corner = c - 12 * u - 10 * n;
  EXPECT_NEAR(rocker[0]->vertices[0].numbers.at(10).front(), corner.x(), 1e-9);
  EXPECT_NEAR(rocker[0]->vertices[0].numbers.at(20).front(), corner.y(), 1e-9);
  EXPECT_NEAR(rocker[2]->numbers.at(10).front(), 180, 1e-9);
  EXPECT_NEAR(rocker[2]->numbers.at(20).front(), 150, 1e-9);
}

TEST(DxfWriter, PlatesMoveWithTheSolvedPose) {
  const Mechanism mech(parse_model(kModel, "m.yaml").model);
  // The crank turned to 90 degrees: its plate turns a quarter turn about O.
  const Sample pose = pose_at(mech, 90);
  const std::string dxf = cutting_dxf(mech, point_positions(mech, pose.taylor.col(0)));
  std::vector<std::string> layers;
  const std::vector<Entity> entities = read_entities(read_pairs(dxf), &layers);
  const Entity& outline = entities.at(0);
  ASSERT_EQ(outline.layer, "crank");
  const double xs[] = {0, 80, 80, 0}, ys[] = {-10, -10, 10, 10};
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(outline.vertices[i].numbers.at(10).front(), -ys[i], 1e-9);
    EXPECT_NEAR(outline.vertices[i].numbers.at(20).front(), xs[i], 1e-9);
  }
  EXPECT_DOUBLE_EQ(outline.vertices[1].numbers.at(42).front(), 1);
  EXPECT_NEAR(entities.at(3).numbers.at(20).front(), 80, 1e-9);  // the hole at A, now at (0, 80)
}

TEST(DxfWriter, NothingToCut) {
  const Mechanism mech(parse_model("points: {O: [0, 0], A: [1, 0]}\nground: [O]\nbodies: {crank: [O, A]}\n"
                                   "drivers: [{angle: crank, from: 0, to: 90}]\n",
                                   "m.yaml")
                           .model);
  std::vector<Eigen::Vector2d> drawn{{0, 0}, {1, 0}};
  EXPECT_THROW(cutting_dxf(mech, drawn), Error);
}

TEST(DxfWriter, LayerNames) {
  EXPECT_EQ(dxf_layer_name("rocker point"), "rocker_point");
  EXPECT_EQ(dxf_layer_name("arm-2$"), "arm-2$");
  EXPECT_EQ(dxf_layer_name("é"), "__");
}

}  // namespace
}  // namespace nbar::io
