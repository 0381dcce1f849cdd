// Plates read from DXF drawings: hand-written files as CAD programs write them (LINE and ARC
// in any order and direction, LWPOLYLINE with bulges, units), the round trip through
// nbar's own cutting DXF, and bad files reported at their line.
#include "nbar/io/dxf_reader.hpp"
#include "nbar/io/dxf_writer.hpp"
#include "nbar/io/model_file.hpp"
#include "nbar/model/diagnostics.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

namespace nbar::io {
namespace {

constexpr double kPi = std::numbers::pi;
using ::testing::HasSubstr;

// Group codes and values from a list of "code value" items, one pair per two lines.
std::string dxf(std::initializer_list<std::pair<int, std::string>> pairs) {
  std::string out;
  for (const auto& [code, value] : pairs) out += std::to_string(code) + "\n" + value + "\n";
  return out;
}

// A slot 0 <= x <= 80, |y| <= 10 with half-round ends, drawn as LINEs and ARCs in a muddled
// order and direction, and a pin hole; as an R2000 file would have it (no header needed).
const std::string kSlotLinesArcs = dxf({{0, "SECTION"}, {2, "ENTITIES"},
                                        {0, "ARC"}, {8, "0"}, {10, "80"}, {20, "0"}, {40, "10"}, {50, "270"}, {51, "90"},
                                        {0, "LINE"}, {8, "0"}, {10, "0"}, {20, "10"}, {11, "80"}, {21, "10"},
                                        {0, "LINE"}, {8, "0"}, {10, "0"}, {20, "-10"}, {11, "80"}, {21, "-10"},
                                        {0, "ARC"}, {8, "0"}, {10, "0"}, {20, "0"}, {40, "10"}, {50, "90"}, {51, "270"},
                                        {0, "CIRCLE"}, {8, "0"}, {10, "80"}, {20, "0"}, {40, "5"},
                                        {0, "ENDSEC"}, {0, "EOF"}});

double slot_area() { return 80 * 20 + kPi * 100 - kPi * 25; }

TEST(DxfReader, LinesAndArcsChainIntoTheOutline) {
  const Region r = read_dxf_plate(kSlotLinesArcs, "slot.dxf", 1e-3);
  ASSERT_NO_THROW(check_region(r));
  ASSERT_EQ(r.outline.size(), 4u);
  EXPECT_EQ(r.circle_holes.size(), 1u);
  const AreaProperties a = area_properties(r);
  EXPECT_NEAR(a.area, slot_area(), 1e-9);
  EXPECT_NEAR(a.centroid.x(), (1600 * 40 + kPi * 100 * 40 - kPi * 25 * 80) / slot_area(), 1e-9);
}

TEST(DxfReader, LwpolylineWithBulgesAndUnits) {
  // The same slot as one closed LWPOLYLINE in centimetres ($INSUNITS 5), read into mm.
  const std::string text = dxf({{0, "SECTION"}, {2, "HEADER"}, {9, "$INSUNITS"}, {70, "5"}, {0, "ENDSEC"},
                                {0, "SECTION"}, {2, "ENTITIES"},
                                {0, "LWPOLYLINE"}, {8, "plate"}, {90, "4"}, {70, "1"},
                                {10, "0"}, {20, "-1"}, {10, "8"}, {20, "-1"}, {42, "1"}, {10, "8"}, {20, "1"},
                                {10, "0"}, {20, "1"}, {42, "1.0"},
                                {0, "LINE"}, {8, "notes"}, {10, "0"}, {20, "0"}, {11, "1"}, {21, "0"},
                                {0, "ENDSEC"}, {0, "EOF"}});
  const Region r = read_dxf_plate(text, "slot.dxf", 1e-3, "PLATE");  // the layer "notes" is left out
  ASSERT_NO_THROW(check_region(r));
  EXPECT_NEAR(area_properties(r).area, 80 * 20 + kPi * 100, 1e-9);
  EXPECT_THROW(read_dxf_plate(text, "slot.dxf", 1e-3), ModelFileError);  // with the stray line: an open loop
}

TEST(DxfReader, BadFilesAtTheirLine) {
  const auto message = [](const std::string& text) {
    try {
      read_dxf_plate(text, "bad.dxf", 1e-3);
    } catch (const ModelFileError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  // An open outline: the last LINE (line 17) ends where nothing starts.
  EXPECT_THAT(message(dxf({{0, "SECTION"}, {2, "ENTITIES"},
                           {0, "LINE"}, {10, "0"}, {20, "0"}, {11, "10"}, {21, "0"},
                           {0, "LINE"}, {10, "10"}, {20, "0"}, {11, "10"}, {21, "10"},
                           {0, "ENDSEC"}, {0, "EOF"}})),
              HasSubstr("bad.dxf:15:1: the outline is not closed: the entity here ends at (10, 10)"));
  // A group code that is not a number: the pairs are out of step.
  // A LINE whose x value (line 8) is missing: the pairs run out of step until ENDSEC lands on a code.
  EXPECT_THAT(message("0\nSECTION\n2\nENTITIES\n0\nLINE\n10\n20\n0\n11\n10\n21\n0\n0\nENDSEC\n0\nEOF\n"),
              HasSubstr("bad.dxf:15:1: a DXF group code (an integer) was expected here, not 'ENDSEC'"));
  EXPECT_THAT(message("0\nSECTION\n2\nENTITIES\n0\nLINE\n10\n"), HasSubstr("bad.dxf:7:1: group code 10 has no value"));
  EXPECT_THAT(message(dxf({{0, "SECTION"}, {2, "ENTITIES"}, {0, "3DFACE"}, {0, "ENDSEC"}, {0, "EOF"}})),
              HasSubstr("bad.dxf:5:1: nbar reads LINE, ARC, CIRCLE, LWPOLYLINE, POLYLINE, SPLINE, ELLIPSE and POINT entities, not 3DFACE"));
  EXPECT_THAT(message(dxf({{0, "SECTION"}, {2, "ENTITIES"}, {0, "CIRCLE"}, {10, "x"}, {20, "0"}, {40, "1"},
                           {0, "ENDSEC"}, {0, "EOF"}})),
              HasSubstr("bad.dxf:8:1: group 10 needs a finite number, not 'x'"));
  EXPECT_THAT(message(dxf({{0, "SECTION"}, {2, "ENTITIES"}, {0, "ENDSEC"}})), HasSubstr("ends without EOF"));
  EXPECT_THAT(message(dxf({{0, "SECTION"}, {2, "ENTITIES"}, {0, "ENDSEC"}, {0, "EOF"}})), HasSubstr("no closed outline"));
}

class TempDir {
 public:
  TempDir() : dir_(std::filesystem::temp_directory_path() / ("nbar_dxf_" + std::to_string(::getpid()))) {
    std::filesystem::create_directories(dir_);
  }
  ~TempDir() { std::filesystem::remove_all(dir_); }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream((dir_ / name).string()) << text;
    return (dir_ / name).string();
  }

 private:
  std::filesystem::path dir_;
};

const std::string kCrank =
    "units: {length: mm}\n"                                       // 1
    "points: {O: [0, 0], A: [80, 0]}\n"                           // 2
    "ground: [O]\n"                                               // 3
    "bodies:\n"                                                   // 4
    "  crank:\n"                                                  // 5
    "    points: [O, A]\n"                                        // 6
    "    thickness: 8\n"                                          // 7
    "    material: steel\n"                                       // 8
    "    shape:\n";                                               // 9

TEST(DxfReader, RoundTripThroughTheCuttingDxf) {
  TempDir dir;
  const Model drawn = parse_model(kCrank +
                                      "      outline: [[0, -10], [80, -10, {bulge: 1}], [80, 10], [0, 10, {bulge: 1}]]\n"
                                      "      holes: [{at: O, radius: 5}, {at: A, radius: 5},\n"
                                      "              {polygon: [[30, -4], [50, -4, {bulge: 0.5}], [50, 4], [30, 4]]}]\n"
                                      "drivers: [{angle: crank, from: 0, to: 360}]\n",
                                  "m.yaml")
                          .model;
  const Mechanism mech(drawn);
  std::vector<Eigen::Vector2d> points;
  for (const Point& p : drawn.points) points.push_back(p.position);
  dir.write("crank.dxf", cutting_dxf(mech, points));
  const std::string path = dir.write("imported.yaml", kCrank + "      import: crank.dxf\n      layer: crank\n"
                                                               "drivers: [{angle: crank, from: 0, to: 360}]\n");
  const Model imported = load_model_file(path).model;
  const AreaProperties a = area_properties(*drawn.bodies[0].shape), b = area_properties(*imported.bodies[0].shape);
  EXPECT_NEAR(b.area, a.area, 1e-15);
  EXPECT_NEAR(b.centroid.x(), a.centroid.x(), 1e-15);
  EXPECT_NEAR(b.centroid.y(), a.centroid.y(), 1e-15);
  EXPECT_NEAR(b.polar(), a.polar(), 1e-20);
  EXPECT_EQ(imported.bodies[0].shape->circle_holes.size(), 2u);
  EXPECT_EQ(imported.bodies[0].shape->polygon_holes.size(), 1u);

  // From text (as the web server parses), a model may not open files.
  try {
    parse_model(kCrank + "      import: crank.dxf\n", "m.yaml");
    FAIL() << "imported from text";
  } catch (const ModelFileError& e) {
    EXPECT_THAT(e.what(), HasSubstr("m.yaml:10:15: `import` reads a file, which only a model read from a file may do"));
  }
  // An open loop in the imported file is reported in that file.
  dir.write("open.dxf", dxf({{0, "SECTION"}, {2, "ENTITIES"}, {0, "LINE"}, {10, "0"}, {20, "0"}, {11, "10"}, {21, "0"},
                             {0, "ENDSEC"}, {0, "EOF"}}));
  const std::string bad = dir.write("bad.yaml", kCrank + "      import: open.dxf\n");
  try {
    load_model_file(bad);
    FAIL() << "imported an open outline";
  } catch (const ModelFileError& e) {
    EXPECT_THAT(e.what(), HasSubstr("open.dxf:5:1: the outline is not closed"));
  }
}

// The same round trip through the SVG of `nbar export --svg`, in a pose (--at): arcs come
// back as arcs (SVG A commands), the size in mm over the viewBox gives the unit back, and the
// plate is the drawn one moved rigidly.
TEST(DxfReader, RoundTripThroughTheSvg) {
  TempDir dir;
  const std::string model = "      outline: [[0, -10], [80, -10, {bulge: 1}], [80, 10], [0, 10, {bulge: 1}]]\n"
                            "      holes: [{at: O, radius: 5}, {at: A, radius: 5},\n"
                            "              {polygon: [[30, -4], [50, -4, {bulge: 0.5}], [50, 4], [30, 4]]}]\n"
                            "drivers: [{angle: crank, from: 0, to: 360}]\n";
  const Model drawn = parse_model(kCrank + model, "m.yaml").model;
  const Mechanism mech(drawn);
  std::vector<Eigen::Vector2d> points;
  for (const Point& p : drawn.points) points.push_back(p.position);
  dir.write("crank.svg", cutting_svg(mech, points));
  const std::string path = dir.write("imported.yaml", kCrank + "      import: crank.svg\n      layer: crank\n"
                                                               "drivers: [{angle: crank, from: 0, to: 360}]\n");
  const Model imported = load_model_file(path).model;
  const AreaProperties a = area_properties(*drawn.bodies[0].shape), b = area_properties(*imported.bodies[0].shape);
  EXPECT_NEAR(b.area, a.area, 1e-15);
  // SVG's y runs down and the export turns it, the import turns it back.
  EXPECT_NEAR(b.centroid.x(), a.centroid.x(), 1e-14);
  EXPECT_NEAR(b.centroid.y(), a.centroid.y(), 1e-14);
  EXPECT_NEAR(b.polar(), a.polar(), 1e-19);
  EXPECT_EQ(imported.bodies[0].shape->circle_holes.size(), 2u);
  EXPECT_EQ(imported.bodies[0].shape->polygon_holes.size(), 1u);
  // In a model in metres the same file reads in metres: its size is stated in mm.
  const std::string metres = dir.write(
      "metres.yaml", "units: {length: m}\npoints: {O: [0, 0], A: [0.08, 0]}\nground: [O]\nbodies:\n  crank:\n"
                     "    points: [O, A]\n    thickness: 0.008\n    material: steel\n    shape: {import: crank.svg}\n"
                     "drivers: [{angle: crank, from: 0, to: 360}]\n");
  EXPECT_NEAR(area_properties(*load_model_file(metres).model.bodies[0].shape).area, a.area, 1e-15);
}

}  // namespace
}  // namespace nbar::io
