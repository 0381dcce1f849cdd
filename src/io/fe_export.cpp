#include "nbar/io/fe_export.hpp"

#include <cmath>
#include <iomanip>
#include <limits>
#include <string>

#include "nbar/model/units.hpp"

namespace nbar::io {

namespace {

// The plate and its field at a step, checked.
struct PlateAtStep {
  const fe::PlateModel& plate;
  fe::StressField field;
};

const fe::PlateModel& plate_of(const Analysis& analysis, int body) {
  if (!analysis.stress || !analysis.stress->fe)
    throw Error(ErrorKind::BadInput, "a mesh export needs the finite-element stress stage");
  const Model& m = analysis.model();
  if (body < 0 || body >= static_cast<int>(m.bodies.size()) || !analysis.stress->fe->analysed(body))
    throw Error(ErrorKind::BadInput, "body " + std::to_string(body) + " has no plate to export");
  return analysis.stress->fe->plate(body);
}

PlateAtStep at_step(const Analysis& analysis, int body, int step) {
  const fe::PlateModel& plate = plate_of(analysis, body);
  const int steps = static_cast<int>(analysis.sweep.samples.size());
  if (step < 0 || step >= steps)
    throw Error(ErrorKind::BadInput,
                "step " + std::to_string(step) + " is not a solved step (0 to " + std::to_string(steps - 1) + ")");
  return {plate, analysis.stress->fe->solve(analysis.dynamics->samples[step], body)};
}

void full_precision(std::ostream& out) { out << std::setprecision(std::numeric_limits<double>::max_digits10); }

// One point-data array of the .vtu: `components` numbers per node from `value(node, k)`.
template <class Value>
void data_array(std::ostream& out, const char* name, int components, int nodes, Value value) {
  out << "        <DataArray type=\"Float64\" Name=\"" << name << "\"";
  if (components > 1) out << " NumberOfComponents=\"" << components << "\"";
  out << " format=\"ascii\">\n";
  for (int n = 0; n < nodes; ++n) {
    out << "         ";
    for (int k = 0; k < components; ++k) out << ' ' << value(n, k);
    out << '\n';
  }
  out << "        </DataArray>\n";
}

}  // namespace

void write_fe_vtu(std::ostream& out, const Analysis& analysis, int body, int step) {
  const PlateAtStep p = at_step(analysis, body, step);
  const fe::TriMesh& mesh = p.plate.mesh();
  const double unit = analysis.model().units.length_scale;
  const int nodes = static_cast<int>(mesh.nodes.size()), cells = static_cast<int>(mesh.triangles.size());
  full_precision(out);
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      << "  <UnstructuredGrid>\n"
      << "    <Piece NumberOfPoints=\"" << nodes << "\" NumberOfCells=\"" << cells << "\">\n"
      << "      <PointData Scalars=\"von_mises\" Vectors=\"displacement\">\n";
  const auto& s = p.field.stress;
  data_array(out, "von_mises", 1, nodes, [&](int n, int) { return to_megapascal(p.field.von_mises[n]); });
  data_array(out, "sigma_xx", 1, nodes, [&](int n, int) { return to_megapascal(s[n][0]); });
  data_array(out, "sigma_yy", 1, nodes, [&](int n, int) { return to_megapascal(s[n][1]); });
  data_array(out, "tau_xy", 1, nodes, [&](int n, int) { return to_megapascal(s[n][2]); });
  data_array(out, "displacement", 3, nodes,
             [&](int n, int k) { return k < 2 ? p.field.displacement[2 * n + k] / unit : 0.0; });
  out << "      </PointData>\n      <Points>\n";
  data_array(out, "Points", 3, nodes, [&](int n, int k) { return k < 2 ? mesh.nodes[n][k] / unit : 0.0; });
  out << "      </Points>\n      <Cells>\n"
      << "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
  for (const auto& t : mesh.triangles)
    out << "          " << t[0] << ' ' << t[1] << ' ' << t[2] << ' ' << t[3] << ' ' << t[4] << ' ' << t[5] << '\n';
  out << "        </DataArray>\n        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
  for (int c = 1; c <= cells; ++c) out << "          " << 6 * c << '\n';
  out << "        </DataArray>\n        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
  for (int c = 0; c < cells; ++c) out << "          22\n";  // VTK_QUADRATIC_TRIANGLE
  out << "        </DataArray>\n      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
}

void write_fe_nodes_csv(std::ostream& out, const Analysis& analysis, int body, int step) {
  const PlateAtStep p = at_step(analysis, body, step);
  const fe::TriMesh& mesh = p.plate.mesh();
  const double unit = analysis.model().units.length_scale;
  full_precision(out);
  out << "node,x,y,ux,uy,sigma_xx,sigma_yy,tau_xy,von_mises\n";
  for (std::size_t n = 0; n < mesh.nodes.size(); ++n) {
    const Eigen::Vector3d& s = p.field.stress[n];
    out << n << ',' << mesh.nodes[n].x() / unit << ',' << mesh.nodes[n].y() / unit << ','
        << p.field.displacement[2 * n] / unit << ',' << p.field.displacement[2 * n + 1] / unit << ','
        << to_megapascal(s[0]) << ',' << to_megapascal(s[1]) << ',' << to_megapascal(s[2]) << ','
        << to_megapascal(p.field.von_mises[n]) << '\n';
  }
}

void write_fe_elements_csv(std::ostream& out, const Analysis& analysis, int body) {
  const fe::TriMesh& mesh = plate_of(analysis, body).mesh();
  out << "element,n0,n1,n2,n3,n4,n5\n";
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    out << t;
    for (int v : mesh.triangles[t]) out << ',' << v;
    out << '\n';
  }
}

}  // namespace nbar::io
