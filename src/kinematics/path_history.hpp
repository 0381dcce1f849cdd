// The series of q at the last point a track accepted before the current one, for a predictor
// that reaches further than the current point's own series: the polynomial that matches the
// Taylor coefficients at both points (Hermite interpolation), evaluated one step on. With three
// coefficients at each point it is of degree 5, so its error falls as h^6 where the current
// series alone errs as h^3: on a sweep of one-degree steps one Newton correction then meets the
// solver's tolerance, where two or three were needed. More points do worse, not better: the
// coefficients are known only to the solver's tolerance, and an extrapolation through more points
// multiplies their errors more.
#pragma once

#include <Eigen/Core>

namespace nbar {

class PathHistory {
 public:
  // Forgets the past point.
  void clear() { has_past_ = false; }
  // Before the step from `parameter` is accepted: remember that point's series.
  void push(double parameter, const Eigen::MatrixXd& series);
  // push() without the copy: the history takes `series`' storage and leaves it the storage of the
  // point it forgets, whose numbers the caller overwrites (a step's new series).
  void take(double parameter, Eigen::MatrixXd& series);
  // After it is accepted: the point it reached, which the next prediction must start from.
  // N > 0 (2, 4, 6 or 8, kinematics/sized.hpp) is the number of coordinates known when
  // compiled, for a step compiled for it; 0 reads it from `series` (as N > 0 does when `series`
  // has another number of rows). The numbers are the same.
  template <int N = 0>
  void mark_current(double parameter, const Eigen::MatrixXd& series);
  // q at parameter + h, from `series` at `parameter` and the past point's series, when the history
  // continues from that point and the step reaches at most twice as far as the last; false
  // otherwise (the caller then predicts from `series` alone). N as for mark_current.
  template <int N = 0>
  bool predict(double parameter, const Eigen::MatrixXd& series, double h, Eigen::VectorXd& q);

 private:
  template <int N>
  bool continues_from(double parameter, const Eigen::MatrixXd& series) const;
  // Whether the weights are those for this reach and number of terms (checked before the call, in
  // line: they almost always are).
  bool weights_fit(double reach, int terms) const;
  void update_weights(double reach, int terms);

  Eigen::MatrixXd past_;
  double past_parameter_ = 0.0;
  bool has_past_ = false;
  // What the current point looked like when the last step reached it.
  double current_parameter_ = 0.0;
  Eigen::VectorXd current_q_, current_rate_;
  // Weights of the current point's and the past point's coefficients (in that order), for
  // offsets scaled so that the past point lies at -1 and the target at `weight_reach_`.
  Eigen::MatrixXd inverse_transpose_;  // M^-T for weight_terms_ terms
  double weight_[16] = {};             // 2 x terms; terms <= Series::kCapacity
  double weight_reach_ = 0.0;          // the reach they are for
  int weight_terms_ = 0;
};

}  // namespace nbar
