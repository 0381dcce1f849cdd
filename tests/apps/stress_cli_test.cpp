// The finite-element stress pictures from the command line: `nbar draw --stress`, `nbar animate
// --stress` and `nbar report --stress-method fe` (the maps themselves are tested in
// tests/render/drawing_test.cpp), and what they refuse.
#include "apps/cli_support.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace nbar::cli_test {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

const std::string kPlates = std::string(NBAR_EXAMPLES_DIR) + "/fourbar-ansys-plates.yaml";

std::string read(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

struct Folder {
  fs::path dir = fs::temp_directory_path() / ("nbar_stress_cli_" + std::to_string(::getpid()));
  Folder() { fs::create_directories(dir); }
  ~Folder() { fs::remove_all(dir); }
};

TEST(StressPicturesCli, DrawColoursEveryPlateWithALegendAndThePeaks) {
  Folder f;
  const std::string out = (f.dir / "map.svg").string();
  const CliRun run = nbar("draw " + kPlates + " --stress --steps 3 -o " + out);
  ASSERT_EQ(run.code, 0) << run.err;
  const std::string svg = read(out);
  EXPECT_THAT(svg, HasSubstr("stress-legend"));
  // The crank's peak: its drive torque through the 20 mm hole (docs/kinetics.md), labelled.
  EXPECT_THAT(svg, HasSubstr("11.2 MPa"));
  // A coarser mesh, given in the model's unit (m), is another picture of nearly the same peak.
  const std::string coarse = (f.dir / "coarse.svg").string();
  ASSERT_EQ(nbar("draw " + kPlates + " --stress --steps 3 --mesh-size 0.1 -o " + coarse).code, 0);
  EXPECT_NE(read(coarse), svg);
  const CliRun at = nbar("draw " + kPlates + " --stress --at 60 -o " + out);
  EXPECT_EQ(at.code, 2);
  EXPECT_THAT(at.err, HasSubstr("give --step instead of --at"));
  const CliRun size = nbar("draw " + kPlates + " --stress --mesh-size -1 -o " + out);
  EXPECT_EQ(size.code, 2);
}

TEST(StressPicturesCli, AnimationAndReport) {
  Folder f;
  const std::string gif = (f.dir / "map.gif").string();
  const CliRun run = nbar("animate " + kPlates + " --stress --steps 3 --frames 3 -o " + gif);
  ASSERT_EQ(run.code, 0) << run.err;
  EXPECT_EQ(read(gif).substr(0, 6), "GIF89a");
  const CliRun svg = nbar("animate " + kPlates + " --stress --steps 3 --frames 3 -o " + (f.dir / "map.svg").string());
  EXPECT_EQ(svg.code, 2);
  EXPECT_THAT(svg.err, HasSubstr("only GIF and MP4 animations"));
  const std::string html = (f.dir / "report.html").string();
  const CliRun report = nbar("report " + kPlates + " --stress-method fe --steps 3 -o " + html);
  ASSERT_EQ(report.code, 0) << report.err;
  EXPECT_THAT(read(html), HasSubstr("stress-legend"));  // the beam report has no map
}

}  // namespace
}  // namespace nbar::cli_test
