// The engine's algorithm for one sweep step written straight for one four-bar, with nothing
// general about it: natural coordinates q = (A, B), the Hermite predictor through the series at
// the last two points, simplified Newton with the last point's LU, the LU at the new point, and
// the series' first and second coefficients from it. It has no step control, branch watch or
// condition estimate. Timed next to the engine and Norton's closed form, it shows what the
// engine's generality costs and what the algorithm itself costs (bench/kinematics_bench.cpp).
#pragma once

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <utility>

namespace nbar_bench {

class StraightFourBar {
 public:
  static constexpr int kN = 4;  // A.x, A.y, B.x, B.y
  // A crank a about the origin at angle omega t, coupler b, output c about (d, 0); `start` and
  // `before` are the series in time (q, dq/dt, d2q/dt2 / 2) at t = 0 and t = -step.
  StraightFourBar(double a, double b, double c, double d, double omega, double step, const double start[3][kN],
                  const double before[3][kN])
      : a_(a), b_(b), c_(c), d_(d), omega_(omega), step_(step) {
    std::copy(&start[0][0], &start[0][0] + 3 * kN, &now_[0][0]);
    std::copy(&before[0][0], &before[0][0] + 3 * kN, &past_[0][0]);
    hermite_weights();
    factorise(now_[0], 0.0, 1.0);
  }

  // One step on: false when the Jacobian is singular or Newton does not converge.
  bool step() {
    double x[kN];
    predict(x);
    time_ = static_cast<double>(++steps_) * step_;  // as a sweep's samples are: no sum of rounded steps
    const double sine = std::sin(omega_ * time_), cosine = std::cos(omega_ * time_);
    if (!correct(x, sine, cosine)) return false;
    std::copy(&now_[0][0], &now_[0][0] + 3 * kN, &past_[0][0]);
    std::copy(x, x + kN, now_[0]);
    if (!factorise(x, sine, cosine)) return false;
    series(sine, cosine);
    return true;
  }

  double time() const { return time_; }
  // Coefficient k (0: position, 1: velocity, 2: acceleration / 2) of coordinate i.
  double coefficient(int k, int i) const { return now_[k][i]; }
  double corrections() const { return corrections_; }

 private:
  // The weights of the degree-5 polynomial through both points' three coefficients, evaluated one
  // step on (offsets in steps: the past point at -1, the target at 1).
  void hermite_weights() {
    Eigen::Matrix<double, 6, 6> m = Eigen::Matrix<double, 6, 6>::Zero();
    const double node[2] = {0.0, -1.0};
    for (int p = 0; p < 2; ++p)
      for (int k = 0; k < 3; ++k)
        for (int j = k; j < 6; ++j) m(3 * p + k, j) = binomial(j, k) * std::pow(node[p], j - k);
    const Eigen::Matrix<double, 6, 1> at_target = Eigen::Matrix<double, 6, 1>::Ones();
    const Eigen::Matrix<double, 6, 1> w = m.transpose().partialPivLu().solve(at_target);
    double scale = 1.0;
    for (int k = 0; k < 3; ++k, scale *= step_) {
      weight_now_[k] = w(k) * scale;
      weight_past_[k] = w(3 + k) * scale;
    }
  }
  static double binomial(int n, int k) {
    double r = 1.0;
    for (int i = 1; i <= k; ++i) r = r * (n - k + i) / i;
    return r;
  }

  void predict(double* x) const {
    for (int i = 0; i < kN; ++i) {
      double sum = 0.0;
      for (int k = 0; k < 3; ++k) sum += weight_now_[k] * now_[k][i] + weight_past_[k] * past_[k][i];
      x[i] = sum;
    }
  }

  void residual(const double* x, double sine, double cosine, double* r) const {
    const double ux = x[2] - x[0], uy = x[3] - x[1], vx = x[2] - d_, vy = x[3];
    r[0] = x[0] * x[0] + x[1] * x[1] - a_ * a_;
    r[1] = ux * ux + uy * uy - b_ * b_;
    r[2] = vx * vx + vy * vy - c_ * c_;
    r[3] = x[0] * sine - x[1] * cosine;
  }

  // Simplified Newton with the last point's factors, at least one correction, to 1e-14 m^2.
  bool correct(double* x, double sine, double cosine) {
    double r[kN], dx[kN];
    for (int iteration = 0; iteration < 8; ++iteration) {
      residual(x, sine, cosine, r);
      double largest = 0.0;
      for (double v : r) largest = std::max(largest, std::abs(v));
      if (iteration > 0 && largest < 1e-14) return true;
      solve(r, dx);
      ++corrections_;
      for (int i = 0; i < kN; ++i) x[i] -= dx[i];
    }
    return false;
  }

  // Partial pivoting, rows swapped in place; the pivots' inverses on the diagonal.
  bool factorise(const double* x, double sine, double cosine) {
    const double ux = x[2] - x[0], uy = x[3] - x[1];
    const double jacobian[kN][kN] = {{2 * x[0], 2 * x[1], 0, 0},
                                     {-2 * ux, -2 * uy, 2 * ux, 2 * uy},
                                     {0, 0, 2 * (x[2] - d_), 2 * x[3]},
                                     {sine, -cosine, 0, 0}};
    for (int i = 0; i < kN; ++i) {
      row_[i] = i;
      std::copy(jacobian[i], jacobian[i] + kN, lu_[i]);
    }
    for (int k = 0; k < kN; ++k) {
      int pivot = k;
      for (int i = k + 1; i < kN; ++i)
        if (std::abs(lu_[i][k]) > std::abs(lu_[pivot][k])) pivot = i;
      if (lu_[pivot][k] == 0.0) return false;
      std::swap(lu_[k], lu_[pivot]);
      std::swap(row_[k], row_[pivot]);
      const double inverse = 1.0 / lu_[k][k];
      lu_[k][k] = inverse;
      for (int i = k + 1; i < kN; ++i) {
        const double l = lu_[i][k] * inverse;
        lu_[i][k] = l;
        for (int j = k + 1; j < kN; ++j) lu_[i][j] -= l * lu_[k][j];
      }
    }
    return true;
  }

  void solve(const double* rhs, double* x) const {
    for (int i = 0; i < kN; ++i) {
      x[i] = rhs[row_[i]];
      for (int j = 0; j < i; ++j) x[i] -= lu_[i][j] * x[j];
    }
    for (int i = kN - 1; i >= 0; --i) {
      for (int j = i + 1; j < kN; ++j) x[i] -= lu_[i][j] * x[j];
      x[i] *= lu_[i][i];
    }
  }

  // Phi_q q_k = -R_k for k = 1, 2, with the crank's sine and cosine series.
  void series(double sine, double cosine) {
    const double w = omega_;
    const double sine1 = cosine * w, cosine1 = -sine * w;
    const double sine2 = -sine * w * w / 2, cosine2 = -cosine * w * w / 2;
    const double* q0 = now_[0];
    double* q1 = now_[1];
    double r[kN] = {0.0, 0.0, 0.0, -(q0[0] * sine1 - q0[1] * cosine1)};
    solve(r, q1);
    const double u1x = q1[2] - q1[0], u1y = q1[3] - q1[1];
    r[0] = -(q1[0] * q1[0] + q1[1] * q1[1]);
    r[1] = -(u1x * u1x + u1y * u1y);
    r[2] = -(q1[2] * q1[2] + q1[3] * q1[3]);
    r[3] = -(q0[0] * sine2 - q0[1] * cosine2 + q1[0] * sine1 - q1[1] * cosine1);
    solve(r, now_[2]);
  }

  double a_, b_, c_, d_, omega_, step_;
  double time_ = 0.0;
  long long steps_ = 0;
  double now_[3][kN], past_[3][kN];
  double weight_now_[3], weight_past_[3];
  double lu_[kN][kN];
  int row_[kN];
  double corrections_ = 0.0;
};

}  // namespace nbar_bench
