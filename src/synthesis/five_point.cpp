#include "nbar/synthesis/five_point.hpp"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

#include "nbar/model/diagnostics.hpp"
#include "nbar/synthesis/five_point_start.hpp"

namespace nbar::synthesis {
namespace {

// Tracker coordinates: t1..t4, tb1..tb4, X, Xb, hx, Y, Yb, hy. The moving pivots are
// homogenized (x = X / hx) on a fixed random patch, so a near-slider solution with a pivot
// hundreds of units away stays at moderate coordinates.
constexpr int kT = 0, kTb = 4, kX = 8, kXb = 9, kHx = 10, kY = 11, kYb = 12, kHy = 13;
constexpr int kVariables = 14;
// Parameters, as complex numbers in a frame centred on the points and scaled by their spread:
// delta_0..delta_4 (coupler points), their independent "conjugates" deltab_0..deltab_4, then
// the pivots alpha, alphab, beta, betab.
constexpr int kParameters = 14;
constexpr int kAlpha = 10, kAlphab = 11, kBeta = 12, kBetab = 13;

const std::array<Complex, 3> kPatchX{Complex(0.5331, -0.2719), Complex(-0.1627, 0.6911), Complex(0.8126, 0.3357)};
const std::array<Complex, 3> kPatchY{Complex(-0.4418, 0.5572), Complex(0.7263, -0.1184), Complex(0.6045, 0.4791)};

double abs1(Complex z) { return std::abs(z.real()) + std::abs(z.imag()); }
Complex reciprocal(Complex z) { return std::conj(z) / std::norm(z); }

// Gaussian elimination with partial pivoting on |re| + |im|, in place; false when singular.
template <int N>
bool solve_small(Eigen::Matrix<Complex, N, N>& a, Eigen::Matrix<Complex, N, 1>& b) {
  for (int k = 0; k < N; ++k) {
    int pivot = k;
    for (int r = k + 1; r < N; ++r)
      if (abs1(a(r, k)) > abs1(a(pivot, k))) pivot = r;
    if (abs1(a(pivot, k)) == 0.0) return false;
    if (pivot != k) {
      a.row(pivot).swap(a.row(k));
      std::swap(b[pivot], b[k]);
    }
    const Complex inverse = reciprocal(a(k, k));
    for (int r = k + 1; r < N; ++r) {
      const Complex factor = a(r, k) * inverse;
      for (int c = k + 1; c < N; ++c) a(r, c) -= factor * a(k, c);
      b[r] -= factor * b[k];
    }
  }
  for (int k = N - 1; k >= 0; --k) {
    Complex sum = b[k];
    for (int c = k + 1; c < N; ++c) sum -= a(k, c) * b[c];
    b[k] = sum * reciprocal(a(k, k));
  }
  return true;
}

// The three equations of position i (i = 1..4) and their derivatives:
//   t_i tb_i - 1 = 0
//   t_i eb_i X + tb_i e_i Xb - eb_0 X - e_0 Xb + (e_i eb_i - e_0 eb_0) hx = 0,  e = delta - alpha
//   the same for Y, hy with e = delta - beta
// (|delta_i + t_i x - alpha|^2 = |delta_0 + x - alpha|^2: the pivot stays on its circle.)
struct PositionRows {
  Eigen::Matrix<Complex, 3, 2> block;   // d/d(t_i, tb_i)
  Eigen::Matrix<Complex, 3, 6> border;  // d/d(X, Xb, hx, Y, Yb, hy)
  Eigen::Vector3cd value;               // F
  // dF/de_i, dF/deb_i, dF/de_0, dF/deb_0 for the X row [0] and the Y row [1]
  std::array<std::array<Complex, 4>, 2> by_offsets;
};

PositionRows position_rows(const CVector& v, const CVector& p, int i) {
  PositionRows rows;
  const Complex t = v[kT + i - 1], tb = v[kTb + i - 1];
  rows.value[0] = t * tb - 1.0;
  rows.block.row(0) << tb, t;
  rows.border.setZero();
  const int pivot[2] = {kAlpha, kBeta};
  const int coords[2] = {kX, kY};
  for (int dyad = 0; dyad < 2; ++dyad) {
    const Complex e = p[i] - p[pivot[dyad]], eb = p[5 + i] - p[pivot[dyad] + 1];
    const Complex e0 = p[0] - p[pivot[dyad]], eb0 = p[5] - p[pivot[dyad] + 1];
    const Complex X = v[coords[dyad]], Xb = v[coords[dyad] + 1], h = v[coords[dyad] + 2];
    const int row = 1 + dyad, col = 3 * dyad;
    rows.value[row] = t * eb * X + tb * e * Xb - eb0 * X - e0 * Xb + (e * eb - e0 * eb0) * h;
    rows.block.row(row) << eb * X, e * Xb;
    rows.border(row, col) = t * eb - eb0;
    rows.border(row, col + 1) = tb * e - e0;
    rows.border(row, col + 2) = e * eb - e0 * eb0;
    rows.by_offsets[dyad] = {tb * Xb + eb * h, t * X + e * h, -Xb - eb0 * h, -X - e0 * h};
  }
  return rows;
}

// Fp dp for the X and Y rows of position i.
Complex parameter_rate(const PositionRows& rows, const CVector& dp, int i, int dyad) {
  const int pivot = dyad == 0 ? kAlpha : kBeta;
  const auto& g = rows.by_offsets[dyad];
  return g[0] * (dp[i] - dp[pivot]) + g[1] * (dp[5 + i] - dp[pivot + 1]) + g[2] * (dp[0] - dp[pivot]) +
         g[3] * (dp[5] - dp[pivot + 1]);
}

class IsotropicFivePoint final : public ParameterizedSystem {
 public:
  int variables() const override { return kVariables; }
  int parameters() const override { return kParameters; }

  void evaluate(const CVector& v, const CVector& p, CVector& f, CMatrix* jx, CMatrix* jp) const override {
    f.resize(kVariables);
    if (jx) jx->setZero(kVariables, kVariables);
    if (jp) jp->setZero(kVariables, kParameters);
    for (int i = 1; i <= 4; ++i) {
      const PositionRows rows = position_rows(v, p, i);
      const int row = 3 * (i - 1);
      f.segment<3>(row) = rows.value;
      if (jx) {
        jx->block<3, 1>(row, kT + i - 1) = rows.block.col(0);
        jx->block<3, 1>(row, kTb + i - 1) = rows.block.col(1);
        jx->block<3, 6>(row, kX) = rows.border;
      }
      if (jp) {
        for (int dyad = 0; dyad < 2; ++dyad) {
          const auto& g = rows.by_offsets[dyad];
          const int r = row + 1 + dyad, pivot = dyad == 0 ? kAlpha : kBeta;
          (*jp)(r, i) += g[0];
          (*jp)(r, 5 + i) += g[1];
          (*jp)(r, 0) += g[2];
          (*jp)(r, 5) += g[3];
          (*jp)(r, pivot) -= g[0] + g[2];
          (*jp)(r, pivot + 1) -= g[1] + g[3];
        }
      }
    }
    f[12] = kPatchX[0] * v[kX] + kPatchX[1] * v[kXb] + kPatchX[2] * v[kHx] - 1.0;
    f[13] = kPatchY[0] * v[kY] + kPatchY[1] * v[kYb] + kPatchY[2] * v[kHy] - 1.0;
    if (jx) {
      for (int k = 0; k < 3; ++k) {
        (*jx)(12, kX + k) = kPatchX[k];
        (*jx)(13, kY + k) = kPatchY[k];
      }
    }
  }

  // The Jacobian is bordered block-diagonal: each position i's three rows involve only its
  // own (t_i, tb_i) and the six pivot coordinates. Eliminating (t_i, tb_i) with the left null
  // vector of its 3x2 block leaves a 6x6 system in the pivot coordinates (a Schur
  // complement), then back-substitution: far fewer operations than a dense 14x14 LU.
  bool linear_solve(const CVector& v, const CVector& p, const CVector* dp, CVector& y) const override {
    using Matrix6 = Eigen::Matrix<Complex, 6, 6>;
    using Vector6 = Eigen::Matrix<Complex, 6, 1>;
    std::array<PositionRows, 4> rows;
    Matrix6 schur;
    Vector6 reduced = Vector6::Zero();
    for (int i = 1; i <= 4; ++i) {
      PositionRows& r = rows[i - 1];
      r = position_rows(v, p, i);
      if (dp) r.value = {0.0, parameter_rate(r, *dp, i, 0), parameter_rate(r, *dp, i, 1)};
      const auto& m = r.block;
      // n^T m = 0 for the (bilinear) cross product of m's columns.
      const Eigen::RowVector3cd n(m(1, 0) * m(2, 1) - m(2, 0) * m(1, 1), m(2, 0) * m(0, 1) - m(0, 0) * m(2, 1),
                                  m(0, 0) * m(1, 1) - m(1, 0) * m(0, 1));
      // the border's X row touches only the X coordinates, its Y row only the Y ones
      schur.block<1, 3>(i - 1, 0) = n[1] * r.border.block<1, 3>(1, 0);
      schur.block<1, 3>(i - 1, 3) = n[2] * r.border.block<1, 3>(2, 3);
      reduced[i - 1] = (n * r.value).value();
    }
    schur.row(4).setZero();
    schur.row(5).setZero();
    for (int k = 0; k < 3; ++k) {
      schur(4, k) = kPatchX[k];
      schur(5, 3 + k) = kPatchY[k];
    }
    if (!dp) {
      reduced[4] = kPatchX[0] * v[kX] + kPatchX[1] * v[kXb] + kPatchX[2] * v[kHx] - 1.0;
      reduced[5] = kPatchY[0] * v[kY] + kPatchY[1] * v[kYb] + kPatchY[2] * v[kHy] - 1.0;
    }
    if (!solve_small(schur, reduced)) return false;
    const Vector6& z = reduced;
    y.resize(kVariables);
    y.tail(6) = z;
    for (int i = 0; i < 4; ++i) {
      const auto& c = rows[i].border;
      const Eigen::Vector3cd r(rows[i].value[0], rows[i].value[1] - (c.block<1, 3>(1, 0) * z.head<3>()).value(),
                               rows[i].value[2] - (c.block<1, 3>(2, 3) * z.tail<3>()).value());
      // the best-conditioned pair of the three rows gives (dt_i, dtb_i)
      const auto& m = rows[i].block;
      int a = 0, b = 1;
      Complex det = m(0, 0) * m(1, 1) - m(0, 1) * m(1, 0);
      for (auto [ra, rb] : {std::pair{0, 2}, std::pair{1, 2}}) {
        const Complex other = m(ra, 0) * m(rb, 1) - m(ra, 1) * m(rb, 0);
        if (std::norm(other) > std::norm(det)) {
          det = other;
          a = ra;
          b = rb;
        }
      }
      const Complex inverse = reciprocal(det);
      y[kT + i] = (r[a] * m(b, 1) - m(a, 1) * r[b]) * inverse;
      y[kTb + i] = (m(a, 0) * r[b] - r[a] * m(b, 0)) * inverse;
    }
    return y.allFinite();
  }

  double infinity_measure(const CVector& v) const override {
    const double mx = std::abs(v[kHx]) / Eigen::Vector3cd(v[kX], v[kXb], v[kHx]).norm();
    const double my = std::abs(v[kHy]) / Eigen::Vector3cd(v[kY], v[kYb], v[kHy]).norm();
    return std::min(mx, my);
  }

  // Affine coordinates: t1..t4, tb1..tb4, x, xb, y, yb.
  CVector to_affine(const CVector& v) const override {
    CVector a(12);
    a.head(8) = v.head(8);
    a[8] = v[kX] / v[kHx];
    a[9] = v[kXb] / v[kHx];
    a[10] = v[kY] / v[kHy];
    a[11] = v[kYb] / v[kHy];
    return a;
  }

  CVector from_affine(const CVector& a) const override {
    CVector v(kVariables);
    v.head(8) = a.head(8);
    const Complex hx = 1.0 / (kPatchX[0] * a[8] + kPatchX[1] * a[9] + kPatchX[2]);
    const Complex hy = 1.0 / (kPatchY[0] * a[10] + kPatchY[1] * a[11] + kPatchY[2]);
    v[kX] = a[8] * hx;
    v[kXb] = a[9] * hx;
    v[kHx] = hx;
    v[kY] = a[10] * hy;
    v[kYb] = a[11] * hy;
    v[kHy] = hy;
    return v;
  }

  // Real when every "conjugate" unknown is the conjugate of its partner.
  bool is_real(const CVector& a) const override {
    auto conjugate_pair = [](Complex z, Complex zb) {
      return std::abs(zb - std::conj(z)) <= 1e-8 * (1.0 + std::abs(z));
    };
    for (int i = 0; i < 4; ++i)
      if (!conjugate_pair(a[i], a[4 + i])) return false;
    return conjugate_pair(a[8], a[9]) && conjugate_pair(a[10], a[11]);
  }
};

const IsotropicFivePoint& isotropic_system() {
  static const IsotropicFivePoint system;
  return system;
}

Complex as_complex(const Eigen::Vector2d& v) { return {v.x(), v.y()}; }

void check_task(const FivePointTask& task) {
  auto finite = [](const Eigen::Vector2d& v) { return v.allFinite(); };
  if (!finite(task.pivot_a) || !finite(task.pivot_b))
    throw Error(ErrorKind::InvalidModel, "five-point task: a pivot is not a finite number");
  for (const auto& d : task.points)
    if (!finite(d)) throw Error(ErrorKind::InvalidModel, "five-point task: a precision point is not a finite number");
  double size = (task.pivot_b - task.pivot_a).norm();
  for (const auto& d : task.points) size = std::max(size, (d - task.pivot_a).norm());
  if ((task.pivot_b - task.pivot_a).norm() <= 1e-9 * size)
    throw Error(ErrorKind::InvalidModel, "five-point task: the two fixed pivots coincide");
  for (int i = 0; i < 5; ++i)
    for (int j = i + 1; j < 5; ++j)
      if ((task.points[i] - task.points[j]).norm() <= 1e-9 * size)
        throw Error(ErrorKind::InvalidModel, "five-point task: precision points " + std::to_string(i + 1) + " and " +
                                                 std::to_string(j + 1) + " coincide");
}

// The frame the solver works in: origin at the points' centroid, lengths in units of their
// RMS distance from it, so that neither far pivots nor tiny tasks spoil the conditioning.
struct Frame {
  Complex origin;
  double scale = 1.0;
  Complex to_frame(const Eigen::Vector2d& v) const { return (as_complex(v) - origin) / scale; }
};

Frame task_frame(const FivePointTask& task) {
  Frame frame;
  for (const auto& d : task.points) frame.origin += as_complex(d) / 5.0;
  double spread = 0.0;
  for (const auto& d : task.points) spread += std::norm(as_complex(d) - frame.origin) / 5.0;
  frame.scale = std::sqrt(spread);
  return frame;
}

CVector task_parameters(const FivePointTask& task) {
  const Frame frame = task_frame(task);
  CVector p(kParameters);
  for (int j = 0; j < 5; ++j) p[j] = frame.to_frame(task.points[j]);
  p[kAlpha] = frame.to_frame(task.pivot_a);
  p[kBeta] = frame.to_frame(task.pivot_b);
  for (int k : {0, 1, 2, 3, 4, kAlpha, kBeta}) p[k == kAlpha || k == kBeta ? k + 1 : 5 + k] = std::conj(p[k]);
  return p;
}

// The largest relative residual of the affine equations: |value| / sum of |terms| per
// equation, so it does not grow with the size of the solution.
double relative_residual(const CVector& p, const CVector& a) {
  double worst = 0.0;
  for (int i = 1; i <= 4; ++i) {
    const Complex t = a[i - 1], tb = a[3 + i];
    worst = std::max(worst, std::abs(t * tb - 1.0) / (std::abs(t * tb) + 1.0));
    for (int dyad = 0; dyad < 2; ++dyad) {
      const int pivot = dyad == 0 ? kAlpha : kBeta;
      const Complex x = a[8 + 2 * dyad], xb = a[9 + 2 * dyad];
      const Complex e = p[i] - p[pivot], eb = p[5 + i] - p[pivot + 1];
      const Complex e0 = p[0] - p[pivot], eb0 = p[5] - p[pivot + 1];
      const std::array<Complex, 6> terms{t * eb * x, tb * e * xb, -eb0 * x, -e0 * xb, e * eb, -e0 * eb0};
      Complex sum = 0.0;
      double size = 0.0;
      for (Complex term : terms) {
        sum += term;
        size += std::abs(term);
      }
      worst = std::max(worst, std::abs(sum) / size);
    }
  }
  return worst;
}

}  // namespace

const ParameterizedSystem& five_point_parameterized_system() { return isotropic_system(); }

FivePointSolution five_point_solution(const FivePointTask& task, const CVector& affine) {
  // `affine`: isotropic coordinates in the solver's frame -> the primer's form, task units.
  FivePointSolution s;
  const double scale = task_frame(task).scale;
  const Complex i(0.0, 1.0);
  for (int k = 0; k < 4; ++k) {
    s.cos_rotation[k] = 0.5 * (affine[k] + affine[4 + k]);
    s.sin_rotation[k] = (affine[k] - affine[4 + k]) / (2.0 * i);
  }
  auto vector_of = [&](Complex z, Complex zb) {
    return std::array<Complex, 2>{0.5 * scale * (z + zb), scale * (z - zb) / (2.0 * i)};
  };
  s.moving_a = vector_of(affine[8], affine[9]);
  s.moving_b = vector_of(affine[10], affine[11]);
  s.real = isotropic_system().is_real(affine);
  s.residual = relative_residual(task_parameters(task), affine);
  if (s.real) {
    const Eigen::Vector2d d0 = task.points[0];
    s.design.ground_a = task.pivot_a;
    s.design.ground_b = task.pivot_b;
    s.design.coupler_point = d0;
    s.design.moving_a = d0 + Eigen::Vector2d(s.moving_a[0].real(), s.moving_a[1].real());
    s.design.moving_b = d0 + Eigen::Vector2d(s.moving_b[0].real(), s.moving_b[1].real());
  }
  return s;
}

PolynomialSystem five_point_system(const std::array<Eigen::Vector2d, 5>& points) {
  auto v = [](int k) { return Polynomial::variable(12, k); };
  const Eigen::Vector2d a(1.0, 0.0);
  const Eigen::Vector2d& d0 = points[0];
  std::vector<Polynomial> eqs;
  for (int i = 1; i <= 4; ++i) {
    const Polynomial c = v(2 * (i - 1)), s = v(2 * (i - 1) + 1);
    const Eigen::Vector2d& d = points[i];
    const double half = 0.5 * (d.squaredNorm() - d0.squaredNorm());
    eqs.push_back(c * c + s * s - 1.0);
    // d^T R = (d1 c + d2 s, -d1 s + d2 c)
    auto dyad = [&](const Eigen::Vector2d& di, const Eigen::Vector2d& dz, int first, double constant) {
      const Polynomial u = v(first), w = v(first + 1);
      return (di.x() * c + di.y() * s - dz.x()) * u + (-di.x() * s + di.y() * c - dz.y()) * w + constant;
    };
    eqs.push_back(dyad(d, d0, 8, half));
    eqs.push_back(dyad(d - a, d0 - a, 10, half - a.dot(d - d0)));
  }
  return PolynomialSystem(std::move(eqs));
}

VariableGroups five_point_groups() { return {{0, 1}, {2, 3}, {4, 5}, {6, 7}, {8, 9}, {10, 11}}; }

namespace {

// The primer's frame: pivot a at the origin, pivot b at (1, 0).
Complex primer_scale(const FivePointTask& task) { return as_complex(task.pivot_b) - as_complex(task.pivot_a); }

std::array<Eigen::Vector2d, 5> primer_points(const FivePointTask& task) {
  std::array<Eigen::Vector2d, 5> points;
  for (int j = 0; j < 5; ++j) {
    const Complex d = (as_complex(task.points[j]) - as_complex(task.pivot_a)) / primer_scale(task);
    points[j] = {d.real(), d.imag()};
  }
  return points;
}

// Isotropic affine coordinates in the solver's frame from the primer's (c, s, x, y).
CVector isotropic_from_primer(const FivePointTask& task, const CVector& z) {
  const Complex i(0.0, 1.0);
  CVector a(12);
  for (int k = 0; k < 4; ++k) {
    a[k] = z[2 * k] + i * z[2 * k + 1];
    a[4 + k] = z[2 * k] - i * z[2 * k + 1];
  }
  a[8] = z[8] + i * z[9];
  a[9] = z[8] - i * z[9];
  a[10] = z[10] + i * z[11];
  a[11] = z[10] - i * z[11];
  // vectors: primer frame -> task units -> solver frame
  const Complex to_task = primer_scale(task);
  const double scale = task_frame(task).scale;
  for (int k : {8, 10}) {
    a[k] *= to_task / scale;
    a[k + 1] *= std::conj(to_task) / scale;
  }
  return a;
}

// A solution found by a path: its affine coordinates and the tracker's condition number there.
struct Found {
  CVector affine;
  double condition = 0;
};

std::vector<FivePointSolution> solutions_of(const FivePointTask& task, const std::vector<Found>& found) {
  std::vector<FivePointSolution> out;
  out.reserve(found.size());
  for (const auto& f : found) {
    out.push_back(five_point_solution(task, f.affine));
    out.back().condition = f.condition;
  }
  return out;
}

}  // namespace

FivePointResult solve_five_point(const FivePointTask& task, const SolverOptions& options) {
  check_task(task);
  const CVector target = task_parameters(task);
  const FivePointStart& start = five_point_start();
  const auto& system = isotropic_system();

  std::vector<CVector> starts;
  for (const auto& a : start.solutions) starts.push_back(system.from_affine(a));
  SolverOptions careful = options;
  careful.retrack_failures = true;  // every one of the 36 paths should arrive
  const SolveResult r = solve_parameter_homotopy(system, start.parameters, starts, target, careful);

  FivePointResult result;
  result.paths = static_cast<int>(starts.size());
  result.failed_paths = r.count(EndpointKind::Failed);
  result.retracked_paths = r.retracked;
  std::vector<Found> found;
  for (const auto* e : r.finite_regular()) found.push_back({system.to_affine(e->x), e->condition});
  if (found.size() == start.solutions.size() && result.failed_paths == 0) {
    result.method = "parameter homotopy (" + std::to_string(starts.size()) + " paths)";
    result.solutions = solutions_of(task, found);
    return result;
  }

  // Fallback: the 96-path linear-product homotopy on the primer's form.
  const PolynomialSystem f = five_point_system(primer_points(task));
  const SolveResult fallback = solve_linear_product(f, five_point_groups(), options);
  result.used_fallback = true;
  result.paths += static_cast<int>(fallback.endpoints.size());
  result.failed_paths += fallback.count(EndpointKind::Failed);  // the note counts both runs' paths
  result.retracked_paths += fallback.retracked;
  result.method = "linear-product homotopy (" + std::to_string(fallback.endpoints.size()) +
                  " paths: " + std::to_string(fallback.count(EndpointKind::Finite)) + " finite, " +
                  std::to_string(fallback.count(EndpointKind::AtInfinity)) + " at infinity, " +
                  std::to_string(fallback.count(EndpointKind::Failed)) +
                  " failed) after the parameter homotopy found " + std::to_string(found.size()) + " of " +
                  std::to_string(start.solutions.size());
  // Every distinct solution either run found.
  for (const auto* e : fallback.finite_regular()) {
    const CVector a = isotropic_from_primer(task, e->x);
    const bool known = std::any_of(found.begin(), found.end(),
                                   [&](const Found& b) { return (a - b.affine).norm() <= 1e-7 * (1.0 + a.norm()); });
    if (!known) found.push_back({a, e->condition});
  }
  result.solutions = solutions_of(task, found);
  return result;
}

// --- generating the stored start instance -------------------------------------------------

FivePointStart generate_five_point_start(std::uint64_t seed, const SolverOptions& options) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal;
  auto rc = [&] { return Complex(normal(rng), normal(rng)); };
  // A random solution first, then parameters that fit it: for each i, subtracting the two
  // dyad equations leaves one linear in (delta_i, deltab_i); with it the first is quadratic.
  CVector a(12), p(kParameters);
  for (int k = 0; k < 4; ++k) {
    a[k] = rc();
    a[4 + k] = 1.0 / a[k];
  }
  for (int k = 8; k < 12; ++k) a[k] = rc();
  // pivot a at the origin (the family is invariant under translation), pivot b anywhere
  p[kAlpha] = p[kAlphab] = 0.0;
  const Complex beta = rc(), betab = rc();
  p[kBeta] = beta;
  p[kBetab] = betab;
  p[0] = rc();
  p[5] = rc();
  const Complex x = a[8], xb = a[9], y = a[10], yb = a[11];
  const Complex d0 = p[0], db0 = p[5], e0 = d0 - beta, eb0 = db0 - betab;
  const Complex kx = db0 * x + d0 * xb + d0 * db0;
  const Complex ky = eb0 * y + e0 * yb + e0 * eb0;
  for (int i = 1; i <= 4; ++i) {
    const Complex t = a[i - 1], tb = a[3 + i];
    const Complex A = t * (x - y) + beta, B = tb * (xb - yb) + betab;
    const Complex R = kx - ky - t * betab * y - tb * beta * yb + beta * betab;
    // -B d^2 + (R - B t x + A tb xb) d + R t x - A kx = 0
    const Complex qa = -B, qb = R - B * t * x + A * tb * xb, qc = R * t * x - A * kx;
    const Complex d = (-qb + std::sqrt(qb * qb - 4.0 * qa * qc)) / (2.0 * qa);
    p[i] = d;
    p[5 + i] = (R - d * B) / A;
  }
  const auto& system = isotropic_system();
  const MonodromyResult m = monodromy_solve(system, p, {system.from_affine(a)}, 36, options, 10, 200);
  FivePointStart start;
  start.parameters = p;
  for (const auto& v : m.solutions) start.solutions.push_back(system.to_affine(v));
  return start;
}

}  // namespace nbar::synthesis
