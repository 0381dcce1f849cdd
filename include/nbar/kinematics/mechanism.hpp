// A Model compiled for solving: the coordinate layout, the constraint rows, the Jacobian's
// sparsity pattern and what the structure analysis found (degrees of freedom, redundant
// constraints, four-bar loops). Immutable once built, like Pinocchio's Model; the numbers
// that change live in a State.
#pragma once

#include <Eigen/Core>

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "nbar/kinematics/loops.hpp"
#include "nbar/model/model.hpp"

namespace nbar {

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

  // The mobility of a model's joints alone, whatever its drivers: for a model being built, whose
  // drivers do not match its degrees of freedom yet (the web app's drawing tools show it). Throws
  // ModelError for an invalid model, as the constructor does.
  static MobilityReport joint_mobility(Model model);

  const Model& model() const { return model_; }
  int coordinate_count() const { return n_; }
  int row_count() const { return row_count_; }
  int constraint_row_count() const { return constraint_rows_; }  // rows before the drivers
  // What a row of the constraints says, for people ("length of crank (O2-A)"): the rows that
  // MobilityReport::redundant and AssemblyError::row() name. 0 <= row < row_count().
  const std::string& row_label(int row) const;
  int column_of(int point) const { return column_[point]; }  // -1 for ground points
  // The linkage's size: the diagonal of the drawn bounding box of the points its joints, sliders,
  // slots and drivers use (or a body's given length, if larger), not of points that only ride
  // along on one body (a coupler point, a centre of mass drawn as a point).
  double characteristic_length() const { return length_scale_; }
  // The diagonal of the whole drawing's bounding box, riding points included (or a body's given
  // length, if larger): the forward dynamics' absolute error weight.
  double drawing_size() const { return drawing_size_; }
  // Positions are converged when every row's residual is below this: 1e-12 of the linkage's
  // size, or of a thousandth of the whole drawing's when a riding point lies further out than a
  // thousand times the linkage's size (its rows' rounding grows with its distance).
  double tolerance() const { return tolerance_; }

  // q of the drawn pose.
  const Eigen::VectorXd& drawn_coordinates() const { return q_drawn_; }
  // Each driver's value (SI) in the drawn pose.
  const std::vector<double>& drawn_driver_values() const { return driver_drawn_; }
  // Position of a point given q. Inline: a simulation's rows ask for every body's points and every centre of mass.
  Eigen::Vector2d point_position(int point, const Eigen::VectorXd& q) const {
    const int col = column_[point];
    return col < 0 ? model_.points[point].position : Eigen::Vector2d(q(col), q(col + 1));
  }

  // The constraint rows themselves, compiled for the solver (each row's equation, the Jacobian's
  // sparsity pattern, the rows grouped for the evaluation loops): the kinematics engine's own,
  // defined in src/kinematics/constraints.hpp, which only the library's sources include.
  struct Equations;
  const Equations& equations() const { return *equations_; }

  const MobilityReport& mobility() const { return mobility_; }
  const std::vector<FourBarLoop>& four_bar_loops() const { return loops_; }
  bool overdetermined() const { return row_count() > n_; }

 private:
  Mechanism(Model model, bool check_drivers);
  void build_rows(Equations& equations);
  void build_pattern(Equations& equations) const;
  void analyse_mobility();
  void analyse_mobility_sparse(const std::vector<double>& jacobian_values);
  // "the mechanism has N degrees of freedom (Gruebler-Kutzbach count: G) but D drivers are given"
  std::string mobility_counts(bool at_least) const;

  Model model_;
  bool check_drivers_ = true;  // false: joint_mobility's, which counts without the drivers' verdict
  int n_ = 0;
  int constraint_rows_ = 0;
  double length_scale_ = 1.0;
  double tolerance_ = 1e-12;
  double drawing_size_ = 1.0;
  std::vector<int> column_;
  int row_count_ = 0;
  // Shared by copies: it never changes once built.
  std::shared_ptr<const Equations> equations_;
  Eigen::VectorXd q_drawn_;
  std::vector<double> driver_drawn_;
  MobilityReport mobility_;
  std::vector<FourBarLoop> loops_;
};

}  // namespace nbar
