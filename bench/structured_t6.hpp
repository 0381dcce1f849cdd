// Structured 6-node triangle meshes of simple plates (rectangles, a rectangle around a round hole,
// a ring), independent of nbar's mesher: the finite-element tests and bench check the solver on
// them. Header-only; test and bench support, not library code.
#pragma once

#include <Eigen/Core>

#include <array>
#include <cmath>
#include <functional>
#include <numbers>
#include <vector>

#include "nbar/stress/plane_stress.hpp"

namespace nbar::fe::structured {

// Which side of the (u, v) parameter square an edge lies on.
enum class Side { v_low, v_high, u_low, u_high };

// The map (u, v) in [0, 1]^2 -> plate, sampled at half steps (mid-side nodes come from the map
// too, so curved boundaries are exact); quads are split along a diagonal and every triangle
// turned counterclockwise. Periodic in u: u = 1 is u = 0 (rings).
inline TriMesh map_grid(int nu, int nv, bool periodic_u, const std::function<Eigen::Vector2d(double, double)>& map,
                        const std::function<BoundaryTag(Side)>& tag) {
  const int columns = periodic_u ? 2 * nu : 2 * nu + 1, rows = 2 * nv + 1;
  std::vector<int> id(static_cast<std::size_t>(columns) * rows, -1);
  TriMesh mesh;
  const auto grid = [&](int i, int j) -> int& {
    return id[static_cast<std::size_t>(j) * columns + (periodic_u ? i % columns : i)];
  };
  for (int pass = 0; pass < 2; ++pass)  // corners first, then mid-side nodes
    for (int j = 0; j < rows; ++j)
      for (int i = 0; i < columns; ++i) {
        const bool corner = i % 2 == 0 && j % 2 == 0;
        if (corner != (pass == 0)) continue;
        grid(i, j) = static_cast<int>(mesh.nodes.size());
        mesh.nodes.push_back(map(double(i) / (2 * nu), double(j) / (2 * nv)));
      }
  mesh.corner_count = 0;
  for (int j = 0; j < rows; j += 2)
    for (int i = 0; i < columns; i += 2) ++mesh.corner_count;
  struct Corner {
    int i, j;
  };
  for (int b = 0; b < nv; ++b)
    for (int a = 0; a < nu; ++a) {
      const int i = 2 * a, j = 2 * b;
      const std::array<std::array<Corner, 6>, 2> halves{{
          {{{i, j}, {i + 2, j}, {i + 2, j + 2}, {i + 1, j}, {i + 2, j + 1}, {i + 1, j + 1}}},
          {{{i, j}, {i + 2, j + 2}, {i, j + 2}, {i + 1, j + 1}, {i + 1, j + 2}, {i, j + 1}}},
      }};
      for (const auto& half : halves) {
        std::array<int, 6> t{};
        for (int k = 0; k < 6; ++k) t[k] = grid(half[k].i, half[k].j);
        const Eigen::Vector2d e1 = mesh.nodes[t[1]] - mesh.nodes[t[0]], e2 = mesh.nodes[t[2]] - mesh.nodes[t[0]];
        std::array<Corner, 6> c = half;
        if (e1.x() * e2.y() - e1.y() * e2.x() < 0) {
          t = {t[0], t[2], t[1], t[5], t[4], t[3]};
          c = {half[0], half[2], half[1], half[5], half[4], half[3]};
        }
        mesh.triangles.push_back(t);
        for (int k = 0; k < 3; ++k) {
          const Corner p = c[k], q = c[(k + 1) % 3];
          const int mid = t[3 + k];
          if (p.j == q.j && p.j == 0) mesh.boundary.push_back({{t[k], t[(k + 1) % 3], mid}, tag(Side::v_low)});
          if (p.j == q.j && p.j == rows - 1) mesh.boundary.push_back({{t[k], t[(k + 1) % 3], mid}, tag(Side::v_high)});
          if (!periodic_u && p.i == q.i && p.i == 0)
            mesh.boundary.push_back({{t[k], t[(k + 1) % 3], mid}, tag(Side::u_low)});
          if (!periodic_u && p.i == q.i && p.i == columns - 1)
            mesh.boundary.push_back({{t[k], t[(k + 1) % 3], mid}, tag(Side::u_high)});
        }
      }
    }
  return mesh;
}

inline BoundaryTag outline_tag(Side) { return {}; }

// The rectangle [x0, x0 + length] x [y0, y0 + height] in nx x ny squares, two triangles each.
inline TriMesh rectangle(double x0, double y0, double length, double height, int nx, int ny) {
  return map_grid(
      nx, ny, false, [=](double u, double v) { return Eigen::Vector2d(x0 + u * length, y0 + v * height); },
      outline_tag);
}

// Grading from the hole (v = 0) outwards: 0 -> 0, 1 -> 1, steps growing by exp(growth / rings).
inline double graded(double v, double growth) { return growth == 0 ? v : std::expm1(growth * v) / std::expm1(growth); }

// The rectangle [x0, x1] x [y0, y1] around circle hole 0 (centre, radius): `around` edges on the
// hole (a multiple of 4; the rectangle's corners are grid points), `rings` graded rings out to
// the rectangle.
inline TriMesh plate_with_hole(double x0, double y0, double x1, double y1, const Eigen::Vector2d& centre, double radius,
                               int around, int rings, double growth) {
  const auto outer = [=](double theta) -> Eigen::Vector2d {  // theta in [-π/4, 7π/4): sides linear in theta
    const double q = std::numbers::pi / 4, xm = (x0 + x1) / 2, ym = (y0 + y1) / 2, hx = (x1 - x0) / 2,
                 hy = (y1 - y0) / 2;
    if (theta < q) return {x1, ym + hy * theta / q};
    if (theta < 3 * q) return {xm - hx * (theta - 2 * q) / q, y1};
    if (theta < 5 * q) return {x0, ym - hy * (theta - 4 * q) / q};
    return {xm + hx * (theta - 6 * q) / q, y0};
  };
  return map_grid(
      around, rings, true,
      [=](double u, double v) {
        const double theta = 2 * std::numbers::pi * u - std::numbers::pi / 4;
        const Eigen::Vector2d on_hole = centre + radius * Eigen::Vector2d(std::cos(theta), std::sin(theta));
        return Eigen::Vector2d(on_hole + graded(v, growth) * (outer(theta) - on_hole));
      },
      [](Side s) {
        return s == Side::v_low ? BoundaryTag{BoundaryTag::Kind::circle_hole, 0} : BoundaryTag{};
      });
}

// The ring a <= r <= b about the origin (circle hole 0 inside, a curved outline outside).
inline TriMesh ring(double a, double b, int around, int rings) {
  return map_grid(
      around, rings, true,
      [=](double u, double v) {
        const double theta = 2 * std::numbers::pi * u, r = a + (b - a) * v;
        return Eigen::Vector2d(r * std::cos(theta), r * std::sin(theta));
      },
      [](Side s) {
        return s == Side::v_low ? BoundaryTag{BoundaryTag::Kind::circle_hole, 0} : BoundaryTag{};
      });
}

// Consistent nodal forces of a traction t(x) (N/m^2, times `thickness`) on the straight boundary
// edges for which `on_edge(first, second)` holds (3-point Gauss: exact for t up to cubic).
inline void add_edge_traction(const TriMesh& mesh, double thickness,
                              const std::function<bool(const Eigen::Vector2d&, const Eigen::Vector2d&)>& on_edge,
                              const std::function<Eigen::Vector2d(const Eigen::Vector2d&)>& traction,
                              std::vector<NodalForce>& out) {
  const double g = std::sqrt(0.6);
  const std::array<std::array<double, 2>, 3> rule{{{-g, 5.0 / 9}, {0.0, 8.0 / 9}, {g, 5.0 / 9}}};
  for (const BoundaryEdge& e : mesh.boundary) {
    const Eigen::Vector2d& a = mesh.nodes[e.nodes[0]];
    const Eigen::Vector2d& b = mesh.nodes[e.nodes[1]];
    if (!on_edge(a, b)) continue;
    const double half_length = 0.5 * (b - a).norm();
    for (const auto& [s, w] : rule) {
      const Eigen::Vector2d t = traction(0.5 * (1 - s) * a + 0.5 * (1 + s) * b) * (w * half_length * thickness);
      out.push_back({e.nodes[0], 0.5 * s * (s - 1) * t});
      out.push_back({e.nodes[1], 0.5 * s * (s + 1) * t});
      out.push_back({e.nodes[2], (1 - s * s) * t});
    }
  }
}

}  // namespace nbar::fe::structured
