// One link's finite-element mesh and stress field at one step, for other programs: a VTK XML
// UnstructuredGrid (.vtu, ASCII, for ParaView) and CSV tables of nodes and elements.
//
// Coordinates are the model's drawing (the plate's own frame, where its shape is given) in the
// model's length unit, z = 0; stresses in MPa; displacements in the model's length unit. Elements
// are the solver's 6-node triangles, VTK_QUADRATIC_TRIANGLE (22): corners 0, 1, 2 counterclockwise,
// then the mid-side nodes of 0-1, 1-2, 2-0 (VTK's order too). Nodes are numbered from 0.
#pragma once

#include <ostream>

#include "nbar/analysis/analysis.hpp"

namespace nbar::io {

// Throw Error(BadInput) as fe_points_table does: no finite-element stage, no plate, no such step.
void write_fe_vtu(std::ostream& out, const Analysis& analysis, int body, int step);
// node,x,y,ux,uy,sigma_xx,sigma_yy,tau_xy,von_mises: one row per node.
void write_fe_nodes_csv(std::ostream& out, const Analysis& analysis, int body, int step);
// element,n0,...,n5: one row per element.
void write_fe_elements_csv(std::ostream& out, const Analysis& analysis, int body);

}  // namespace nbar::io
