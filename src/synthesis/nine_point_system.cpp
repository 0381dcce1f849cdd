// The isotropic nine-point system and its group of six (see nine_point.hpp for the equations).
#include <Eigen/LU>

#include <array>
#include <cmath>

#include "nbar/synthesis/nine_point_start.hpp"

namespace nbar::synthesis {
namespace {

constexpr int kPositions = 8;
constexpr int kT = 0, kTb = 8, kDyad0 = 16, kDyad1 = 21;
constexpr int kVariables = 26, kParameters = 16;
// Within a dyad's block: X, Xb, A, Ab, H.
constexpr int kX = 0, kXb = 1, kA = 2, kAb = 3, kH = 4;

// Random fixed patches: each dyad's homogeneous coordinates satisfy patch . (X, Xb, A, Ab, H) = 1.
const std::array<std::array<Complex, 5>, 2> kPatch{{
    {Complex(0.4127, -0.3351), Complex(-0.2263, 0.5718), Complex(0.3819, 0.2904), Complex(-0.5522, -0.1376),
     Complex(0.7301, 0.4419)},
    {Complex(-0.3168, 0.4853), Complex(0.5247, 0.1932), Complex(-0.2675, -0.4481), Complex(0.3316, -0.3769),
     Complex(0.6614, -0.5237)},
}};

double abs1(Complex z) { return std::abs(z.real()) + std::abs(z.imag()); }
Complex reciprocal(Complex z) { return std::conj(z) / std::norm(z); }

int dyad_base(int dyad) { return dyad == 0 ? kDyad0 : kDyad1; }

// Position j's three rows: t tb - 1 and, per dyad, the homogenized circle equation
//   t X (db H - Ab) + tb Xb (d H - A) + d db H^2 - d Ab H - A db H + X Ab + A Xb = 0
// (|d + t x - a|^2 = |x - a|^2 with t tb = 1 used, then x = X/H, a = A/H).
struct PositionRows {
  Eigen::Matrix<Complex, 3, 2> block;                  // d/d(t, tb)
  std::array<Eigen::Matrix<Complex, 1, 5>, 2> border;  // dyad row d/d(its five coordinates)
  Eigen::Vector3cd value;
  std::array<std::array<Complex, 2>, 2> by_parameter;  // dyad row d/d(delta, deltab)
};

PositionRows position_rows(const CVector& v, const CVector& p, int i) {
  PositionRows r;
  const Complex t = v[kT + i], tb = v[kTb + i];
  const Complex d = p[i], db = p[kPositions + i];
  r.value[0] = t * tb - 1.0;
  r.block.row(0) << tb, t;
  for (int dyad = 0; dyad < 2; ++dyad) {
    const int b = dyad_base(dyad);
    const Complex X = v[b + kX], Xb = v[b + kXb], A = v[b + kA], Ab = v[b + kAb], H = v[b + kH];
    const Complex u = db * H - Ab, ub = d * H - A;
    r.value[1 + dyad] = t * X * u + tb * Xb * ub + d * db * H * H - d * Ab * H - A * db * H + X * Ab + A * Xb;
    r.block.row(1 + dyad) << X * u, Xb * ub;
    r.border[dyad] << t * u + Ab, tb * ub + A, -tb * Xb - db * H + Xb, -t * X - d * H + X,
        t * X * db + tb * Xb * d + 2.0 * d * db * H - d * Ab - A * db;
    r.by_parameter[dyad] = {tb * Xb * H + db * H * H - Ab * H, t * X * H + d * H * H - A * H};
  }
  return r;
}

Complex patch_value(const CVector& v, int dyad) {
  Complex s = -1.0;
  for (int k = 0; k < 5; ++k) s += kPatch[dyad][k] * v[dyad_base(dyad) + k];
  return s;
}

class IsotropicNinePoint final : public ParameterizedSystem {
 public:
  int variables() const override { return kVariables; }
  int parameters() const override { return kParameters; }

  void evaluate(const CVector& v, const CVector& p, CVector& f, CMatrix* jx, CMatrix* jp) const override {
    f.resize(kVariables);
    if (jx) jx->setZero(kVariables, kVariables);
    if (jp) jp->setZero(kVariables, kParameters);
    for (int i = 0; i < kPositions; ++i) {
      const PositionRows r = position_rows(v, p, i);
      const int row = 3 * i;
      f.segment<3>(row) = r.value;
      if (jx) {
        jx->block<3, 1>(row, kT + i) = r.block.col(0);
        jx->block<3, 1>(row, kTb + i) = r.block.col(1);
        for (int dyad = 0; dyad < 2; ++dyad) jx->block<1, 5>(row + 1 + dyad, dyad_base(dyad)) = r.border[dyad];
      }
      if (jp)
        for (int dyad = 0; dyad < 2; ++dyad) {
          (*jp)(row + 1 + dyad, i) = r.by_parameter[dyad][0];
          (*jp)(row + 1 + dyad, kPositions + i) = r.by_parameter[dyad][1];
        }
    }
    for (int dyad = 0; dyad < 2; ++dyad) {
      f[24 + dyad] = patch_value(v, dyad);
      if (jx)
        for (int k = 0; k < 5; ++k) (*jx)(24 + dyad, dyad_base(dyad) + k) = kPatch[dyad][k];
    }
  }

  // Bordered block-diagonal: each position's rows involve its own (t, tb) and the ten dyad
  // coordinates. The left null vector of each 3x2 block eliminates (t, tb), leaving a 10x10
  // system in the dyad coordinates, then back-substitution.
  bool linear_solve(const CVector& v, const CVector& p, const CVector* dp, CVector& y) const override {
    using Matrix10 = Eigen::Matrix<Complex, 10, 10>;
    using Vector10 = Eigen::Matrix<Complex, 10, 1>;
    std::array<PositionRows, kPositions> rows;
    Matrix10 schur = Matrix10::Zero();
    Vector10 reduced = Vector10::Zero();
    for (int i = 0; i < kPositions; ++i) {
      PositionRows& r = rows[i];
      r = position_rows(v, p, i);
      if (dp) {
        r.value[0] = 0.0;
        for (int dyad = 0; dyad < 2; ++dyad)
          r.value[1 + dyad] = r.by_parameter[dyad][0] * (*dp)[i] + r.by_parameter[dyad][1] * (*dp)[kPositions + i];
      }
      const auto& m = r.block;
      const Eigen::RowVector3cd n(m(1, 0) * m(2, 1) - m(2, 0) * m(1, 1), m(2, 0) * m(0, 1) - m(0, 0) * m(2, 1),
                                  m(0, 0) * m(1, 1) - m(1, 0) * m(0, 1));
      schur.block<1, 5>(i, 0) = n[1] * r.border[0];
      schur.block<1, 5>(i, 5) = n[2] * r.border[1];
      reduced[i] = (n * r.value).value();
    }
    for (int dyad = 0; dyad < 2; ++dyad) {
      for (int k = 0; k < 5; ++k) schur(8 + dyad, 5 * dyad + k) = kPatch[dyad][k];
      reduced[8 + dyad] = dp ? Complex(0.0) : patch_value(v, dyad);
    }
    const Eigen::PartialPivLU<Matrix10> lu(schur);
    const Vector10 z = lu.solve(reduced);
    if (!z.allFinite()) return false;
    y.resize(kVariables);
    y.tail<10>() = z;
    for (int i = 0; i < kPositions; ++i) {
      const PositionRows& r = rows[i];
      const Eigen::Vector3cd rhs(r.value[0], r.value[1] - (r.border[0] * z.head<5>()).value(),
                                 r.value[2] - (r.border[1] * z.tail<5>()).value());
      const auto& m = r.block;
      int a = 0, b = 1;
      Complex det = m(0, 0) * m(1, 1) - m(0, 1) * m(1, 0);
      for (auto [ra, rb] : {std::pair{0, 2}, std::pair{1, 2}}) {
        const Complex other = m(ra, 0) * m(rb, 1) - m(ra, 1) * m(rb, 0);
        if (abs1(other) > abs1(det)) {
          det = other;
          a = ra;
          b = rb;
        }
      }
      if (det == Complex(0.0)) return false;
      const Complex inverse = reciprocal(det);
      y[kT + i] = (rhs[a] * m(b, 1) - m(a, 1) * rhs[b]) * inverse;
      y[kTb + i] = (m(a, 0) * rhs[b] - rhs[a] * m(b, 0)) * inverse;
    }
    return y.allFinite();
  }

  double infinity_measure(const CVector& v) const override {
    double measure = 1.0;
    for (int dyad = 0; dyad < 2; ++dyad) {
      const auto block = v.segment<5>(dyad_base(dyad));
      measure = std::min(measure, std::abs(block[kH]) / block.norm());
    }
    return measure;
  }

  CVector to_affine(const CVector& v) const override {
    CVector a(24);
    a.head<16>() = v.head<16>();
    for (int dyad = 0; dyad < 2; ++dyad) {
      const int b = dyad_base(dyad);
      for (int k = 0; k < 4; ++k) a[16 + 4 * dyad + k] = v[b + k] / v[b + kH];
    }
    return a;
  }

  CVector from_affine(const CVector& a) const override {
    CVector v(kVariables);
    v.head<16>() = a.head<16>();
    for (int dyad = 0; dyad < 2; ++dyad) {
      const int b = dyad_base(dyad);
      Complex denominator = kPatch[dyad][kH];
      for (int k = 0; k < 4; ++k) denominator += kPatch[dyad][k] * a[16 + 4 * dyad + k];
      const Complex h = 1.0 / denominator;
      for (int k = 0; k < 4; ++k) v[b + k] = a[16 + 4 * dyad + k] * h;
      v[b + kH] = h;
    }
    return v;
  }

  bool is_real(const CVector& a) const override {
    auto conjugate_pair = [](Complex z, Complex zb) {
      return std::abs(zb - std::conj(z)) <= 1e-7 * (1.0 + std::abs(z));
    };
    for (int i = 0; i < kPositions; ++i)
      if (!conjugate_pair(a[i], a[kPositions + i])) return false;
    for (int k = 16; k < 24; k += 2)
      if (!conjugate_pair(a[k], a[k + 1])) return false;
    return true;
  }
};

}  // namespace

const ParameterizedSystem& nine_point_system() {
  static const IsotropicNinePoint system;
  return system;
}

CVector swap_dyads(const CVector& affine) {
  CVector s = affine;
  s.segment<4>(16) = affine.segment<4>(20);
  s.segment<4>(20) = affine.segment<4>(16);
  return s;
}

// With P the coupler point, the loop P = A + u + v (u: input link, v: coupler side A1 -> P)
// = B + w + rho v (rho = y / x). Its cognate on A takes v as the input link and u as the
// coupler side; its second moving pivot A + v + k u, k = 1 / (1 - rho), turns about the
// third fixed pivot C = A + k (B - A) on a link k w of constant length.
CVector roberts_cognate(const CVector& s, const CVector& p) {
  CVector c(24);
  const Complex x = s[16], xb = s[17], a = s[18], ab = s[19], y = s[20], yb = s[21], b = s[22], bb = s[23];
  const Complex k = 1.0 / (1.0 - y / x), kb = 1.0 / (1.0 - yb / xb);
  for (int i = 0; i < kPositions; ++i) {
    c[i] = (p[i] + s[i] * x - a) / (x - a);
    c[kPositions + i] = (p[kPositions + i] + s[kPositions + i] * xb - ab) / (xb - ab);
  }
  c[16] = a - x;
  c[17] = ab - xb;
  c[18] = a;
  c[19] = ab;
  c[20] = (a - x) * (1.0 - k);
  c[21] = (ab - xb) * (1.0 - kb);
  c[22] = a + k * (b - a);
  c[23] = ab + kb * (bb - ab);
  return c;
}

std::vector<CVector> nine_point_orbit(const CVector& affine, const CVector& parameters) {
  std::vector<CVector> orbit{affine};
  auto known = [&](const CVector& s) {
    for (const auto& o : orbit)
      if ((o - s).norm() <= 1e-7 * (1.0 + o.norm())) return true;
    return false;
  };
  for (size_t i = 0; i < orbit.size() && orbit.size() < 6; ++i) {
    for (const CVector& image : {swap_dyads(orbit[i]), roberts_cognate(orbit[i], parameters)})
      if (image.allFinite() && !known(image)) orbit.push_back(image);
  }
  return orbit;
}

Eigen::Matrix<Complex, 6, 1> orbit_key(const CVector& s) {
  const Complex x = s[16], xb = s[17], a = s[18], ab = s[19], y = s[20], yb = s[21], b = s[22], bb = s[23];
  const Complex c = a + (b - a) / (1.0 - y / x), cb = ab + (bb - ab) / (1.0 - yb / xb);
  Eigen::Matrix<Complex, 6, 1> key;
  key << a + b + c, a * b + b * c + c * a, a * b * c, ab + bb + cb, ab * bb + bb * cb + cb * ab, ab * bb * cb;
  return key;
}

}  // namespace nbar::synthesis
