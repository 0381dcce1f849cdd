// Stresses in links: internal forces along every body that has a shape, from the equilibrium
// of the part on one side of each cross-section, then normal, shear and von Mises stresses.
//
// A body's axis runs from its first to its second point. Sections are cut perpendicular to the
// axis (at least 100 per body, denser near holes and joints). The part between the cut and the
// body's first point carries the joint and applied forces acting on it and its share of the
// gravity and d'Alembert (inertia) forces of the distributed mass; the other part's action on it
// at the cut is the internal force: N along the axis (tension positive), V across it and M.
// Then sigma = N/A - M y/I across the section (y from the neutral axis, to the left of the
// axis), tau = V Q/(I t), and von Mises sqrt(sigma^2 + 3 tau^2) at both extreme fibres and at
// the neutral axis. Plane stress, rigid links, no stress concentration factors.
#pragma once

#include <Eigen/Core>

#include <memory>
#include <optional>
#include <vector>

#include "nbar/dynamics/inverse_dynamics.hpp"
#include "nbar/model/run_control.hpp"
#include "nbar/stress/section.hpp"

namespace nbar {

struct SectionStress {
  double position = 0.0;                          // along the axis from the body's first point, m
  double area = 0.0, inertia = 0.0;               // m^2, m^4
  double axial = 0.0, shear = 0.0, moment = 0.0;  // N, V (N) and M (N m)
  double sigma_low = 0.0, sigma_high = 0.0;       // normal stress at the extreme fibres (right, left of the axis), Pa
  double tau_max = 0.0;                           // Pa, at the neutral axis
  double von_mises = 0.0;                         // largest of the three places, Pa
  double sigma = 0.0, tau = 0.0;                  // components where von_mises is
  Eigen::Vector2d where{0, 0};                    // that place in the body frame: x along the axis, y to its left, m
};

// The forces on the part of a body between a section and its first point (or the other part),
// and their moment about the section's centroid, d'Alembert forces included: the internal
// force at the cut balances them.
struct PartLoads {
  Eigen::Vector2d force{0, 0};
  double moment = 0.0;
};

class LinkStress {
 public:
  // At least `sections` cuts per body with a shape. Shares the dynamics (and so the mechanism).
  LinkStress(std::shared_ptr<const InverseDynamics> dynamics, int sections = 200);

  bool analysed(int body) const { return !bodies_[body].sections.empty(); }
  // Every section of `body` under the forces of one solved sample.
  std::vector<SectionStress> profile(const DynamicsResult& forces, int body) const;
  // side -1: the part towards the first point; +1: the other part.
  PartLoads part_loads(const DynamicsResult& forces, int body, int section, int side) const;
  const InverseDynamics& dynamics() const { return *dynamics_; }
  int section_count(int body) const { return static_cast<int>(bodies_[body].sections.size()); }

 private:
  struct Part {
    double mass = 0.0;
    Eigen::Vector2d centre{0, 0};  // starting pose
    double inertia = 0.0;          // about its centre
  };
  struct Section {
    double position = 0.0;
    SectionProperties props;
    Eigen::Vector2d centroid{0, 0};  // starting pose
    Part part[2];                    // towards the first point, and the rest
  };
  struct BodySections {
    std::vector<Section> sections;
    Eigen::Vector2d origin{0, 0}, axis{1, 0};  // starting pose, unit axis
  };

  // What acts on one body at one step: computed once, then summed over each section's side.
  struct StepLoads {
    BodyMotion motion;
    Eigen::Vector2d axis{1, 0};  // current, unit
    std::vector<Eigen::Vector2d> at, force;
    std::vector<double> couple;
  };
  StepLoads step_loads(const DynamicsResult& forces, int body) const;
  PartLoads part_loads(const StepLoads& step, int body, int section, int side) const;

  std::shared_ptr<const InverseDynamics> dynamics_;
  std::vector<BodySections> bodies_;
};

struct StressPeak {
  int body = -1;
  int step = -1;
  SectionStress at;                     // the section and place of the largest von Mises
  std::optional<double> safety_factor;  // yield strength / von Mises, when the material has one
};

// The largest von Mises stress of every analysed body over the sweep, from the dynamics
// already solved at every sample (`per_sample[i]` at sweep.samples[i]). Checks `control`
// between samples.
std::vector<StressPeak> stress_peaks(const LinkStress& stress, const SweepResult& sweep,
                                     const std::vector<DynamicsResult>& per_sample, const RunControl& control = {});

}  // namespace nbar
