// The finite-element stress pictures from the command line: `nbar draw --stress`, `nbar animate
// --stress` and `nbar report --stress-method fe` (the maps themselves are tested in
// tests/render/drawing_test.cpp), and what they refuse.
#include "apps/cli_support.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

namespace nbar::cli_test {
namespace {

using ::testing::HasSubstr;

const std::string kPlates = std::string(NBAR_EXAMPLES_DIR) + "/fourbar-ansys-plates.yaml";

TEST(StressPicturesCli, DrawColoursEveryPlateWithALegendAndThePeaks) {
  ScratchDir f("nbar_stress_cli");
  const std::string out = f.file("map.svg");
  const CliRun run = nbar("draw " + kPlates + " --stress --steps 3 -o " + out);
  ASSERT_EQ(run.code, 0) << run.err;
  const std::string svg = read_file(out);
  EXPECT_THAT(svg, HasSubstr("stress-legend"));
  // The crank's peak: its drive torque through the 20 mm hole (docs/kinetics.md), labelled.
  EXPECT_THAT(svg, HasSubstr("11.2 MPa"));
  // A coarser mesh, given in the model's unit (m), is another picture of nearly the same peak.
  const std::string coarse = f.file("coarse.svg");
  ASSERT_EQ(nbar("draw " + kPlates + " --stress --steps 3 --mesh-size 0.1 -o " + coarse).code, 0);
  EXPECT_NE(read_file(coarse), svg);
  const CliRun at = nbar("draw " + kPlates + " --stress --at 60 -o " + out);
  EXPECT_EQ(at.code, 2);
  EXPECT_THAT(at.err, HasSubstr("give --step instead of --at"));
  const CliRun size = nbar("draw " + kPlates + " --stress --mesh-size -1 -o " + out);
  EXPECT_EQ(size.code, 2);
}

TEST(StressPicturesCli, AnimationAndReport) {
  ScratchDir f("nbar_stress_cli");
  const std::string gif = f.file("map.gif");
  const CliRun run = nbar("animate " + kPlates + " --stress --steps 3 --frames 3 -o " + gif);
  ASSERT_EQ(run.code, 0) << run.err;
  EXPECT_EQ(read_file(gif).substr(0, 6), "GIF89a");
  const CliRun svg = nbar("animate " + kPlates + " --stress --steps 3 --frames 3 -o " + f.file("map.svg"));
  EXPECT_EQ(svg.code, 2);
  EXPECT_THAT(svg.err, HasSubstr("only GIF and MP4 animations"));
  const std::string html = f.file("report.html");
  const CliRun report = nbar("report " + kPlates + " --stress-method fe --steps 3 -o " + html);
  ASSERT_EQ(report.code, 0) << report.err;
  EXPECT_THAT(read_file(html), HasSubstr("stress-legend"));  // the beam report has no map
}

}  // namespace
}  // namespace nbar::cli_test
