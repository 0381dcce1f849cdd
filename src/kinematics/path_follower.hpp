// Pseudo-arclength continuation of a sweep's path Phi(q, p) = 0 in y = (q, u), u the path
// parameter scaled so that the sweep's span is as long as the model: unlike track(), which moves
// p forward, it follows the curve through the positions where p turns back (limits), which it
// locates, and through change points, which it reports. The kinematics engine's own (not
// installed): limits.cpp finds the limits with it, the sweep reverses at them with it.
#pragma once

#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

#include "nbar/kinematics/continuation.hpp"
#include "nbar/kinematics/limits.hpp"

namespace nbar {

// The whole constraint Jacobian (every row, drivers included) as a dense matrix at q, with the
// drivers at `driver_values` (SI).
Eigen::MatrixXd dense_jacobian(const Mechanism& mech, const Eigen::VectorXd& q,
                               const std::vector<double>& driver_values);

class PathFollower {
 public:
  // `span`: the length of p that is scaled to the model's size.
  PathFollower(const Mechanism& mech, DriverPath path, double span);

  double scaled(double p) const { return p / p_scale_; }
  double parameter(const Eigen::VectorXd& y) const { return y[n_] * p_scale_; }

  struct Step {
    Eigen::VectorXd y, t;  // the point reached and the unit tangent there
    double h = 0.0;        // the next step's length (model units)
    int det_sign = 0;      // sign of the bordered Jacobian's determinant (0: not watched)
  };
  // At a point on the path, heading where p grows (direction +1) or falls (-1).
  Step begin(const Eigen::VectorXd& y, int direction);

  struct Advance {
    bool ok = true;
    std::string reason;  // when !ok: why the path could not be followed
    std::optional<PathSingularity> limit, change_point;
  };
  // One step along the curve. When the step passes a limit, the limit is located (to the
  // rounding of the pose) and `step` is left at it, heading on past it.
  Advance advance(Step& step);

  // Newton on Phi(q, p) = 0 with p fixed, from y: the pose at p nearest y. False if it does not
  // converge.
  bool solve_at_parameter(Eigen::VectorXd& y, double p);

  // The pose y of the path as a PathSingularity of `kind` (its parameter and driver values), for
  // where a search stopped or a singular pose was found.
  PathSingularity singularity(const Eigen::VectorXd& y, PathSingularityKind kind);

  // Every step factorises dense matrices of the model's size, so a large model on a slowly
  // followed path could take minutes: the follower counts its work (rows x columns^2 of each
  // factorisation, about its flops, plus the cost of filling the matrix) and advance() refuses to
  // go on past the budget (kDefaultLimitSearchWork unless set).
  void set_work_budget(double budget) { work_budget_ = budget; }
  double work() const { return work_; }
  bool over_budget() const { return work_ > work_budget_; }

 private:
  void evaluate(const Eigen::VectorXd& y);
  bool tangent(const Eigen::VectorXd& y, const Eigen::VectorXd& border, Eigen::VectorXd& t);
  bool correct(Eigen::VectorXd& y, const Eigen::VectorXd& border, const Eigen::VectorXd& anchor);
  int determinant_sign(const Eigen::VectorXd& y, const Eigen::VectorXd& t);
  // The point at arclength sigma from `from` along `t` (corrected): false if it does not converge.
  bool point_at(const Step& from, double sigma, Eigen::VectorXd& y);
  std::string budget_reason() const;
  // Whether [Phi_q Phi_u] loses rank at y too (a limit where branches also cross).
  bool branches_cross_at(const Eigen::VectorXd& y);
  std::optional<PathSingularity> locate_limit(const Step& from, double h, Eigen::VectorXd& y_limit);
  std::optional<PathSingularity> locate_change(const Step& from, double h);

  const Mechanism& mech_;
  DriverPath path_;
  Eigen::Index n_ = 0;
  double p_scale_ = 1.0, length_ = 1.0, tolerance_ = 0.0;
  double conditioning_ = 1.0;  // of the bordered Jacobian at the last tangent (tangent())
  double work_ = 0.0, work_budget_ = kDefaultLimitSearchWork;
  void count_factorisation(Eigen::Index rows) { work_ += double(rows) * double(n_ + 1) * double(n_ + 1) + 5000.0; }
  std::vector<int> independent_rows_;  // the rows without the redundant ones, when they are n
  // Scratch: the rows and the augmented Jacobian [Phi_q Phi_u] at the last point evaluated.
  State state_;
  std::vector<Series> values_;
  std::vector<double> jacobian_values_;
  Eigen::VectorXd phi_, rate_;
  Eigen::MatrixXd augmented_, coefficients_;
};

}  // namespace nbar
