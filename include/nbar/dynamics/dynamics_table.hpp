// Inverse-dynamics columns for the result table, filled from solved samples (the analysis
// pipeline solves each sample once and keeps the results). Forces in N, torques in N m and
// energies in J whatever the model's length unit.
#pragma once

#include <string>
#include <vector>

#include "nbar/dynamics/inverse_dynamics.hpp"
#include "nbar/kinematics/table.hpp"

namespace nbar {

// A joint force shown in the table: `name` is the prefix of its columns (`A.crank>coupler`
// with two links at the joint: the force the first exerts on the second; `A.pin>coupler` with
// three or more: the pin's force on each), `joint_link` indexes InverseDynamics::joint_links(),
// and `receiver` is the body whose axis gives the `.along` / `.across` components (-1: none).
struct JointForceColumn {
  std::string name;
  std::size_t joint_link = 0;
  int receiver = -1;
};
std::vector<JointForceColumn> joint_force_columns(const InverseDynamics& dynamics);

struct ColumnName {
  std::string name, unit;
};
// In table order: for every joint force `.Fx`, `.Fy` (and `.along`, `.across` on a receiving
// body), every slider's normal force and couple (`piston.slider.N`, `.M`), every slot's normal
// force (`D.slot.N`), every driver's effort (`crank.torque` or `.force`), and the kinetic and
// potential energy (`energy.kinetic`, `energy.potential`).
std::vector<ColumnName> dynamics_columns(const InverseDynamics& dynamics);

// Those columns for one sample at a time (for writers that stream a sweep), value j at
// out[j * stride].
class DynamicsRows {
 public:
  explicit DynamicsRows(const InverseDynamics& dynamics);
  std::size_t column_count() const { return count_; }
  void fill(const Sample& sample, const DynamicsResult& result, double* out, std::ptrdiff_t stride = 1) const;

 private:
  const InverseDynamics& dynamics_;
  std::vector<JointForceColumn> forces_;
  std::size_t count_ = 0;
};

// Appends those columns to `table`, whose rows are the sweep's samples; `results[i]` is the
// solution at sweep.samples[i].
void append_dynamics_columns(const InverseDynamics& dynamics, const SweepResult& sweep,
                             const std::vector<DynamicsResult>& results, ResultTable& table);
void append_dynamics_columns(const InverseDynamics& dynamics, const SweepResult& sweep,
                             const std::vector<DynamicsResult>& results, ColumnTable& table);

}  // namespace nbar
