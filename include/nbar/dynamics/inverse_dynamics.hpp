// Inverse dynamics: from the motion (positions, velocities, accelerations of a sample), the
// force every joint transmits and the effort every driver must give.
//
// Newton-Euler for every moving body (3 equations) and for every joint pin shared by two or
// more links (a massless node: 2 equations). The unknowns are the force each pin exerts on each
// link meeting there, the normal force and couple of every slider, the normal force of every
// slot, and the effort of every driver. With drivers equal to the degrees of freedom and no
// redundant constraint the system is square and regular; with redundant constraints it has more
// unknowns than independent equations and the minimum-norm set of forces is given, flagged as
// not unique. Equivalent to solving M q'' + Phi_q^T lambda = Q for the multipliers, but the
// unknowns are directly the forces a designer reads.
#pragma once

#include <Eigen/Core>

#include <memory>
#include <string>
#include <vector>

#include "nbar/kinematics/sweep.hpp"

namespace nbar {

// Mass properties of a body: given, or from its shape, thickness and material; zero otherwise.
struct MassProperties {
  double mass = 0.0;         // kg
  Eigen::Vector2d cg{0, 0};  // m, in the starting pose
  double inertia = 0.0;      // kg m^2 about the centre of mass
  double area = 0.0;         // m^2 of the shape, when there is one
  bool from_shape = false;
};
MassProperties mass_properties(const Body& body);

// Where a body is: an origin point and a direction vector of constant length, both moving with
// it. Bodies of two or more points use their first two points; a one-point slider block uses
// its point and its guide's direction.
struct BodyFrame {
  int origin = -1;
  int from = -1, to = -1;  // the direction vector is r[to] - r[from]
};
BodyFrame body_frame(const Model& model, int body);

// Position, velocity and acceleration of a body-fixed point and the body's rotation.
struct BodyMotion {
  Eigen::Vector2d origin[3];     // r, v, a of the origin point
  Eigen::Vector2d direction[3];  // w, dw/dt, d2w/dt2
  double omega = 0.0, alpha = 0.0;
  // Body-fixed point given by its starting-pose position.
  Eigen::Vector2d point(const Eigen::Vector2d& drawn, int derivative) const;
  Eigen::Vector2d drawn_origin, drawn_direction;
};
// Position, velocity and acceleration of every point of a sample, computed once.
struct SampleMotion {
  std::vector<Eigen::Vector2d> r, v, a;
};
SampleMotion sample_motion(const Mechanism& mech, const Sample& sample);
BodyMotion body_motion(const Model& model, const SampleMotion& motion, int body);
BodyMotion body_motion(const Mechanism& mech, const Sample& sample, int body);

// A link meeting at a joint: a body index, or -1 for the ground.
struct JointLink {
  int point = -1;
  int link = -1;
};

// A force or couple applied directly to a body (not through a joint pin): loads, springs and
// actuators at points only that body has, slider and slot contact, driver efforts.
struct AppliedLoad {
  int body = -1;
  Eigen::Vector2d at{0, 0};     // where it acts, current pose, m
  Eigen::Vector2d force{0, 0};  // N
  double couple = 0.0;          // N m
};

struct DynamicsResult {
  // Force the pin at `joint_links[i].point` exerts on `joint_links[i].link`, N.
  std::vector<Eigen::Vector2d> pin_forces;
  std::vector<double> slider_normal;  // N, on the slider body, along the guide's left normal
  std::vector<double> slider_couple;  // N m, on the slider body
  std::vector<double> slot_normal;    // N, on the pin, along the guide's left normal
  std::vector<double> driver_effort;  // N m for angle drivers, N for distance and slide drivers
  std::vector<AppliedLoad> applied;   // every direct load on a body, gravity excepted
  SampleMotion motion;                // the sample's point motions the forces were computed for
  double kinetic_energy = 0.0;        // J
  double potential_energy = 0.0;      // J: gravity and springs
  double residual = 0.0;              // max |equation residual|, N or N m
  bool unique = true;                 // false when redundant constraints leave forces undetermined
};

// Scratch memory for InverseDynamics::solve: sized once for a mechanism and reused for every
// sample, so a sweep allocates nothing per sample but the results. Not shared between threads:
// give each thread its own. Opaque: its matrices and factorisations (dense and sparse LU, a
// complete orthogonal decomposition) live in inverse_dynamics.cpp, so this header needs no Eigen
// decomposition and the units including it instantiate none.
class DynamicsWorkspace {
 public:
  DynamicsWorkspace();
  ~DynamicsWorkspace();
  DynamicsWorkspace(DynamicsWorkspace&&) noexcept;
  DynamicsWorkspace& operator=(DynamicsWorkspace&&) noexcept;

  struct Scratch;  // inverse_dynamics.cpp

 private:
  friend class InverseDynamics;
  std::unique_ptr<Scratch> scratch_;
};

class InverseDynamics {
 public:
  // Square systems with more unknowns than this are factorised by sparse LU (3 equations per
  // body, a few unknowns per joint: a few non-zeros per row); smaller ones by dense LU, which
  // is faster there. Every bundled example is below it (the 21-body press has 63).
  static constexpr int kDenseLimit = 120;

  // Shares the mechanism, so the solver may outlive the caller's pointer (Python, the server).
  explicit InverseDynamics(std::shared_ptr<const Mechanism> mechanism);

  // Needs the sample's Taylor coefficients to order 2 at least. Uses `workspace` for scratch
  // (resized on first use); the solver itself is never modified, so threads may share it, each
  // with its own workspace.
  DynamicsResult solve(const Sample& sample, DynamicsWorkspace& workspace) const;
  // The same with a workspace of the calling thread's own.
  DynamicsResult solve(const Sample& sample) const;
  // Solves made by every InverseDynamics of the process so far: a pipeline is tested to solve
  // each sample once.
  static long solve_count();

  const std::vector<JointLink>& joint_links() const { return joint_links_; }
  // Joints: points shared by two or more links (bodies, or a body and the ground).
  const std::vector<int>& joints() const { return joints_; }
  const std::vector<MassProperties>& masses() const { return masses_; }
  const Mechanism& mechanism() const { return *mechanism_; }
  const std::shared_ptr<const Mechanism>& shared_mechanism() const { return mechanism_; }
  int unknown_count() const { return unknowns_; }
  int equation_count() const { return equations_; }

 private:
  std::shared_ptr<const Mechanism> mechanism_;
  std::vector<MassProperties> masses_;
  std::vector<BodyFrame> frames_;
  std::vector<int> joints_;
  std::vector<int> node_of_point_;  // -1 when the point is not a joint
  std::vector<JointLink> joint_links_;
  std::vector<int> single_body_of_point_;  // the only moving body of a non-joint point, or -1
  // At every joint one link, the ground when it is there, takes the pin's balance: its force
  // follows from the others', so only 3 equations per body remain (square when the drivers
  // match Gruebler's count).
  std::vector<int> dependent_;                  // per joint: index into joint_links_ of the link that balances the pin
  std::vector<int> pin_column_;                 // per joint link: first of its two unknowns, -1 for the dependent one
  std::vector<int> slider_guide_, slot_guide_;  // the body owning each guide, -1 for the ground
  int slider_base_ = 0, slot_base_ = 0, driver_base_ = 0, unknowns_ = 0, equations_ = 0;

  class Assembly;  // the steps of one solve (inverse_dynamics.cpp)
};

}  // namespace nbar
