// The nine-point solver's internals that its tests, its bench and the program that writes the
// stored instance need: the isotropic system, the group of six, monodromy from scratch and
// the stored instance. Not for front-ends.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "nbar/synthesis/nine_point.hpp"
#include "nbar/synthesis/solve.hpp"

namespace nbar::synthesis {

// Affine coordinates (24): t1..t8, tb1..tb8, then x, xb, a, ab (first dyad: moving pivot
// relative to the first point, fixed pivot) and y, yb, b, bb (second dyad).
// Parameters (16): delta_1..delta_8 then deltab_1..deltab_8 (points relative to the first).
// Tracker coordinates (26): t, tb, then X, Xb, A, Ab, H and Y, Yb, B, Bb, K (homogenized).
const ParameterizedSystem& nine_point_system();

// The group of six, on affine solutions of F(.; p): relabelling the dyads, and the Roberts
// cognate that keeps the first dyad's fixed pivot.
CVector swap_dyads(const CVector& affine);
CVector roberts_cognate(const CVector& affine, const CVector& parameters);
// The orbit of an affine solution: up to six distinct solutions, the solution first.
std::vector<CVector> nine_point_orbit(const CVector& affine, const CVector& parameters);
// What every member of an orbit shares: the symmetric functions of its three fixed pivots.
Eigen::Matrix<Complex, 6, 1> orbit_key(const CVector& affine);

struct NinePointStart {
  CVector parameters;                    // generic complex
  std::vector<CVector> representatives;  // affine, one per orbit
  int loops = 0;                         // monodromy: edges tracked
  int paths = 0;
  bool closed = false;  // every orbit at every node went along every edge: nothing new
};

// Random complex four-bar -> nine points on its coupler curve and that one solution; then
// monodromy on a graph of three parameter nodes (edges along random arcs, both ways) until
// the sets are closed under it. Every orbit is tracked by one representative.
NinePointStart generate_nine_point_start(std::uint64_t seed, const NinePointOptions& options = {});

// The instance moved to other generic parameters by a parameter homotopy, then monodromy at
// them if orbits were lost on the way.
NinePointStart move_nine_point_start(const NinePointStart& from, const CVector& to,
                                     const NinePointOptions& options = {});

// Monodromy at `parameters` from known representatives (grown in place); returns whether
// the graph closed. `paths` and `loops` accumulate. With `enough` > 0 it stops as soon as that
// many orbits are known at `parameters`: at a task, the count of the complete stored instance
// (the generic number of regular solutions) certifies the set, and closure adds nothing.
bool nine_point_monodromy(const CVector& parameters, std::vector<CVector>& representatives,
                          const NinePointOptions& options, int& paths, int& loops, int enough = 0);

// The instance kept in src/synthesis/data/nine_point_start.inc (nbar-nine-point-start).
const NinePointStart& nine_point_start();
// That file's text for an instance (base64 of little-endian doubles, as C++ string lines).
std::string encode_nine_point_start(const NinePointStart& start);

// The solver's parameters of nine points (first point at the origin, scaled by their spread).
CVector nine_point_parameters(const std::array<Eigen::Vector2d, 9>& points);

}  // namespace nbar::synthesis
