// Sketches read from drawing files, against closed forms: hand-written fixtures laid out as
// LibreCAD (R12) and AutoCAD (R2000: LWPOLYLINE bulges, SPLINE, ELLIPSE) write DXF, as Inkscape
// writes SVG, and as the thesis tool's Inventor macro writes its CSV; bad files at their line.
#include "nbar/io/dxf_reader.hpp"
#include "nbar/io/model_file.hpp"
#include "nbar/io/sketch.hpp"
#include "nbar/io/sketch_model.hpp"
#include "nbar/model/curves.hpp"
#include "nbar/model/diagnostics.hpp"
#include "nbar/model/geometry.hpp"
#include "test_constants.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

namespace nbar::io {
namespace {

using nbar::test_constants::kPi;
using ::testing::HasSubstr;

std::string fixture(const std::string& name) {
  std::ifstream in(std::string(NBAR_SOURCE_DIR) + "/tests/io/sketches/" + name, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

Region plate(const std::string& name, double model_metres_per_unit, const std::string& layer = {}) {
  const Sketch sketch = read_sketch(fixture(name), name, *sketch_format(name), layer);
  return plate_from_sketch(sketch, sketch_scale(sketch, std::nullopt, model_metres_per_unit));
}

std::string error_of(const std::string& text, const std::string& name, const std::string& layer = {}) {
  try {
    read_sketch(text, name, *sketch_format(name), layer);
  } catch (const ModelFileError& e) {
    return e.what();
  }
  return "no error";
}

TEST(SketchImport, LibreCadR12LinesArcsCirclesOnALayer) {
  // Drawn in mm ($INSUNITS 4), read into a model in cm: the slot 80 x 20 with half-round ends
  // minus two pin holes of radius 5, exact (arcs stay arcs).
  const Region r = plate("librecad-r12-slot.dxf", 1e-2, "crank");
  const AreaProperties a = area_properties(r);
  EXPECT_NEAR(a.area, (1600 + 100 * kPi - 50 * kPi) * 1e-2, 1e-12);
  EXPECT_NEAR(a.centroid.x(), 4.0, 1e-14);
  EXPECT_EQ(r.circle_holes.size(), 2u);
  // Without the layer, the note's TEXT is left out: the same plate.
  const Sketch all = read_sketch(fixture("librecad-r12-slot.dxf"), "s.dxf", SketchFormat::kDxf);
  EXPECT_THAT(all.annotations, ::testing::ElementsAre("TEXT"));
  EXPECT_NEAR(area_properties(plate_from_sketch(all, 1e-1)).area, a.area, 1e-12);
}

TEST(SketchImport, AutoCadR2000LwpolylineEllipseAndSpline) {
  // The layer "slot": a closed LWPOLYLINE with bulges, two pin holes and an ELLIPSE hole of
  // semi-axes 10 and 4 (polygonised within 1e-4 of the drawing's size).
  const Region slot = plate("autocad-r2000-plates.dxf", 1e-3, "slot");
  const double tolerance = kRelativeCurveTolerance * std::hypot(90.0, 20.0);
  EXPECT_NEAR(area_properties(slot).area, 1600 + 100 * kPi - 50 * kPi - 40 * kPi, 2.0 / 3 * tolerance * 48.5);
  EXPECT_NEAR(area_properties(slot).centroid.x(), 40, 1e-9);
  ASSERT_EQ(slot.polygon_holes.size(), 1u);
  // The layer "plate2": a quarter disc of radius 10 whose arc is a rational quadratic SPLINE.
  const Region quarter = plate("autocad-r2000-plates.dxf", 1e-3, "plate2");
  const double t2 = kRelativeCurveTolerance * std::hypot(10.0, 10.0);
  EXPECT_NEAR(area_properties(quarter).area, 25 * kPi, 2.0 / 3 * t2 * 15.8);
  EXPECT_LT(25 * kPi - area_properties(quarter).area, 2.0 / 3 * t2 * 15.8);
  for (const Eigen::Vector2d& v : quarter.outline) {
    const double r = (v - Eigen::Vector2d(100, 0)).norm();
    if (v.x() > 100 + 1e-9 && v.y() > 1e-9) {
      EXPECT_NEAR(r, 10, 1e-12);  // vertices on the arc
    }
  }
}

TEST(SketchImport, InkscapeSvgPathsArcsBeziersAndUnits) {
  // width 100mm over a viewBox 100 wide: 1 user unit = 1 mm. The slot (arcs by A, exact), two
  // pin circles, and a window between a chord and a quadratic Bézier: 2/3 of its triangle,
  // 2/3 × (20 × 15 / 2) = 100 mm².
  const Region r = plate("inkscape-slot.svg", 1e-3, "crank");
  const AreaProperties a = area_properties(r);
  const double tolerance = kRelativeCurveTolerance * std::hypot(100.0, 20.0);
  EXPECT_NEAR(a.area, 1600 + 100 * kPi - 50 * kPi - 100, 2.0 / 3 * tolerance * 25);
  EXPECT_NEAR(a.centroid.x(), 50, 1e-6);
  // y turned up: the slot's centre line y = 25 in the SVG is y = -25.
  EXPECT_NEAR(r.circle_holes[0].centre.y(), -25, 1e-12);
  EXPECT_FALSE(r.outline_bulges.empty());
  // The unused path in <defs> is not read, nor the note's <text> in another group; without
  // the layer the <text> is left out as a note.
  const Sketch all = read_sketch(fixture("inkscape-slot.svg"), "s.svg", SketchFormat::kSvg);
  EXPECT_THAT(all.annotations, ::testing::ElementsAre("<text>"));
  EXPECT_NEAR(area_properties(plate_from_sketch(all, 1.0)).area, a.area, 1e-12);
}

// Each kind of SVG curve against its closed form (unitless: read in the model's unit).
TEST(SketchImport, SvgCurvesAgainstClosedForms) {
  const auto area = [](const std::string& svg) {
    const Sketch s = read_sketch(svg, "c.svg", SketchFormat::kSvg);
    return area_properties(plate_from_sketch(s, 1.0)).area;
  };
  const auto within = [](double size, double length) { return 2.0 / 3 * kRelativeCurveTolerance * size * length; };
  // A cubic from (0, 0) over controls (0, -10), (40, -10) to (40, 0), closed by its chord:
  // ∫ y dx = 18 h w ∫ t²(1 - t)² dt = 0.6 h w = 240 (relative c, s after it: the same shape).
  EXPECT_NEAR(area("<svg><path d=\"M 0 0 C 0 -10 40 -10 40 0 Z\"/></svg>"), 240, within(40, 45));
  EXPECT_NEAR(area("<svg><path d=\"m 0 0 c 0 -10 40 -10 40 0 z\"/></svg>"), 240, within(40, 45));
  // Half an ellipse of semi-axes 20 and 10 by an elliptical arc: 100π.
  EXPECT_NEAR(area("<svg><path d=\"M -20 0 A 20 10 0 0 1 20 0 Z\"/></svg>"), 100 * kPi, within(40, 50));
  // Half a circle of radius 20 by an arc: exact (a bulge).
  EXPECT_NEAR(area("<svg><path d=\"M -20 0 A 20 20 0 0 0 20 0 Z\"/></svg>"), 200 * kPi, 1e-10);
  EXPECT_NEAR(area("<svg><ellipse cx=\"3\" cy=\"4\" rx=\"5\" ry=\"3\"/></svg>"), 15 * kPi, within(10, 26));
  EXPECT_NEAR(area("<svg><rect x=\"1\" y=\"2\" width=\"30\" height=\"10\"/></svg>"), 300, 1e-12);
  EXPECT_NEAR(area("<svg><polygon points=\"0,0 10,0 10,10\"/></svg>"), 50, 1e-12);
  // H and V; a quadratic and its reflection by T (segments of ±2/3 of their triangles, 100
  // each, cancelling) over a 40 x 10 rectangle: 400.
  EXPECT_NEAR(area("<svg><path d=\"M 0 0 H 10 V 10 H 0 Z\"/></svg>"), 100, 1e-12);
  EXPECT_NEAR(area("<svg><path d=\"M 0 0 Q 10 -15 20 0 T 40 0 V 10 H 0 Z\"/></svg>"), 400, within(40, 100));
}

TEST(SketchImport, ThesisSketchCsv) {
  // Four New_Line entities chained into a 0.1 x 0.02 m rectangle, a New_Circle of points at
  // 0.01 rad steps (a pin hole of radius 4 mm) and two Point joints.
  const Sketch s = read_sketch(fixture("inventor-bar.csv"), "bar.csv", SketchFormat::kCsv);
  ASSERT_EQ(s.points.size(), 2u);
  EXPECT_EQ(s.points[1].at, Eigen::Vector2d(0.09, 0.01));
  ASSERT_EQ(s.circles.size(), 1u);
  EXPECT_NEAR(s.circles[0].circle.radius, 0.004, 1e-8);
  EXPECT_NEAR((s.circles[0].circle.centre - Eigen::Vector2d(0.01, 0.01)).norm(), 0, 1e-7);
  const Region r = plate_from_sketch(s, 1000);  // metres into a model in mm
  EXPECT_NEAR(area_properties(r).area, 2000 - kPi * 16, 1e-3);
  EXPECT_THAT(error_of("X, Y\nNew_Line\n0, 0\n1, zero\n", "b.csv"),
              HasSubstr("b.csv:4:1: a sketch CSV line is 'x, y'"));
  EXPECT_THAT(error_of("X, Y\n0, 0\n", "b.csv"), HasSubstr("b.csv:2:1: coordinates before the first 'New <name>'"));
  // A circle from three or four points on it (eight were needed; fewer said they were off a circle).
  for (const char* points : {"14, 10\n10, 14\n6, 10\n10, 6\n", "14, 10\n10, 14\n6, 10\n"}) {
    const Sketch few =
        read_sketch(std::string("X, Y\nNew_Circle\n") + points + "New_Line\n0, 0\n20, 0\n20, 20\n0, 20\n0, 0\n",
                    "c.csv", SketchFormat::kCsv);
    ASSERT_EQ(few.circles.size(), 1u) << points;
    EXPECT_NEAR(few.circles[0].circle.radius, 4, 1e-12);
    EXPECT_NEAR((few.circles[0].circle.centre - Eigen::Vector2d(10, 10)).norm(), 0, 1e-12);
  }
  EXPECT_THAT(error_of("X, Y\nNew_Circle\n14, 10\n10, 14\n", "c.csv"),
              HasSubstr("c.csv:2:1: the circle '_Circle' has 2 points; a circle needs at least 3"));
  EXPECT_THAT(error_of("X, Y\nNew_Circle\n0, 0\n1, 0\n2, 0\n", "c.csv"),
              HasSubstr("c.csv:2:1: the points of the circle '_Circle' do not lie on a circle"));
}

TEST(SketchImport, BadFilesAtTheirLine) {
  // An open loop: the last LINE stops short of the start.
  EXPECT_THAT(error_of("X, Y\nNew_Line\n0, 0\n10, 0\nNew_Line\n10, 0\n10, 10\nNew_Line\n10, 10\n0, 1\n", "o.csv"),
              HasSubstr("o.csv:8:1: the outline is not closed"));
  // A bow tie: the outline crosses itself at (5, 5), between the entities at lines 2 and 8.
  EXPECT_THAT(
      error_of("X, Y\nNew_A\n0, 0\n10, 10\nNew_B\n10, 10\n10, 0\nNew_C\n10, 0\n0, 10\nNew_D\n0, 10\n0, 0\n", "x.csv"),
      HasSubstr("x.csv:2:1: the outline crosses itself at (5, 5): the entity here meets the one at line 8"));
  EXPECT_THAT(error_of("<svg><path d=\"M 0 0 L 10 0 L 10 10 X\"/></svg>", "p.svg"),
              HasSubstr("p.svg:1:1: path data: unknown command 'X'"));
  EXPECT_THAT(error_of("<svg>\n<g transform=\"rotate(30)\">\n</g></svg>", "t.svg"),
              HasSubstr("t.svg:2:1: nbar applies only translate()"));
  EXPECT_THAT(error_of("<svg>\n<path d=\"M 0 0 L 10 0 L 10 10\"/>\n</svg>", "o.svg"),
              HasSubstr("o.svg:2:1: the outline is not closed"));
  EXPECT_THAT(error_of("<svg>\n<path d=\"M 0 0 L 10 0 L 10 10 z\">\n", "u.svg"), HasSubstr("still open"));
}

// A plate's holes that meet the outline or each other, or lie outside it, are errors at the
// line where the hole is drawn, naming the outline's line (they were errors at the model's
// `import:` line, naming "polygon hole 0", a number the drawing does not show).
TEST(SketchImport, PlateHoleErrorsAtTheirLine) {
  const auto error = [](const std::string& text) {
    try {
      checked_plate_from_sketch(read_sketch(text, "h.csv", SketchFormat::kCsv), 1.0, "h.csv");
    } catch (const ModelFileError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string outline = "X, Y\nNew_Plate\n0, 0\n100, 0\n100, 50\n0, 50\n0, 0\n";  // lines 2 to 7
  // A square hole touching the outline's bottom edge, drawn from line 8.
  EXPECT_THAT(error(outline + "New_Hole\n10, 0\n20, 0\n20, 10\n10, 10\n10, 0\n"),
              HasSubstr("h.csv:8:1: the hole drawn here meets the outline (the outline starts at line 2)"));
  // Two holes that overlap: the second is named by its line.
  EXPECT_THAT(
      error(outline + "New_A\n10, 10\n30, 10\n30, 30\n10, 30\n10, 10\n" +
            "New_B\n20, 20\n40, 20\n40, 40\n20, 40\n20, 20\n"),
      HasSubstr("h.csv:8:1: the hole drawn here and the one at line 14 overlap (the outline starts at line 2)"));
  // A plate with a hole well inside it is a plate.
  EXPECT_EQ(error(outline + "New_Hole\n10, 10\n20, 10\n20, 20\n10, 20\n10, 10\n"), "no error");
}

TEST(SketchImport, CrossingOutlinesAreRefusedAtTheirLine) {
  // Two plates that cross, and a small square inside both: it could be a hole of either.
  const std::string text =
      "X, Y\nNew_A\n0, 0\n10, 0\n10, 10\n0, 10\n0, 0\n"
      "New_B\n5, 1\n15, 1\n15, 9\n5, 9\n5, 1\n"
      "New_C\n6, 4\n7, 4\n7, 5\n6, 5\n6, 4\n";
  const Sketch sketch = read_sketch(text, "c.csv", SketchFormat::kCsv);
  ASSERT_EQ(sketch.loops.size(), 3u);
  try {
    model_from_sketch(sketch, {"c.csv", "mm", 1.0, 5.0, "steel"});
    ADD_FAILURE() << "crossing outlines were accepted";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("c.csv:14:1: this outline lies inside two outlines that cross (at lines 2 and 8)"));
  }
  // A plate with nothing to say how it moves.
  try {
    model_from_sketch(read_sketch("X, Y\nNew_A\n0, 0\n10, 0\n10, 10\n0, 0\n", "e.csv", SketchFormat::kCsv),
                      {"e.csv", "mm", 1.0, 5.0, "steel"});
    ADD_FAILURE() << "a plate without pins was accepted";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("e.csv:2:1: the outline here holds no pin hole"));
  }
}

// Two slotted links that overlap at their joint (100, 0): a along x, b up from the joint. Only
// wholly inside another is an outline a hole, whichever vertex either starts at.
TEST(SketchImport, LinksOverlappingAtAJointAreNoHoles) {
  const std::string a =
      "0\nLWPOLYLINE\n8\na\n90\n4\n70\n1\n10\n0\n20\n-10\n10\n100\n20\n-10\n42\n1\n"
      "10\n100\n20\n10\n10\n0\n20\n10\n42\n1\n"
      "0\nCIRCLE\n8\na\n10\n0\n20\n0\n40\n4\n0\nCIRCLE\n8\na\n10\n100\n20\n0\n40\n4\n";
  const std::string pins = "0\nCIRCLE\n8\nb\n10\n100\n20\n60\n40\n4\n0\nCIRCLE\n8\nb\n10\n100\n20\n0\n40\n4\n";
  // b starting at the joint's side (92, 0), inside a; and starting at (108, 60), outside it.
  const std::string b_inside =
      "0\nLWPOLYLINE\n8\nb\n90\n4\n70\n1\n10\n92\n20\n0\n42\n1\n10\n108\n20\n0\n"
      "10\n108\n20\n60\n42\n1\n10\n92\n20\n60\n";
  const std::string b_outside =
      "0\nLWPOLYLINE\n8\nb\n90\n4\n70\n1\n10\n108\n20\n60\n42\n1\n10\n92\n20\n60\n"
      "10\n92\n20\n0\n42\n1\n10\n108\n20\n0\n";
  for (const std::string& b : {b_inside, b_outside}) {
    const std::string text = "0\nSECTION\n2\nENTITIES\n" + a + b + pins + "0\nENDSEC\n0\nEOF\n";
    const std::string model =
        model_from_sketch(read_sketch(text, "i.dxf", SketchFormat::kDxf), {"i.dxf", "mm", 1.0, 5.0, "steel"});
    EXPECT_THAT(model, HasSubstr("2 links, 1 joint between links")) << b;
    EXPECT_THAT(model, HasSubstr("\n  a:\n    points: [P1, P2]")) << b;
    EXPECT_THAT(model, HasSubstr("\n  b:\n    points: [P2, P3]")) << b;
    EXPECT_THAT(model, ::testing::Not(HasSubstr("polygon:"))) << b;
    // Each plate is whole: a's slot less its two pins, pi 100 + 2000 - 2 pi 16 mm^2 (the model holds m^2).
    const Model m = parse_model(model + "drivers: [{angle: a, from: 0, to: 360}]\n", "i.yaml").model;
    EXPECT_NEAR(area_properties(*m.bodies[0].shape).area * 1e6, kPi * 100 + 2000 - 2 * kPi * 16, 1e-9) << b;
  }
  // A square wholly inside stays a hole: 20 x 20 less 4 x 4 about (10, 10), with a pin at (5, 5).
  const std::string holed = model_from_sketch(
      read_sketch("X, Y\nNew_A\n0, 0\n20, 0\n20, 20\n0, 20\n0, 0\nNew_H\n12, 8\n12, 12\n8, 12\n8, 8\n12, 8\n"
                  "Point\n5, 5\n",
                  "h.csv", SketchFormat::kCsv),
      {"h.csv", "mm", 1.0, 5.0, "steel"});
  EXPECT_THAT(holed, HasSubstr("1 link,"));
  EXPECT_THAT(holed, HasSubstr("        - polygon:\n"));
}

// Notes on a part's own layer, as sketches carry them: left out, and counted in the skeleton.
TEST(SketchImport, AnnotationsAreLeftOutWithANote) {
  const std::string text =
      "0\nSECTION\n2\nENTITIES\n"
      "0\nLWPOLYLINE\n8\nplate\n90\n4\n70\n1\n10\n0\n20\n0\n10\n100\n20\n0\n10\n100\n20\n40\n10\n0\n20\n40\n"
      "0\nCIRCLE\n8\nplate\n10\n20\n20\n20\n40\n5\n"
      "0\nTEXT\n8\nplate\n10\n0\n20\n0\n40\n2.5\n1\nhello\n"
      "0\nMTEXT\n8\nplate\n10\n0\n20\n50\n40\n2.5\n1\nsteel 5 mm\n"
      "0\nDIMENSION\n8\nplate\n10\n0\n20\n-10\n70\n0\n"
      "0\nTEXT\n8\nplate\n10\n50\n20\n0\n40\n2.5\n1\nA\n"
      "0\nENDSEC\n0\nEOF\n";
  const Sketch sketch = read_sketch(text, "notes.dxf", SketchFormat::kDxf);
  EXPECT_NEAR(area_properties(plate_from_sketch(sketch, 1.0)).area, 4000 - kPi * 25, 1e-9);
  EXPECT_THAT(model_from_sketch(sketch, {"notes.dxf", "mm", 1.0, 5.0, "steel"}),
              HasSubstr("# Left out of the sketch, as notes that draw no link: 1 DIMENSION, 1 MTEXT, 2 TEXT.\n"));
  const Sketch svg = read_sketch(
      "<svg>\n<rect width=\"10\" height=\"5\"/><circle cx=\"2\" cy=\"2\" r=\"1\"/>\n"
      "<text x=\"0\" y=\"0\">crank<tspan>arm</tspan></text>\n</svg>\n",
      "notes.svg", SketchFormat::kSvg);
  EXPECT_NEAR(area_properties(plate_from_sketch(svg, 1.0)).area, 50 - kPi, 1e-9);
  EXPECT_THAT(svg.annotations, ::testing::ElementsAre("<text>"));
  // A block is geometry nbar does not read: an error that says what to do in either use.
  EXPECT_THAT(error_of("0\nSECTION\n2\nENTITIES\n0\nINSERT\n2\nPLATE\n0\nENDSEC\n0\nEOF\n", "b.dxf"),
              HasSubstr("b.dxf:5:1: nbar reads LINE, ARC, CIRCLE, LWPOLYLINE, POLYLINE, SPLINE, ELLIPSE and POINT "
                        "entities, not INSERT: explode it into those or delete it"));
}

// Pin holes that overlap, or meet their plate's outline, were written into a model that `nbar
// check` then refused at a line of that model: they are refused here, at the circle's line.
TEST(SketchImport, PinHolesThatMeetAreRefusedAtTheCirclesLine) {
  const std::string plate =
      "0\nLWPOLYLINE\n8\np\n90\n4\n70\n1\n10\n0\n20\n0\n10\n100\n20\n0\n10\n100\n20\n20\n10\n0\n20\n20\n";
  const auto circle = [](int x, int r) { return fmt::format("0\nCIRCLE\n8\np\n10\n{}\n20\n10\n40\n{}\n", x, r); };
  const auto error = [&](const std::string& entities) {
    try {
      model_from_sketch(
          read_sketch("0\nSECTION\n2\nENTITIES\n" + entities + "0\nENDSEC\n0\nEOF\n", "p.dxf", SketchFormat::kDxf),
          {"p.dxf", "mm", 1.0, 5.0, "steel"});
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  // The plate is lines 5-28, the first circle 29-38, the second from 39.
  EXPECT_THAT(
      error(plate + circle(10, 4) + circle(12, 4)),
      HasSubstr("p.dxf:39:1: this pin hole (centre (12, 10), radius 4) overlaps the pin hole drawn at line 29"));
  EXPECT_THAT(error(plate + circle(10, 4) + circle(90, 15)),
              HasSubstr("p.dxf:39:1: this pin hole (centre (90, 10), radius 15) meets the outline drawn at line 5"));
  EXPECT_EQ(error(plate + circle(10, 4) + circle(90, 4)), "no error");
  // A circle on no plate is left out with a note (it was dropped without a word).
  const std::string stray = model_from_sketch(
      read_sketch("0\nSECTION\n2\nENTITIES\n" + plate + circle(10, 4) + circle(500, 3) + "0\nENDSEC\n0\nEOF\n", "p.dxf",
                  SketchFormat::kDxf),
      {"p.dxf", "mm", 1.0, 5.0, "steel"});
  EXPECT_THAT(stray, HasSubstr("# Left out: the circle at line 39 (500, 10) lies on no link.\n"));
}

// A DXF with every coordinate and radius of its ENTITIES multiplied by `scale` (as if drawn in
// another unit; the header's $INSUNITS kept): groups 10-18, 20-28, 30-38, a CIRCLE's or ARC's
// radius (40), an LWPOLYLINE's width (43), a SPLINE's tolerances (42-44). Bulges, angles,
// ratios, knots and weights have no length. `extra` (pairs, in the unscaled drawing's units) is
// added at the end of the ENTITIES.
std::string scaled_dxf(const std::string& text, double scale, const std::string& extra = {}) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    lines.push_back(line);
  }
  const auto trimmed = [](std::string s) {
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.erase(s.begin());
    return s;
  };
  std::string out, section, entity, previous;
  const auto add = [&](const std::string& code_text, std::string value) {
    const int code = std::atoi(code_text.c_str());
    if (code == 0) entity = value;
    if (code == 2 && previous == "SECTION") section = value;
    if (code == 0) previous = value;
    const bool length = (code >= 10 && code <= 38 && code % 10 <= 8) ||
                        (code == 40 && (entity == "CIRCLE" || entity == "ARC")) ||
                        (code == 43 && entity == "LWPOLYLINE") || (code >= 42 && code <= 44 && entity == "SPLINE");
    if (section == "ENTITIES" && code != 0 && length)
      value = fmt::format("{:.17g}", std::strtod(value.c_str(), nullptr) * scale);
    out += code_text + "\n" + value + "\n";
  };
  for (std::size_t i = 0; i + 1 < lines.size(); i += 2) {
    const std::string code = trimmed(lines[i]), value = trimmed(lines[i + 1]);
    if (code == "0" && value == "ENDSEC" && section == "ENTITIES") {
      std::istringstream more(extra);
      for (std::string c, v; std::getline(more, c) && std::getline(more, v);) add(c, v);
    }
    add(code, value);
  }
  return out;
}

// A model written by model_from_sketch, taken apart: its text with each number replaced by #,
// and the numbers, each marked as a length (a coordinate or radius) or not (a bulge, the
// thickness, or in a comment: counts of links and joints, lines of the file).
struct ModelNumbers {
  std::string shape;
  std::vector<double> values;
  std::vector<bool> lengths;
};

ModelNumbers numbers_of(const std::string& model) {
  ModelNumbers m;
  std::size_t line_start = 0;
  for (std::size_t i = 0; i < model.size();) {
    const char c = model[i];
    if (c == '\n') line_start = i + 1;
    const bool starts =
        (std::isdigit(static_cast<unsigned char>(c)) ||
         (c == '-' && i + 1 < model.size() && std::isdigit(static_cast<unsigned char>(model[i + 1])))) &&
        (i == 0 ||
         !(std::isalnum(static_cast<unsigned char>(model[i - 1])) || model[i - 1] == '_' || model[i - 1] == '.'));
    if (!starts) {
      m.shape += c;
      ++i;
      continue;
    }
    char* end = nullptr;
    m.values.push_back(std::strtod(model.c_str() + i, &end));
    const std::string before = model.substr(line_start, i - line_start);
    m.lengths.push_back(before.find('#') == std::string::npos && !before.ends_with("bulge: ") &&
                        !before.ends_with("thickness: "));
    m.shape += '#';
    i = static_cast<std::size_t>(end - model.c_str());
  }
  return m;
}

// The model of `drawing(scale)` at each scale is the model at scale 1, every length times the
// scale (to 1e-9 of itself), the rest as it is: the same links, joints, holes and vertices.
template <class Drawing>
void expect_same_model_at_every_scale(const Drawing& drawing, const std::string& name, const std::string& counts) {
  const SketchModelOptions options{name, "mm", 1.0, 5.0, "steel"};
  const std::string unit = model_from_sketch(read_sketch(drawing(1.0), name, *sketch_format(name)), options);
  ASSERT_THAT(unit, HasSubstr(counts));
  const ModelNumbers reference = numbers_of(unit);
  for (const double scale : {1e-90, 1e-15, 1e-6, 1e-3, 1e3, 1e6, 1e90}) {
    std::string model;
    try {
      model = model_from_sketch(read_sketch(drawing(scale), name, *sketch_format(name)), options);
    } catch (const std::exception& e) {
      ADD_FAILURE() << name << " at the scale " << scale << ": " << e.what();
      continue;
    }
    const ModelNumbers scaled = numbers_of(model);
    if (scaled.shape != reference.shape || scaled.values.size() != reference.values.size()) {
      ADD_FAILURE() << name << " at the scale " << scale << " is not the model at 1:\n" << model << "\nat 1:\n" << unit;
      continue;
    }
    // The numbers that differ, each reported once per scale with the first of them.
    std::size_t wrong = 0, first = 0;
    for (std::size_t i = 0; i < scaled.values.size(); ++i) {
      const double expected = reference.lengths[i] ? reference.values[i] * scale : reference.values[i];
      const double allowed = reference.lengths[i] ? 1e-9 * std::abs(expected) : 0.0;
      if (std::abs(scaled.values[i] - expected) <= allowed) continue;
      if (wrong++ == 0) first = i;
    }
    EXPECT_EQ(wrong, 0u) << name << " at the scale " << scale << ": number " << first << " is " << scaled.values[first]
                         << ", not " << reference.values[first] << (reference.lengths[first] ? " times the scale" : "")
                         << ":\n"
                         << model;
  }
}

// The unit a drawing is made in must not change what is imported: the same shapes in numbers
// 1e-3 (a part in mm drawn in metres), 1e-6, 1e-15 or 1e-90 (above 1e-100, refused as too small)
// or 1e3 to 1e90 times as large are the same model, scaled. The models were written rounded to
// 1e-9 of the unit: 5 significant digits at 1e-6, all zeros at 1e-15 (outlines whose vertices
// coincide), and at 1e3 other digits than at 1 (196.27069731, not 196.270697). An SVG subpath of
// relative moves closed by Z doubled its first vertex at 1e-3 (0.06 + -0.02 is not 0.04), and
// an A semicircle's bulge came out 0.99999998 at 1e-15.
TEST(SketchImport, TheDrawingsUnitChangesNothingButTheScale) {
  // The AutoCAD fixture (an LWPOLYLINE slot with bulges, pin holes and an ELLIPSE window; a
  // quarter disc of a rational SPLINE and two LINEs), with a POINT marking the quarter disc's
  // pivot, which holds no pin hole of its own.
  const std::string plates = fixture("autocad-r2000-plates.dxf");
  expect_same_model_at_every_scale(
      [&](double scale) { return scaled_dxf(plates, scale, "0\nPOINT\n8\nplate2\n10\n104\n20\n3\n"); }, "plates.dxf",
      "2 links, 0 joints");
  // The example four-bar: three slotted links, LWPOLYLINEs with bulges, pins coinciding at two
  // joints.
  std::ifstream in(std::string(NBAR_SOURCE_DIR) + "/examples/sketches/fourbar-sketch.dxf", std::ios::binary);
  std::ostringstream fourbar;
  fourbar << in.rdbuf();
  expect_same_model_at_every_scale([&](double scale) { return scaled_dxf(fourbar.str(), scale); }, "fourbar.dxf",
                                   "3 links, 2 joints");
  // An SVG of two links sharing a pin (the one circle at their joint): paths with arcs, a
  // quadratic Bézier window, a cubic end and an <ellipse> hole.
  const auto svg = [](double scale) {
    const auto v = [scale](double x) { return fmt::format("{:.17g}", x * scale); };
    return fmt::format(
        "<svg width=\"100mm\" height=\"50mm\" viewBox=\"0 0 100 50\">\n"
        "<g id=\"crank\">\n"
        "<path d=\"M {0},{1} H {2} A {0},{0} 0 0 1 {2},{3} H {0} A {0},{0} 0 0 1 {0},{1} Z\"/>\n"
        "<path d=\"m {4},{5} h {5} q {6},{1} {7},0 z\"/>\n"
        "<circle cx=\"{0}\" cy=\"{8}\" r=\"{9}\"/>\n"
        "<circle cx=\"{10}\" cy=\"{8}\" r=\"{9}\"/>\n"
        "</g>\n"
        "<g id=\"bar\">\n"
        "<path d=\"M {11},{8} A {0},{0} 0 0 1 {12},{8} L {12},{13} C {12},{14} {11},{14} {11},{13} Z\"/>\n"
        "<ellipse cx=\"{10}\" cy=\"{15}\" rx=\"{16}\" ry=\"{17}\"/>\n"
        "<circle cx=\"{10}\" cy=\"{18}\" r=\"{16}\"/>\n"
        "</g>\n"
        "</svg>\n",
        v(10), v(15), v(90), v(35), v(40), v(20), v(-10), v(-20), v(25), v(5), v(90), v(80), v(100), v(125), v(138),
        v(80), v(4), v(8), v(120));
  };
  expect_same_model_at_every_scale(svg, "two-links.svg", "2 links, 1 joint");
}

TEST(SketchImport, AFileInUtf16IsSaidToBeNotTextAtItsFirstLine) {
  // Notepad's "Unicode": the SVG reader said "the value of '" of an attribute it misread.
  const std::string svg = "<svg xmlns=\"http://www.w3.org/2000/svg\"><circle cx=\"1\" cy=\"2\" r=\"3\"/></svg>";
  std::string utf16 = "\xFF\xFE";
  for (char c : svg) utf16.append({c, '\0'});
  EXPECT_THAT(
      error_of(utf16, "u.svg"),
      HasSubstr("u.svg:1:1: the file is not text: it holds a NUL byte and starts with a UTF-16 byte-order mark; "
                "save it as UTF-8 (or ASCII)"));
  EXPECT_THAT(error_of(std::string("X, Y\nNew_Line\n\0", 15), "b.csv"),
              HasSubstr("b.csv:3:1: the file is not text: it holds a NUL byte (UTF-16, UTF-32 or a binary file?)"));
}

}  // namespace
}  // namespace nbar::io
