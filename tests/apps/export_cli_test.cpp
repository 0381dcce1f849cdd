// nbar export --dxf from the command line: the file written, the pose, and the errors.
#include "apps/cli_support.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Core>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

namespace nbar::cli_test {
namespace {

using ::testing::HasSubstr;

// The second VERTEX of the file's first POLYLINE (the crank's outline), checked to start the
// arc (bulge 1).
Eigen::Vector2d second_vertex(const std::string& dxf) {
  std::istringstream in(dxf);
  std::string code, value;
  int vertices = 0;
  Eigen::Vector2d v(NAN, NAN);
  double bulge = 0;
  while (std::getline(in, code) && std::getline(in, value)) {
    const int c = std::stoi(code);
    if (c == 0) {
      if (vertices == 2) break;
      if (value == "VERTEX") ++vertices;
    } else if (vertices == 2) {
      if (c == 10) v.x() = std::stod(value);
      if (c == 20) v.y() = std::stod(value);
      if (c == 42) bulge = std::stod(value);
    }
  }
  EXPECT_EQ(bulge, 1.0);
  return v;
}

const std::string kExample = std::string(NBAR_EXAMPLES_DIR) + "/fourbar-rounded-crank.yaml";

TEST(ExportCli, WritesTheDxfAsDrawnAndInAPose) {
  ScratchDir dir("nbar_export");
  const CliRun drawn = nbar("export " + kExample + " --dxf " + dir.file("drawn.dxf"));
  ASSERT_EQ(drawn.code, 0) << drawn.err;
  const std::string text = read_file(dir.file("drawn.dxf"));
  EXPECT_EQ(text.rfind("  0\nSECTION\n  2\nHEADER\n", 0), 0u);
  EXPECT_TRUE(text.ends_with("  0\nEOF\n"));
  for (const char* layer : {"\ncrank\n", "\ncoupler\n", "\nrocker\n"}) EXPECT_THAT(text, HasSubstr(layer));
  // The crank's arc-starting vertex (80, -10) and its bulge, as drawn.
  EXPECT_THAT(text, HasSubstr(" 10\n80\n 20\n-10\n 30\n0\n 42\n1\n"));

  const CliRun turned = nbar("export " + kExample + " --dxf " + dir.file("at90.dxf") + " --at 90");
  ASSERT_EQ(turned.code, 0) << turned.err;
  // A quarter turn about O2 takes the crank's second vertex (80, -10) to (10, 80), to the
  // pose's precision; its bulge stays.
  const Eigen::Vector2d v = second_vertex(read_file(dir.file("at90.dxf")));
  EXPECT_NEAR(v.x(), 10, 1e-9);
  EXPECT_NEAR(v.y(), 80, 1e-9);
  EXPECT_EQ(second_vertex(text), Eigen::Vector2d(80, -10));
}

TEST(ExportCli, Errors) {
  ScratchDir dir("nbar_export");
  const CliRun none =
      nbar("export " + std::string(NBAR_EXAMPLES_DIR) + "/fourbar-crank-rocker.yaml --dxf " + dir.file("x.dxf"));
  EXPECT_EQ(none.code, 2);
  EXPECT_THAT(none.err, HasSubstr("there is nothing to cut"));
  const CliRun neither = nbar("export " + kExample);
  EXPECT_EQ(neither.code, 2);
  EXPECT_THAT(neither.err, HasSubstr("needs --dxf FILE.dxf or --svg FILE.svg"));
  EXPECT_EQ(nbar("export " + kExample + " --dxf /nonexistent-dir/x.dxf").code, 2);
}

// nbar import on the example sketch: three slotted links, pins coinciding at A and B. The
// skeleton, with the driver its last comment suggests, checks as a crank-rocker whose crank
// plate is the 50 x 16 mm slot with half-round ends less two 4 mm pin holes.
TEST(ImportCli, SketchBecomesAModelSkeleton) {
  ScratchDir dir("nbar_export");
  const std::string sketch = std::string(NBAR_EXAMPLES_DIR) + "/sketches/fourbar-sketch.dxf";
  const CliRun run = nbar("import " + sketch + " -o " + dir.file("skeleton.yaml"));
  ASSERT_EQ(run.code, 0) << run.err;
  std::string yaml = read_file(dir.file("skeleton.yaml"));
  EXPECT_THAT(yaml, HasSubstr("ground: [P1, P4]\n"));
  EXPECT_THAT(yaml, HasSubstr("  coupler:\n    points: [P2, P3]"));
  yaml += "drivers: [{angle: crank, from: 0, to: 360, speed: 60 rpm}]\n";
  { std::ofstream(dir.file("driven.yaml")) << yaml; }
  const CliRun check = nbar("check " + dir.file("driven.yaml"));
  ASSERT_EQ(check.code, 0) << check.err;
  EXPECT_THAT(check.out, HasSubstr("Degrees of freedom: 1"));
  EXPECT_THAT(check.out, HasSubstr("crank-coupler-rocker: crank-rocker"));
  EXPECT_THAT(check.out, HasSubstr("area 900.531"));  // 800 + 64π - 32π

  // A sketch that is not one: exit 1 at the file's line; an unknown format: exit 2.
  { std::ofstream(dir.file("open.csv")) << "X, Y\nNew_Line\n0, 0\n10, 0\nNew_Line\n10, 0\n10, 10\n"; }
  const CliRun open = nbar("import " + dir.file("open.csv"));
  EXPECT_EQ(open.code, 1);
  EXPECT_THAT(open.err, HasSubstr("open.csv:5:1: the outline is not closed"));
  EXPECT_EQ(nbar("import " + dir.file("skeleton.yaml")).code, 2);

  // A material of the user's own is written as asked, with a warning that the model must define it.
  EXPECT_EQ(run.err, "");
  const CliRun own = nbar("import " + sketch + " --material unobtainium");
  EXPECT_EQ(own.code, 0) << own.err;
  EXPECT_THAT(own.out, HasSubstr("material: unobtainium"));
  EXPECT_THAT(own.err, HasSubstr("warning: 'unobtainium' is not a built-in material (steel, "));
  EXPECT_THAT(own.err, HasSubstr("define it under `materials:` in the model written"));
}

}  // namespace
}  // namespace nbar::cli_test
