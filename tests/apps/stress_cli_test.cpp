// The finite-element stress pictures from the command line: `nbar draw --stress`, `nbar animate
// --stress` and `nbar report --stress-method fe` (the maps themselves are tested in
// tests/render/drawing_test.cpp), and what they refuse.
#include "apps/cli_support.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

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
namespace {

// nbar stress --method fe --converge: the table of meshes and peaks, and the same as JSON.
TEST(StressConvergenceCli, TableAndJsonOfTheMeshes) {
  const CliRun table = nbar("stress " + kPlates + " --method fe --steps 3 --converge --tolerance 2");
  ASSERT_EQ(table.code, 0) << table.err;
  EXPECT_THAT(table.out, HasSubstr("mesh  body"));
  EXPECT_THAT(table.out, HasSubstr("converged: every peak changed by less than 2 % on the last mesh"));
  const CliRun json = nbar("stress " + kPlates + " --method fe --steps 3 --converge --tolerance 2 --format json");
  ASSERT_EQ(json.code, 0) << json.err;
  const auto j = nlohmann::json::parse(json.out);
  EXPECT_EQ(j["tolerance"], 2.0);
  EXPECT_EQ(j["converged"], true);
  ASSERT_GE(j["meshes"].size(), 2u);
  const auto& first = j["meshes"][0]["links"];
  const auto& second = j["meshes"][1]["links"];
  EXPECT_EQ(first[0]["body"], "crank");
  EXPECT_TRUE(first[0]["change"].is_null());
  const double a = first[0]["von_mises"], b = second[0]["von_mises"];
  EXPECT_NEAR(second[0]["change"].get<double>(), 100 * std::abs(b - a) / b, 1e-9);
  EXPECT_NEAR(second[0]["mesh_size"].get<double>(), first[0]["mesh_size"].get<double>() / 2, 1e-12);

  const CliRun beam = nbar("stress " + kPlates + " --steps 3 --converge");
  EXPECT_EQ(beam.code, 2);
  EXPECT_THAT(beam.err, HasSubstr("--converge: is for finite elements: give --method fe too"));
  const CliRun alone = nbar("stress " + kPlates + " --method fe --steps 3 --tolerance 2");
  EXPECT_EQ(alone.code, 2);
  EXPECT_THAT(alone.err, HasSubstr("--tolerance: needs --converge"));
}

}  // namespace
}  // namespace nbar::cli_test

namespace nbar::cli_test {
namespace {

// A CSV table: its header and rows of numbers.
struct Csv {
  std::vector<std::string> columns;
  std::vector<std::vector<double>> rows;
  std::size_t column(const std::string& name) const {
    for (std::size_t c = 0; c < columns.size(); ++c)
      if (columns[c] == name) return c;
    ADD_FAILURE() << "no column " << name;
    return 0;
  }
  double largest(const std::string& name) const {
    double out = -1e300;
    for (const auto& r : rows) out = std::max(out, r[column(name)]);
    return out;
  }
};

Csv parse_csv(const std::string& text) {
  Csv csv;
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    std::istringstream cells(line);
    std::string cell;
    std::vector<std::string> texts;
    while (std::getline(cells, cell, ',')) texts.push_back(cell);
    if (csv.columns.empty()) {
      csv.columns = texts;
      continue;
    }
    std::vector<double> row;
    for (const std::string& t : texts) {  // a text cell (a body's name) is NaN
      char* end = nullptr;
      const double v = std::strtod(t.c_str(), &end);
      row.push_back(end != t.c_str() && *end == '\0' ? v : std::nan(""));
    }
    csv.rows.push_back(row);
  }
  return csv;
}

Csv stress_csv(const std::string& options) {
  const CliRun run = nbar("stress " + kPlates + " --steps 1 --method fe --format csv " + options);
  EXPECT_EQ(run.code, 0) << run.err;
  return parse_csv(run.out);
}

TEST(StressFieldCli, AroundAHoleTheDrivingTorquesShearAndTheOtherHolesFigure) {
  // The crank's drive torque, 405.6 N m as a uniform shear in its 20 mm, 0.1 m thick hole:
  // tau = T / (2 pi r^2 t) = 6.456 MPa, von Mises sqrt(3) tau = 11.18 MPa (docs/kinetics.md).
  const Csv o2 = stress_csv("--around-hole crank:O2");
  EXPECT_EQ(o2.rows.size(), 96u);  // 48 edges, corner and mid-side nodes
  EXPECT_NEAR(o2.largest("von_mises"), 11.18, 0.005 * 11.18);
  // Hole 2 is the one at A, and the same as naming A; its peak is docs/kinetics.md's "other hole".
  const Csv a = stress_csv("--section-profile crank --around-hole 2");
  EXPECT_EQ(a.rows, stress_csv("--around-hole crank:A").rows);
  EXPECT_NEAR(a.largest("von_mises"), 0.667, 0.002);
  // On a circle at 10 hole radii the stresses are a fraction of the edge's.
  const Csv far = stress_csv("--around-hole crank:O2 --radius 0.1 --samples 360");
  EXPECT_EQ(far.rows.size(), 360u);
  EXPECT_LT(far.largest("von_mises"), 0.2);
}

TEST(StressFieldCli, AtThePeakThePointQueryIsThePeak) {
  // The report's peak is a node's value at a place in the body's frame: the query there returns it
  // (the JSON report, whose numbers are whole; its CSV rounds to 6 digits).
  const CliRun report = nbar("stress " + kPlates + " --steps 1 --method fe --format json");
  ASSERT_EQ(report.code, 0) << report.err;
  const nlohmann::json coupler = nlohmann::json::parse(report.out)["links"][1];
  ASSERT_EQ(coupler["body"], "coupler");
  std::ostringstream at;
  at.precision(17);
  at << "--section-profile coupler --at=" << coupler["x"].get<double>() << "," << coupler["y"].get<double>();
  const Csv point = stress_csv(at.str());
  ASSERT_EQ(point.rows.size(), 1u);
  EXPECT_NEAR(point.rows[0][point.column("von_mises")], coupler["von_mises"].get<double>(), 1e-9);
}

TEST(StressFieldCli, TheFiniteElementSectionsCarryTheBeamsForces) {
  // Equilibrium: a cut across the crank's plate carries the N, V and M the beam model finds from
  // the same pin forces (the field integrated over the cut; 0.5 m from either hole).
  const Csv fe = stress_csv("--section-profile crank --samples 11");
  const CliRun beam_run = nbar("stress " + kPlates + " --steps 1 --section-profile crank --format csv");
  ASSERT_EQ(beam_run.code, 0) << beam_run.err;
  const Csv beam = parse_csv(beam_run.out);
  const auto& cut = fe.rows[5];
  ASSERT_NEAR(cut[0], 0.5, 1e-6);
  // The beam's sections straddle x = 0.5: interpolate.
  std::size_t k = 0;
  while (beam.rows[k + 1][0] < 0.5) ++k;
  const double share = (0.5 - beam.rows[k][0]) / (beam.rows[k + 1][0] - beam.rows[k][0]);
  for (const char* name : {"N", "V", "M"}) {
    const std::size_t c = beam.column(name);
    const double expected = beam.rows[k][c] + share * (beam.rows[k + 1][c] - beam.rows[k][c]);
    EXPECT_NEAR(cut[fe.column(name)], expected, 0.002 * std::abs(expected)) << name;
  }
  EXPECT_NEAR(cut[fe.column("area")], 0.05, 1e-6);
}

TEST(StressFieldCli, ExportMeshWritesEachLinkAtItsPeakOrAtTheStep) {
  ScratchDir f("nbar_stress_cli");
  const std::string dir = f.file("meshes");
  const CliRun all = nbar("stress " + kPlates + " --steps 3 --method fe --export-mesh " + dir);
  ASSERT_EQ(all.code, 0) << all.err;
  // Each link at its peak's step (docs/kinetics.md: the crank's at the last of these three).
  EXPECT_THAT(read_file(dir + "/crank-step2.vtu"), HasSubstr("<VTKFile type=\"UnstructuredGrid\""));
  EXPECT_THAT(read_file(dir + "/rocker-step1-nodes.csv"), HasSubstr("node,x,y,ux,uy"));
  const CliRun one = nbar("stress " + kPlates +
                          " --steps 3 --method fe --section-profile coupler --step 0 "
                          "--export-mesh " +
                          dir + " --format csv");
  ASSERT_EQ(one.code, 0) << one.err;
  EXPECT_THAT(read_file(dir + "/coupler-step0-elements.csv"), HasSubstr("element,n0,n1,n2,n3,n4,n5"));
  const CliRun beam = nbar("stress " + kPlates + " --steps 3 --export-mesh " + dir);
  EXPECT_EQ(beam.code, 2);
  EXPECT_THAT(beam.err, HasSubstr("--export-mesh writes the finite-element meshes: give --method fe too"));
}

TEST(StressFieldCli, AlongALineAndWhatIsRefused) {
  // From hole to hole along the crank's axis: the samples in the holes are left out.
  const Csv line = stress_csv("--section-profile crank --along O2,A --samples 101");
  EXPECT_EQ(line.rows.size(), 99u);  // x = 0 and x = 1 are the holes' centres
  EXPECT_NEAR(line.rows.front()[line.column("arc")], 0.01, 1e-12);
  const CliRun off = nbar("stress " + kPlates + " --steps 1 --method fe --section-profile crank --at O2");
  EXPECT_EQ(off.code, 2);
  EXPECT_THAT(off.err, HasSubstr("the point (0, 0) m in the body's frame"));
  EXPECT_THAT(off.err, HasSubstr("is not on the plate of 'crank'"));
  const CliRun beam = nbar("stress " + kPlates + " --steps 1 --section-profile crank --at 0.5,0");
  EXPECT_EQ(beam.code, 2);
  EXPECT_THAT(beam.err, HasSubstr("--at reads the finite-element field: give --method fe too"));
  const CliRun hole = nbar("stress " + kPlates + " --steps 1 --method fe --around-hole crank:3");
  EXPECT_EQ(hole.code, 2);
  EXPECT_THAT(hole.err, HasSubstr("1 to 2"));
}

}  // namespace
}  // namespace nbar::cli_test
