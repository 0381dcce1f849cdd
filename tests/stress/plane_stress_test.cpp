// The plane-stress finite elements against closed-form elasticity, published stress
// concentration factors, beam theory and CalculiX. The figures are recorded in docs/fe.md.
#include "test_constants.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include <unistd.h>

#include "nbar/io/calculix.hpp"
#include "nbar/model/diagnostics.hpp"
#include "nbar/stress/plane_stress.hpp"
#include "structured_t6.hpp"

namespace nbar::fe {
namespace {

using nbar::test_constants::kPi;
const ElasticMaterial kSteel{200e9, 0.3, 0.01, 7850};

double max_principal(const Eigen::Vector3d& s) { return 0.5 * (s[0] + s[1]) + std::hypot(0.5 * (s[0] - s[1]), s[2]); }

// Uniform tension `stress` along x on the edges x = x_min and x = x_max of a mesh.
std::vector<NodalForce> end_tension(const TriMesh& mesh, double x_min, double x_max, double stress, double thickness) {
  std::vector<NodalForce> out;
  const auto on = [](double x) {
    return [x](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
      return std::abs(a.x() - x) < 1e-12 && std::abs(b.x() - x) < 1e-12;
    };
  };
  structured::add_edge_traction(
      mesh, thickness, on(x_max), [&](const Eigen::Vector2d&) { return Eigen::Vector2d(stress, 0); }, out);
  structured::add_edge_traction(
      mesh, thickness, on(x_min), [&](const Eigen::Vector2d&) { return Eigen::Vector2d(-stress, 0); }, out);
  return out;
}

// The largest hoop (max principal) stress over the nodes of circle hole 0.
double hole_peak(const TriMesh& mesh, const StressField& field) {
  double peak = 0;
  for (const BoundaryEdge& e : mesh.boundary)
    if (e.on.kind == BoundaryTag::Kind::circle_hole)
      for (int v : e.nodes) peak = std::max(peak, max_principal(field.stress[v]));
  return peak;
}

TEST(PlaneStress, UniformTensionIsReproducedExactly) {
  // The patch test: a constant stress state is in the elements' span, so every node has it.
  const TriMesh mesh = structured::rectangle(0, 0, 0.2, 0.05, 8, 3);
  const PlateModel model(mesh, kSteel);
  LoadCase loads;
  loads.nodal = end_tension(mesh, 0, 0.2, 50e6, kSteel.thickness);
  const StressField field = model.solve(loads);
  for (std::size_t i = 0; i < mesh.nodes.size(); ++i) {
    EXPECT_NEAR(field.stress[i][0], 50e6, 1e-6 * 50e6);
    EXPECT_NEAR(field.stress[i][1], 0, 1e-6 * 50e6);
    EXPECT_NEAR(field.stress[i][2], 0, 1e-6 * 50e6);
  }
  EXPECT_NEAR(field.peak, 50e6, 1e-6 * 50e6);
  EXPECT_LT(field.load_unbalance, 1e-12);
  EXPECT_LT(field.support_reaction, 1e-9);
  // The displacement is affine, u = u0 + G x, with the strain (G + Gᵀ)/2 = (σ/E, −νσ/E, 0) (the
  // supports may add a rigid rotation, the antisymmetric part).
  const auto node_at = [&](double x, double y) {
    for (std::size_t i = 0; i < mesh.nodes.size(); ++i)
      if ((mesh.nodes[i] - Eigen::Vector2d(x, y)).norm() < 1e-12) return static_cast<int>(i);
    return -1;
  };
  const int origin = node_at(0, 0), right = node_at(0.2, 0), top = node_at(0, 0.05);
  ASSERT_GE(std::min({origin, right, top}), 0);
  Eigen::Matrix2d gradient;
  gradient.col(0) = (field.displacement.segment<2>(2 * right) - field.displacement.segment<2>(2 * origin)) / 0.2;
  gradient.col(1) = (field.displacement.segment<2>(2 * top) - field.displacement.segment<2>(2 * origin)) / 0.05;
  const Eigen::Matrix2d strain = 0.5 * (gradient + gradient.transpose());
  EXPECT_NEAR(strain(0, 0), 50e6 / 200e9, 1e-9 * 50e6 / 200e9);
  EXPECT_NEAR(strain(1, 1), -0.3 * 50e6 / 200e9, 1e-9 * 50e6 / 200e9);
  EXPECT_NEAR(strain(0, 1), 0, 1e-9 * 50e6 / 200e9);
}

// A cantilever 1 m long and 0.1 m deep with a tip load P carried by a parabolic shear, held at
// its root by the tractions of the elasticity solution (Timoshenko & Goodier): σxx = P (L − x) y / I.
TEST(PlaneStress, CantileverMatchesBeamTheoryAwayFromItsEnds) {
  const double length = 1.0, depth = 0.1, thickness = kSteel.thickness, load = 1000.0;
  const double inertia = thickness * depth * depth * depth / 12;
  const TriMesh mesh = structured::rectangle(0, -depth / 2, length, depth, 40, 8);
  const PlateModel model(mesh, kSteel);
  const auto shear = [&](double y) { return 1.5 * load / (depth * thickness) * (1 - 4 * y * y / (depth * depth)); };
  const auto at_x = [](double x) {
    return [x](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
      return std::abs(a.x() - x) < 1e-12 && std::abs(b.x() - x) < 1e-12;
    };
  };
  LoadCase loads;
  structured::add_edge_traction(
      mesh, thickness, at_x(length), [&](const Eigen::Vector2d& p) { return Eigen::Vector2d(0, -shear(p.y())); },
      loads.nodal);
  structured::add_edge_traction(
      mesh, thickness, at_x(0),
      [&](const Eigen::Vector2d& p) { return Eigen::Vector2d(-load * length * p.y() / inertia, shear(p.y())); },
      loads.nodal);
  const StressField field = model.solve(loads);
  EXPECT_LT(field.load_unbalance, 1e-12);
  EXPECT_LT(field.support_reaction, 1e-9);
  double top_fibre = 0;
  for (std::size_t i = 0; i < mesh.nodes.size(); ++i) {
    const Eigen::Vector2d& p = mesh.nodes[i];
    if (std::abs(p.x() - 0.5) > 1e-12) continue;
    if (std::abs(p.y() - depth / 2) < 1e-12) top_fibre = field.stress[i][0];
    const double beam = load * (length - p.x()) * p.y() / inertia;  // M c / I with M = P (L − x)
    EXPECT_NEAR(field.stress[i][0], beam, 0.002 * load * length * depth / 2 / inertia) << "at y = " << p.y();
    EXPECT_NEAR(field.stress[i][2], -shear(p.y()), 0.02 * shear(0)) << "at y = " << p.y();
  }
  // Mid-span top fibre: σ = M c / I = 500 N m x 0.05 m / 8.33e-7 m^4 = 30 MPa.
  std::printf("Cantilever mid-span top fibre: %.6g Pa, M c / I = %.6g Pa\n", top_fibre, 30e6);
  EXPECT_NEAR(load * 0.5 * (depth / 2) / inertia, 30e6, 1e-6);
  EXPECT_NEAR(top_fibre, 30e6, 0.005 * 30e6);
}

struct KirschRun {
  double kt = 0;
  int nodes = 0;
};

// A plate 30 hole diameters long and W = 15 d wide, a central hole, tension σ along its length.
KirschRun kirsch(int around, int rings) {
  const double radius = 0.01, half_width = 15 * radius, half_length = 45 * radius, stress = 1e6;
  const TriMesh mesh = structured::plate_with_hole(-half_length, -half_width, half_length, half_width, {0, 0}, radius,
                                                   around, rings, 4.5);
  const PlateModel model(mesh, kSteel);
  LoadCase loads;
  loads.nodal = end_tension(mesh, -half_length, half_length, stress, kSteel.thickness);
  const StressField field = model.solve(loads);
  EXPECT_LT(field.load_unbalance, 1e-12);
  EXPECT_LT(field.support_reaction, 1e-9);
  // The peak is the hoop stress at the top and bottom of the hole.
  EXPECT_NEAR(std::abs(field.peak_at.y()), radius, 1e-9);
  EXPECT_NEAR(field.peak_at.x(), 0, 1e-9);
  return {hole_peak(mesh, field) / stress, static_cast<int>(mesh.nodes.size())};
}

// Kirsch: Kt = 3 in an infinite plate. For d/W = 1/15 Heywood's finite-width formula (Peterson,
// Stress Concentration Factors, eq. 4.1 context) gives Ktn = 2 + (1 − d/W)^3 on the net section,
// i.e. Ktg = Ktn / (1 − d/W) = 3.014 on the gross stress.
TEST(PlaneStress, KirschHoleInAWidePlateAndMeshConvergence) {
  const double d_over_w = 1.0 / 15;
  const double heywood = (2 + std::pow(1 - d_over_w, 3)) / (1 - d_over_w);
  EXPECT_NEAR(heywood, 3.014, 0.001);
  const KirschRun coarse = kirsch(32, 12), medium = kirsch(64, 24), fine = kirsch(128, 48);
  std::printf("Kirsch (d/W = 1/15): Kt = %.4f (%d nodes), %.4f (%d nodes), %.4f (%d nodes); Heywood %.4f\n", coarse.kt,
              coarse.nodes, medium.kt, medium.nodes, fine.kt, fine.nodes, heywood);
  EXPECT_NEAR(fine.kt, heywood, 0.01 * heywood);
  EXPECT_NEAR(medium.kt, heywood, 0.02 * heywood);
  EXPECT_LT(std::abs(fine.kt - medium.kt) / fine.kt, 0.02);  // converged between the two finest levels
}

// A lug: width H, hole d at distance H from its end (h/H = 1), a pin pulling it towards the end,
// the far end of the shank in uniform tension. Peterson's chart 5.12 (Pilkey & Pilkey, Peterson's
// Stress Concentration Factors, 3rd ed.; Frocht & Hill's photoelastic lugs, close-fitting pin,
// h/H >= 1) is fitted by Ktn = 12.882 − 52.714 (d/H) + 89.762 (d/H)^2 − 51.667 (d/H)^3 on the net
// section P / ((H − d) t): 2.51 at d/H = 0.5 and 3.75 at d/H = 0.3. The cosine bearing pressure
// idealises the pin (a real pin's contact pressure peaks more sharply): nbar's converged Ktn
// (2.31 and 3.33, unchanged within 1 % on a mesh twice as fine or with h/H = 2) is 8 % and 11 %
// below the curve; the test holds them to 10 % and 15 % and below it.
double lug_kt(double d_over_h, int around, int rings) {
  const double height = 0.04, radius = d_over_h * height / 2, load = 1000.0;
  const TriMesh mesh =
      structured::plate_with_hole(-height, -height / 2, 4 * height, height / 2, {0, 0}, radius, around, rings, 2.5);
  const PlateModel model(mesh, kSteel);
  LoadCase loads;
  loads.bearings.push_back({0, {-load, 0}});
  loads.nodal = end_tension(mesh, -1, 4 * height, load / (height * kSteel.thickness), kSteel.thickness);
  const StressField field = model.solve(loads);
  EXPECT_LT(field.load_unbalance, 1e-9);
  EXPECT_LT(field.support_reaction, 1e-9);
  const double nominal = load / ((height - 2 * radius) * kSteel.thickness);
  return hole_peak(mesh, field) / nominal;
}

double peterson_lug(double r) { return 12.882 - 52.714 * r + 89.762 * r * r - 51.667 * r * r * r; }

TEST(PlaneStress, PinLoadedLugAgainstPetersonsCurve) {
  for (auto [ratio, tolerance] : {std::pair{0.3, 0.15}, std::pair{0.5, 0.10}}) {
    const double kt = lug_kt(ratio, 96, 32), reference = peterson_lug(ratio);
    std::printf("Lug d/H = %.2f, h/H = 1: Ktn = %.3f; Peterson (Frocht & Hill fit) %.3f\n", ratio, kt, reference);
    EXPECT_NEAR(kt, reference, tolerance * reference);
    EXPECT_LT(kt, reference);  // the cosine pressure's known bias
  }
  EXPECT_NEAR(peterson_lug(0.5), 2.507, 0.001);
}

// A ring spinning about its centre: the body force ρω²r alone (balanced, so no relief). Plane
// stress, free edges: σθ(a) = (3 + ν)/4 ρω² (b² + (1 − ν)/(3 + ν) a²) at the bore (Timoshenko).
TEST(PlaneStress, SpinningRingMatchesTheClosedForm) {
  const double a = 0.02, b = 0.1, omega = 300.0, rho = kSteel.density, nu = kSteel.poisson_ratio;
  const TriMesh mesh = structured::ring(a, b, 96, 24);
  const PlateModel model(mesh, kSteel);
  LoadCase loads;
  loads.body = RigidBodyField{{0, 0}, {0, 0}, omega, 0.0, {0, 0}};
  const StressField field = model.solve(loads);
  EXPECT_LT(field.load_unbalance, 1e-9);
  EXPECT_LT(field.support_reaction, 1e-9);
  const double bore = (3 + nu) / 4 * rho * omega * omega * (b * b + (1 - nu) / (3 + nu) * a * a);
  std::printf("Spinning ring: bore hoop stress %.5g Pa, closed form %.5g Pa\n", hole_peak(mesh, field), bore);
  EXPECT_NEAR(hole_peak(mesh, field), bore, 0.005 * bore);
  EXPECT_NEAR(field.peak, bore, 0.005 * bore);
  // Mid-radius: σr = (3 + ν)/8 ρω² (a² + b² − a²b²/r² − r²).
  const double r = 0.5 * (a + b);
  const double radial = (3 + nu) / 8 * rho * omega * omega * (a * a + b * b - a * a * b * b / (r * r) - r * r);
  for (std::size_t i = 0; i < mesh.nodes.size(); ++i) {
    if (std::abs(mesh.nodes[i].norm() - r) > 1e-9) continue;
    const Eigen::Vector2d n = mesh.nodes[i] / r;
    const Eigen::Vector3d& s = field.stress[i];
    const double sigma_r = s[0] * n.x() * n.x() + s[1] * n.y() * n.y() + 2 * s[2] * n.x() * n.y();
    EXPECT_NEAR(sigma_r, radial, 0.005 * bore);
  }
}

// Loads are placed as the header promises: the bearing's resultant is the force through the
// hole's centre, the couple's moment is the moment, a point force keeps its line of action. So
// sets in equilibrium show no unbalance; a lone load is relieved and its unbalance reported.
TEST(PlaneStress, LoadsHaveTheirResultantsAndUnbalanceIsRelieved) {
  const TriMesh mesh = structured::plate_with_hole(-0.05, -0.02, 0.15, 0.02, {0, 0}, 0.008, 48, 12, 2.0);
  const PlateModel model(mesh, kSteel);
  const auto [centre, radius] = model.hole_circle(0);
  EXPECT_NEAR(centre.norm(), 0, 1e-12);
  EXPECT_NEAR(radius, 0.008, 1e-12);
  const auto net = [&](const LoadCase& loads) {
    const Eigen::VectorXd f = model.nodal_loads(loads).forces;
    Eigen::Vector3d out = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < mesh.nodes.size(); ++i) {
      out.head<2>() += f.segment<2>(2 * i);
      out[2] += mesh.nodes[i].x() * f[2 * i + 1] - mesh.nodes[i].y() * f[2 * i];
    }
    return out;
  };
  LoadCase lone;
  lone.bearings.push_back({0, {300, -400}});
  EXPECT_LT(net(lone).norm(), 1e-9);  // relieved
  EXPECT_GT(model.nodal_loads(lone).load_unbalance, 0.99);
  EXPECT_GT(model.solve(lone).peak, 0);
  EXPECT_LT(model.solve(lone).support_reaction, 1e-9);

  LoadCase collinear;  // the point force on the bearing's line of action, through the hole's centre
  collinear.bearings.push_back({0, {300, -400}});
  collinear.forces.push_back({{0.012, -0.016}, {-300, 400}});
  EXPECT_LT(model.nodal_loads(collinear).load_unbalance, 1e-9);
  collinear.forces[0].at = {0.0, -0.016};  // off the line: a 400 N x 0.012 m couple is left
  EXPECT_NEAR(model.nodal_loads(collinear).load_unbalance, 400 * 0.012 / (0.2 * std::sqrt(1.04)) / 500, 1e-9);

  LoadCase couple;  // a couple on the hole against two opposite point forces 0.09 m apart
  couple.couples.push_back({0, 45.0});
  couple.forces.push_back({{0.05, 0.0}, {0, 500}});
  couple.forces.push_back({{0.14, 0.0}, {0, -500}});
  EXPECT_LT(model.nodal_loads(couple).load_unbalance, 1e-9);
  const StressField field = model.solve(couple);
  EXPECT_LT(field.support_reaction, 1e-9);
  EXPECT_GT(field.peak, 0);
  EXPECT_TRUE(std::isfinite(field.peak));
}

TEST(PlaneStress, BadInputIsRefusedWithAClearMessage) {
  const TriMesh mesh = structured::plate_with_hole(-0.05, -0.02, 0.15, 0.02, {0, 0}, 0.008, 16, 4, 1.0);
  const auto message = [](auto&& f) {
    try {
      f();
    } catch (const nbar::Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message([&] {
              PlateModel(mesh, {0, 0.3, 0.01, 0});
            }),
            "finite elements: Young's modulus must be a positive number");
  EXPECT_EQ(message([&] {
              PlateModel(mesh, {1e9, 0.5, 0.01, 0});
            }),
            "finite elements: Poisson's ratio must be in [0, 0.5)");
  EXPECT_EQ(message([&] {
              PlateModel(mesh, {1e9, 0.3, -1, 0});
            }),
            "finite elements: the plate thickness must be a positive number");
  TriMesh broken = mesh;
  broken.triangles[3][4] = 100000;
  EXPECT_NE(message([&] { PlateModel(broken, kSteel); }).find("triangle 3 refers to node 100000"), std::string::npos);
  TriMesh two_pieces = structured::rectangle(0, 0, 1, 1, 2, 2);
  const TriMesh other = structured::rectangle(2, 0, 1, 1, 1, 1);
  const int offset = static_cast<int>(two_pieces.nodes.size());
  for (const auto& p : other.nodes) two_pieces.nodes.push_back(p);
  for (auto t : other.triangles) {
    for (int& v : t) v += offset;
    two_pieces.triangles.push_back(t);
  }
  EXPECT_NE(message([&] { PlateModel(two_pieces, kSteel); }).find("more than one piece"), std::string::npos);
  const PlateModel model(mesh, kSteel);
  LoadCase loads;
  loads.bearings.push_back({2, {1, 0}});
  EXPECT_EQ(message([&] { model.solve(loads); }), "finite elements: the plate has no circle hole 2 (it has 1)");
  loads.bearings = {{0, {std::nan(""), 0}}};
  EXPECT_EQ(message([&] { model.solve(loads); }), "finite elements: the bearing force on hole 0 is not finite");
  loads.bearings.clear();
  loads.forces.push_back({{1.0, 1.0}, {1, 0}});
  EXPECT_EQ(message([&] { model.solve(loads); }),
            "finite elements: the point force at (1.000000, 1.000000) is outside the plate");
  loads.forces = {{{0.0, 0.0}, {1, 0}}};  // the hole's centre is not in the plate
  EXPECT_NE(message([&] { model.solve(loads); }).find("outside the plate"), std::string::npos);
  // No load: zero stress, no NaN.
  const StressField none = model.solve({});
  EXPECT_EQ(none.peak, 0.0);
  EXPECT_EQ(none.load_unbalance, 0.0);
}

}  // namespace
}  // namespace nbar::fe

namespace nbar::fe {
namespace {

// The same mesh, material, supports and balanced nodal loads in CalculiX's CPS6 elements (Debian's
// calculix-ccx, run here): displacements and stresses must agree, node by node. ccx expands CPS6
// into a layer of solid elements as thick as the section, which is plane stress only while it is
// thin: at t = r (the 10 mm plate this test had) its σzz reached 0.2 of the net stress at the hole
// and its σxx ran 1.5 % high. The plate here is 1 mm thick, a tenth of the hole's radius.
TEST(PlaneStress, AgreesWithCalculix) {
  const double height = 0.04, radius = 0.01, load = 1000.0;
  const ElasticMaterial thin{kSteel.youngs_modulus, kSteel.poisson_ratio, 0.001, kSteel.density};
  const TriMesh mesh =
      structured::plate_with_hole(-height, -height / 2, 4 * height, height / 2, {0, 0}, radius, 64, 20, 2.5);
  const PlateModel model(mesh, thin);
  LoadCase loads;
  loads.bearings.push_back({0, {-load * 0.8, load * 0.6}});
  loads.couples.push_back({0, 2.0});
  loads.body = RigidBodyField{{0.08, 0}, {3, -2}, 40.0, 500.0, {0, -9.81}};
  loads.nodal = end_tension(mesh, -1, 4 * height, load / (height * thin.thickness), thin.thickness);
  const StressField ours = model.solve(loads);

  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("nbar-ccx-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  {
    std::ofstream deck(dir / "lug.inp");
    write_calculix_input(deck, model, loads, "nbar lug");
  }
  const std::string command = "cd '" + dir.string() + "' && ccx -i lug > ccx.log 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0)
      << "ccx failed or is not installed (Debian package calculix-ccx); see " << dir / "ccx.log";
  std::ifstream frd(dir / "lug.frd");
  ASSERT_TRUE(frd) << "ccx wrote no " << dir / "lug.frd";
  const CalculixResults theirs = read_calculix_frd(frd);
  ASSERT_EQ(theirs.displacement.size(), mesh.nodes.size());
  ASSERT_EQ(theirs.stress.size(), mesh.nodes.size());
  ASSERT_EQ(theirs.stress_zz.size(), mesh.nodes.size());

  const auto von_mises = [](const Eigen::Vector3d& s) {
    return std::sqrt(s[0] * s[0] - s[0] * s[1] + s[1] * s[1] + 3 * s[2] * s[2]);
  };
  double largest = 0, worst = 0, their_peak = 0, worst_stress = 0, worst_far = 0, largest_zz = 0;
  Eigen::Vector2d worst_at(0, 0);
  for (std::size_t i = 0; i < mesh.nodes.size(); ++i)
    largest = std::max(largest, ours.displacement.segment<2>(2 * i).norm());
  for (std::size_t i = 0; i < mesh.nodes.size(); ++i) {
    worst = std::max(worst, (ours.displacement.segment<2>(2 * i) - theirs.displacement[i]).norm());
    their_peak = std::max(their_peak, von_mises(theirs.stress[i]));
    largest_zz = std::max(largest_zz, std::abs(theirs.stress_zz[i]));
  }
  // Node by node, relative to the peak: everywhere, and more than two radii from the hole.
  for (std::size_t i = 0; i < mesh.nodes.size(); ++i) {
    const double difference = std::abs(von_mises(ours.stress[i]) - von_mises(theirs.stress[i])) / ours.peak;
    if (difference > worst_stress) worst_at = mesh.nodes[i];
    worst_stress = std::max(worst_stress, difference);
    if (mesh.nodes[i].norm() > 3 * radius) worst_far = std::max(worst_far, difference);
  }
  std::printf(
      "CalculiX: %zu nodes, 1 mm plate; largest displacement difference %.3g of the largest displacement; "
      "peak von Mises %.6g Pa (nbar) and %.6g Pa (ccx): %.3f %%; von Mises node by node within %.3f %% of the "
      "peak, at (%.4g, %.4g) m (%.3f %% beyond 3 r); ccx's largest sigma_zz %.3g of the peak\n",
      mesh.nodes.size(), worst / largest, ours.peak, their_peak, 100 * (ours.peak / their_peak - 1), 100 * worst_stress,
      worst_at.x(), worst_at.y(), 100 * worst_far, largest_zz / their_peak);
  EXPECT_LT(worst / largest, 0.01);
  EXPECT_NEAR(ours.peak, their_peak, 0.01 * their_peak);
  // The largest difference is on the loaded hole's edge, under the bearing pressure and the
  // shear couple (6.8 % of the peak, ccx's stresses there extrapolated from its wedges' points);
  // beyond three radii, 0.8 %.
  EXPECT_LT(worst_stress, 0.08);
  EXPECT_LT(worst_at.norm(), 1.01 * radius);
  EXPECT_LT(worst_far, 0.01);
  EXPECT_LT(largest_zz, 0.05 * their_peak);
  std::filesystem::remove_all(dir);
}

// Every number of a deck fits ccx's 20-character fields, with the digits to read it back exactly
// where they fit: -9.18485099360515e-19 (21 characters) was read as -0.918.
TEST(PlaneStress, CalculixFieldsFitTwentyCharacters) {
  TriMesh mesh = structured::rectangle(0, 0, 0.2, 0.05, 4, 2);
  mesh.nodes[0].x() = -9.18485099360515e-19;  // on the rectangle's corner, to rounding
  const PlateModel model(mesh, kSteel);
  LoadCase loads;
  loads.nodal = end_tension(mesh, 0, 0.2, 1.0 / 3.0, kSteel.thickness);
  std::ostringstream deck;
  write_calculix_input(deck, model, loads);
  std::istringstream lines(deck.str());
  std::string line;
  int fields = 0;
  bool in_nodes = false;
  while (std::getline(lines, line)) {
    if (line.rfind("*", 0) == 0) {
      in_nodes = line.rfind("*NODE, NSET", 0) == 0;
      continue;
    }
    std::istringstream cells(line);
    std::string cell;
    std::vector<std::string> row;
    while (std::getline(cells, cell, ',')) {
      if (!cell.empty() && cell[0] == ' ') cell.erase(0, 1);
      EXPECT_LE(cell.size(), 20u) << line;
      row.push_back(cell);
      ++fields;
    }
    if (in_nodes && row.size() == 3) {
      const int node = std::stoi(row[0]) - 1;
      // 14 significant digits at the least, 16 or 17 for most numbers.
      EXPECT_NEAR(std::stod(row[1]), mesh.nodes[node].x(), 1e-13 * std::abs(mesh.nodes[node].x())) << line;
      EXPECT_NEAR(std::stod(row[2]), mesh.nodes[node].y(), 1e-13 * std::abs(mesh.nodes[node].y())) << line;
    }
  }
  EXPECT_GT(fields, 100);
  EXPECT_NE(deck.str().find("1, -9.1848509936051e-19, 0\n"), std::string::npos) << deck.str().substr(0, 200);
}

}  // namespace
}  // namespace nbar::fe

namespace nbar::fe {
namespace {

// solve_many gives what solve gives, case by case, across several blocks.
TEST(PlaneStress, SolveManyMatchesSolve) {
  const TriMesh mesh = structured::plate_with_hole(-0.05, -0.02, 0.15, 0.02, {0, 0}, 0.008, 32, 8, 2.0);
  const PlateModel model(mesh, kSteel);
  std::vector<LoadCase> cases;
  for (int i = 0; i < 37; ++i) {
    LoadCase c;
    c.bearings.push_back({0, {100.0 * std::cos(0.3 * i), 100.0 * std::sin(0.3 * i)}});
    c.couples.push_back({0, 0.5 * i});
    c.body = RigidBodyField{{0.05, 0}, {1, 2}, 3.0 + i, 10.0 - i, {0, -9.81}};
    cases.push_back(c);
  }
  const std::vector<StressField> many = model.solve_many(cases);
  ASSERT_EQ(many.size(), cases.size());
  for (std::size_t i = 0; i < cases.size(); i += 6) {
    const StressField one = model.solve(cases[i]);
    EXPECT_NEAR(many[i].peak, one.peak, 1e-12 * one.peak);
    EXPECT_EQ(many[i].peak_node, one.peak_node);
    EXPECT_LT((many[i].displacement - one.displacement).norm(), 1e-12 * one.displacement.norm());
    EXPECT_LT(one.support_reaction, 1e-9);
  }
  EXPECT_TRUE(model.solve_many({}).empty());
}

}  // namespace
}  // namespace nbar::fe

namespace nbar::fe {
namespace {

TEST(PlaneStress, CalculixResultsReaderReadsBlocksAndLocatesBadLines) {
  std::istringstream good(
      "    2C                             2                                     1\n"
      " -1         1 0.00000E+00 0.00000E+00 0.00000E+00\n"
      " -3\n"
      " -4  DISP        4    1\n"
      " -5  D1          1    2    1    0\n"
      " -1         1 1.00000E-03-2.00000E-03 0.00000E+00\n"
      " -1         2 3.00000E-03 4.00000E-03 0.00000E+00\n"
      " -3\n"
      " -4  STRESS      6    1\n"
      " -1         2 1.00000E+06 2.00000E+06 0.00000E+00 3.00000E+06 0.00000E+00 0.00000E+00\n"
      " -3\n");
  const CalculixResults r = read_calculix_frd(good);
  ASSERT_EQ(r.displacement.size(), 2u);
  EXPECT_EQ(r.displacement[0], Eigen::Vector2d(1e-3, -2e-3));
  EXPECT_EQ(r.displacement[1], Eigen::Vector2d(3e-3, 4e-3));
  ASSERT_EQ(r.stress.size(), 2u);
  EXPECT_EQ(r.stress[1], Eigen::Vector3d(1e6, 2e6, 3e6));
  std::istringstream bad(" -4  DISP        4    1\n -1         1 1.0000\n");
  try {
    read_calculix_frd(bad);
    ADD_FAILURE() << "no error";
  } catch (const nbar::Error& e) {
    EXPECT_NE(std::string(e.what()).find("line 2"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace nbar::fe

namespace nbar::fe {
namespace {

// The same checks on meshes from nbar's own mesher (mesh_region), as the link pipeline makes them.

// A bar with a 20 mm hole at each end, 40 mm wide, ends 40 mm beyond the hole centres (h/H = 1,
// d/H = 0.5), pulled apart by its two pins: each end is the lug above.
Region two_hole_bar() { return make_bar({0, 0}, {0.2, 0}, 0.04, 0.04, 0.01, 0.01); }

struct MeshedLug {
  double kt = 0;
  int nodes = 0;
  StressField field;
};

MeshedLug meshed_lug(double size, int segments) {
  MeshOptions options;
  options.size = size;
  options.segments_per_hole = segments;
  const TriMesh mesh = mesh_region(two_hole_bar(), options);
  const PlateModel model(mesh, kSteel);
  LoadCase loads;
  loads.bearings = {{0, {-1000, 0}}, {1, {1000, 0}}};
  MeshedLug out;
  out.field = model.solve(loads);
  // Quadratic edges approximate the circle: a bearing's discrete resultant is turned onto F by
  // ~1e-8 rad, which leaves a moment of that order times r / size.
  EXPECT_LT(out.field.load_unbalance, 1e-8);
  EXPECT_LT(out.field.support_reaction, 1e-9);
  out.kt = hole_peak(mesh, out.field) / (1000 / ((0.04 - 0.02) * kSteel.thickness));
  out.nodes = static_cast<int>(mesh.nodes.size());
  return out;
}

TEST(PlaneStress, MeshedTwoHoleBarIsTheLugAndConverges) {
  const MeshedLug coarse = meshed_lug(0.008, 32), medium = meshed_lug(0.004, 48), fine = meshed_lug(0.002, 96);
  std::printf("Meshed two-hole bar (lug d/H = 0.5, h/H = 1): Ktn = %.4f (%d nodes), %.4f (%d nodes), %.4f (%d nodes)\n",
              coarse.kt, coarse.nodes, medium.kt, medium.nodes, fine.kt, fine.nodes);
  EXPECT_LT(std::abs(fine.kt - medium.kt) / fine.kt, 0.02);
  EXPECT_NEAR(fine.kt, 2.31, 0.03 * 2.31);  // the structured lug mesh's converged value
  EXPECT_NEAR(fine.kt, peterson_lug(0.5), 0.10 * peterson_lug(0.5));
  // The peak sits beside a hole, across the net section.
  const Eigen::Vector2d at = fine.field.peak_at;
  const double from_hole = std::min(at.norm(), (at - Eigen::Vector2d(0.2, 0)).norm());
  EXPECT_NEAR(from_hole, 0.01, 1e-6);
  EXPECT_GT(std::abs(at.y()), 0.008);
}

// Kirsch on a mesher-made plate: W = 15 d, length 30 d.
TEST(PlaneStress, MeshedKirschPlate) {
  const double radius = 0.01, half_width = 15 * radius, half_length = 30 * radius;
  Region plate;
  plate.outline = {
      {-half_length, -half_width}, {half_length, -half_width}, {half_length, half_width}, {-half_length, half_width}};
  plate.circle_holes = {Circle{{0, 0}, radius}};
  MeshOptions options;
  options.size = 0.02;
  options.segments_per_hole = 128;
  const TriMesh mesh = mesh_region(plate, options);
  const PlateModel model(mesh, kSteel);
  LoadCase loads;
  loads.nodal = end_tension(mesh, -half_length, half_length, 1e6, kSteel.thickness);
  const StressField field = model.solve(loads);
  const double kt = hole_peak(mesh, field) / 1e6;
  std::printf("Meshed Kirsch plate (d/W = 1/15): Kt = %.4f with %zu nodes; Heywood 3.014\n", kt, mesh.nodes.size());
  EXPECT_NEAR(kt, 3.014, 0.015 * 3.014);
  EXPECT_LT(field.support_reaction, 1e-9);
}

// A strap W wide with a central hole of d = W / 2, pulled along its length, meshed at the automatic
// size and at a half and a quarter of it: the holes' edges are refined with the size, so the peak
// converges (at a fixed 48 edges per hole it wobbled: 43.18 / 43.07 / 43.02 / 43.14 MPa on the
// bundled plates). Reference: Howland's Kt for a hole in a strip as fitted in Peterson's chart 4.1,
// Ktn = 3 - 3.14 (d/W) + 3.667 (d/W)^2 - 1.527 (d/W)^3 = 2.156 at d/W = 0.5 (Heywood's 2 + (1 -
// d/W)^3 = 2.125), on the net section; the peak is Ktn times the net stress.
TEST(PlaneStress, PeakAtAHoleConvergesWithTheMeshSize) {
  const double width = 0.04, radius = 0.01, half_length = 0.2, stress = 1e6;
  Region strap;
  strap.outline = {
      {-half_length, -width / 2}, {half_length, -width / 2}, {half_length, width / 2}, {-half_length, width / 2}};
  strap.circle_holes = {Circle{{0, 0}, radius}};
  const double d_over_w = 2 * radius / width;
  const double howland = 3 - 3.14 * d_over_w + 3.667 * d_over_w * d_over_w - 1.527 * std::pow(d_over_w, 3);
  const double net = stress * width / (width - 2 * radius);
  const double automatic = automatic_mesh_size(strap);
  std::vector<double> peaks;
  std::vector<std::size_t> nodes;
  for (double refinement : {1.0, 2.0, 4.0, 8.0}) {
    MeshOptions options;
    options.size = automatic / refinement;
    const TriMesh mesh = mesh_region(strap, options);
    const PlateModel model(mesh, kSteel);
    LoadCase loads;
    loads.nodal = end_tension(mesh, -half_length, half_length, stress, kSteel.thickness);
    peaks.push_back(hole_peak(mesh, model.solve(loads)) / net);
    nodes.push_back(mesh.nodes.size());
  }
  std::printf("Strap d/W = 0.5: Ktn %.5f / %.5f / %.5f / %.5f at %zu / %zu / %zu / %zu nodes; Howland %.4f\n", peaks[0],
              peaks[1], peaks[2], peaks[3], nodes[0], nodes[1], nodes[2], nodes[3], howland);
  for (std::size_t i = 1; i < peaks.size(); ++i) EXPECT_GT(nodes[i], 2 * nodes[i - 1]) << "the holes refine too";
  // The change shrinks from 0.14 % to below 0.03 %, where it stays (the nodal averages' scatter).
  const auto change = [&](std::size_t i) { return std::abs(peaks[i] - peaks[i - 1]) / peaks[i]; };
  EXPECT_LT(change(2), 0.25 * change(1));
  EXPECT_LT(change(2), 3e-4);
  EXPECT_LT(change(3), 3e-4);
  EXPECT_NEAR(peaks.back(), howland, 0.01 * howland);
  EXPECT_NEAR(peaks.back(), 2 + std::pow(1 - d_over_w, 3), 0.03 * howland);
}

}  // namespace
}  // namespace nbar::fe

namespace nbar::fe {
namespace {

// docs/fe.md's example, as written there.
TEST(PlaneStress, DocsExampleRuns) {
  const Region bar = make_bar({0, 0}, {0.2, 0}, 0.04, 0.03, 0.01, 0.01);
  const fe::PlateModel model(fe::mesh_region(bar, {.size = 0.004}), {200e9, 0.3, 0.01, 7850});
  fe::LoadCase loads;
  loads.bearings = {{0, {-1000, 0}}, {1, {1000, 0}}};
  loads.body = fe::RigidBodyField{.origin = {0, 0}, .omega = 5.0, .gravity = {0, -9.81}};
  const fe::StressField field = model.solve(loads);
  // Beside a hole, about Ktn × P / ((H − d) t) = 2.3 × 5 MPa.
  EXPECT_NEAR(field.peak, 2.3 * 1000 / (0.02 * 0.01), 0.1 * 2.3 * 1000 / (0.02 * 0.01));
  EXPECT_NEAR(std::min(field.peak_at.norm(), (field.peak_at - Eigen::Vector2d(0.2, 0)).norm()), 0.01, 1e-6);
  EXPECT_GT(field.load_unbalance, 0);  // the spin and gravity are relieved
  EXPECT_LT(field.support_reaction, 1e-9);
}

}  // namespace
}  // namespace nbar::fe
