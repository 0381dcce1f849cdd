// CalculiX (ccx) decks of a plate model, for checking nbar's finite elements against an
// independent solver or taking a link's stresses further there.
//
// write_calculix_input() writes the same mesh as CPS6 plane-stress elements, the same material and
// thickness, the same three minimal supports and the same balanced nodal loads (*CLOAD, after
// inertia relief) as PlateModel::solve() uses; ccx writes nodal displacements and stresses to
// its .frd file (*NODE FILE U, *EL FILE S), which read_calculix_frd() reads back.
// Node n of the mesh is CalculiX node n + 1, triangle t element t + 1.
#pragma once

#include <Eigen/Core>

#include <istream>
#include <ostream>
#include <string>
#include <vector>

#include "nbar/stress/plane_stress.hpp"

namespace nbar::fe {

void write_calculix_input(std::ostream& out, const PlateModel& model, const LoadCase& loads,
                          const std::string& heading = "nbar plate");

struct CalculixResults {
  std::vector<Eigen::Vector2d> displacement;  // per node (index = ccx node - 1), m
  std::vector<Eigen::Vector3d> stress;        // per node: (σxx, σyy, τxy), Pa (ccx's nodal averages)
  // Per node: σzz, Pa. 0 in plane stress; ccx expands CPS6 into a layer of solid elements as
  // thick as the section, whose σzz grows with the thickness against the hole's radius.
  std::vector<double> stress_zz;
};

// Reads the DISP and STRESS blocks of an ASCII .frd file. Throws Error(ErrorKind::BadInput) with the line
// number when a result line cannot be read.
CalculixResults read_calculix_frd(std::istream& in);

}  // namespace nbar::fe
