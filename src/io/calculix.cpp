#include "nbar/io/calculix.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "nbar/model/diagnostics.hpp"

namespace nbar::fe {

namespace {

// ccx reads at most 20 characters a field (it read -9.18485099360515e-19 as -0.918): the most
// significant digits, from 17 down, whose text fits; 13 always do (-1.234567890123e-308).
std::string field(double x) {
  for (int digits = 17; digits > 13; --digits) {
    std::string text = fmt::format("{:.{}g}", x, digits);
    if (text.size() <= 20) return text;
  }
  return fmt::format("{:.13g}", x);
}

}  // namespace

void write_calculix_input(std::ostream& out, const PlateModel& model, const LoadCase& loads,
                          const std::string& heading) {
  const TriMesh& mesh = model.mesh();
  const ElasticMaterial& material = model.material();
  out << "*HEADING\n" << heading << "\n*NODE, NSET=NALL\n";
  for (std::size_t i = 0; i < mesh.nodes.size(); ++i)
    out << fmt::format("{}, {}, {}\n", i + 1, field(mesh.nodes[i].x()), field(mesh.nodes[i].y()));
  // ccx's CPS6 numbers its nodes as TriMesh does: corners counterclockwise, then mid-sides 1-2, 2-3, 3-1.
  out << "*ELEMENT, TYPE=CPS6, ELSET=EALL\n";
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& v = mesh.triangles[t];
    out << fmt::format("{}, {}, {}, {}, {}, {}, {}\n", t + 1, v[0] + 1, v[1] + 1, v[2] + 1, v[3] + 1, v[4] + 1,
                       v[5] + 1);
  }
  out << fmt::format("*MATERIAL, NAME=PLATE\n*ELASTIC\n{}, {}\n", field(material.youngs_modulus),
                     field(material.poisson_ratio));
  out << fmt::format("*SOLID SECTION, ELSET=EALL, MATERIAL=PLATE\n{}\n", field(material.thickness));
  out << "*BOUNDARY\n";
  for (const Support& s : model.supports())
    out << fmt::format("{}, {}, {}\n", s.node + 1, s.direction + 1, s.direction + 1);
  out << "*STEP\n*STATIC\n*CLOAD\n";
  const Eigen::VectorXd forces = model.nodal_loads(loads).forces;
  for (int i = 0; i < forces.size(); ++i)
    if (forces[i] != 0) out << fmt::format("{}, {}, {}\n", i / 2 + 1, i % 2 + 1, field(forces[i]));
  out << "*NODE FILE, OUTPUT=2D\nU\n*EL FILE, OUTPUT=2D\nS\n*END STEP\n";
}

namespace {

// A result line: " -1", the node number in 10 columns, then values in 12 columns each.
void read_result_line(const std::string& line, int line_number, int values, std::vector<double>& into, int& node) {
  const auto fail = [&] {
    throw Error(ErrorKind::BadInput,
                fmt::format("CalculiX results, line {}: cannot read the result line '{}'", line_number, line));
  };
  if (line.size() < 13 + 12 * static_cast<std::size_t>(values)) fail();
  try {
    node = std::stoi(line.substr(3, 10));
    into.resize(values);
    for (int k = 0; k < values; ++k) into[k] = std::stod(line.substr(13 + 12 * k, 12));
  } catch (const std::logic_error&) {
    fail();
  }
  if (node < 1) fail();
}

}  // namespace

CalculixResults read_calculix_frd(std::istream& in) {
  CalculixResults out;
  enum class Block { none, displacement, stress } block = Block::none;
  std::string line;
  std::vector<double> values;
  for (int line_number = 1; std::getline(in, line); ++line_number) {
    if (line.rfind(" -4", 0) == 0) {
      block = line.find("DISP") != std::string::npos     ? Block::displacement
              : line.find("STRESS") != std::string::npos ? Block::stress
                                                         : Block::none;
    } else if (line.rfind(" -3", 0) == 0) {
      block = Block::none;
    } else if (block != Block::none && line.rfind(" -1", 0) == 0) {
      int node = 0;
      read_result_line(line, line_number, block == Block::displacement ? 2 : 4, values, node);
      if (block == Block::displacement) {
        if (out.displacement.size() < static_cast<std::size_t>(node))
          out.displacement.resize(node, Eigen::Vector2d::Zero());
        out.displacement[node - 1] = {values[0], values[1]};
      } else {
        if (out.stress.size() < static_cast<std::size_t>(node)) {
          out.stress.resize(node, Eigen::Vector3d::Zero());
          out.stress_zz.resize(node, 0.0);
        }
        out.stress[node - 1] = {values[0], values[1], values[3]};
        out.stress_zz[node - 1] = values[2];
      }
    }
  }
  return out;
}

}  // namespace nbar::fe
