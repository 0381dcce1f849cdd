// The plate mesher: areas against the exact geometry, valid 6-node triangles (counterclockwise,
// positive Jacobian at every node), the smallest angle, the boundary covered once with the
// plate on its left, holes left empty, grading near holes and re-entrant corners,
// reproducibility, limits and errors; over random convex plates with round holes too.
#include "nbar/stress/mesh.hpp"
#include "model/region_support.hpp"
#include "nbar/io/model_file.hpp"
#include "nbar/model/diagnostics.hpp"
#include "nbar/model/model.hpp"
#include "test_constants.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <numbers>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

namespace nbar::fe {
namespace {

using Eigen::Vector2d;
using Polygon = std::vector<Vector2d>;
using nbar::test_constants::kPi;
using ::testing::HasSubstr;
// What the mesher promises for plates whose corners are all at least 60° (docs/fe.md).
constexpr double kGuaranteedMinAngleDeg = 28.0;

double cross(const Vector2d& a, const Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

Region plate(Polygon outline) {
  Region r;
  r.outline = std::move(outline);
  return r;
}

Polygon rectangle(double x0, double y0, double x1, double y1) { return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}; }

Region l_shape() { return plate({{0, 0}, {1, 0}, {1, 0.2}, {0.2, 0.2}, {0.2, 1}, {0, 1}}); }

// The crank of examples/fourbar-rounded-crank.yaml (m): a slot with half-round ends around two
// 10 mm pin holes.
Region rounded_crank() {
  Region r = plate({{0, -0.01}, {0.08, -0.01}, {0.08, 0.01}, {0, 0.01}});
  r.outline_bulges = {0, 1, 0, 1};
  r.circle_holes = {{{0, 0}, 0.005}, {{0.08, 0}, 0.005}};
  return r;
}

// det J of the 6-node triangle's map at the reference point (xi, eta), written out from the
// shape functions' derivatives.
double jacobian(const TriMesh& m, const std::array<int, 6>& t, double xi, double eta) {
  const double l1 = 1 - xi - eta;
  const double dxi[6] = {1 - 4 * l1, 4 * xi - 1, 0, 4 * (l1 - xi), 4 * eta, -4 * eta};
  const double deta[6] = {1 - 4 * l1, 0, 4 * eta - 1, -4 * xi, 4 * xi, 4 * (l1 - eta)};
  Vector2d a(0, 0), b(0, 0);
  for (int i = 0; i < 6; ++i) {
    a += dxi[i] * m.nodes[t[i]];
    b += deta[i] * m.nodes[t[i]];
  }
  return cross(a, b);
}

double straight_area(const TriMesh& m) {
  double a = 0;
  for (const auto& t : m.triangles) a += cross(m.nodes[t[1]] - m.nodes[t[0]], m.nodes[t[2]] - m.nodes[t[0]]) / 2;
  return a;
}

bool inside_hole(const Region& r, const Vector2d& x) {
  for (const Circle& c : r.circle_holes) {
    if ((x - c.centre).norm() < c.radius * (1 - 1e-9)) return true;
  }
  for (const Polygon& h : r.polygon_holes) {
    if (test_support::inside_polygon(h, x)) return true;
  }
  return false;
}

// Everything a mesh of r must be, whatever r is: numbering, orientation, Jacobians, boundary
// edges once each with the plate on their left and on the right curve, holes empty.
void expect_valid_mesh(const Region& r, const TriMesh& m) {
  ASSERT_FALSE(m.triangles.empty());
  ASSERT_GT(m.corner_count, 2);
  const int n = static_cast<int>(m.nodes.size());
  std::map<std::pair<int, int>, int> directed;  // corner edge a -> b: its mid-side node
  int bad_numbering = 0, non_positive = 0, repeated = 0;
  for (const auto& t : m.triangles) {
    for (int i = 0; i < 3; ++i) bad_numbering += t[i] < 0 || t[i] >= m.corner_count;
    for (int i = 3; i < 6; ++i) bad_numbering += t[i] < m.corner_count || t[i] >= n;
    constexpr double kNodes[6][2] = {{0, 0}, {1, 0}, {0, 1}, {0.5, 0}, {0.5, 0.5}, {0, 0.5}};
    for (const auto& p : kNodes) non_positive += !(jacobian(m, t, p[0], p[1]) > 0);
    for (int i = 0; i < 3; ++i) repeated += !directed.emplace(std::pair(t[i], t[(i + 1) % 3]), t[3 + i]).second;
    const Vector2d centroid = (m.nodes[t[0]] + m.nodes[t[1]] + m.nodes[t[2]]) / 3;
    EXPECT_FALSE(inside_hole(r, centroid)) << "a triangle in a hole at " << centroid.transpose();
  }
  EXPECT_EQ(bad_numbering, 0) << "corner nodes come first, then mid-side nodes";
  EXPECT_EQ(non_positive, 0) << "triangles with a non-positive Jacobian at a node";
  EXPECT_EQ(repeated, 0) << "a directed edge in two triangles: overlap or wrong orientation";
  // Every edge is shared by two triangles (as a -> b and b -> a) with one mid-side node, except
  // the boundary edges, which are listed once each, in the triangle's direction.
  std::map<std::pair<int, int>, const BoundaryEdge*> listed;
  for (const BoundaryEdge& e : m.boundary) {
    EXPECT_TRUE(listed.emplace(std::pair(e.nodes[0], e.nodes[1]), &e).second) << "a boundary edge listed twice";
  }
  int open_edges = 0;
  for (const auto& [edge, mid] : directed) {
    const auto back = directed.find({edge.second, edge.first});
    if (back != directed.end()) {
      EXPECT_EQ(back->second, mid) << "two mid-side nodes on one edge";
      continue;
    }
    ++open_edges;
    const auto it = listed.find(edge);
    ASSERT_NE(it, listed.end()) << "a free edge that is not a boundary edge (or runs the wrong way)";
    EXPECT_EQ(it->second->nodes[2], mid);
  }
  EXPECT_EQ(open_edges, static_cast<int>(m.boundary.size()));
  // Boundary nodes lie on the curve they are tagged with.
  for (const BoundaryEdge& e : m.boundary) {
    if (e.on.kind != BoundaryTag::Kind::circle_hole) continue;
    ASSERT_LT(e.on.index, static_cast<int>(r.circle_holes.size()));
    const Circle& c = r.circle_holes[e.on.index];
    for (int k = 0; k < 3; ++k) EXPECT_NEAR((m.nodes[e.nodes[k]] - c.centre).norm(), c.radius, 1e-12 * c.radius);
  }
}

// ---- exactness ----

TEST(Mesh, PolygonalPlatesHaveTheirExactArea) {
  Region holed = plate(rectangle(0, 0, 1.2, 0.5));
  holed.polygon_holes = {{{0.3, 0.1}, {0.5, 0.1}, {0.4, 0.35}}, rectangle(0.7, 0.2, 0.9, 0.3)};
  for (const Region& r : {plate(rectangle(0, 0, 1, 1)), l_shape(), holed}) {
    const TriMesh m = mesh_region(r);
    expect_valid_mesh(r, m);
    const double exact = area_properties(r).area;
    EXPECT_NEAR(straight_area(m), exact, 1e-13 * exact);
    EXPECT_NEAR(mesh_quality(m).area, exact, 1e-13 * exact);
  }
}

TEST(Mesh, PolygonBoundaryLengthIsThePerimeter) {
  const Region r = l_shape();
  const TriMesh m = mesh_region(r);
  double length = 0;
  for (const BoundaryEdge& e : m.boundary) {
    EXPECT_EQ(e.on.kind, BoundaryTag::Kind::outline);
    length += (m.nodes[e.nodes[1]] - m.nodes[e.nodes[0]]).norm();
    // Straight edges: the mid-side node is the middle.
    EXPECT_NEAR((m.nodes[e.nodes[2]] - (m.nodes[e.nodes[0]] + m.nodes[e.nodes[1]]) / 2).norm(), 0, 1e-15);
  }
  EXPECT_NEAR(length, 4.0, 1e-13);
}

// How much the mesh's area exceeds the plate's because its curved edges are parabolas through
// three points of a circle rather than the circle: for an edge seeing the angle φ at the
// centre of its circle of radius R, the circular segment R²/2 (φ − sin φ) against the parabolic
// segment 2/3 chord × sagitta, R² φ⁵ / 960 to leading order; added where the curve bulges
// into the plate (holes), taken away where it bulges out of it.
double expected_curved_excess(const TriMesh& m) {
  double excess = 0;
  for (const BoundaryEdge& e : m.boundary) {
    const Vector2d &a = m.nodes[e.nodes[0]], &b = m.nodes[e.nodes[1]], &mid = m.nodes[e.nodes[2]];
    const double chord = (b - a).norm();
    const double sagitta = std::abs(cross(b - a, mid - a)) / chord;
    if (sagitta < 1e-12 * chord) continue;  // straight
    const double radius = (chord * chord / 4 + sagitta * sagitta) / (2 * sagitta);
    const double phi = 2 * std::asin(chord / (2 * radius));
    const double difference = radius * radius / 2 * (phi - std::sin(phi)) - 2.0 / 3 * chord * sagitta;
    excess += cross(b - a, mid - a) > 0 ? difference : -difference;
  }
  return excess;
}

int edges_on(const TriMesh& m, BoundaryTag::Kind kind) {
  return static_cast<int>(
      std::count_if(m.boundary.begin(), m.boundary.end(), [&](const BoundaryEdge& e) { return e.on.kind == kind; }));
}

// The curved (isoparametric) area errs by the parabolic segments alone, so by O(n⁻⁴) with n
// edges around a hole: 16 times less for twice the edges (the straight-sided area by O(n⁻²)).
TEST(Mesh, CurvedAreaConvergesAtTheFourthPower) {
  const double radius = 0.01;
  Region r = plate(rectangle(-0.1, -0.05, 0.1, 0.05));
  r.circle_holes = {{{0.0, 0.0}, radius}};
  const double exact = area_properties(r).area;
  std::vector<double> curved, straight;
  for (int segments : {32, 64, 128}) {
    MeshOptions o;
    o.segments_per_hole = segments;
    const TriMesh m = mesh_region(r, o);
    expect_valid_mesh(r, m);
    ASSERT_EQ(edges_on(m, BoundaryTag::Kind::circle_hole), segments);
    const double excess = mesh_quality(m).area - exact;
    EXPECT_NEAR(excess, expected_curved_excess(m), 1e-14 * exact);
    EXPECT_NEAR(excess, std::pow(2 * kPi, 5) * radius * radius / (960 * std::pow(segments, 4)), 0.02 * excess);
    curved.push_back(excess);
    straight.push_back(straight_area(m) - exact);
  }
  for (std::size_t i = 0; i + 1 < curved.size(); ++i) {
    EXPECT_NEAR(std::log2(curved[i] / curved[i + 1]), 4.0, 0.02) << i;
    EXPECT_NEAR(std::log2(straight[i] / straight[i + 1]), 2.0, 0.02) << i;
  }
  // 32 edges around a 20 mm hole already give the plate's area to 1e-7.
  EXPECT_LT(curved[0], 1e-7 * exact);
}

TEST(Mesh, ArcOutlinesAndHolesAreExactUpToTheirParabolas) {
  // The rounded crank, and a plate with a concave arc edge and a polygon hole with an arc side.
  Region scalloped = plate({{0, 0}, {0.3, 0}, {0.3, 0.1}, {0, 0.1}});
  scalloped.outline_bulges = {0, 0, -0.15, 0};  // the top edge dips into the plate
  scalloped.polygon_holes = {{{0.1, 0.02}, {0.2, 0.02}, {0.15, 0.05}}};
  scalloped.polygon_hole_bulges = {{0.2, 0, 0}};
  scalloped.circle_holes = {{{0.25, 0.03}, 0.01}};
  // A disc of two half circles: every boundary point on one circle, the most degenerate input
  // for Delaunay triangulation (and for the rule that splits curved edges, see too_curved()).
  Region disc = plate({{-0.05, 0}, {0.05, 0}});
  disc.outline_bulges = {1, 1};
  Region washer = disc;
  washer.circle_holes = {{{0.01, 0}, 0.02}};
  for (const Region& r : {rounded_crank(), scalloped, disc, washer}) {
    const double exact = area_properties(r).area;
    for (int segments : {16, 48, 96}) {
      MeshOptions o;
      o.segments_per_hole = segments;
      const TriMesh m = mesh_region(r, o);
      expect_valid_mesh(r, m);
      EXPECT_GT(edges_on(m, BoundaryTag::Kind::outline), 8);
      EXPECT_NEAR(mesh_quality(m).area - exact, expected_curved_excess(m), 1e-13 * exact) << segments;
      // A whole circle of 48 edges errs by (2π)⁵/(960 · 48⁴) = 1.9e-6 of R², 6e-7 of its area.
      if (segments == 48) {
        EXPECT_LT(std::abs(mesh_quality(m).area - exact), 1e-6 * exact);
      }
    }
  }
}

// Every plate of the example models (bars with pin holes, the gravity example's coupler with a
// lightening hole, the slotted crank with arc ends), in the model's own units made metres.
TEST(Mesh, EveryExamplePlateMeshes) {
  int plates = 0;
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(NBAR_EXAMPLES_DIR)) {
    if (entry.path().extension() == ".yaml") files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  for (const auto& file : files) {
    const Model model = io::load_model_file(file.string()).model;
    for (const Body& body : model.bodies) {
      if (!body.shape) continue;
      SCOPED_TRACE(file.filename().string() + ": " + body.name);
      const TriMesh m = mesh_region(*body.shape);
      expect_valid_mesh(*body.shape, m);
      EXPECT_GE(mesh_quality(m).min_angle_deg, kGuaranteedMinAngleDeg);
      const double exact = area_properties(*body.shape).area;
      EXPECT_NEAR(mesh_quality(m).area, exact, 1e-6 * exact);
      ++plates;
    }
  }
  EXPECT_GE(plates, 9);  // as many as the examples had when this was written
}

// Corners sharper than 60° void the angle guarantee, not the mesh: it is still valid, exact in
// area, and finished quickly (refinement stops at tiny edges instead of chasing the corner).
TEST(Mesh, SharpCornersStillGiveValidMeshes) {
  Region star;
  for (int i = 0; i < 10; ++i) {
    const double angle = i * kPi / 5, radius = i % 2 ? 0.1 : 1.0;  // 7.3° tips
    star.outline.push_back(radius * Vector2d(std::cos(angle), std::sin(angle)));
  }
  Region sliver = plate({{0, 0}, {1, 0}, {0, 0.1}});  // 5.7°
  Region dart = plate(rectangle(0, 0, 1, 1));
  dart.polygon_holes = {{{0.2, 0.2}, {0.8, 0.25}, {0.2, 0.3}}};  // an 11° hole corner: 349° of plate
  Region notch = plate({{0, 0}, {1, 0}, {1, 1}, {0.5, 0.001}, {0, 1}});
  for (const Region& r : {star, sliver, dart, notch}) {
    const TriMesh m = mesh_region(r);
    expect_valid_mesh(r, m);
    EXPECT_NEAR(straight_area(m), area_properties(r).area, 1e-13);
    EXPECT_LT(m.nodes.size(), 5000u);
  }
}

// ---- quality ----

TEST(Mesh, SmallestAngleAtLeastTheGuarantee) {
  Region lug = make_bar({0, 0}, {1.2, 0}, 0.5, 0.25, 0.01, 0.01);
  Region l_holed = l_shape();
  l_holed.circle_holes = {{{0.1, 0.9}, 0.03}, {{0.9, 0.1}, 0.03}};
  for (const Region& r : {plate(rectangle(0, 0, 1, 1)), lug, l_holed, rounded_crank()}) {
    const TriMesh m = mesh_region(r);
    expect_valid_mesh(r, m);
    EXPECT_GE(mesh_quality(m).min_angle_deg, kGuaranteedMinAngleDeg);
  }
}

// Mean corner-edge length of the triangles whose centroid satisfies `where`.
template <typename Where>
double mean_edge(const TriMesh& m, Where where) {
  double sum = 0;
  int count = 0;
  for (const auto& t : m.triangles) {
    const Vector2d c = (m.nodes[t[0]] + m.nodes[t[1]] + m.nodes[t[2]]) / 3;
    if (!where(c)) continue;
    for (int i = 0; i < 3; ++i) sum += (m.nodes[t[i]] - m.nodes[t[(i + 1) % 3]]).norm();
    count += 3;
  }
  return count ? sum / count : 0.0;
}

TEST(Mesh, GradedFromSmallHolesToTheRequestedSize) {
  // A 1 m link, 0.2 m wide, with 20 mm holes 0.1 m from its ends.
  const Region r = make_bar({0, 0}, {0.8, 0}, 0.2, 0.1, 0.01, 0.01);
  MeshOptions o;
  o.size = 0.05;
  const TriMesh m = mesh_region(r, o);
  expect_valid_mesh(r, m);
  const double near = mean_edge(m, [](const Vector2d& c) { return (c - Vector2d(0, 0)).norm() < 0.0115; });
  const double far = mean_edge(m, [](const Vector2d& c) { return std::abs(c.x() - 0.4) < 0.1; });
  // The hole's edges are 2π 10 mm / 48 = 1.3 mm; the middle's about `size`.
  EXPECT_NEAR(near, 2 * kPi * 0.01 / 48, 0.3e-3);
  EXPECT_GT(far, 0.6 * o.size);
  EXPECT_LT(far, 1.4 * o.size);
  EXPECT_GT(far / near, 10.0);
  EXPECT_LE(mesh_quality(m).max_edge, 1.6 * o.size);
}

TEST(Mesh, ReentrantCornersAreRefined) {
  const Region r = l_shape();
  MeshOptions o;
  o.size = 0.05;
  const TriMesh m = mesh_region(r, o);
  const Vector2d reentrant(0.2, 0.2), convex(1, 0);
  const double at_reentrant = mean_edge(m, [&](const Vector2d& c) { return (c - reentrant).norm() < 0.01; });
  const double at_convex = mean_edge(m, [&](const Vector2d& c) { return (c - convex).norm() < 0.05; });
  EXPECT_GT(at_reentrant, 0);
  EXPECT_LT(at_reentrant, 0.25 * o.size);
  EXPECT_GT(at_convex, 0.4 * o.size);
}

// ---- reproducibility, limits, errors ----

TEST(Mesh, SameInputSameMesh) {
  const Region r = make_bar({0, 0}, {1.2, 0}, 0.5, 0.25, 0.01, 0.01);
  const TriMesh a = mesh_region(r), b = mesh_region(r);
  ASSERT_EQ(a.nodes.size(), b.nodes.size());
  EXPECT_EQ(a.corner_count, b.corner_count);
  for (std::size_t i = 0; i < a.nodes.size(); ++i) EXPECT_EQ(a.nodes[i], b.nodes[i]);
  EXPECT_EQ(a.triangles, b.triangles);
  ASSERT_EQ(a.boundary.size(), b.boundary.size());
  for (std::size_t i = 0; i < a.boundary.size(); ++i) EXPECT_EQ(a.boundary[i].nodes, b.boundary[i].nodes);
}

TEST(Mesh, OrientationOfTheInputDoesNotMatter) {
  Region cw = l_shape();
  std::reverse(cw.outline.begin(), cw.outline.end());
  const TriMesh m = mesh_region(cw);
  expect_valid_mesh(cw, m);
  EXPECT_NEAR(straight_area(m), area_properties(cw).area, 1e-13);
}

TEST(Mesh, MaxNodesIsHonoured) {
  const Region r = make_bar({0, 0}, {1.2, 0}, 0.5, 0.25, 0.01, 0.01);
  const TriMesh m = mesh_region(r);
  MeshOptions o;
  o.max_nodes = static_cast<int>(m.nodes.size());
  EXPECT_EQ(mesh_region(r, o).nodes.size(), m.nodes.size());
  o.max_nodes -= 1;
  EXPECT_THAT([&] { mesh_region(r, o); }, ::testing::ThrowsMessage<nbar::Error>(HasSubstr("max_nodes")));
  // A size far too small fails fast at the boundary, not after filling memory.
  o = {};
  o.size = 1e-9;
  EXPECT_THAT([&] { mesh_region(r, o); }, ::testing::ThrowsMessage<nbar::Error>(HasSubstr("max_nodes")));
  // A size whose boundary fits (34 000 stations) but whose interior needs about 7e7 corners fails
  // before refining, from the area (it refined for minutes until the budget stopped it).
  o.size = 1e-4;
  EXPECT_THAT([&] { mesh_region(r, o); },
              ::testing::ThrowsMessage<nbar::Error>(HasSubstr("the mesh would have about")));
}

// Halving the size halves the elements at the holes too (they kept 48 edges from the automatic
// size down to 2πr / 48), and an edge size asked for refines the holes alone.
TEST(Mesh, HoleEdgesFollowTheSizeAndTheEdgeSize) {
  const Region r = make_bar({0, 0}, {0.2, 0}, 0.04, 0.02, 0.01, 0.01);
  const double automatic = automatic_mesh_size(r);
  EXPECT_NEAR(automatic, std::hypot(0.24, 0.04) / 20, 1e-12);
  for (double refinement : {1.0, 2.0, 4.0}) {
    MeshOptions o;
    o.size = automatic / refinement;
    // Refinement may split an edge or two more.
    const int edges = edges_on(mesh_region(r, o), BoundaryTag::Kind::circle_hole);
    EXPECT_GE(edges, static_cast<int>(2 * 48 * refinement)) << refinement;
    EXPECT_LE(edges, static_cast<int>(2 * 48 * refinement) + 4) << refinement;
  }
  MeshOptions o;
  o.edge_size = 2 * kPi * 0.01 / 100;  // 100 edges a hole
  const TriMesh fine_edges = mesh_region(r, o);
  EXPECT_GE(edges_on(fine_edges, BoundaryTag::Kind::circle_hole), 2 * 100);
  EXPECT_LE(edges_on(fine_edges, BoundaryTag::Kind::circle_hole), 2 * 100 + 4);
  o.edge_size = 1.0;  // larger than the automatic edge: the automatic mesh
  EXPECT_EQ(mesh_region(r, o).nodes, mesh_region(r).nodes);
  o.edge_size = -1;
  EXPECT_THAT([&] { mesh_region(r, o); }, ::testing::ThrowsMessage<nbar::Error>(HasSubstr("edge element size")));
}

// The node estimate that refuses a mesh before meshing counts the graded refinement near holes
// and corners: within 20 % of the mesh's count, and a size whose mesh passes the budget is
// refused in milliseconds, before meshing.
TEST(Mesh, NodeEstimateFollowsTheGrading) {
  const Region bar = make_bar({0, 0}, {0.2, 0}, 0.04, 0.02, 0.01, 0.01);
  const Region ansys_crank = make_bar({0, 0}, {1.0, 0}, 0.5, 0.1, 0.01, 0.01);
  struct Case {
    const Region* region;
    double refinement;
    double edge_size;
  };
  for (const Case& c : {Case{&bar, 1, 0}, Case{&bar, 4, 0}, Case{&bar, 1, 2e-4}, Case{&ansys_crank, 1, 0},
                        Case{&ansys_crank, 2, 0}, Case{&ansys_crank, 1, 5e-4}}) {
    MeshOptions o;
    o.size = automatic_mesh_size(*c.region) / c.refinement;
    o.edge_size = c.edge_size;
    const double nodes = static_cast<double>(mesh_region(*c.region, o).nodes.size());
    const double estimate = estimated_mesh_nodes(*c.region, o);
    std::printf("node estimate %.1f for %.0f nodes (%.4f)\n", estimate, nodes, estimate / nodes);
    EXPECT_NEAR(estimate / nodes, 1.0, 0.2) << c.refinement << " " << c.edge_size;
  }
  // At an eighth of the automatic size the crank's mesh would have about 90 000 nodes, its far
  // field alone 42 000: a budget of 50 000 is refused by the graded estimate, before meshing.
  MeshOptions o;
  o.size = automatic_mesh_size(ansys_crank) / 8;
  EXPECT_NEAR(estimated_mesh_nodes(ansys_crank, o), 90500, 1000);
  o.max_nodes = 50000;
  const auto start = std::chrono::steady_clock::now();
  EXPECT_THAT([&] { check_mesh_budget(ansys_crank, o); },
              ::testing::ThrowsMessage<nbar::Error>(HasSubstr("the mesh would have about")));
  EXPECT_THAT([&] { mesh_region(ansys_crank, o); },
              ::testing::ThrowsMessage<nbar::Error>(HasSubstr("the mesh would have about")));
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 0.5);
}

TEST(Mesh, BadInputIsRefusedWithAReason) {
  const Region good = plate(rectangle(0, 0, 1, 1));
  auto refused = [](const Region& r, const MeshOptions& o, const std::string& why) {
    EXPECT_THAT([&] { mesh_region(r, o); }, ::testing::ThrowsMessage<nbar::Error>(HasSubstr(why)));
  };
  refused(plate({{0, 0}, {1, 1}, {1, 0}, {0, 1}}), {}, "intersect");
  Region outside = good;
  outside.circle_holes = {{{1.5, 0.5}, 0.1}};
  refused(outside, {}, "hole");
  MeshOptions o;
  o.size = -1;
  refused(good, o, "element size");
  o = {};
  o.size = std::nan("");
  refused(good, o, "element size");
  o = {};
  o.grading = 1.0;
  refused(good, o, "grading");
  o = {};
  o.segments_per_hole = 3;
  refused(good, o, "segments_per_hole");
  o = {};
  o.max_nodes = 0;
  refused(good, o, "max_nodes");
}

// ---- random plates ----

}  // namespace
}  // namespace nbar::fe

namespace nbar {
// How rapidcheck shows a failing plate.
void showValue(const Region& r, std::ostream& os) {
  os.precision(17);
  os << "outline";
  for (const Eigen::Vector2d& p : r.outline) os << " {" << p.x() << ", " << p.y() << "}";
  for (const Circle& c : r.circle_holes) os << "\nhole {" << c.centre.x() << ", " << c.centre.y() << "} r " << c.radius;
}
}  // namespace nbar

namespace nbar::fe {
namespace {

// A convex polygon inscribed in a circle with no corner under 60° (consecutive vertices at
// most 120° apart around it), with up to three round holes somewhere inside.
rc::Gen<Region> random_plate() {
  return rc::gen::exec([] {
    const int n = *rc::gen::inRange(5, 13);
    std::vector<double> gaps;
    double sum = 0;
    for (int i = 0; i < n; ++i) {
      gaps.push_back(1 + *rc::gen::inRange(0, 1001) / 1000.0);
      sum += gaps.back();
    }
    const double radius = 0.05 + *rc::gen::inRange(0, 1000) / 1000.0;
    const Vector2d centre(*rc::gen::inRange(-100, 101) / 100.0, *rc::gen::inRange(-100, 101) / 100.0);
    Region r;
    double angle = *rc::gen::inRange(0, 628) / 100.0;
    for (double g : gaps) {
      r.outline.push_back(centre + radius * Vector2d(std::cos(angle), std::sin(angle)));
      angle += 2 * kPi * g / sum;
    }
    const int holes = *rc::gen::inRange(0, 4);
    for (int k = 0; k < holes; ++k) {
      const double rho = radius * *rc::gen::inRange(0, 60) / 100.0;
      const double phi = *rc::gen::inRange(0, 628) / 100.0;
      const double hole = radius * (0.01 + *rc::gen::inRange(0, 20) / 100.0);
      r.circle_holes.push_back({centre + rho * Vector2d(std::cos(phi), std::sin(phi)), hole});
    }
    return r;
  });
}

RC_GTEST_PROP(MeshProperty, RandomConvexPlatesWithHoles, ()) {
  const Region r = *random_plate();
  try {
    check_region(r);
  } catch (const nbar::Error&) {
    RC_DISCARD("holes overlap or touch the outline");
  }
  // Nor all but touching (a gap of 1e-17 m passes check_region; its mesh is valid but has
  // straightened edges there, see quadratic_mesh()).
  for (std::size_t i = 0; i < r.circle_holes.size(); ++i) {
    const Circle& c = r.circle_holes[i];
    for (std::size_t j = 0; j < i; ++j) {
      const Circle& d = r.circle_holes[j];
      RC_PRE((c.centre - d.centre).norm() - c.radius - d.radius > 0.01 * std::min(c.radius, d.radius));
    }
    for (std::size_t k = 0; k < r.outline.size(); ++k) {
      const Vector2d a = r.outline[k], b = r.outline[(k + 1) % r.outline.size()];
      const double along = std::clamp((c.centre - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
      RC_PRE((a + along * (b - a) - c.centre).norm() - c.radius > 0.01 * c.radius);
    }
  }
  const TriMesh m = mesh_region(r);
  // Failures are recorded per gtest test, across all of rapidcheck's cases: count this case's.
  const ::testing::TestResult& result = *::testing::UnitTest::GetInstance()->current_test_info()->result();
  const int failures_before = result.total_part_count();
  expect_valid_mesh(r, m);
  RC_ASSERT(result.total_part_count() == failures_before);
  const double exact = area_properties(r).area;
  RC_ASSERT(std::abs(mesh_quality(m).area - exact) < 1e-6 * exact);
  RC_ASSERT(mesh_quality(m).min_angle_deg >= kGuaranteedMinAngleDeg);
}

}  // namespace
}  // namespace nbar::fe
