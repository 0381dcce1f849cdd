// A Model compiled for solving: the coordinate layout, the constraint rows, the Jacobian's
// sparsity pattern and what the structure analysis found (degrees of freedom, redundant
// constraints, four-bar loops). Immutable once built, like Pinocchio's Model; the numbers
// that change live in a State.
#pragma once

#include <Eigen/Core>

#include <string>
#include <utility>
#include <vector>

#include "nbar/kinematics/constraints.hpp"
#include "nbar/kinematics/loops.hpp"
#include "nbar/model/model.hpp"

namespace nbar {

struct JacobianEntry {
  int row = 0;
  int col = 0;
};

// The terms of the Gruebler-Kutzbach count G = 3 (n - 1) - 2 PI - PII: each point shared by k
// links (bodies, and the ground when the point is fixed) makes k - 1 revolute pairs, each slider
// one prismatic pair (PI, one freedom each); each slot a pin-in-slot pair (PII, two freedoms).
struct PairCount {
  int links = 0;         // n, the ground included
  int lower_pairs = 0;   // PI
  int higher_pairs = 0;  // PII
  int dof = 0;           // G
};
PairCount count_pairs(const Model& model);

// The largest model a Mechanism is built for: its rank analysis and every sweep step grow with
// the number of moving points.
inline constexpr int kMaxMovingPoints = 20000;

struct MobilityReport {
  int coordinates = 0;                // moving points x 2
  int constraint_rows = 0;            // without drivers
  int grubler = 0;                    // Gruebler-Kutzbach count
  int rank = 0;                       // rank of the constraint Jacobian at the drawn pose
  int dof = 0;                        // true mobility: coordinates - rank
  std::vector<int> redundant;         // rows that depend on the others (one choice of them)
  double reciprocal_condition = 0.0;  // of the driven system at the drawn pose
};

class Mechanism {
 public:
  // Validates, builds the rows and analyses the structure. Throws ModelError when the
  // model is invalid, including drivers that do not match the degrees of freedom.
  explicit Mechanism(Model model);

  const Model& model() const { return model_; }
  int coordinate_count() const { return n_; }
  int row_count() const { return static_cast<int>(rows_.size()); }
  int constraint_row_count() const { return constraint_rows_; }  // rows before the drivers
  const std::vector<Constraint>& rows() const { return rows_; }
  int column_of(int point) const { return column_[point]; }  // -1 for ground points
  double characteristic_length() const { return length_scale_; }
  double tolerance() const { return 1e-12 * length_scale_; }

  // q of the drawn pose.
  const Eigen::VectorXd& drawn_coordinates() const { return q_drawn_; }
  // Each driver's value (SI) in the drawn pose.
  const std::vector<double>& drawn_driver_values() const { return driver_drawn_; }
  // Position of a point given q.
  Eigen::Vector2d point_position(int point, const Eigen::VectorXd& q) const;

  const std::vector<JacobianEntry>& jacobian_pattern() const { return pattern_; }
  // The rows as the evaluation loops read them, and the coordinates of the points fixed to the
  // frame (x, y of every point, in the model's order) that CompiledRow::at points into.
  const std::vector<CompiledRow>& compiled_rows() const { return compiled_; }
  const std::vector<RowGroup>& row_groups() const { return groups_; }
  const std::vector<double>& fixed_coordinates() const { return fixed_xy_; }
  // Index of the first pattern entry of `row` for its point slot `slot` (x, then y at +1);
  // -1 when that point is fixed.
  int entry_index(int row, int slot) const { return entry_[row][slot]; }

  const MobilityReport& mobility() const { return mobility_; }
  const std::vector<FourBarLoop>& four_bar_loops() const { return loops_; }
  bool overdetermined() const { return row_count() > n_; }

 private:
  void build_rows();
  void build_pattern();
  void analyse_mobility();
  void analyse_mobility_sparse(const std::vector<double>& jacobian_values);
  // "the mechanism has N degrees of freedom (Gruebler-Kutzbach count: G) but D drivers are given"
  std::string mobility_counts(bool at_least) const;

  Model model_;
  int n_ = 0;
  int constraint_rows_ = 0;
  double length_scale_ = 1.0;
  std::vector<int> column_;
  std::vector<Constraint> rows_;
  std::vector<JacobianEntry> pattern_;
  std::vector<std::array<int, 4>> entry_;
  std::vector<CompiledRow> compiled_;
  std::vector<RowGroup> groups_;
  std::vector<double> fixed_xy_;
  Eigen::VectorXd q_drawn_;
  std::vector<double> driver_drawn_;
  MobilityReport mobility_;
  std::vector<FourBarLoop> loops_;
};

}  // namespace nbar
