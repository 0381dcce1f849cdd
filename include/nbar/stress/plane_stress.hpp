// Linear-elastic plane-stress finite elements on a link plate meshed by mesh_region().
//
// A PlateModel assembles the stiffness of quadratic 6-node triangles once and factorises it
// once (Eigen's sparse Cholesky), so each load case is a back-substitution. Link loads come from
// the inverse dynamics in equilibrium (pin forces, couples, d'Alembert and gravity body forces);
// the rigid-body modes are removed by inertia relief: the small unbalance left by rounding is
// cancelled by a rigid-body acceleration field and reported, then three minimal supports hold
// the plate and their reactions are reported too (they are ~0 when the loads balance).
//
// Coordinates: the plate's own frame, the one its Region is given in (the model's starting pose).
#pragma once

#include <Eigen/Core>

#include <array>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "nbar/stress/mesh.hpp"

namespace nbar::fe {

struct ElasticMaterial {
  double youngs_modulus = 0.0;  // Pa, > 0
  double poisson_ratio = 0.0;   // in [0, 0.5)
  double thickness = 0.0;       // m, > 0
  double density = 0.0;         // kg/m^3, >= 0 (for body forces and inertia relief)
};

// A pin pressing on the plate through circle hole `hole` with resultant `force` (N): a cosine
// bearing pressure over the half of the hole facing the force (the usual lug model).
struct BearingLoad {
  int hole = 0;
  Eigen::Vector2d force{0, 0};
};

// A couple (N m, counterclockwise positive) applied through circle hole `hole` as a uniform
// shear traction around it (a keyed or bonded shaft: driver torques, applied torques).
struct HoleCouple {
  int hole = 0;
  double moment = 0.0;
};

// A force at a point of the plate (no hole there), spread over the element containing it.
struct PointForce {
  Eigen::Vector2d at{0, 0};
  Eigen::Vector2d force{0, 0};
};

// Body force per unit mass b(x) = g − (a_O + α × (x − O) − ω² (x − O)): gravity and d'Alembert
// forces of a rigid body with origin O moving with acceleration a_O, angular velocity ω and
// angular acceleration α (all in the plate's frame).
struct RigidBodyField {
  Eigen::Vector2d origin{0, 0};
  Eigen::Vector2d origin_acceleration{0, 0};
  double omega = 0.0, alpha = 0.0;
  Eigen::Vector2d gravity{0, 0};
};

// A force straight on a mesh node (N): for tractions the caller has already made nodal (tests,
// imported loads).
struct NodalForce {
  int node = 0;
  Eigen::Vector2d force{0, 0};
};

struct LoadCase {
  std::vector<BearingLoad> bearings;
  std::vector<HoleCouple> couples;
  std::vector<PointForce> forces;
  std::optional<RigidBodyField> body;
  std::vector<NodalForce> nodal;
};

struct StressField {
  Eigen::VectorXd displacement;         // (u, v) of every node, m: 2 * node count
  std::vector<double> von_mises;        // at every node (averaged from the elements around it), Pa
  std::vector<Eigen::Vector3d> stress;  // (σxx, σyy, τxy) at every node, Pa
  double peak = 0.0;                    // largest nodal von Mises, Pa
  int peak_node = -1;
  Eigen::Vector2d peak_at{0, 0};  // m
  // Numerical honesty: |net force| + |net moment| / size of the applied loads before inertia
  // relief, relative to the largest applied load (0 for loads in exact equilibrium), and the
  // largest support reaction after it, relative likewise.
  double load_unbalance = 0.0;
  double support_reaction = 0.0;
};

// The nodal forces of a load case (2 per node, x then y), balanced by inertia relief: what the
// stiffness is solved against, and what a CalculiX deck (nbar/io/calculix.hpp) applies as *CLOAD.
struct NodalLoads {
  Eigen::VectorXd forces;
  double load_unbalance = 0.0;  // as StressField::load_unbalance
  double load_scale = 0.0;      // the largest applied load, N (what the unbalance is relative to)
};

// One of the three minimal supports: `node`'s displacement along x (direction 0) or y (1) held.
struct Support {
  int node = -1;
  int direction = 0;
};

class PlateModel {
 public:
  // Assembles and factorises. Throws Error(ErrorKind::BadInput) for a bad material or mesh.
  PlateModel(TriMesh mesh, ElasticMaterial material);
  ~PlateModel();
  PlateModel(PlateModel&&) noexcept;
  PlateModel& operator=(PlateModel&&) noexcept;

  // Throws Error(ErrorKind::BadInput) for a hole index the plate does not have or a point outside it.
  StressField solve(const LoadCase& loads) const;
  // The same for many load cases (the steps of a sweep), in order: about 3 times faster per case
  // than solve() one by one, since each block of 16 cases reads the factor once. A field holds
  // 6 doubles per node: to bound memory over a long sweep, pass the steps 16 or 32 at a time and
  // keep what is needed (the peak, the field of the worst step).
  std::vector<StressField> solve_many(const std::vector<LoadCase>& cases) const;

  const TriMesh& mesh() const;
  const ElasticMaterial& material() const;

  // The balanced nodal forces solve() applies (for export and checks).
  NodalLoads nodal_loads(const LoadCase& loads) const;
  // The three supports: x and y at one node, one direction at the node farthest from it.
  const std::array<Support, 3>& supports() const;
  // Centre and radius of circle hole `hole`, as fitted to its boundary nodes. Throws
  // Error(ErrorKind::BadInput) when the mesh has no such hole.
  std::pair<Eigen::Vector2d, double> hole_circle(int hole) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace nbar::fe
