// The kinetics part of the model file: gravity, materials, bodies' shapes and mass
// properties, forces, torques and springs.
// The project headers come first: <signal.h>, which gtest pulls in, defines a macro
// named value_si that would break units.hpp's Quantity::value_si.
#include "io/model_file_support.hpp"
#include "nbar/io/model_file.hpp"
#include "nbar/model/geometry.hpp"
#include "nbar/model/materials.hpp"
#include "test_constants.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

namespace nbar::io {
namespace {

using nbar::test_constants::kPi;
constexpr double kMm = 1e-3;
constexpr double kMm2 = 1e-6;

// Lines 1-11, in millimetres; the tests append their own lines from line 12 on.
const std::string kFourBarMm =
    "units: {length: mm}\n"  // 1
    "points:\n"              // 2
    "  O2: [0, 0]\n"         // 3
    "  O4: [200, 0]\n"       // 4
    "  A: [40, 0]\n"         // 5
    "  B: [160, 120]\n"      // 6
    "  P: [100, 150]\n"      // 7
    "ground: [O2, O4]\n"     // 8
    "bodies:\n"              // 9
    "  crank: [O2, A]\n"     // 10
    "  rocker: [O4, B]\n";   // 11

// The four-bar with a long-form coupler whose other keys start on line 14, column 5.
std::string coupler(const std::string& lines) {
  return kFourBarMm +
         "  coupler:\n"             // 12
         "    points: [A, B, P]\n"  // 13
         + lines;
}

// The four-bar with a short-form coupler; sections appended from line 13 on.
const std::string kLinkage = kFourBarMm + "  coupler: [A, B, P]\n";  // 12

// Lines 1-9, in millimetres; bodies from line 10 on.
const std::string kSliderCrankMm =
    "units: {length: mm}\n"                          // 1
    "points:\n"                                      // 2
    "  O: [0, 0]\n"                                  // 3
    "  X: [100, 0]\n"                                // 4
    "  A: [30, 40]\n"                                // 5
    "  C: [150, 0]\n"                                // 6
    "ground: [O, X]\n"                               // 7
    "sliders:\n"                                     // 8
    "  - {body: piston, point: C, along: [O, X]}\n"  // 9
    "bodies:\n";                                     // 10

using test_support::fails_at;

// The example of the documentation's kinetics section.
const std::string kKinetics = R"yaml(units: {length: mm}
points:
  O2: [0, 0]
  O4: [200, 0]
  A: [40, 0]
  B: [160, 120]
  P: [100, 150]
ground: [O2, O4]
gravity: [0, -9.81]
materials:
  my-alloy: {density: 2800, yield: 250 MPa}
bodies:
  crank:
    points: [O2, A]
    mass: 0.3
    inertia: 1.2e-4
  coupler:
    points: [A, B, P]
    shape:
      outline: [[30, -10], [170, -10], [170, 160], [30, 160]]
      holes:
        - {at: A, radius: 5}
        - {circle: [100, 50], radius: 4}
        - {polygon: [[90, 80], [110, 80], [100, 95]]}
    thickness: 10
    material: my-alloy
  rocker:
    points: [O4, B]
    bar: {width: 20, margin: 10, hole: 5}
    thickness: 8
    material: aluminium
forces:
  - {point: P, force: [0, -100]}
  - {point: P, body: coupler, fx: "100*sin(2*pi*t)", fy: 0}
torques:
  - {body: rocker, torque: -5}
springs:
  - {between: [P, O4], stiffness: 2000, free_length: 120, damping: 5, name: return-spring}
  - {between: [A, O4], stiffness: 2 N/mm}
drivers:
  - {angle: crank, from: 0, to: 360, speed: 60 rpm}
)yaml";

const std::string kKineticsJson = R"json({
  "units": {"length": "mm"},
  "points": {"O2": [0, 0], "O4": [200, 0], "A": [40, 0], "B": [160, 120], "P": [100, 150]},
  "ground": ["O2", "O4"],
  "gravity": [0, -9.81],
  "materials": {"my-alloy": {"density": 2800, "yield": "250 MPa"}},
  "bodies": {
    "crank": {"points": ["O2", "A"], "mass": 0.3, "inertia": 1.2e-4},
    "coupler": {
      "points": ["A", "B", "P"],
      "shape": {
        "outline": [[30, -10], [170, -10], [170, 160], [30, 160]],
        "holes": [{"at": "A", "radius": 5}, {"circle": [100, 50], "radius": 4},
                  {"polygon": [[90, 80], [110, 80], [100, 95]]}]
      },
      "thickness": 10,
      "material": "my-alloy"
    },
    "rocker": {"points": ["O4", "B"], "bar": {"width": 20, "margin": 10, "hole": 5}, "thickness": 8,
               "material": "aluminium"}
  },
  "forces": [{"point": "P", "force": [0, -100]}, {"point": "P", "body": "coupler", "fx": "100*sin(2*pi*t)", "fy": 0}],
  "torques": [{"body": "rocker", "torque": -5}],
  "springs": [{"between": ["P", "O4"], "stiffness": 2000, "free_length": 120, "damping": 5, "name": "return-spring"},
              {"between": ["A", "O4"], "stiffness": "2 N/mm"}],
  "drivers": [{"angle": "crank", "from": 0, "to": 360, "speed": "60 rpm"}]
})json";

// Area of a bar of width w between ends L apart, extended m past each, with holes r1, r2.
double bar_area(double w, double length, double m, double r1, double r2) {
  return w * (length + 2 * m) - kPi * (r1 * r1 + r2 * r2);
}

// ---- valid files ----

TEST(ModelFileKinetics, ParsesTheDocumentedExample) {
  const LoadedModel loaded = parse_model(kKinetics, "kinetics.yaml");
  const Model& m = loaded.model;

  // Gravity is in m/s^2 whatever the length unit.
  EXPECT_EQ(m.gravity, Eigen::Vector2d(0, -9.81));

  ASSERT_EQ(m.bodies.size(), 3u);
  const Body& crank = m.bodies[0];
  EXPECT_EQ(crank.points, (std::vector<int>{0, 2}));
  EXPECT_FALSE(crank.shape.has_value());
  EXPECT_FALSE(crank.material.has_value());
  ASSERT_TRUE(crank.inertia.has_value());
  EXPECT_DOUBLE_EQ(crank.inertia->mass, 0.3);
  EXPECT_DOUBLE_EQ(crank.inertia->inertia, 1.2e-4);
  EXPECT_EQ(crank.inertia->cg, Eigen::Vector2d(0, 0));  // its first point

  const Body& coupler = m.bodies[1];
  EXPECT_EQ(coupler.points, (std::vector<int>{2, 3, 4}));
  ASSERT_TRUE(coupler.shape.has_value());
  EXPECT_FALSE(coupler.inertia.has_value());
  ASSERT_EQ(coupler.shape->outline.size(), 4u);
  EXPECT_NEAR(coupler.shape->outline[2].x(), 0.17, 1e-15);
  EXPECT_NEAR(coupler.shape->outline[2].y(), 0.16, 1e-15);
  ASSERT_EQ(coupler.shape->circle_holes.size(), 2u);
  EXPECT_NEAR(coupler.shape->circle_holes[0].centre.x(), 0.04, 1e-15);  // at A
  EXPECT_NEAR(coupler.shape->circle_holes[0].centre.y(), 0.0, 1e-15);
  EXPECT_NEAR(coupler.shape->circle_holes[0].radius, 0.005, 1e-15);
  EXPECT_NEAR(coupler.shape->circle_holes[1].centre.x(), 0.1, 1e-15);
  EXPECT_NEAR(coupler.shape->circle_holes[1].centre.y(), 0.05, 1e-15);
  EXPECT_NEAR(coupler.shape->circle_holes[1].radius, 0.004, 1e-15);
  ASSERT_EQ(coupler.shape->polygon_holes.size(), 1u);
  ASSERT_EQ(coupler.shape->polygon_holes[0].size(), 3u);
  EXPECT_NEAR(coupler.shape->polygon_holes[0][2].y(), 0.095, 1e-15);
  // 140 x 170 mm less two circles and a triangle of base 20 and height 15.
  const double coupler_area = (140 * 170 - kPi * (25 + 16) - 150) * kMm2;
  EXPECT_NEAR(area_properties(*coupler.shape).area, coupler_area, 1e-12 * coupler_area);
  EXPECT_DOUBLE_EQ(coupler.thickness, 0.01);
  ASSERT_TRUE(coupler.material.has_value());
  EXPECT_EQ(coupler.material->name, "my-alloy");
  EXPECT_DOUBLE_EQ(coupler.material->density, 2800);
  EXPECT_DOUBLE_EQ(*coupler.material->yield_strength, 250e6);

  const Body& rocker = m.bodies[2];
  ASSERT_TRUE(rocker.shape.has_value());
  const double length = std::hypot(40.0, 120.0);  // O4 to B, mm
  const double rocker_area = bar_area(20, length, 10, 5, 5) * kMm2;
  EXPECT_NEAR(area_properties(*rocker.shape).area, rocker_area, 1e-12 * rocker_area);
  // The bar is symmetric about the middle of O4-B.
  EXPECT_NEAR(area_properties(*rocker.shape).centroid.x(), 0.18, 1e-12);
  EXPECT_NEAR(area_properties(*rocker.shape).centroid.y(), 0.06, 1e-12);
  EXPECT_EQ(rocker.shape->circle_holes.size(), 2u);
  EXPECT_DOUBLE_EQ(rocker.thickness, 0.008);
  EXPECT_EQ(rocker.material->name, "aluminium");
  EXPECT_DOUBLE_EQ(rocker.material->density, 2700);
  EXPECT_DOUBLE_EQ(*rocker.material->yield_strength, 276e6);

  ASSERT_EQ(m.point_loads.size(), 2u);
  EXPECT_EQ(m.point_loads[0].point, 4);
  EXPECT_EQ(m.point_loads[0].body, -1);  // on the pin
  EXPECT_EQ(m.point_loads[0].fx.value(0.3), 0.0);
  EXPECT_EQ(m.point_loads[0].fy.value(0.3), -100.0);  // N, not scaled by the length unit
  EXPECT_EQ(m.point_loads[1].body, 1);
  EXPECT_NEAR(m.point_loads[1].fx.value(0.25), 100.0, 1e-12);
  EXPECT_EQ(m.point_loads[1].fx.text(), "100*sin(2*pi*t)");
  EXPECT_EQ(m.point_loads[1].fy.value(0.25), 0.0);

  ASSERT_EQ(m.torques.size(), 1u);
  EXPECT_EQ(m.torques[0].body, 2);
  EXPECT_EQ(m.torques[0].torque.value(1.0), -5.0);

  ASSERT_EQ(m.springs.size(), 2u);
  const Spring& s = m.springs[0];
  EXPECT_EQ(s.name, "return-spring");
  EXPECT_EQ(s.points, (std::array<int, 2>{4, 1}));
  EXPECT_DOUBLE_EQ(s.stiffness, 2000);  // N/m whatever the length unit
  EXPECT_DOUBLE_EQ(s.free_length, 0.12);
  EXPECT_DOUBLE_EQ(s.damping, 5);
  const Spring& t = m.springs[1];
  EXPECT_EQ(t.name, "spring1");
  EXPECT_DOUBLE_EQ(t.stiffness, 2000);
  EXPECT_DOUBLE_EQ(t.free_length, 0.16);  // the drawn distance A-O4
  EXPECT_EQ(t.damping, 0.0);

  const SourceMap& src = loaded.source;
  ASSERT_EQ(src.bodies.size(), 3u);
  EXPECT_EQ(src.bodies[1].line, 17);
  ASSERT_EQ(src.point_loads.size(), 2u);
  EXPECT_EQ(src.point_loads[1].line, 34);
  EXPECT_EQ(src.point_loads[1].column, 5);
  EXPECT_EQ(src.find({EntityRef::Kind::PointLoad, 0}).line, 33);
  EXPECT_EQ(src.find({EntityRef::Kind::Torque, 0}).line, 36);
  EXPECT_EQ(src.find({EntityRef::Kind::Spring, 1}).line, 39);
  EXPECT_EQ(src.find({EntityRef::Kind::Spring, 1}).column, 5);
  EXPECT_EQ(src.find({EntityRef::Kind::Spring, 2}).line, 1);  // unknown: the model
  EXPECT_EQ(locate(src, ModelError({EntityRef::Kind::Torque, 0}, "too much")), "kinetics.yaml:36:5: too much");
}

// Every complete model in the kinetics section of docs/model-format.md parses, and the first is
// kKinetics.
TEST(ModelFileKinetics, DocumentedExamplesParse) {
  std::ifstream in(std::string(NBAR_EXAMPLES_DIR) + "/../docs/model-format.md");
  ASSERT_TRUE(in) << "cannot read docs/model-format.md";
  std::ostringstream text;
  text << in.rdbuf();
  const std::string doc = text.str();
  const std::size_t begin = doc.find("## Kinetics: mass, shapes, materials, loads");
  const std::size_t end = doc.find("\n## Examples", begin);
  ASSERT_NE(begin, std::string::npos);
  ASSERT_NE(end, std::string::npos);
  const std::string section = doc.substr(begin, end - begin);
  std::vector<std::string> models;
  for (std::size_t at = section.find("```yaml\n"); at != std::string::npos; at = section.find("```yaml\n", at)) {
    at += 8;
    const std::size_t close = section.find("```", at);
    ASSERT_NE(close, std::string::npos);
    const std::string block = section.substr(at, close - at);
    if (block.find("\npoints:") != std::string::npos) models.push_back(block);
    at = close + 3;
  }
  ASSERT_EQ(models.size(), 3u);
  EXPECT_EQ(models[0], kKinetics);
  for (const std::string& model : models) EXPECT_NO_THROW(parse_model(model, "doc.yaml")) << model;
}

TEST(ModelFileKinetics, JsonReadsLikeYaml) {
  const Model y = parse_model(kKinetics).model;
  const Model j = parse_model(kKineticsJson, "kinetics.json").model;
  EXPECT_EQ(j.gravity, y.gravity);
  ASSERT_EQ(j.bodies.size(), y.bodies.size());
  for (std::size_t i = 0; i < y.bodies.size(); ++i) {
    const Body& a = j.bodies[i];
    const Body& b = y.bodies[i];
    EXPECT_EQ(a.points, b.points);
    EXPECT_EQ(a.thickness, b.thickness);
    ASSERT_EQ(a.shape.has_value(), b.shape.has_value());
    if (a.shape) {
      EXPECT_EQ(a.shape->outline, b.shape->outline);
      EXPECT_EQ(a.shape->polygon_holes, b.shape->polygon_holes);
      ASSERT_EQ(a.shape->circle_holes.size(), b.shape->circle_holes.size());
      for (std::size_t k = 0; k < a.shape->circle_holes.size(); ++k) {
        EXPECT_EQ(a.shape->circle_holes[k].centre, b.shape->circle_holes[k].centre);
        EXPECT_EQ(a.shape->circle_holes[k].radius, b.shape->circle_holes[k].radius);
      }
    }
    ASSERT_EQ(a.material.has_value(), b.material.has_value());
    if (a.material) {
      EXPECT_EQ(a.material->name, b.material->name);
      EXPECT_EQ(a.material->density, b.material->density);
      EXPECT_EQ(a.material->yield_strength, b.material->yield_strength);
    }
    ASSERT_EQ(a.inertia.has_value(), b.inertia.has_value());
    if (a.inertia) {
      EXPECT_EQ(a.inertia->mass, b.inertia->mass);
      EXPECT_EQ(a.inertia->cg, b.inertia->cg);
      EXPECT_EQ(a.inertia->inertia, b.inertia->inertia);
    }
  }
  ASSERT_EQ(j.point_loads.size(), y.point_loads.size());
  for (std::size_t i = 0; i < y.point_loads.size(); ++i) {
    EXPECT_EQ(j.point_loads[i].point, y.point_loads[i].point);
    EXPECT_EQ(j.point_loads[i].body, y.point_loads[i].body);
    EXPECT_EQ(j.point_loads[i].fx.text(), y.point_loads[i].fx.text());
    EXPECT_EQ(j.point_loads[i].fy.text(), y.point_loads[i].fy.text());
  }
  ASSERT_EQ(j.torques.size(), 1u);
  EXPECT_EQ(j.torques[0].body, y.torques[0].body);
  EXPECT_EQ(j.torques[0].torque.value(0), y.torques[0].torque.value(0));
  ASSERT_EQ(j.springs.size(), y.springs.size());
  for (std::size_t i = 0; i < y.springs.size(); ++i) {
    EXPECT_EQ(j.springs[i].name, y.springs[i].name);
    EXPECT_EQ(j.springs[i].points, y.springs[i].points);
    EXPECT_EQ(j.springs[i].stiffness, y.springs[i].stiffness);
    EXPECT_EQ(j.springs[i].free_length, y.springs[i].free_length);
    EXPECT_EQ(j.springs[i].damping, y.springs[i].damping);
  }
}

TEST(ModelFileKinetics, NoKineticsMeansNone) {
  const Model m = parse_model(kLinkage).model;
  EXPECT_EQ(m.gravity, Eigen::Vector2d(0, 0));
  EXPECT_TRUE(m.point_loads.empty());
  EXPECT_TRUE(m.torques.empty());
  EXPECT_TRUE(m.springs.empty());
  for (const Body& b : m.bodies) {
    EXPECT_FALSE(b.shape || b.material || b.inertia);
    EXPECT_EQ(b.thickness, 0.0);
  }
  // Empty sections are empty, as elsewhere.
  const Model n = parse_model(kLinkage + "gravity:\nmaterials:\nforces:\ntorques:\nsprings:\n").model;
  EXPECT_EQ(n.gravity, Eigen::Vector2d(0, 0));
  EXPECT_TRUE(n.springs.empty());
}

TEST(ModelFileKinetics, Gravity) {
  EXPECT_EQ(parse_model(kLinkage + "gravity: standard\n").model.gravity, Eigen::Vector2d(0, -9.80665));
  // Not scaled by the length unit, nor by inches.
  EXPECT_EQ(parse_model(kLinkage + "gravity: [9.81, 0]\n").model.gravity, Eigen::Vector2d(9.81, 0));
  const std::string inches = "units: {length: in}\n" + kLinkage.substr(kLinkage.find('\n') + 1);
  EXPECT_EQ(parse_model(inches + "gravity: [0, -32.2]\n").model.gravity, Eigen::Vector2d(0, -32.2));
}

TEST(ModelFileKinetics, BarsAreMadeWithMakeBar) {
  const Model m = parse_model(coupler("    bar: {width: 12, margin: 9, holes: [5, 0], between: [B, P]}\n"
                                      "    thickness: 3\n"
                                      "    material: steel\n"))
                      .model;
  const Body& b = m.bodies[2];
  ASSERT_TRUE(b.shape.has_value());
  const double length = std::hypot(60.0, 30.0);  // B to P
  const double area = bar_area(12, length, 9, 5, 0) * kMm2;
  EXPECT_NEAR(area_properties(*b.shape).area, area, 1e-12 * area);
  ASSERT_EQ(b.shape->circle_holes.size(), 1u);  // radius 0 = no hole
  EXPECT_NEAR(b.shape->circle_holes[0].centre.x(), 0.16, 1e-15);
  EXPECT_NEAR(b.shape->circle_holes[0].centre.y(), 0.12, 1e-15);
  EXPECT_DOUBLE_EQ(b.thickness, 0.003);
  // The same bar made directly, in metres.
  const Region direct = make_bar(Eigen::Vector2d(0.16, 0.12), Eigen::Vector2d(0.1, 0.15), 0.012, 0.009, 0.005, 0);
  ASSERT_EQ(direct.outline.size(), b.shape->outline.size());
  for (std::size_t i = 0; i < direct.outline.size(); ++i) {
    EXPECT_NEAR((direct.outline[i] - b.shape->outline[i]).norm(), 0.0, 1e-15);
  }

  // Without margin, the bar extends half its width past each end; without holes it has none.
  const Model n = parse_model(coupler("    bar: {width: 10}\n    thickness: 2\n    material: brass\n")).model;
  const double ab = std::hypot(120.0, 120.0);
  const double plain = bar_area(10, ab, 5, 0, 0) * kMm2;
  EXPECT_NEAR(area_properties(*n.bodies[2].shape).area, plain, 1e-12 * plain);
  EXPECT_TRUE(n.bodies[2].shape->circle_holes.empty());
}

TEST(ModelFileKinetics, GivenMassProperties) {
  const Model m = parse_model(kSliderCrankMm +
                              "  crank: {points: [O, A], mass: 1}\n"
                              "  rod: {points: [A, C], mass: 0.2, cg: [90, 20]}\n"
                              "  piston: {points: [C], mass: 0.5, cg: C, inertia: 1.2e-4}\n")
                      .model;
  EXPECT_EQ(m.bodies[0].inertia->cg, Eigen::Vector2d(0, 0));
  EXPECT_EQ(m.bodies[0].inertia->inertia, 0.0);
  EXPECT_DOUBLE_EQ(m.bodies[1].inertia->mass, 0.2);
  EXPECT_DOUBLE_EQ(m.bodies[1].inertia->cg.x(), 0.09);
  EXPECT_DOUBLE_EQ(m.bodies[1].inertia->cg.y(), 0.02);
  EXPECT_DOUBLE_EQ(m.bodies[2].inertia->mass, 0.5);
  EXPECT_DOUBLE_EQ(m.bodies[2].inertia->cg.x(), 0.15);
  EXPECT_DOUBLE_EQ(m.bodies[2].inertia->inertia, 1.2e-4);  // kg m^2, not scaled

  // A mass with a shape: the shape serves the stresses, its centroid is the default cg, and no
  // material is needed.
  const Model n = parse_model(kSliderCrankMm +
                              "  crank:\n"
                              "    points: [O, A]\n"
                              "    bar: {width: 10}\n"
                              "    thickness: 5\n"
                              "    mass: 1\n"
                              "  rod: [A, C]\n"
                              "  piston: {points: [C], mass: 0, bar: {width: 10, between: [O, X]}, thickness: 1}\n")
                      .model;
  const Body& crank = n.bodies[0];
  ASSERT_TRUE(crank.shape && crank.inertia);
  EXPECT_FALSE(crank.material.has_value());
  EXPECT_NEAR(crank.inertia->cg.x(), 0.015, 1e-15);  // the middle of O-A
  EXPECT_NEAR(crank.inertia->cg.y(), 0.02, 1e-15);
  EXPECT_NEAR(area_properties(*crank.shape).area, bar_area(10, 50, 5, 0, 0) * kMm2, 1e-15);
  EXPECT_EQ(n.bodies[2].inertia->mass, 0.0);
  EXPECT_NEAR(n.bodies[2].inertia->cg.x(), 0.05, 1e-15);  // the bar's centroid, not the point C
}

TEST(ModelFileKinetics, Materials) {
  const auto material_of = [](const std::string& spec) {
    const Model m = parse_model("materials:\n  my-alloy: {density: 2800, yield: 250 MPa}\n  soft: {density: 900}\n" +
                                coupler("    bar: {width: 20}\n    thickness: 5\n    material: " + spec + "\n"))
                        .model;
    return *m.bodies[2].material;
  };
  EXPECT_EQ(material_of("my-alloy").name, "my-alloy");
  EXPECT_FALSE(material_of("soft").yield_strength.has_value());
  EXPECT_EQ(material_of("soft").density, 900.0);

  const Material aluminum = material_of("aluminum");  // the American spelling
  EXPECT_EQ(aluminum.name, "aluminium");
  EXPECT_EQ(aluminum.density, 2700.0);
  EXPECT_FALSE(material_of("cast-iron").yield_strength.has_value());
  EXPECT_DOUBLE_EQ(*material_of("titanium").yield_strength, 880e6);

  const Material inline_ksi = material_of("{density: 7850, yield: 36 ksi}");
  EXPECT_EQ(inline_ksi.name, "");
  EXPECT_DOUBLE_EQ(inline_ksi.density, 7850);
  EXPECT_NEAR(*inline_ksi.yield_strength, 248.211e6, 1e3);
  EXPECT_DOUBLE_EQ(*material_of("{density: 1000, yield: 2.5e8}").yield_strength, 2.5e8);  // Pa
  EXPECT_DOUBLE_EQ(*material_of("{density: 1000, yield: 30000 psi}").yield_strength, 30000 * 6894.757293168361);
  EXPECT_DOUBLE_EQ(*material_of("{density: 1000, yield: 1.2GPa}").yield_strength, 1.2e9);
  EXPECT_DOUBLE_EQ(*material_of("{density: 1000, yield: '500 kPa'}").yield_strength, 5e5);
  EXPECT_DOUBLE_EQ(*material_of("{density: 1000, yield: 7 Pa}").yield_strength, 7);

  // Elastic constants, for finite-element stresses.
  const Material elastic = material_of("{density: 2800, youngs_modulus: 72 GPa, poisson_ratio: 0.33}");
  EXPECT_DOUBLE_EQ(*elastic.youngs_modulus, 72e9);
  EXPECT_DOUBLE_EQ(*elastic.poisson_ratio, 0.33);
  EXPECT_DOUBLE_EQ(*material_of("{density: 1, youngs_modulus: 3e9, poisson_ratio: 0}").youngs_modulus, 3e9);  // Pa
  EXPECT_FALSE(material_of("soft").youngs_modulus.has_value());
  EXPECT_FALSE(material_of("soft").poisson_ratio.has_value());
  EXPECT_DOUBLE_EQ(*material_of("steel").youngs_modulus, 200e9);
  EXPECT_DOUBLE_EQ(*material_of("steel").poisson_ratio, 0.3);
}

TEST(ModelFileKinetics, BuiltinMaterials) {
  const std::vector<std::string> names = builtin_material_names();
  EXPECT_EQ(names, (std::vector<std::string>{"steel", "stainless-steel", "aluminium", "brass", "cast-iron", "titanium",
                                             "abs", "acrylic", "nylon", "aluminum"}));
  ASSERT_EQ(builtin_materials().size(), 9u);
  for (const std::string& name : names) {
    const std::optional<Material> m = builtin_material(name);
    ASSERT_TRUE(m.has_value()) << name;
    EXPECT_GT(m->density, 0.0) << name;
    // Every built-in material can be meshed: E between a soft plastic's and a steel's.
    ASSERT_TRUE(m->youngs_modulus && m->poisson_ratio) << name;
    EXPECT_GE(*m->youngs_modulus, 2e9) << name;
    EXPECT_LE(*m->youngs_modulus, 210e9) << name;
    EXPECT_GT(*m->poisson_ratio, 0.2) << name;
    EXPECT_LT(*m->poisson_ratio, 0.45) << name;
  }
  EXPECT_DOUBLE_EQ(*builtin_material("aluminium")->youngs_modulus, 68.9e9);
  EXPECT_DOUBLE_EQ(*builtin_material("titanium")->poisson_ratio, 0.34);
  EXPECT_DOUBLE_EQ(builtin_material("steel")->density, 7850);
  EXPECT_DOUBLE_EQ(*builtin_material("steel")->yield_strength, 250e6);
  EXPECT_DOUBLE_EQ(*builtin_material("stainless-steel")->yield_strength, 215e6);
  EXPECT_DOUBLE_EQ(builtin_material("brass")->density, 8500);
  EXPECT_DOUBLE_EQ(builtin_material("abs")->density, 1050);
  EXPECT_DOUBLE_EQ(*builtin_material("acrylic")->yield_strength, 70e6);
  EXPECT_DOUBLE_EQ(builtin_material("nylon")->density, 1150);
  EXPECT_FALSE(builtin_material("Steel").has_value());
  EXPECT_FALSE(builtin_material("unobtainium").has_value());
}

TEST(ModelFileKinetics, Loads) {
  const Model m = parse_model(kLinkage +
                              "forces:\n"
                              "  - {point: B, fy: 5}\n"
                              "  - {point: A, body: crank, force: [\"10*t\", +3]}\n"
                              "  - {point: P, fx: -2.5e1}\n"
                              "torques:\n"
                              "  - {body: crank, torque: \"2*t\"}\n"
                              "  - body: coupler\n"
                              "    torque: 0.5\n")
                      .model;
  ASSERT_EQ(m.point_loads.size(), 3u);
  EXPECT_EQ(m.point_loads[0].fx.value(1), 0.0);
  EXPECT_EQ(m.point_loads[0].fy.value(1), 5.0);
  EXPECT_EQ(m.point_loads[1].body, 0);
  EXPECT_EQ(m.point_loads[1].fx.value(0.5), 5.0);
  EXPECT_EQ(m.point_loads[1].fy.value(0.5), 3.0);
  EXPECT_EQ(m.point_loads[2].fx.value(0), -25.0);
  EXPECT_EQ(m.point_loads[2].fy.value(0), 0.0);
  ASSERT_EQ(m.torques.size(), 2u);
  EXPECT_EQ(m.torques[0].torque.value(3), 6.0);
  EXPECT_EQ(m.torques[1].body, 2);  // coupler, after crank and rocker
  EXPECT_EQ(m.torques[1].torque.value(3), 0.5);
}

TEST(ModelFileKinetics, Springs) {
  const Model m = parse_model(kLinkage +
                              "springs:\n"
                              "  - {between: [B, O2], stiffness: 10 lbf/in, damping: 0.5 N s/mm}\n"
                              "  - {between: [P, O2], damping: '3 N*s/m', name: spring2}\n"
                              "  - {between: [P, O4], stiffness: 1.5 kN/m, free_length: 0}\n"
                              "  - {between: [A, O4], stiffness: 2N/mm, damping: 4 Ns/m}\n")
                      .model;
  ASSERT_EQ(m.springs.size(), 4u);
  EXPECT_EQ(m.springs[0].name, "spring1");
  EXPECT_NEAR(m.springs[0].stiffness, 1751.2683524647638, 1e-9);
  EXPECT_DOUBLE_EQ(m.springs[0].damping, 500);
  EXPECT_DOUBLE_EQ(m.springs[0].free_length, 0.2);  // |B - O2| = 200 mm
  EXPECT_EQ(m.springs[1].name, "spring2");
  EXPECT_EQ(m.springs[1].stiffness, 0.0);
  EXPECT_DOUBLE_EQ(m.springs[1].damping, 3);
  EXPECT_EQ(m.springs[2].name, "spring3");  // spring2 is taken
  EXPECT_DOUBLE_EQ(m.springs[2].stiffness, 1500);
  EXPECT_EQ(m.springs[2].free_length, 0.0);
  EXPECT_EQ(m.springs[3].name, "spring4");
  EXPECT_DOUBLE_EQ(m.springs[3].stiffness, 2000);
  EXPECT_DOUBLE_EQ(m.springs[3].damping, 4);
}

// ---- errors, each at its exact place ----

TEST(ModelFileKineticsErrors, UnknownKeys) {
  EXPECT_TRUE(fails_at(kLinkage + "gravty: standard\n", "13:1",
                       "unknown key 'gravty' at the top level; did you mean 'gravity'?"));
  EXPECT_TRUE(fails_at(coupler("    mas: 1\n"), "14:5", "unknown key 'mas' in a body; did you mean 'mass'?"));
  EXPECT_TRUE(fails_at(coupler("    shape: {outline: [[0, 0], [1, 0], [0, 1]], hole: []}\n"), "14:48",
                       "unknown key 'hole' in a `shape`; did you mean 'holes'?"));
  EXPECT_TRUE(fails_at(coupler("    shape:\n      outline: [[30, -10], [170, -10], [170, 160]]\n      holes:\n"
                               "        - {at: A, radus: 5}\n"),
                       "17:19", "unknown key 'radus' in a hole; did you mean 'radius'?"));
  EXPECT_TRUE(
      fails_at(coupler("    bar: {widht: 5}\n"), "14:11", "unknown key 'widht' in a `bar`; did you mean 'width'?"));
  EXPECT_TRUE(fails_at(kLinkage + "materials:\n  foo: {densty: 5}\n", "14:9",
                       "unknown key 'densty' in a material; did you mean 'density'?"));
  EXPECT_TRUE(fails_at(kLinkage + "forces:\n  - {point: P, fz: 5}\n", "14:16",
                       "unknown key 'fz' in a force; did you mean 'fx'?"));
  EXPECT_TRUE(fails_at(kLinkage + "torques:\n  - {body: crank, moment: 5}\n", "14:19",
                       "unknown key 'moment' in a torque (allowed: body, torque, no_load_speed)"));
  EXPECT_TRUE(fails_at(kLinkage + "springs:\n  - {between: [P, A], stifness: 5}\n", "14:23",
                       "unknown key 'stifness' in a spring; did you mean 'stiffness'?"));
}

TEST(ModelFileKineticsErrors, BodyLongForm) {
  EXPECT_TRUE(fails_at(kFourBarMm + "  coupler: {mass: 1}\n", "12:3", "body 'coupler' needs `points`"));
  EXPECT_TRUE(fails_at(kFourBarMm + "  coupler: {points: A}\n", "12:21",
                       "`points` must be a list of point names like [A, B], not 'A'"));
  EXPECT_TRUE(fails_at(kFourBarMm + "  coupler: {points: [A, Z]}\n", "12:25", "unknown point 'Z'"));
  EXPECT_TRUE(fails_at(coupler("    shape: {outline: [[30, -10], [170, -10], [170, 160]]}\n"
                               "    bar: {width: 5}\n    thickness: 2\n    material: steel\n"),
                       "15:5", "body 'coupler' has either a `shape` or a `bar`, not both"));
  EXPECT_TRUE(fails_at(coupler("    bar: {width: 20}\n    material: steel\n"), "14:5",
                       "body 'coupler' has a bar but no `thickness`"));
  EXPECT_TRUE(fails_at(coupler("    thickness: 3\n    mass: 1\n"), "14:5",
                       "`thickness` applies only to a body with a `shape` or a `bar`"));
  EXPECT_TRUE(fails_at(coupler("    bar: {width: 20}\n    thickness: 0\n    material: steel\n"), "15:16",
                       "the thickness must be positive"));
  EXPECT_TRUE(fails_at(coupler("    shape: {outline: [[30, -10], [170, -10], [170, 160]]}\n    thickness: 2\n"), "14:5",
                       "body 'coupler' has a shape but no material: give `material:` or `mass:`"));
  EXPECT_TRUE(fails_at(coupler("    bar: {width: 20}\n    thickness: 2\n"), "14:5",
                       "body 'coupler' has a bar but no material: give `material:` or `mass:`"));
  EXPECT_TRUE(fails_at(coupler("    material: steel\n"), "14:5",
                       "body 'coupler' has a material but nothing to weigh: give it a `shape` or a `bar`"));
  EXPECT_TRUE(fails_at(coupler("    cg: A\n"), "14:5", "`cg` applies only with `mass`"));
  EXPECT_TRUE(
      fails_at(coupler("    bar: {width: 20}\n    thickness: 2\n    material: steel\n    inertia: 1\n"), "17:5",
               "`inertia` applies only with `mass` (otherwise the shape and material give the mass properties)"));
  EXPECT_TRUE(fails_at(coupler("    mass: -1\n"), "14:11", "the mass (kg) must not be negative"));
  EXPECT_TRUE(fails_at(coupler("    mass: heavy\n"), "14:11", "the mass (kg) must be a number, not 'heavy'"));
  EXPECT_TRUE(
      fails_at(coupler("    mass: 1\n    inertia: -2\n"), "15:14", "the inertia (kg m^2) must not be negative"));
  EXPECT_TRUE(fails_at(coupler("    mass: 1\n    cg: Z\n"), "15:9", "unknown point 'Z'"));
  EXPECT_TRUE(fails_at(coupler("    mass: 1\n    cg: [1, 2, 3]\n"), "15:9", "`cg` needs [x, y], not a list"));
  EXPECT_TRUE(
      fails_at(coupler("    mass: 1\n    cg: {x: 1}\n"), "15:9", "`cg` must be a point name or [x, y], not a mapping"));
  EXPECT_TRUE(fails_at(coupler("    mass: 1\n    cg: [1, .nan]\n"), "15:13", "y must be a finite number"));
}

TEST(ModelFileKineticsErrors, Materials) {
  const std::string bar = "    bar: {width: 20}\n    thickness: 2\n";  // lines 14-15
  EXPECT_TRUE(fails_at(coupler(bar + "    material: stel\n"), "16:15",
                       "unknown material 'stel'; did you mean 'steel'? (known materials: steel, stainless-steel, "
                       "aluminium, brass, cast-iron, titanium, abs, acrylic, nylon, aluminum; or define it under "
                       "`materials:`)"));
  EXPECT_TRUE(fails_at(coupler(bar + "    material: unobtainium\n"), "16:15",
                       "unknown material 'unobtainium' (known materials: steel,"));
  EXPECT_TRUE(fails_at("materials: {my-alloy: {density: 1}}\n" + coupler(bar + "    material: my-aloy\n"), "17:15",
                       "unknown material 'my-aloy'; did you mean 'my-alloy'? (known materials: my-alloy, steel,"));
  EXPECT_TRUE(fails_at(coupler(bar + "    material: [steel]\n"), "16:15",
                       "`material` must be a material name like steel, or a mapping like {density: 7850, yield: 250 "
                       "MPa}, not a list"));
  EXPECT_TRUE(
      fails_at(coupler(bar + "    material: {density: -3}\n"), "16:25", "the density (kg/m^3) must be positive"));
  EXPECT_TRUE(fails_at(coupler(bar + "    material: {yield: 3 MPa}\n"), "16:15", "a material needs `density`"));

  // Lines 13 on.
  EXPECT_TRUE(fails_at(kLinkage + "materials: [steel]\n", "13:12",
                       "`materials` must be a mapping like {my-alloy: {density: 2800, yield: 250 MPa}}, not a list"));
  EXPECT_TRUE(fails_at(kLinkage + "materials:\n  steel: {density: 7800}\n", "14:3",
                       "'steel' is a built-in material; give yours another name"));
  EXPECT_TRUE(fails_at(kLinkage + "materials:\n  aluminum: {density: 2700}\n", "14:3", "is a built-in material"));
  EXPECT_TRUE(fails_at(kLinkage + "materials:\n  foo: 5\n", "14:8",
                       "material 'foo' needs a mapping like {density: 2800, yield: 250 MPa}, not '5'"));
  EXPECT_TRUE(fails_at(kLinkage + "materials:\n  foo: {density: 1}\n  foo: {density: 2}\n", "15:3",
                       "material 'foo' is defined twice (first given on line 14)"));
  EXPECT_TRUE(
      fails_at(kLinkage + "materials:\n  foo: {density: 0}\n", "14:18", "the density (kg/m^3) must be positive"));
  EXPECT_TRUE(fails_at(kLinkage + "materials:\n  foo: {density: 1, yield: 5 Mpa}\n", "14:28",
                       "unknown unit in the yield strength '5 Mpa' (use Pa, kPa, MPa, GPa, psi, ksi)"));
  EXPECT_TRUE(fails_at(kLinkage + "materials:\n  foo: {density: 1, yield: lots}\n", "14:28",
                       "the yield strength must be a number or a quantity like '250 MPa', not 'lots'"));
  EXPECT_TRUE(fails_at(kLinkage + "materials:\n  foo: {density: 1, yield: -5 MPa}\n", "14:28",
                       "the yield strength must be positive (leave `yield` out for a brittle material)"));
  EXPECT_TRUE(fails_at(kLinkage + "materials:\n  foo: {density: 1, yield: 0}\n", "14:28",
                       "the yield strength must be positive"));
  EXPECT_TRUE(fails_at(kLinkage + "materials:\n  foo: {density: 1, yield: .inf}\n", "14:28",
                       "the yield strength must be a finite number, not '.inf'"));
  EXPECT_TRUE(fails_at(kLinkage + "materials:\n  foo: {density: 1, yield: [1]}\n", "14:28",
                       "the yield strength must be a number or a quantity like '250 MPa', not a list"));
  EXPECT_TRUE(fails_at(kLinkage + "materials:\n  foo: {density: 1, yield: 250 mpa}\n", "14:28",
                       "unknown unit in the yield strength '250 mpa'"));
  EXPECT_TRUE(fails_at(kLinkage + "materials:\n  foo: {density: 1, yield: MPa}\n", "14:28",
                       "the yield strength must be a number or a quantity like '250 MPa', not 'MPa'"));
  EXPECT_TRUE(fails_at(kLinkage + "materials:\n  foo: {density: 1, yield: 1e999 Pa}\n", "14:28",
                       "the yield strength must be a finite number, not '1e999 Pa'"));
  EXPECT_TRUE(fails_at(kLinkage + "materials:\n  foo: {density: 1, poisson_ratio: 0.5}\n", "14:36",
                       "Poisson's ratio must be at least 0 and less than 0.5 (0.3 for steel), not 0.5"));
  EXPECT_TRUE(fails_at(kLinkage + "materials:\n  foo: {density: 1, poisson_ratio: -0.1}\n", "14:36",
                       "Poisson's ratio must be at least 0 and less than 0.5"));
  EXPECT_TRUE(
      fails_at(kLinkage + "materials:\n  foo: {density: 1, poisson_ratio: soft}\n", "14:36", "Poisson's ratio"));
  EXPECT_TRUE(fails_at(kLinkage + "materials:\n  foo: {density: 1, youngs_modulus: 0 GPa}\n", "14:37",
                       "Young's modulus must be positive, like 200 GPa for steel"));
  EXPECT_TRUE(fails_at(kLinkage + "materials:\n  foo: {density: 1, youngs_modulus: 200 Gpa}\n", "14:37",
                       "unknown unit in Young's modulus '200 Gpa' (use Pa, kPa, MPa, GPa, psi, ksi)"));
}

TEST(ModelFileKineticsErrors, Shapes) {
  const std::string tail = "    thickness: 2\n    material: steel\n";
  EXPECT_TRUE(fails_at(coupler("    shape: [1, 2]\n" + tail), "14:12", "`shape` must be a mapping like"));
  EXPECT_TRUE(fails_at(coupler("    shape: {holes: []}\n" + tail), "14:12", "a shape needs `outline`"));
  EXPECT_TRUE(fails_at(coupler("    shape: {outline: 5}\n" + tail), "14:22",
                       "`outline` must be a list of vertices like [[0, 0], [100, 0], [100, 20]], not '5'"));
  EXPECT_TRUE(fails_at(coupler("    shape: {outline: [[0, 0], [1, 0]]}\n" + tail), "14:22",
                       "an outline needs at least 3 vertices, not 2"));
  EXPECT_TRUE(fails_at(coupler("    shape: {outline: [[0, 0], [1, 0], [1]]}\n" + tail), "14:39",
                       "a vertex needs [x, y], not a list"));
  EXPECT_TRUE(fails_at(coupler("    shape: {outline: [[0, 0], [1, 0], [1, a]]}\n" + tail), "14:43",
                       "y must be a number, not 'a'"));
  EXPECT_TRUE(fails_at(coupler("    shape: {outline: [[0, 0], [100, 100], [100, 0], [0, 100]]}\n" + tail), "14:22",
                       "the shape of body 'coupler' is not valid: the outline"));
  EXPECT_TRUE(fails_at(coupler("    shape: {outline: [[0, 0], [1, 0], [2, 0]]}\n" + tail), "14:22",
                       "the shape of body 'coupler' is not valid: the outline has zero area"));

  // Holes: the outline on line 15, holes from line 17.
  const auto holes = [&](const std::string& items) {
    return coupler("    shape:\n      outline: [[30, -10], [170, -10], [170, 160], [30, 160]]\n      holes:\n" + items +
                   tail);
  };
  EXPECT_NO_THROW(parse_model(holes("        - {at: A, radius: 5}\n")));
  EXPECT_TRUE(fails_at(holes("        - {at: A, radius: 5}\n        - {circle: [300, 50], radius: 4}\n"), "18:11",
                       "the shape of body 'coupler' is not valid: the hole (centre (300, 50), radius 4) is outside "
                       "the outline"));
  EXPECT_TRUE(fails_at(holes("        - {at: A, radius: 11}\n"), "17:11",
                       "is not valid: the hole (centre (40, 0), radius 11) meets the outline"));
  EXPECT_TRUE(fails_at(holes("        - {polygon: [[90, 80], [110, 80], [100, 95], [95, 70]]}\n"), "17:11",
                       "is not valid: the hole intersects itself"));
  EXPECT_TRUE(fails_at(holes("        - {at: A, radius: 5}\n        - {circle: [100, 50], radius: 4}\n"
                             "        - {circle: [44, 0], radius: 4}\n"),
                       "19:11",
                       "the shape of body 'coupler' is not valid: this hole overlaps or touches hole 1 (line 17)"));
  EXPECT_TRUE(fails_at(holes("        - {polygon: [[90, 80], [110, 80], [100, 95]]}\n"
                             "        - {circle: [100, 85], radius: 1}\n"),
                       "18:11", "this hole overlaps or touches hole 1 (line 17)"));
  EXPECT_TRUE(fails_at(holes("        - {polygon: [[90, 80], [190, 80], [100, 95]]}\n"), "17:11",
                       "the shape of body 'coupler' is not valid: the hole meets the outline"));
  EXPECT_TRUE(fails_at(holes("        - {at: Z, radius: 5}\n"), "17:16", "unknown point 'Z'"));
  EXPECT_TRUE(fails_at(holes("        - {at: A, circle: [1, 2], radius: 3}\n"), "17:19",
                       "a hole has exactly one of `at`, `circle` or `polygon`; this one already has `at`"));
  EXPECT_TRUE(fails_at(holes("        - {radius: 3}\n"), "17:11",
                       "a hole needs one of `at: <point>`, `circle: [x, y]` or `polygon: [[x, y], ...]`"));
  EXPECT_TRUE(fails_at(holes("        - {at: A}\n"), "17:11", "a round hole needs `radius`"));
  EXPECT_TRUE(fails_at(holes("        - {polygon: [[90, 80], [110, 80], [100, 95]], radius: 2}\n"), "17:55",
                       "`radius` applies only to a round hole (`at` or `circle`)"));
  EXPECT_TRUE(fails_at(holes("        - {at: A, radius: 0}\n"), "17:27", "the radius must be positive"));
  EXPECT_TRUE(fails_at(holes("        - {circle: [1], radius: 1}\n"), "17:20", "`circle` needs [x, y], not a list"));
  EXPECT_TRUE(fails_at(holes("        - {polygon: [[90, 80], [110, 80]]}\n"), "17:21",
                       "a polygon hole needs at least 3 vertices, not 2"));
  EXPECT_TRUE(fails_at(holes("        - 5\n"), "17:11", "a hole is a mapping like {at: A, radius: 5}"));
  EXPECT_TRUE(fails_at(coupler("    shape:\n      outline: [[0, 0], [1, 0], [0, 1]]\n      holes: {at: A}\n" + tail),
                       "16:14", "`holes` must be a list like [{at: A, radius: 5}], not a mapping"));
}

TEST(ModelFileKineticsErrors, Bars) {
  const std::string tail = "    thickness: 2\n    material: steel\n";
  EXPECT_TRUE(fails_at(coupler("    bar: 20\n" + tail), "14:10",
                       "`bar` must be a mapping like {width: 20, margin: 10, hole: 5}, not '20'"));
  EXPECT_TRUE(fails_at(coupler("    bar: {margin: 3}\n" + tail), "14:10", "a bar needs `width`"));
  EXPECT_TRUE(fails_at(coupler("    bar: {width: 0}\n" + tail), "14:18", "the width must be positive"));
  EXPECT_TRUE(
      fails_at(coupler("    bar: {width: 20, margin: -1}\n" + tail), "14:30", "the margin must not be negative"));
  EXPECT_TRUE(
      fails_at(coupler("    bar: {width: 20, hole: -1}\n" + tail), "14:28", "the hole radius must not be negative"));
  EXPECT_TRUE(fails_at(coupler("    bar: {width: 20, hole: 2, holes: [2, 3]}\n" + tail), "14:31",
                       "give a bar either `hole` (both ends) or `holes: [r1, r2]`, not both"));
  EXPECT_TRUE(fails_at(coupler("    bar: {width: 20, holes: [2]}\n" + tail), "14:29",
                       "`holes` needs two radii [r1, r2], one per end (0 for none), not a list"));
  EXPECT_TRUE(fails_at(coupler("    bar: {width: 20, holes: [2, -3]}\n" + tail), "14:33",
                       "a hole radius must not be negative"));
  EXPECT_TRUE(fails_at(coupler("    bar: {width: 20, margin: 10, hole: 12}\n" + tail), "14:10",
                       "the bar of body 'coupler' is not valid: a hole of radius 12 does not fit in a bar of width 20 "
                       "with margin 10"));
  EXPECT_TRUE(fails_at(coupler("    bar: {width: 20, between: [A, A]}\n" + tail), "14:31",
                       "a bar runs between two different points"));
  EXPECT_TRUE(fails_at(coupler("    bar: {width: 20, between: [A, Z]}\n" + tail), "14:35", "unknown point 'Z'"));
  EXPECT_TRUE(fails_at(coupler("    bar: {width: 20, between: A}\n" + tail), "14:31",
                       "`between` needs two point names, like [A, B], not 'A'"));
  EXPECT_TRUE(fails_at(kSliderCrankMm + "  crank: [O, A]\n  rod: [A, C]\n"
                                        "  piston: {points: [C], bar: {width: 10}, thickness: 5, mass: 0.5}\n",
                       "13:25", "body 'piston' has a single point: say where its bar runs with `between: [P, Q]`"));
}

TEST(ModelFileKineticsErrors, Gravity) {
  EXPECT_TRUE(fails_at(kLinkage + "gravity: 9.81\n", "13:10",
                       "`gravity` must be [gx, gy] in m/s^2 or `standard`, not '9.81' (write [0, -9.81] for 9.81 m/s^2 "
                       "downwards)"));
  EXPECT_TRUE(fails_at(kLinkage + "gravity: -9.81\n", "13:10", "(write [0, -9.81] for 9.81 m/s^2 downwards)"));
  EXPECT_TRUE(fails_at(kLinkage + "gravity: earth\n", "13:10",
                       "`gravity` must be [gx, gy] in m/s^2 or `standard`, not 'earth'"));
  EXPECT_TRUE(fails_at(kLinkage + "gravity: [0]\n", "13:10", "not a list"));
  EXPECT_TRUE(fails_at(kLinkage + "gravity: {y: 1}\n", "13:10", "not a mapping"));
  EXPECT_TRUE(fails_at(kLinkage + "gravity: [0, x]\n", "13:14", "gy (m/s^2) must be a number, not 'x'"));
  EXPECT_TRUE(fails_at(kLinkage + "gravity: [.inf, 0]\n", "13:11", "gx (m/s^2) must be a finite number"));
}

TEST(ModelFileKineticsErrors, Forces) {
  // Items on line 14.
  const std::string head = kLinkage + "forces:\n";
  EXPECT_TRUE(fails_at(kLinkage + "forces: {point: P}\n", "13:9",
                       "`forces` must be a list like [{point: P, force: [0, -100]}], not a mapping"));
  EXPECT_TRUE(fails_at(head + "  - P\n", "14:5", "a force is a mapping like {point: P, force: [0, -100]}, not 'P'"));
  EXPECT_TRUE(fails_at(head + "  - {force: [0, 1]}\n", "14:5", "a force needs `point`"));
  EXPECT_TRUE(fails_at(head + "  - {point: Z, force: [0, 1]}\n", "14:13", "unknown point 'Z'"));
  EXPECT_TRUE(fails_at(head + "  - {point: P, body: crank, force: [0, 1]}\n", "14:22",
                       "point 'P' is not a point of body 'crank' (its points are: O2, A)"));
  EXPECT_TRUE(fails_at(head + "  - {point: A, body: crnk, force: [0, 1]}\n", "14:22",
                       "unknown body 'crnk'; did you mean 'crank'?"));
  EXPECT_TRUE(fails_at(head + "  - {point: P, force: [0, 1], fx: 3}\n", "14:31",
                       "give a force either as `force: [fx, fy]` or as `fx` and `fy`, not both"));
  EXPECT_TRUE(fails_at(head + "  - {point: P}\n", "14:5", "a force needs `force: [fx, fy]`, or `fx` and/or `fy` (N)"));
  EXPECT_TRUE(fails_at(head + "  - {point: P, force: [1]}\n", "14:23",
                       "`force` needs two components [fx, fy] in N, not a list"));
  EXPECT_TRUE(fails_at(head + "  - {point: P, force: 100}\n", "14:23", "not '100'"));
  EXPECT_TRUE(fails_at(head + "  - {point: P, fx: [1, 2]}\n", "14:20",
                       "fx must be a number or an expression in t like \"100*sin(2*pi*t)\", not a list"));
  EXPECT_TRUE(fails_at(head + "  - {point: P, fy: .inf}\n", "14:20", "fy must be a finite number, not '.inf'"));
  EXPECT_TRUE(fails_at(head + "  - {point: P, fx: }\n", "14:16", "fx must be a number or an expression in t"));
  // A law's error points at its character: the '+' ends the law 2*t + in column 26.
  EXPECT_TRUE(
      fails_at(head + "  - {point: P, fx: '2*t +'}\n", "14:26", "in the law '2*t +': unexpected end of expression"));
  EXPECT_TRUE(fails_at(head + "  - {point: P, force: [0, 'sin(x)']}\n", "14:32", "unknown name 'x'"));
}

TEST(ModelFileKineticsErrors, Torques) {
  const std::string head = kLinkage + "torques:\n";  // items on line 14
  EXPECT_TRUE(
      fails_at(kLinkage + "torques: 5\n", "13:10", "`torques` must be a list like [{body: crank, torque: -5}]"));
  EXPECT_TRUE(fails_at(head + "  - 5\n", "14:5", "a torque is a mapping like {body: crank, torque: -5}, not '5'"));
  EXPECT_TRUE(fails_at(head + "  - {torque: 5}\n", "14:5", "a torque needs `body`"));
  EXPECT_TRUE(fails_at(head + "  - {body: crank}\n", "14:5", "a torque needs `torque`"));
  EXPECT_TRUE(
      fails_at(head + "  - {body: rockr, torque: 5}\n", "14:12", "unknown body 'rockr'; did you mean 'rocker'?"));
  EXPECT_TRUE(fails_at(head + "  - {body: rocker, torque: [5]}\n", "14:28",
                       "the torque must be a number or an expression in t"));
  EXPECT_TRUE(fails_at(head + "  - {body: rocker, torque: 5 N m}\n", "14:30",
                       "(the torque is in N m: write a number without its unit, or an expression in t)"));
}

TEST(ModelFileKineticsErrors, Springs) {
  const std::string head = kLinkage + "springs:\n";  // items on line 14
  EXPECT_TRUE(fails_at(kLinkage + "springs: {between: [P, A]}\n", "13:10", "`springs` must be a list like"));
  EXPECT_TRUE(fails_at(head + "  - [P, A]\n", "14:5", "a spring is a mapping like {between: [P, Q], stiffness: 2000}"));
  EXPECT_TRUE(fails_at(head + "  - {stiffness: 5}\n", "14:5", "a spring needs `between`"));
  EXPECT_TRUE(fails_at(head + "  - {between: [P, P], stiffness: 5}\n", "14:15",
                       "a spring joins two different points, not point 'P' to itself"));
  EXPECT_TRUE(fails_at(head + "  - {between: [P], stiffness: 5}\n", "14:15",
                       "`between` needs two point names, like [P, Q], not a list"));
  EXPECT_TRUE(fails_at(head + "  - {between: [P, Z], stiffness: 5}\n", "14:19", "unknown point 'Z'"));
  EXPECT_TRUE(fails_at(head + "  - {between: [P, O2]}\n", "14:5",
                       "a spring needs `stiffness` (N/m), `damping` (N s/m) or both"));
  EXPECT_TRUE(
      fails_at(head + "  - {between: [P, O2], stiffness: -5}\n", "14:35", "the stiffness must not be negative"));
  EXPECT_TRUE(
      fails_at(head + "  - {between: [P, O2], stiffness: -5 N/mm}\n", "14:35", "the stiffness must not be negative"));
  EXPECT_TRUE(fails_at(head + "  - {between: [P, O2], stiffness: 5 N/cm}\n", "14:35",
                       "unknown unit in the stiffness '5 N/cm' (use N/m, N/mm, kN/m, lbf/in)"));
  EXPECT_TRUE(fails_at(head + "  - {between: [P, O2], stiffness: stiff}\n", "14:35",
                       "the stiffness must be a number or a quantity like '2 N/mm', not 'stiff'"));
  EXPECT_TRUE(fails_at(head + "  - {between: [P, O2], stiffness: .inf}\n", "14:35",
                       "the stiffness must be a finite number, not '.inf'"));
  EXPECT_TRUE(fails_at(head + "  - {between: [P, O2], stiffness: [1]}\n", "14:35",
                       "the stiffness must be a number or a quantity like '2 N/mm', not a list"));
  EXPECT_TRUE(fails_at(head + "  - {between: [P, O2], damping: 5 N/m}\n", "14:33",
                       "unknown unit in the damping '5 N/m' (use N s/m, N s/mm)"));
  EXPECT_TRUE(fails_at(head + "  - {between: [P, O2], damping: -1}\n", "14:33", "the damping must not be negative"));
  EXPECT_TRUE(fails_at(head + "  - {between: [P, O2], stiffness: 1, free_length: -1}\n", "14:51",
                       "the free length must not be negative"));
  EXPECT_TRUE(
      fails_at(head + "  - {between: [P, O2], stiffness: 1, name: ''}\n", "14:44", "a spring name cannot be empty"));
  EXPECT_TRUE(fails_at(head + "  - {between: [P, O2], stiffness: 1, name: a}\n"
                              "  - {between: [P, O4], stiffness: 1, name: a}\n",
                       "15:44", "two springs are named 'a' (first on line 14)"));
}

}  // namespace
}  // namespace nbar::io

namespace nbar::io {
namespace {

// The keys of forward dynamics (issue 38): free drivers, spring preloads, motor lines.
TEST(ModelFileKinetics, ForwardDynamicsKeys) {
  const LoadedModel loaded = parse_model(kLinkage +
                                         "torques:\n  - {body: crank, torque: 2, no_load_speed: 600 rpm}\n"
                                         "springs:\n  - {between: [P, O4], stiffness: 10, preload: -3.5}\n"
                                         "drivers:\n  - {angle: crank, free: true, initial_speed: 2 rad/s}\n");
  const Model& m = loaded.model;
  ASSERT_TRUE(m.torques[0].no_load_speed);
  EXPECT_NEAR(*m.torques[0].no_load_speed, 600 * 2 * kPi / 60, 1e-12);
  EXPECT_EQ(m.springs[0].preload, -3.5);
  EXPECT_TRUE(m.drivers[0].free);
  EXPECT_EQ(m.drivers[0].initial_speed, 2.0);
  const LoadedModel plain = parse_model(kLinkage + "drivers:\n  - {angle: crank, from: 10}\n");
  EXPECT_FALSE(plain.model.drivers[0].free);
  EXPECT_EQ(plain.model.drivers[0].initial_speed, 0.0);
}

TEST(ModelFileKineticsErrors, ForwardDynamicsKeys) {
  EXPECT_TRUE(fails_at(kLinkage + "drivers:\n  - {angle: crank, free: maybe}\n", "14:26",
                       "`free` is true or false, not 'maybe'"));
  EXPECT_TRUE(fails_at(kLinkage + "drivers:\n  - {angle: crank, initial_speed: 3}\n", "14:20",
                       "`initial_speed` applies only to a driver with `free: true`"));
  EXPECT_TRUE(fails_at(kLinkage + "drivers:\n  - {angle: crank, free: true, initial_speed: 2 m/s}\n", "14:47",
                       "'2 m/s' is a linear speed"));
  EXPECT_TRUE(fails_at(kLinkage + "torques:\n  - {body: crank, torque: 2, no_load_speed: 0}\n", "14:45",
                       "the no-load speed of a motor cannot be zero"));
  EXPECT_TRUE(fails_at(kLinkage + "springs:\n  - {between: [P, O4], stiffness: 10, preload: lots}\n", "14:48",
                       "the preload (N)"));
}

}  // namespace
}  // namespace nbar::io
