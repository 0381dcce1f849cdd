// Finite-element stresses in links: every body with a shape is meshed (mesh_region) and its
// plane-stress model factorised once (PlateModel); every solved sample of the inverse dynamics
// then becomes a load case on that plate, a back-substitution.
//
// The loads of a sample on a body, in the plate's own frame (the starting pose: world vectors
// are rotated back by the body's rotation since then):
// - the forces at a point inside a circle hole (pin forces, and any force applied there) add up
//   to one resultant, a cosine bearing pressure on that hole (the pin presses with the
//   resultant);
// - couples at a point inside a circle hole (driver torques, applied torques) are a shear
//   couple around the hole (a keyed shaft);
// - a force at a point of the plate with no hole is a point force; a force at a point outside
//   the plate is carried to the nearest node with the couple of that transfer (a rigid bracket);
// - a couple not at a hole is spread over the nodes around its point as a rigid-patch shear;
// - gravity and the d'Alembert forces of the body's motion are a body force (RigidBodyField),
//   with the body's mass spread evenly over its plate, as the beam model does.
// The loads balance when the plate's mass properties are the body's; otherwise (given masses)
// the solver's inertia relief takes the difference, reported as the load unbalance.
#pragma once

#include <Eigen/Core>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "nbar/dynamics/inverse_dynamics.hpp"
#include "nbar/model/run_control.hpp"
#include "nbar/stress/field_query.hpp"
#include "nbar/stress/plane_stress.hpp"

namespace nbar {

struct FeOptions {
  // Target element edge far from holes and corners, m; 0: the mesher's default (a twentieth of
  // the plate's bounding-box diagonal).
  double mesh_size = 0.0;
  // Worker threads over the samples of a sweep (1 or 2 is what a desktop needs; 0: the
  // hardware's, at most 2).
  int threads = 0;
  // A plate that would need more nodes is an error (the web server bounds its requests so).
  int max_nodes = 400000;
  // Edges around each circle hole at least, and the element edge along holes, arcs and
  // re-entrant corners at most (m; 0: automatic, scaled with mesh_size): fe::MeshOptions.
  int segments_per_hole = 48;
  double edge_size = 0.0;
  // Every plate's element sizes (mesh_size or its automatic size, and edge_size) divided by this
  // (>= 1): the meshes of a convergence study (converge_fe_peaks).
  double refinement = 1.0;
};

// Where a load acting at one point of a body reaches its plate.
struct PlatePlacement {
  Eigen::Vector2d at{0, 0};  // the point, plate frame
  int hole = -1;             // the circle hole it lies in, or -1
  bool inside = true;        // on the plate (when not in a hole); false: carried to `node`
  int node = -1;             // the nearest interior corner node, for a point off the plate
  std::vector<int> patch;    // interior corner nodes around the point, for couples
};

class LinkFe {
 public:
  // Meshes and factorises every body with a shape and a thickness. Throws Error(InvalidModel)
  // about a body whose material lacks Young's modulus or Poisson's ratio, or whose plate cannot
  // be meshed (too many nodes for the mesh size). Checks `control` between bodies.
  LinkFe(std::shared_ptr<const InverseDynamics> dynamics, const FeOptions& options = {},
         const RunControl& control = {});
  ~LinkFe();

  bool analysed(int body) const;
  const fe::PlateModel& plate(int body) const;
  double mesh_size(int body) const;  // the edge length asked of the mesher, m
  // The loads of one solved sample on `body`'s plate, in the plate's frame.
  fe::LoadCase load_case(const DynamicsResult& forces, int body) const;
  fe::StressField solve(const DynamicsResult& forces, int body) const;
  // The plate-frame point of a world point of `body` at that sample, and back.
  Eigen::Vector2d to_plate(const DynamicsResult& forces, int body, const Eigen::Vector2d& world) const;
  Eigen::Vector2d to_world(const DynamicsResult& forces, int body, const Eigen::Vector2d& plate_point) const;

  const InverseDynamics& dynamics() const { return *dynamics_; }
  const FeOptions& options() const { return options_; }

 private:
  struct Link;
  const PlatePlacement& placement(const Link& link, const Eigen::Vector2d& at, PlatePlacement& scratch) const;
  std::shared_ptr<const InverseDynamics> dynamics_;
  FeOptions options_;
  std::vector<std::unique_ptr<Link>> links_;  // per body; null when not analysed
};

// The largest nodal von Mises stress of one link over the sweep, with the figures that say how
// far to trust it.
struct FePeak {
  int body = -1;
  int step = -1;             // the sample's step number
  double von_mises = 0.0;    // Pa
  Eigen::Vector2d at{0, 0};  // where, plate frame (the starting pose), m
  int node = -1;
  std::optional<double> safety_factor;  // yield strength / von Mises, when the material has one
  int nodes = 0, elements = 0;          // the mesh
  double mesh_size = 0.0;               // m
  double min_angle_deg = 0.0;           // the mesh's smallest triangle angle
  // Over the sweep: the largest relative unbalance of the loads and support reaction
  // (StressField), both ~0 for loads in equilibrium.
  double load_unbalance = 0.0;
  double support_reaction = 0.0;
  // When the peak lies on a circle hole's edge: the arc of that edge within kFlatPeak of it at the
  // peak's step (plate frame), which says how far the peak's location is arbitrary.
  std::optional<fe::FlatArc> flat;
};
inline constexpr double kFlatPeak = 0.005;

// Every analysed body's peak over the samples (`per_sample[i]` at sweep.samples[i]), on
// options().threads threads. Checks `control` between samples.
std::vector<FePeak> fe_peaks(const LinkFe& fe, const SweepResult& sweep, const std::vector<DynamicsResult>& per_sample,
                             const RunControl& control = {});

// A convergence study of the finite-element peaks: the meshes, each with every plate's element
// sizes halved from the one before, and every link's peak on each.
struct FeConvergence {
  struct Mesh {
    double refinement = 1.0;  // FeOptions::refinement
    std::vector<FePeak> peaks;
    // Per peak, |this peak - the last mesh's| / this peak; empty for the first mesh.
    std::vector<double> change;
  };
  std::vector<Mesh> meshes;
  double tolerance = 0.01;
  bool converged = false;  // every peak of the last mesh changed by less than the tolerance
  std::string stopped;     // when not converged: why (the node budget, the most meshes)
};

// Refines from `options` (whose peaks are `first`, as fe_peaks gave them) by halving every
// plate's element sizes until every peak changes by less than `tolerance` (relative) from one
// mesh to the next, the next mesh would pass options.max_nodes (refused before meshing), or
// `max_meshes` meshes are done. Checks `control` between samples and meshes.
FeConvergence converge_fe_peaks(const std::shared_ptr<const InverseDynamics>& dynamics, const FeOptions& options,
                                std::vector<FePeak> first, const SweepResult& sweep,
                                const std::vector<DynamicsResult>& per_sample, double tolerance, int max_meshes = 8,
                                const RunControl& control = {});

// A point of body `body` drawn in the starting pose (a plate-frame point), in the body's frame
// as the stress reports give places: x along the body from its first point towards its
// second, y to the left (m).
Eigen::Vector2d body_frame_point(const Model& m, int body, const Eigen::Vector2d& drawn);

// The resultant of a load case about the plate-frame origin, its body force integrated over
// `plate` with the density and thickness of `material` and its nodal forces at the nodes of
// `mesh`: force (N) and moment (N m). Zero for loads in equilibrium. For tests and reports.
struct LoadResultant {
  Eigen::Vector2d force{0, 0};
  double moment = 0.0;
};
LoadResultant load_resultant(const fe::LoadCase& loads, const Region& plate, const fe::ElasticMaterial& material,
                             const fe::TriMesh& mesh);

}  // namespace nbar
