// Finite-element link stresses: the load cases built from the inverse dynamics balance (net
// force and moment ~0 with the d'Alembert forces, checked with the exact plate geometry), go to
// the right holes, and end to end give beam theory's stresses far from the holes of a bar in a
// turned pose.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "../kinematics/helpers/kinematics_support.hpp"
#include "nbar/model/materials.hpp"
#include "nbar/stress/link_fe.hpp"
#include "nbar/stress/link_stress.hpp"

namespace nbar::ktest {
namespace {

constexpr double kWidth = 0.02, kThickness = 0.005, kMargin = 0.015, kHole = 0.004;

Material steel() { return *builtin_material("steel"); }

void give_bar(Model& m, int body, int p, int q) {
  m.bodies[body].shape = make_bar(m.points[p].position, m.points[q].position, kWidth, kMargin, kHole, kHole);
  m.bodies[body].thickness = kThickness;
  m.bodies[body].material = steel();
}

// A steel four-bar accelerating under gravity, with a torque on the rocker, a force on the
// coupler inside its plate (P, no hole) and one on a point of the coupler off its plate (Q).
Model loaded_four_bar() {
  Model m;
  const int o2 = add_point(m, "O2", {0, 0}, true);
  const int o4 = add_point(m, "O4", {0.2, 0}, true);
  const int a = add_point(m, "A", {0.05, 0});
  const int b = add_point(m, "B", {0.17, 0.1156});
  const int p = add_point(m, "P", {0.11, 0.0578});
  const int q = add_point(m, "Q", {0.11, 0.12});
  const int crank = add_body(m, "crank", {o2, a});
  const int coupler = add_body(m, "coupler", {a, b, p, q});
  const int rocker = add_body(m, "rocker", {o4, b});
  give_bar(m, crank, o2, a);
  give_bar(m, coupler, a, b);
  give_bar(m, rocker, o4, b);
  m.drivers.push_back(angle_driver("crank", crank, 0.0, 2 * kPi, 12.0, 40.0));
  m.gravity = {0, -9.81};
  m.torques.push_back(BodyTorque{rocker, Law::parse("2"), std::nullopt});
  m.point_loads.push_back(PointLoad{p, coupler, Law::parse("30"), Law::parse("-45")});
  m.point_loads.push_back(PointLoad{q, coupler, Law::parse("-20"), Law::parse("10")});
  m.sweep.steps = 7;
  return m;
}

struct Solved {
  std::shared_ptr<const InverseDynamics> dynamics;
  SweepResult sweep;
  std::vector<DynamicsResult> forces;
  LinkFe fe;
  Solved(Model m, FeOptions options)
      : dynamics(std::make_shared<const InverseDynamics>(std::make_shared<const Mechanism>(std::move(m)))),
        sweep(run_sweep(dynamics->mechanism(), sweep_options(2))),
        fe(dynamics, options) {
    for (const Sample& s : sweep.samples) forces.push_back(dynamics->solve(s));
  }
  const Model& model() const { return dynamics->mechanism().model(); }
};

FeOptions coarse() {
  FeOptions o;
  o.mesh_size = 0.004;
  return o;
}

// The size of a load case: its largest force, for relative tolerances.
double largest_force(const fe::LoadCase& loads, double weight) {
  double f = weight;
  for (const auto& b : loads.bearings) f = std::max(f, b.force.norm());
  for (const auto& p : loads.forces) f = std::max(f, p.force.norm());
  for (const auto& p : loads.nodal) f = std::max(f, p.force.norm());
  return f;
}

TEST(LinkFe, LoadCasesBalanceTheirDalembertForces) {
  const Solved s(loaded_four_bar(), coarse());
  ASSERT_EQ(s.sweep.samples.size(), 7u);
  int checked = 0;
  for (std::size_t i = 0; i < s.sweep.samples.size(); ++i) {
    for (int body = 0; body < 3; ++body) {
      ASSERT_TRUE(s.fe.analysed(body));
      const fe::LoadCase loads = s.fe.load_case(s.forces[i], body);
      ASSERT_TRUE(loads.body.has_value());
      const LoadResultant r =
          load_resultant(loads, *s.model().bodies[body].shape, s.fe.plate(body).material(), s.fe.plate(body).mesh());
      const double weight = s.dynamics->masses()[body].mass * 9.81;
      const double scale = largest_force(loads, weight);
      EXPECT_GT(scale, 0.1);
      EXPECT_LT(r.force.norm(), 1e-9 * scale) << "step " << i << " body " << body;
      EXPECT_LT(std::abs(r.moment), 1e-9 * scale * 0.2) << "step " << i << " body " << body;
      ++checked;
    }
  }
  EXPECT_EQ(checked, 21);
}

TEST(LinkFe, LoadsGoToTheirHoles) {
  const Solved s(loaded_four_bar(), coarse());
  const DynamicsResult& forces = s.forces[3];
  // The crank: bearings at O2 (hole 0) and A (hole 1), and the motor's torque around O2.
  const fe::LoadCase crank = s.fe.load_case(forces, 0);
  ASSERT_EQ(crank.bearings.size(), 2u);
  EXPECT_EQ(crank.bearings[0].hole, 0);
  EXPECT_EQ(crank.bearings[1].hole, 1);
  ASSERT_EQ(crank.couples.size(), 1u);
  EXPECT_EQ(crank.couples[0].hole, 0);
  EXPECT_NEAR(crank.couples[0].moment, forces.driver_effort[0], 1e-12 * std::abs(forces.driver_effort[0]));
  EXPECT_TRUE(crank.forces.empty());
  // A bearing carries the pin's force turned into the plate's frame: same magnitude.
  const auto& links = s.dynamics->joint_links();
  for (std::size_t i = 0; i < links.size(); ++i) {
    if (links[i].link == 0 && links[i].point == 0) {
      EXPECT_NEAR(crank.bearings[0].force.norm(), forces.pin_forces[i].norm(), 1e-12 * forces.pin_forces[i].norm());
    }
  }

  // The rocker: its torque around O4.
  const fe::LoadCase rocker = s.fe.load_case(forces, 2);
  ASSERT_EQ(rocker.couples.size(), 1u);
  EXPECT_EQ(rocker.couples[0].hole, 0);
  EXPECT_DOUBLE_EQ(rocker.couples[0].moment, 2.0);

  // The coupler: P's force where it acts, |(30, -45)|; Q's carried to a node with the couple of
  // the transfer spread over the nodes around it (nodal forces).
  const fe::LoadCase coupler = s.fe.load_case(forces, 1);
  EXPECT_EQ(coupler.bearings.size(), 2u);
  EXPECT_TRUE(coupler.couples.empty());
  const Eigen::Vector2d p = s.model().points[4].position;
  int at_p = 0;
  for (const auto& f : coupler.forces)
    if ((f.at - p).norm() < 1e-12) {
      ++at_p;
      EXPECT_NEAR(f.force.norm(), std::hypot(30.0, 45.0), 1e-9);
    }
  EXPECT_EQ(at_p, 1);
  EXPECT_EQ(coupler.forces.size(), 1u);
  EXPECT_EQ(coupler.nodal.size(), 9u);  // Q's force at its nearest node, and the 8-node patch couple
}

TEST(LinkFe, PlateFrameRoundTrip) {
  const Solved s(loaded_four_bar(), coarse());
  const DynamicsResult& forces = s.forces[2];
  const Eigen::Vector2d world(0.3, -0.1);
  for (int body = 0; body < 3; ++body) {
    EXPECT_LT((s.fe.to_world(forces, body, s.fe.to_plate(forces, body, world)) - world).norm(), 1e-14);
    // A body's own point: its drawn position in the plate's frame.
    const int point = s.model().bodies[body].points[1];
    EXPECT_LT((s.fe.to_plate(forces, body, forces.motion.r[point]) - s.model().points[point].position).norm(), 1e-12);
  }
}

TEST(LinkFe, NeedsElasticConstants) {
  Model m = loaded_four_bar();
  m.bodies[1].material->youngs_modulus.reset();
  m.bodies[1].material->name = "my-alloy";
  try {
    Solved s(m, coarse());
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::InvalidModel);
    EXPECT_EQ(e.where().kind, EntityRef::Kind::Body);
    EXPECT_EQ(e.where().index, 1);
    EXPECT_NE(e.message().find("material 'my-alloy' of body 'coupler' has no Young's modulus"), std::string::npos)
        << e.message();
  }
}

// A size too fine for one plate is refused before any plate is meshed: the coupler's was refused
// only after the crank had been meshed (54 s and 2 GB for the steel four-bar at 0.2 mm).
TEST(LinkFe, ASizeTooFineForAnyPlateIsRefusedBeforeMeshing) {
  const Model m = loaded_four_bar();
  const auto dynamics = std::make_shared<const InverseDynamics>(std::make_shared<const Mechanism>(m));
  FeOptions options;
  // At 2 mm the crank's plate (about 80 x 20 mm) needs fewer nodes than the coupler's (about
  // 170 x 20 mm); the budget lets the crank by and refuses the coupler, by the mesher's estimate
  // (refused when over 1.25 times the budget).
  options.mesh_size = 0.002;
  fe::MeshOptions mesh;
  mesh.size = options.mesh_size;
  const double crank = fe::estimated_mesh_nodes(*m.bodies[0].shape, mesh);
  const double coupler = fe::estimated_mesh_nodes(*m.bodies[1].shape, mesh);
  ASSERT_LT(crank, 0.9 * coupler);
  options.max_nodes = static_cast<int>(0.95 * coupler / 1.25);
  std::vector<std::string> stages;
  RunControl control;
  control.on_progress = [&](const Progress& p) {
    stages.push_back(p.stage);
    return true;
  };
  try {
    LinkFe fe(dynamics, options, control);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.where().kind, EntityRef::Kind::Body);
    EXPECT_EQ(e.where().index, 1);
    EXPECT_NE(e.message().find("the plate of body 'coupler' cannot be analysed by finite elements: mesh: the mesh "
                               "would have about"),
              std::string::npos)
        << e.message();
  }
  EXPECT_EQ(std::count(stages.begin(), stages.end(), "mesh"), 0);
  // With room for the coupler, every plate is meshed.
  options.max_nodes = 400000;
  stages.clear();
  LinkFe fe(dynamics, options, control);
  EXPECT_EQ(std::count(stages.begin(), stages.end(), "mesh"), 3);
}

// A massless steel bar held by a motor at O, turned to 30 degrees, with a vertical force at A:
// far from both holes the stress across the bar is beam theory's, N/A - M y/I, in the plate's
// own (unturned) frame.
TEST(LinkFe, TurnedCantileverMatchesBeamTheoryBetweenTheHoles) {
  const double length = 0.3, force = -400.0, angle = kPi / 6;
  Model m;
  const int o = add_point(m, "O", {0, 0}, true);
  const int a = add_point(m, "A", {length, 0});
  const int bar = add_body(m, "bar", {o, a});
  give_bar(m, bar, o, a);
  m.bodies[bar].inertia = GivenInertia{0.0, {length / 2, 0}, 0.0};
  m.drivers.push_back(angle_driver("bar", bar, angle, angle, 1.0));
  m.point_loads.push_back(PointLoad{a, bar, Law::parse("0"), Law::parse(std::to_string(force))});
  m.sweep.steps = 2;
  FeOptions options;
  options.mesh_size = 0.003;
  const Solved s(m, options);
  const fe::StressField field = s.fe.solve(s.forces[0], bar);
  EXPECT_LT(field.load_unbalance, 1e-9);
  EXPECT_LT(field.support_reaction, 1e-6);

  // The force in the plate's frame: turned back by 30 degrees.
  const double fx = force * std::sin(angle), fy = force * std::cos(angle);
  const double area = kWidth * kThickness, inertia = kThickness * std::pow(kWidth, 3) / 12.0;
  const fe::TriMesh& mesh = s.fe.plate(bar).mesh();
  int checked = 0;
  for (std::size_t n = 0; n < mesh.nodes.size(); ++n) {
    const Eigen::Vector2d& x = mesh.nodes[n];
    if (x.x() < 0.1 || x.x() > 0.2 || std::abs(std::abs(x.y()) - kWidth / 2) > 1e-9) continue;
    const double moment = (length - x.x()) * fy;  // of the force at A about the section
    const double sigma = fx / area - moment * x.y() / inertia;
    EXPECT_NEAR(field.stress[n].x(), sigma, 0.02 * std::abs(moment * kWidth / 2 / inertia)) << x.transpose();
    ++checked;
  }
  EXPECT_GE(checked, 10);

  // And nbar's beam model of the same link under the same forces (LinkStress, section by
  // section): its extreme-fibre stresses are the FE's at the nodes on the plate's edges.
  const LinkStress beam(s.dynamics, 200);
  const std::vector<SectionStress> sections = beam.profile(s.forces[0], bar);
  int compared = 0;
  for (std::size_t n = 0; n < mesh.nodes.size(); ++n) {
    const Eigen::Vector2d& x = mesh.nodes[n];
    if (x.x() < 0.1 || x.x() > 0.2 || std::abs(std::abs(x.y()) - kWidth / 2) > 1e-9) continue;
    const SectionStress* nearest = nullptr;
    for (const SectionStress& c : sections)
      if (!nearest || std::abs(c.position - x.x()) < std::abs(nearest->position - x.x())) nearest = &c;
    ASSERT_NE(nearest, nullptr);
    ASSERT_LT(std::abs(nearest->position - x.x()), 0.002);
    // The beam model's section at `position` is the FE's at x up to the gap between them.
    const double gap = std::abs(nearest->position - x.x()) * std::abs(fy) * (kWidth / 2) / inertia;
    const double beam_sigma = x.y() > 0 ? nearest->sigma_high : nearest->sigma_low;  // left of the axis is +y
    EXPECT_NEAR(field.stress[n].x(), beam_sigma, gap + 0.02 * std::abs(fy * (length - x.x()) * kWidth / 2 / inertia))
        << x.transpose();
    ++compared;
  }
  EXPECT_GE(compared, 10);
}

TEST(LinkFe, PeaksOverTheSweepAreTheSameOnOneOrTwoThreads) {
  FeOptions one = coarse(), two = coarse();
  one.threads = 1;
  two.threads = 2;
  const Solved s1(loaded_four_bar(), one), s2(loaded_four_bar(), two);
  const std::vector<FePeak> p1 = fe_peaks(s1.fe, s1.sweep, s1.forces), p2 = fe_peaks(s2.fe, s2.sweep, s2.forces);
  ASSERT_EQ(p1.size(), 3u);
  ASSERT_EQ(p2.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(p1[k].body, static_cast<int>(k));
    EXPECT_EQ(p1[k].step, p2[k].step);
    // Blocks of cases are back-substituted together: the same to rounding whatever the blocks.
    EXPECT_NEAR(p1[k].von_mises, p2[k].von_mises, 1e-12 * p1[k].von_mises);
    EXPECT_GT(p1[k].von_mises, 0.0);
    EXPECT_GT(p1[k].nodes, 100);
    EXPECT_GT(p1[k].elements, 40);
    EXPECT_EQ(p1[k].mesh_size, 0.004);
    ASSERT_TRUE(p1[k].safety_factor.has_value());
    EXPECT_NEAR(*p1[k].safety_factor * p1[k].von_mises, 250e6, 1e-6);
    EXPECT_LT(p1[k].load_unbalance, 1e-6);
    EXPECT_LT(p1[k].support_reaction, 1e-6);
    // The peak is the largest nodal stress of its step's field.
    const fe::StressField at_peak = s1.fe.solve(s1.forces[p1[k].step], p1[k].body);
    EXPECT_NEAR(at_peak.peak, p1[k].von_mises, 1e-12 * p1[k].von_mises);
    for (std::size_t i = 0; i < s1.forces.size(); ++i)
      EXPECT_LE(s1.fe.solve(s1.forces[i], p1[k].body).peak, p1[k].von_mises * (1 + 1e-12));
  }
}

}  // namespace
}  // namespace nbar::ktest

namespace nbar::ktest {
namespace {

// A convergence study halves every plate's element sizes until every peak changes by less than
// the tolerance, each change |p_k - p_k-1| / p_k of the meshes it lists; or it stops, saying why,
// when the next mesh would pass the node budget (refused before meshing).
TEST(LinkFe, ConvergenceHalvesTheSizesUntilThePeaksSettle) {
  const Solved s(loaded_four_bar(), coarse());
  const std::vector<FePeak> first = fe_peaks(s.fe, s.sweep, s.forces);
  const FeConvergence c = converge_fe_peaks(s.dynamics, s.fe.options(), first, s.sweep, s.forces, 0.01);
  ASSERT_TRUE(c.converged) << c.stopped;
  ASSERT_GE(c.meshes.size(), 2u);
  for (std::size_t i = 1; i < c.meshes.size(); ++i) {
    EXPECT_EQ(c.meshes[i].refinement, 2 * c.meshes[i - 1].refinement);
    for (std::size_t k = 0; k < first.size(); ++k) {
      const FePeak& now = c.meshes[i].peaks[k];
      const FePeak& before = c.meshes[i - 1].peaks[k];
      EXPECT_EQ(now.mesh_size, before.mesh_size / 2);
      EXPECT_GT(now.nodes, before.nodes);
      EXPECT_DOUBLE_EQ(c.meshes[i].change[k], std::abs(now.von_mises - before.von_mises) / now.von_mises);
    }
  }
  for (double change : c.meshes.back().change) EXPECT_LT(change, 0.01);
  std::printf("converged in %zu meshes; crank %.6g -> %.6g MPa\n", c.meshes.size(), first[0].von_mises / 1e6,
              c.meshes.back().peaks[0].von_mises / 1e6);

  // A budget that the second mesh passes.
  FeOptions tight = s.fe.options();
  tight.max_nodes = first[1].nodes + 10;
  const FeConvergence stopped = converge_fe_peaks(s.dynamics, tight, first, s.sweep, s.forces, 1e-6);
  EXPECT_FALSE(stopped.converged);
  EXPECT_EQ(stopped.meshes.size(), 1u);
  EXPECT_NE(stopped.stopped.find("stopped at the node budget"), std::string::npos) << stopped.stopped;
  EXPECT_NE(stopped.stopped.find("max_nodes"), std::string::npos) << stopped.stopped;
  EXPECT_THROW(converge_fe_peaks(s.dynamics, s.fe.options(), first, s.sweep, s.forces, 0.0), Error);
}

}  // namespace
}  // namespace nbar::ktest
