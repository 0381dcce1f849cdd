// The finite-element mesh export (io/fe_export.hpp): the .vtu read back by a small XML reader
// (tinyxml2) and the CSV tables, against the mesh and the field they were written from.
#include <gtest/gtest.h>
#include <tinyxml2.h>

#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

#include "nbar/analysis/fe_tables.hpp"
#include "nbar/io/fe_export.hpp"
#include "nbar/io/model_file.hpp"

namespace nbar {
namespace {

Analysis plates_by_fe() {
  const io::LoadedModel file = io::load_model_file(std::string(NBAR_EXAMPLES_DIR) + "/fourbar-ansys-plates.yaml");
  AnalysisOptions options;
  options.steps = 2;
  options.stress = true;
  options.stress_method = StressMethod::fe;
  return analyse(std::make_shared<const Mechanism>(file.model), options);
}

// The numbers of one DataArray of a .vtu's piece, by name.
std::vector<double> numbers_of(const tinyxml2::XMLElement* piece, const std::string& name) {
  for (const char* section : {"PointData", "Points", "Cells"}) {
    const tinyxml2::XMLElement* group = piece->FirstChildElement(section);
    for (auto* a = group ? group->FirstChildElement("DataArray") : nullptr; a; a = a->NextSiblingElement("DataArray"))
      if (a->Attribute("Name", name.c_str())) {
        std::istringstream text(a->GetText());
        std::vector<double> out;
        for (double v; text >> v;) out.push_back(v);
        return out;
      }
  }
  ADD_FAILURE() << "no DataArray " << name;
  return {};
}

TEST(FeExport, TheVtuReadsBackAsTheMeshAndTheField) {
  const Analysis analysis = plates_by_fe();
  const int body = analysis.model().find_body("coupler");
  std::ostringstream vtu;
  io::write_fe_vtu(vtu, analysis, body, 1);
  tinyxml2::XMLDocument doc;
  ASSERT_EQ(doc.Parse(vtu.str().c_str()), tinyxml2::XML_SUCCESS);
  const tinyxml2::XMLElement* grid = doc.FirstChildElement("VTKFile");
  ASSERT_NE(grid, nullptr);
  EXPECT_STREQ(grid->Attribute("type"), "UnstructuredGrid");
  const tinyxml2::XMLElement* piece = grid->FirstChildElement("UnstructuredGrid")->FirstChildElement("Piece");
  const fe::TriMesh& mesh = analysis.stress->fe->plate(body).mesh();
  const fe::StressField field = analysis.stress->fe->solve(analysis.dynamics->samples[1], body);
  const auto nodes = static_cast<std::size_t>(piece->IntAttribute("NumberOfPoints"));
  const auto cells = static_cast<std::size_t>(piece->IntAttribute("NumberOfCells"));
  ASSERT_EQ(nodes, mesh.nodes.size());
  ASSERT_EQ(cells, mesh.triangles.size());
  const std::vector<double> points = numbers_of(piece, "Points"), connectivity = numbers_of(piece, "connectivity");
  const std::vector<double> offsets = numbers_of(piece, "offsets"), types = numbers_of(piece, "types");
  const std::vector<double> von_mises = numbers_of(piece, "von_mises"), tau = numbers_of(piece, "tau_xy");
  ASSERT_EQ(points.size(), 3 * nodes);
  ASSERT_EQ(connectivity.size(), 6 * cells);
  ASSERT_EQ(offsets.size(), cells);
  ASSERT_EQ(types.size(), cells);
  ASSERT_EQ(von_mises.size(), nodes);
  for (std::size_t t = 0; t < cells; ++t) {
    EXPECT_EQ(types[t], 22);  // VTK_QUADRATIC_TRIANGLE
    EXPECT_EQ(offsets[t], 6.0 * (t + 1));
    for (int k = 0; k < 6; ++k) ASSERT_EQ(connectivity[6 * t + k], mesh.triangles[t][k]);
  }
  for (std::size_t n = 0; n < nodes; ++n) {
    // Written at full precision: read back to the last bit (the model is in metres, stresses in MPa).
    EXPECT_EQ(points[3 * n], mesh.nodes[n].x());
    EXPECT_EQ(points[3 * n + 1], mesh.nodes[n].y());
    EXPECT_EQ(points[3 * n + 2], 0.0);
    EXPECT_EQ(von_mises[n], field.von_mises[n] / 1e6);
    EXPECT_EQ(tau[n], field.stress[n][2] / 1e6);
  }
  // The largest value in the file is the step's peak.
  double largest = 0;
  for (double v : von_mises) largest = std::max(largest, v);
  EXPECT_EQ(largest, field.peak / 1e6);
}

TEST(FeExport, TheCsvTablesHaveEveryNodeAndElement) {
  const Analysis analysis = plates_by_fe();
  const int body = analysis.model().find_body("crank");
  std::ostringstream nodes, elements;
  io::write_fe_nodes_csv(nodes, analysis, body, 0);
  io::write_fe_elements_csv(elements, analysis, body);
  const fe::TriMesh& mesh = analysis.stress->fe->plate(body).mesh();
  const auto lines = [](const std::string& text) { return std::count(text.begin(), text.end(), '\n'); };
  EXPECT_EQ(lines(nodes.str()), static_cast<long>(mesh.nodes.size()) + 1);
  EXPECT_EQ(lines(elements.str()), static_cast<long>(mesh.triangles.size()) + 1);
  EXPECT_EQ(nodes.str().substr(0, nodes.str().find('\n')), "node,x,y,ux,uy,sigma_xx,sigma_yy,tau_xy,von_mises");
  std::ostringstream first;
  first << "0," << mesh.triangles[0][0] << ',' << mesh.triangles[0][1];
  EXPECT_EQ(elements.str().substr(elements.str().find('\n') + 1, first.str().size()), first.str());
  std::ostringstream bad;
  EXPECT_THROW(io::write_fe_vtu(bad, analysis, body, 5), Error);
}

}  // namespace
}  // namespace nbar
