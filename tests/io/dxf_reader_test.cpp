// Plates read from DXF drawings: hand-written files as CAD programs write them (LINE and ARC
// in any order and direction, LWPOLYLINE with bulges, units), the round trip through
// nbar's own cutting DXF, and bad files reported at their line.
#include "nbar/io/dxf_reader.hpp"
#include "nbar/io/dxf_writer.hpp"
#include "nbar/io/model_file.hpp"
#include "nbar/io/sketch.hpp"
#include "nbar/model/diagnostics.hpp"
#include "test_constants.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

// The DXF group lists are laid out one entity per line, as a DXF file reads.
// clang-format off
namespace nbar::io {
namespace {

using nbar::test_constants::kPi;
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

// The entities between an ENTITIES section's head and the file's end.
std::string entities(const std::string& body) {
  return dxf({{0, "SECTION"}, {2, "ENTITIES"}}) + body + dxf({{0, "ENDSEC"}, {0, "EOF"}});
}

std::string error_of(const std::string& text) {
  try {
    read_dxf_plate(text, "bad.dxf", 1e-3);
  } catch (const ModelFileError& e) {
    return e.what();
  }
  return "no error";
}

TEST(DxfReader, BinaryGarbageIsQuotedShortAndEscaped) {
  // A file of random bytes: its first "group code" went into the message as it was, 200 bytes
  // of binary to the terminal.
  std::string garbage = "\xa8]";
  for (int i = 0; i < 300; ++i) garbage += static_cast<char>((i * 37 + 11) % 256 == 10 ? 1 : (i * 37 + 11) % 256);
  const std::string message = error_of(garbage + "\n0\n");
  EXPECT_THAT(message, HasSubstr("bad.dxf:1:1: a DXF group code (an integer) was expected here, not '\\xa8]"));
  EXPECT_THAT(message, HasSubstr("...': the group-code/value pairs are broken"));
  EXPECT_LT(message.size(), 300u);
  for (const char c : message) EXPECT_TRUE(c >= 0x20 && c < 0x7f) << static_cast<int>(static_cast<unsigned char>(c));
}

// Entities drawn in their own coordinate system with the extrusion (0, 0, -1), as SolidWorks
// writes them: OCS x is -x of the drawing, so each is drawn here at negated x and must come
// back where the plain drawing has it, not mirrored.
TEST(DxfReader, ExtrusionDownwardsMirrorsTheOcs) {
  // An L: 60 x 20 along x and 20 x 40 above its left end; area 2000, centroid
  // ((1200 * 30 + 800 * 10) / 2000, the same in y) = (22, 22).
  const std::string l_shape =
      dxf({{0, "LWPOLYLINE"}, {8, "0"}, {90, "6"}, {70, "1"}, {210, "0"}, {220, "0"}, {230, "-1"},
           {10, "0"}, {20, "0"}, {10, "-60"}, {20, "0"}, {10, "-60"}, {20, "20"}, {10, "-20"}, {20, "20"},
           {10, "-20"}, {20, "60"}, {10, "0"}, {20, "60"}});
  const AreaProperties l = area_properties(read_dxf_plate(entities(l_shape), "l.dxf", 1e-3));
  EXPECT_NEAR(l.area, 2000, 1e-9);
  EXPECT_NEAR(l.centroid.x(), 22, 1e-12);
  EXPECT_NEAR(l.centroid.y(), 22, 1e-12);
  // The same L as an R12 POLYLINE, its bulge on the top edge: a half disc of radius 10 bulging
  // up over x 0..20 (OCS x 0..-20, drawn clockwise there, so its bulge is -1).
  const std::string r12 =
      dxf({{0, "POLYLINE"}, {8, "0"}, {66, "1"}, {70, "1"}, {210, "0"}, {220, "0"}, {230, "-1"},
           {0, "VERTEX"}, {10, "0"}, {20, "0"}, {0, "VERTEX"}, {10, "-60"}, {20, "0"},
           {0, "VERTEX"}, {10, "-60"}, {20, "20"}, {0, "VERTEX"}, {10, "-20"}, {20, "20"},
           {0, "VERTEX"}, {10, "-20"}, {20, "60"}, {42, "-1"}, {0, "VERTEX"}, {10, "0"}, {20, "60"}, {0, "SEQEND"}});
  const AreaProperties p = area_properties(read_dxf_plate(entities(r12), "p.dxf", 1e-3));
  const double half_disc = kPi * 100 / 2;
  EXPECT_NEAR(p.area, 2000 + half_disc, 1e-9);
  EXPECT_NEAR(p.centroid.x(), (2000 * 22 + half_disc * 10) / (2000 + half_disc), 1e-12);
  EXPECT_NEAR(p.centroid.y(), (2000 * 22 + half_disc * (60 + 40 / (3 * kPi))) / (2000 + half_disc), 1e-12);

  // A 100 x 40 plate about the origin with a hole of radius 10 at (30, 0): centroid
  // x = -(100 pi * 30) / (4000 - 100 pi) = -2.557.
  const std::string plate_with_hole =
      dxf({{0, "LWPOLYLINE"}, {8, "0"}, {90, "4"}, {70, "1"}, {10, "-50"}, {20, "-20"}, {10, "50"}, {20, "-20"},
           {10, "50"}, {20, "20"}, {10, "-50"}, {20, "20"},
           {0, "CIRCLE"}, {8, "0"}, {10, "-30"}, {20, "0"}, {40, "10"}, {210, "0"}, {220, "0"}, {230, "-1"}});
  const AreaProperties c = area_properties(read_dxf_plate(entities(plate_with_hole), "c.dxf", 1e-3));
  EXPECT_NEAR(c.centroid.x(), -100 * kPi * 30 / (4000 - 100 * kPi), 1e-12);
  EXPECT_NEAR(c.centroid.x(), -2.557, 1e-3);

  // The slot of kSlotLinesArcs with its right end an OCS arc: centre (-80, 0) and 90 to 270
  // degrees there are (80, 0) and -90 to 90 degrees here.
  const std::string slot =
      dxf({{0, "LINE"}, {10, "0"}, {20, "-10"}, {11, "80"}, {21, "-10"},
           {0, "ARC"}, {10, "-80"}, {20, "0"}, {40, "10"}, {50, "90"}, {51, "270"}, {210, "0"}, {220, "0"}, {230, "-1"},
           {0, "LINE"}, {10, "80"}, {20, "10"}, {11, "0"}, {21, "10"},
           {0, "ARC"}, {10, "0"}, {20, "0"}, {40, "10"}, {50, "90"}, {51, "270"},
           {0, "CIRCLE"}, {10, "80"}, {20, "0"}, {40, "5"}});
  const AreaProperties a = area_properties(read_dxf_plate(entities(slot), "a.dxf", 1e-3));
  EXPECT_NEAR(a.area, slot_area(), 1e-9);
  EXPECT_NEAR(a.centroid.x(), (1600 * 40 + kPi * 100 * 40 - kPi * 25 * 80) / slot_area(), 1e-9);

  // The lower half of the ellipse with semi-axes 50 and 25 closed by its diameter: the major
  // axis (-50, 0) is in the drawing's coordinates, the minor is the extrusion x the major,
  // (0, 25), so the parameters pi..2 pi run below the axis: centroid y = -4 * 25 / (3 pi) = -10.61.
  const std::string half_ellipse =
      dxf({{0, "ELLIPSE"}, {10, "0"}, {20, "0"}, {11, "-50"}, {21, "0"}, {210, "0"}, {220, "0"}, {230, "-1"},
           {40, "0.5"}, {41, "3.141592653589793"}, {42, "6.283185307179586"},
           {0, "LINE"}, {10, "-50"}, {20, "0"}, {11, "50"}, {21, "0"}});
  const AreaProperties e = area_properties(read_dxf_plate(entities(half_ellipse), "e.dxf", 1e-3));
  EXPECT_NEAR(e.area, kPi * 50 * 25 / 2, 1e-3 * e.area);  // polygonised within 1e-4 of the size
  EXPECT_NEAR(e.centroid.y(), -4 * 25 / (3 * kPi), 1e-2);
  EXPECT_NEAR(e.centroid.x(), 0, 1e-9);
}

TEST(DxfReader, ExtrusionOutOfThePlaneIsAnError) {
  // Tilted about y: the circle is an ellipse in the plane, which nbar will not guess.
  EXPECT_THAT(error_of(entities(dxf({{0, "CIRCLE"}, {10, "0"}, {20, "0"}, {40, "10"},
                                     {210, "0.6"}, {220, "0"}, {230, "0.8"}}))),
              HasSubstr("bad.dxf:13:1: this CIRCLE's extrusion direction (groups 210, 220, 230) (0.6, 0, 0.8) puts "
                        "it out of the drawing plane"));
  // Within rounding of (0, 0, -1), unnormalised, is (0, 0, -1).
  const std::string round_hole =
      dxf({{0, "LWPOLYLINE"}, {90, "4"}, {70, "1"}, {10, "0"}, {20, "0"}, {10, "10"}, {20, "0"},
           {10, "10"}, {20, "10"}, {10, "0"}, {20, "10"},
           {0, "CIRCLE"}, {10, "-3"}, {20, "5"}, {40, "1"}, {210, "1e-17"}, {220, "0"}, {230, "-2"}});
  EXPECT_EQ(read_dxf_plate(entities(round_hole), "r.dxf", 1e-3).circle_holes.at(0).centre.x(), 3);
  EXPECT_THAT(error_of(entities(dxf({{0, "CIRCLE"}, {10, "0"}, {20, "0"}, {40, "10"},
                                     {210, "0"}, {220, "0"}, {230, "0"}}))),
              HasSubstr("bad.dxf:13:1: this CIRCLE's extrusion direction"));
}

// A rounded 1 x 0.5 rectangle (corner radius 0.1) with holes of radius 0.05 and 0.08, in the
// unit $INSUNITS `code` states.
std::string rounded_plate(const std::string& code) {
  return dxf({{0, "SECTION"}, {2, "HEADER"}, {9, "$INSUNITS"}, {70, code}, {0, "ENDSEC"}}) +
         entities(dxf({{0, "LWPOLYLINE"}, {90, "8"}, {70, "1"},
                       {10, "0.1"}, {20, "0"}, {10, "0.9"}, {20, "0"}, {42, "0.41421356237309503"},
                       {10, "1"}, {20, "0.1"}, {10, "1"}, {20, "0.4"}, {42, "0.41421356237309503"},
                       {10, "0.9"}, {20, "0.5"}, {10, "0.1"}, {20, "0.5"}, {42, "0.41421356237309503"},
                       {10, "0"}, {20, "0.4"}, {10, "0"}, {20, "0.1"}, {42, "0.41421356237309503"},
                       {0, "CIRCLE"}, {10, "0.2"}, {20, "0.25"}, {40, "0.05"},
                       {0, "CIRCLE"}, {10, "0.75"}, {20, "0.3"}, {40, "0.08"}}));
}

TEST(DxfReader, EveryInsunitsCode) {
  // In decimetres read into mm: 100 x 50 less the four corners' (4 - pi) 10^2 and the holes
  // pi (5^2 + 8^2): 4634.56 mm^2.
  const double area_mm2 = 5000 - (4 - kPi) * 100 - kPi * (25 + 64);
  EXPECT_NEAR(area_properties(read_dxf_plate(rounded_plate("14"), "dm.dxf", 1e-3)).area, area_mm2, 1e-9);
  EXPECT_NEAR(area_mm2, 4634.56, 5e-3);
  const std::vector<std::pair<std::string, double>> metres = {
      {"3", 1609.344}, {"7", 1000}, {"8", 2.54e-8}, {"9", 2.54e-5}, {"10", 0.9144}, {"11", 1e-10},
      {"12", 1e-9}, {"13", 1e-6}, {"14", 0.1}, {"15", 10}, {"16", 100}, {"17", 1e9}, {"18", 149597870700},
      {"19", 9460730472580800}, {"20", 3.0856775814913673e16}, {"21", 1200.0 / 3937}};
  for (const auto& [code, m] : metres) {
    EXPECT_DOUBLE_EQ(*read_sketch(rounded_plate(code), "u.dxf", SketchFormat::kDxf).metres_per_unit, m) << code;
  }
  EXPECT_FALSE(read_sketch(rounded_plate("0"), "u.dxf", SketchFormat::kDxf).metres_per_unit);
  EXPECT_THAT(error_of(rounded_plate("22")), HasSubstr("bad.dxf:8:1: $INSUNITS 22 is no DXF unit"));
}

TEST(DxfReader, PaperSpaceAndViewportsAreLeftOut) {
  // A 100 x 40 plate with two pin holes in model space; a sheet's frame, a title block and a
  // viewport onto the model in paper space.
  const std::string model_space =
      dxf({{0, "LWPOLYLINE"}, {8, "0"}, {90, "4"}, {70, "1"}, {10, "0"}, {20, "0"}, {10, "100"}, {20, "0"},
           {10, "100"}, {20, "40"}, {10, "0"}, {20, "40"},
           {0, "CIRCLE"}, {10, "20"}, {20, "20"}, {40, "5"}, {0, "CIRCLE"}, {10, "80"}, {20, "20"}, {40, "5"}});
  const std::string paper_space =
      dxf({{0, "VIEWPORT"}, {67, "1"}, {8, "0"}, {10, "148.5"}, {20, "105"}, {40, "297"}, {41, "210"}, {69, "1"},
           {0, "VIEWPORT"}, {8, "0"}, {10, "148.5"}, {20, "105"}, {40, "297"}, {41, "210"}, {69, "2"},
           {0, "LINE"}, {67, "1"}, {10, "0"}, {20, "0"}, {11, "420"}, {21, "0"},
           {0, "LINE"}, {67, "1"}, {10, "420"}, {20, "0"}, {11, "420"}, {21, "297"},
           {0, "LINE"}, {67, "1"}, {10, "420"}, {20, "297"}, {11, "0"}, {21, "297"},
           {0, "LINE"}, {67, "1"}, {10, "0"}, {20, "297"}, {11, "0"}, {21, "0"},
           {0, "LWPOLYLINE"}, {67, "1"}, {90, "4"}, {70, "1"}, {10, "300"}, {20, "100"}, {10, "350"}, {20, "100"},
           {10, "350"}, {20, "120"}, {10, "300"}, {20, "120"},
           {0, "POLYLINE"}, {67, "1"}, {66, "1"}, {70, "1"}, {0, "VERTEX"}, {67, "1"}, {10, "300"}, {20, "200"},
           {0, "VERTEX"}, {67, "1"}, {10, "310"}, {20, "200"}, {0, "VERTEX"}, {67, "1"}, {10, "310"}, {20, "210"},
           {0, "SEQEND"}, {67, "1"}});
  const Region r = read_dxf_plate(entities(paper_space + model_space), "sheet.dxf", 1e-3);
  EXPECT_TRUE(r.polygon_holes.empty());
  EXPECT_EQ(r.circle_holes.size(), 2u);
  EXPECT_NEAR(area_properties(r).area, 4000 - 2 * kPi * 25, 1e-9);
  EXPECT_NEAR(area_properties(r).centroid.x(), 50, 1e-12);
}

TEST(DxfReader, ByteOrderMarkBinaryDxfAndAWholeArc) {
  // A disc of radius 10 about (50, 0) drawn as an ARC from 0 to 360 degrees, with a pin hole of
  // radius 3: pi (100 - 9).
  const std::string disc = entities(dxf({{0, "ARC"}, {10, "50"}, {20, "0"}, {40, "10"}, {50, "0"}, {51, "360"},
                                         {0, "CIRCLE"}, {10, "50"}, {20, "0"}, {40, "3"}}));
  const Region r = read_dxf_plate("\xEF\xBB\xBF" + disc, "bom.dxf", 1e-3);
  EXPECT_NEAR(area_properties(r).area, kPi * 91, 1e-9);
  EXPECT_NEAR(area_properties(r).centroid.x(), 50, 1e-12);
  EXPECT_EQ(r.circle_holes.size(), 1u);
  // The same arc inside a square is a round hole (exact, as bulges), and reversed (360 to 0) too.
  for (const std::string& angles : {std::string("0\n51\n360"), std::string("360\n51\n0")}) {
    const std::string arc_hole = "0\nARC\n10\n50\n20\n0\n40\n10\n50\n" + angles + "\n";
    const Region square = read_dxf_plate(
        entities(dxf({{0, "LWPOLYLINE"}, {90, "4"}, {70, "1"}, {10, "30"}, {20, "-20"}, {10, "70"}, {20, "-20"},
                      {10, "70"}, {20, "20"}, {10, "30"}, {20, "20"}}) + arc_hole),
        "hole.dxf", 1e-3);
    EXPECT_NEAR(area_properties(square).area, 1600 - kPi * 100, 1e-9) << angles;
  }
  EXPECT_THAT(error_of(std::string("AutoCAD Binary DXF\r\n\x1a") + '\0' + "SECTION"),
              HasSubstr("bad.dxf:1:1: binary DXF is not supported: save the drawing as ASCII DXF"));
}

TEST(DxfReader, SplineFitPolylineLeavesItsFrameOut) {
  // An R12 spline-fit POLYLINE (flag 4): the fitted vertices (flag 8) make an octagon, then the
  // frame's control points (flag 16) a 100 x 50 rectangle about it. The octagon: the rectangle
  // 80 x 40 from (10, 5), triangles of base 80 and height 3 below and above, of base 40 and
  // height 7 left and right: 3200 + 2 * 120 + 2 * 140 = 3720.
  std::string polyline = dxf({{0, "POLYLINE"}, {66, "1"}, {70, "5"}, {75, "6"}});
  for (const auto& [x, y] : std::vector<std::pair<int, int>>{{10, 5}, {50, 2}, {90, 5}, {97, 25}, {90, 45}, {50, 48},
                                                              {10, 45}, {3, 25}}) {
    polyline += dxf({{0, "VERTEX"}, {10, std::to_string(x)}, {20, std::to_string(y)}, {70, "8"}});
  }
  for (const auto& [x, y] : std::vector<std::pair<int, int>>{{0, 0}, {100, 0}, {100, 50}, {0, 50}}) {
    polyline += dxf({{0, "VERTEX"}, {10, std::to_string(x)}, {20, std::to_string(y)}, {70, "16"}});
  }
  polyline += dxf({{0, "SEQEND"}});
  const Region r = read_dxf_plate(entities(polyline), "fit.dxf", 1e-3);
  EXPECT_EQ(r.outline.size(), 8u);
  EXPECT_NEAR(area_properties(r).area, 3720, 1e-9);
  EXPECT_NEAR(area_properties(r).centroid.x(), 50, 1e-12);
}

TEST(DxfReader, ABowTiePolylineCrossesItselfAtAPoint) {
  // One closed LWPOLYLINE (line 5) drawn (0, 0), (100, 40), (100, 0), (0, 40): its diagonals
  // cross at (50, 20).
  EXPECT_THAT(error_of(entities(dxf({{0, "LWPOLYLINE"}, {90, "4"}, {70, "1"}, {10, "0"}, {20, "0"}, {10, "100"},
                                     {20, "40"}, {10, "100"}, {20, "0"}, {10, "0"}, {20, "40"}}))),
              HasSubstr("bad.dxf:5:1: the outline crosses itself at (50, 20), within the entity here"));
}

// A drawing far below the precision of the arithmetic: its points would merge into an outline
// of "1 vertex"; the message says that the drawing is too small, and how small.
TEST(DxfReader, ADrawingTooSmallToComputeWithSaysSo) {
  EXPECT_THAT(error_of(entities(dxf({{0, "LWPOLYLINE"}, {90, "4"}, {70, "1"}, {10, "0"}, {20, "0"}, {10, "3e-200"},
                                     {20, "0"}, {10, "3e-200"}, {20, "4e-200"}, {10, "0"}, {20, "4e-200"}}))),
              HasSubstr("bad.dxf:5:1: the drawing is too small to compute with: it spans 5e-200 (the diagonal of its "
                        "bounding box, in the drawing's units), below 1e-100, where its points merge; scale it up"));
  // The same plate 1e-90 the size is still read.
  EXPECT_EQ(error_of(entities(dxf({{0, "LWPOLYLINE"}, {90, "4"}, {70, "1"}, {10, "0"}, {20, "0"}, {10, "3e-90"},
                                   {20, "0"}, {10, "3e-90"}, {20, "4e-90"}, {10, "0"}, {20, "4e-90"}}))),
            "no error");
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

// Bodies whose layer names differ only in case once their characters are replaced: the SVG's
// group ids are the DXF layers, so `layer:` picks the same plate from either file.
TEST(DxfReader, SvgGroupIdsAreTheDxfLayers) {
  const Model m = parse_model(
                      "units: {length: mm}\npoints: {O: [0, 0], A: [80, 0], C: [0, 80], B: [50, 80]}\nground: [O, C]\n"
                      "bodies:\n"
                      "  crank arm: {points: [O, A], thickness: 5, material: steel, bar: {width: 20, hole: 5}}\n"
                      "  Crank/arm: {points: [C, B], thickness: 5, material: steel, bar: {width: 10, hole: 2}}\n"
                      "drivers: [{angle: crank arm, from: 0, to: 360}, {angle: Crank/arm, from: 0, to: 360}]\n",
                      "two.yaml")
                      .model;
  const Mechanism mech(m);
  std::vector<Eigen::Vector2d> points;
  for (const Point& p : m.points) points.push_back(p.position);
  const std::string svg = cutting_svg(mech, points);
  EXPECT_THAT(svg, HasSubstr("<g id=\"crank_arm\">"));
  EXPECT_THAT(svg, HasSubstr("<g id=\"Crank_arm_2\">"));
  const auto area_of = [&](const std::string& layer) {
    return area_properties(plate_from_sketch(read_sketch(svg, "two.svg", SketchFormat::kSvg, layer), 1.0)).area;
  };
  // A bar w wide over L with margins w/2 and two holes r: w (L + w) - 2 pi r^2.
  EXPECT_NEAR(area_of("Crank_arm_2"), 10 * 60 - 2 * kPi * 4, 1e-9);
  EXPECT_NEAR(area_of("crank_arm"), 20 * 100 - 2 * kPi * 25, 1e-9);
  EXPECT_NEAR(area_of("CRANK_ARM"), 20 * 100 - 2 * kPi * 25, 1e-9);
  // A drawing of someone else's whose groups differ only in case: `layer` cannot tell them apart.
  try {
    read_sketch("<svg>\n<g id=\"Crank\"><rect width=\"10\" height=\"5\"/></g>\n"
                "<g id=\"crank\"><rect width=\"20\" height=\"5\"/></g>\n</svg>\n",
                "case.svg", SketchFormat::kSvg, "crank");
    ADD_FAILURE() << "two groups were read as one layer";
  } catch (const ModelFileError& e) {
    EXPECT_THAT(e.what(), HasSubstr("case.svg:3:1: the groups 'Crank' (line 2) and 'crank' (here) both match the "
                                    "layer 'crank' (compared without case): rename one"));
  }
}

}  // namespace
}  // namespace nbar::io
// clang-format on
