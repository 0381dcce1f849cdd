#include "nbar/synthesis/burmester.hpp"

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/QR>

#include <algorithm>
#include <cmath>
#include <complex>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>

#include "linear_algebra.hpp"
#include "nbar/model/diagnostics.hpp"
#include "nbar/synthesis/solve.hpp"

namespace nbar::synthesis {
namespace {

using Vec2 = Eigen::Vector2d;
using Mat2 = Eigen::Matrix2d;
using Row3 = Eigen::RowVector3d;
using Mat3 = Eigen::Matrix3d;
using CVec2 = Eigen::Vector2cd;
using CVec4 = Eigen::Vector4cd;
using CRow3 = Eigen::RowVector3cd;

// Messages number positions from 1.
template <class... Parts>
[[noreturn]] void fail(const Parts&... parts) {
  std::ostringstream message;
  message << "Burmester synthesis: ";
  (message << ... << parts);
  throw Error(ErrorKind::InvalidModel, message.str());
}

Mat2 rotation(double angle) {
  Mat2 r;
  r << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
  return r;
}

double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// Angles equal modulo 2 pi.
bool same_angle(double a, double b, double tolerance) { return std::abs(std::sin(0.5 * (a - b))) <= tolerance; }

void check_poses(std::span<const BodyPose> poses) {
  for (std::size_t i = 0; i < poses.size(); ++i)
    if (!poses[i].point.allFinite() || !std::isfinite(poses[i].angle)) fail("position ", i + 1, " is not finite");
  double size = 0;
  for (const BodyPose& p : poses) size = std::max(size, p.point.cwiseAbs().maxCoeff());
  for (std::size_t i = 0; i < poses.size(); ++i)
    for (std::size_t j = i + 1; j < poses.size(); ++j)
      if ((poses[i].point - poses[j].point).norm() <= 1e-12 * size && same_angle(poses[i].angle, poses[j].angle, 1e-12))
        fail("positions ", i + 1, " and ", j + 1, " coincide");
}

// The poses in a frame with the centroid of the reference points at the origin and their RMS
// distance from it as the unit of length, so that tolerances are relative and the algebra
// does not lose digits on large coordinates.
struct LocalFrame {
  Vec2 origin{0, 0};
  double scale = 1;
  std::vector<Vec2> points;  // reference points, local
  std::vector<double> angles;

  explicit LocalFrame(std::span<const BodyPose> poses) {
    for (const BodyPose& p : poses) origin += p.point;
    origin /= static_cast<double>(poses.size());
    scale = pose_scale(poses);
    for (const BodyPose& p : poses) {
      points.push_back(to_local(p.point));
      angles.push_back(p.angle);
    }
  }
  Vec2 to_local(const Vec2& x) const { return (x - origin) / scale; }
  Vec2 to_world(const Vec2& x) const { return origin + scale * x; }
};

// The body's displacement from its first position to another one: x -> D x + d (points of
// the body given where they are in the first position).
struct Displacement {
  Mat2 D = Mat2::Identity();
  Vec2 d{0, 0};
  Vec2 apply(const Vec2& x) const { return D * x + d; }
  Displacement inverse() const { return {D.transpose(), -D.transpose() * d}; }
};

std::vector<Displacement> displacements(const LocalFrame& f) {
  std::vector<Displacement> out;
  for (std::size_t i = 0; i < f.points.size(); ++i) {
    const Mat2 D = rotation(f.angles[i] - f.angles[0]);
    out.push_back({D, f.points[i] - D * f.points[0]});
  }
  return out;
}

// Seen from the body, the ground moves the other way: the same problem with the roles of
// centre and circle points exchanged.
std::vector<Displacement> inverted(const std::vector<Displacement>& disp) {
  std::vector<Displacement> out;
  for (const Displacement& t : disp) out.push_back(t.inverse());
  return out;
}

// The pole of positions i and j (the point of the plane that the body occupies at the same
// place in both), in local coordinates; none when the two have one angle.
std::optional<Vec2> pole(const LocalFrame& f, std::size_t i, std::size_t j) {
  if (same_angle(f.angles[i], f.angles[j], 1e-9)) return std::nullopt;
  const Mat2 ri = rotation(f.angles[i]), rj = rotation(f.angles[j]);
  const Vec2 body = (ri - rj).partialPivLu().solve(f.points[j] - f.points[i]);
  return Vec2(ri * body + f.points[i]);
}

// The circumcentre of three points; `what` names them in messages.
Vec2 circumcentre(const std::array<Vec2, 3>& z, const char* what, const char* centre_name) {
  double size = 1;
  for (const Vec2& p : z) size = std::max(size, p.norm());
  for (int i = 0; i < 3; ++i)
    for (int j = i + 1; j < 3; ++j)
      if ((z[i] - z[j]).norm() <= 1e-12 * size)
        fail("the ", what, " is at the same place in positions ", i + 1, " and ", j + 1,
             " (it is their pole), so no single ", centre_name, " fits it");
  const Vec2 a = z[1] - z[0], b = z[2] - z[0];
  const double twice_area = cross(a, b);
  if (std::abs(twice_area) <= 1e-12 * a.norm() * b.norm())
    fail("the three positions of the ", what, " are collinear: its ", centre_name,
         " is at infinity (a slider would guide it)");
  const double den = 2 * twice_area;
  return z[0] + Vec2((b.y() * a.squaredNorm() - a.y() * b.squaredNorm()) / den,
                     (a.x() * b.squaredNorm() - b.x() * a.squaredNorm()) / den);
}

// ---- The compatibility matrix ------------------------------------------------------------
//
// A fixed pivot c and a moving pivot q (first position) make a dyad for positions 0 and i
// when E_i = (|D_i q + d_i - c|^2 - |q - c|^2) / 2 = 0. The |q|^2 and |c|^2 terms cancel:
//   E_i = q.(I - D_i^T) c + q.D_i^T d_i + |d_i|^2 / 2 - d_i.c,
// bilinear in (c, q). For a given c it is the row [((I - D_i^T) c + D_i^T d_i)^T,
// |d_i|^2/2 - d_i.c] times [q; 1], a row affine in c.
struct CompatibilityRows {
  std::vector<Displacement> disp;  // disp[0] is the identity
  std::vector<Row3> base, dx, dy;  // row i-1 (position i): base + c_x dx + c_y dy

  explicit CompatibilityRows(std::vector<Displacement> d) : disp(std::move(d)) {
    for (std::size_t i = 1; i < disp.size(); ++i) {
      const Mat2 Dt = disp[i].D.transpose();
      const Vec2& t = disp[i].d;
      const Mat2 A = Mat2::Identity() - Dt;
      const Vec2 b = Dt * t;
      base.push_back(Row3(b.x(), b.y(), 0.5 * t.squaredNorm()));
      dx.push_back(Row3(A(0, 0), A(1, 0), -t.x()));
      dy.push_back(Row3(A(0, 1), A(1, 1), -t.y()));
    }
  }
  Row3 row(int k, const Vec2& c) const { return base[k] + c.x() * dx[k] + c.y() * dy[k]; }
  CRow3 row(int k, const CVec2& c) const {
    return base[k].cast<Complex>() + c.x() * dx[k].cast<Complex>() + c.y() * dy[k].cast<Complex>();
  }
  // dE/dc for the row of position k + 1 at moving pivot q: (I - D) q - d.
  CVec2 dc(int k, const CVec2& q) const {
    const Displacement& t = disp[static_cast<std::size_t>(k) + 1];
    return (Mat2::Identity() - t.D).cast<Complex>() * q - t.d.cast<Complex>();
  }
};

// The moving pivot that goes with fixed pivot c on the 4-position curve: the null vector of
// the (singular) 3x3 compatibility matrix, from the best-conditioned pair of rows.
std::optional<Vec2> partner(const CompatibilityRows& rows, const Vec2& c, double far) {
  std::array<Row3, 3> r{rows.row(0, c), rows.row(1, c), rows.row(2, c)};
  Eigen::Vector3d best = Eigen::Vector3d::Zero();
  for (int i = 0; i < 3; ++i)
    for (int j = i + 1; j < 3; ++j) {
      const Eigen::Vector3d v = r[i].transpose().cross(r[j].transpose());
      if (v.norm() > best.norm()) best = v;
    }
  if (!(std::abs(best.z()) * far > best.head<2>().norm())) return std::nullopt;
  return Vec2(best.head<2>() / best.z());
}

// ---- Four positions: tracing the centre-point curve det M(c) = 0 ---------------------------

class CurveTracer {
 public:
  CurveTracer(const CompatibilityRows& rows, double radius, double step) : rows_(rows), radius_(radius), step_(step) {}

  // Polylines through every seed (seeds on a part already traced are skipped).
  std::vector<std::vector<Vec2>> trace(const std::vector<Vec2>& seeds) const {
    std::vector<std::vector<Vec2>> lines;
    for (const Vec2& seed : seeds) {
      const std::optional<Vec2> start = correct(seed);
      if (!start || start->norm() > radius_ || covered(lines, *start)) continue;
      const Vec2 t = tangent(*start, Vec2::Zero());
      if (!t.allFinite()) continue;
      bool closed = false;
      std::vector<Vec2> forward = follow(*start, t, closed);
      if (!closed) {
        std::vector<Vec2> backward = follow(*start, -t, closed);
        std::reverse(backward.begin(), backward.end());
        backward.insert(backward.end(), forward.begin() + 1, forward.end());
        forward = std::move(backward);
      }
      if (forward.size() >= 2) lines.push_back(std::move(forward));
    }
    return lines;
  }

  // Seeds on every part of the curve crossing a grid of lines over the window, plus `extra`.
  std::vector<Vec2> seeds(const std::vector<Vec2>& extra) const {
    std::vector<Vec2> out;
    for (const Vec2& e : extra)
      if (e.norm() < radius_) out.push_back(e);
    const int lines = 48, samples = 400;
    for (int axis = 0; axis < 2; ++axis)
      for (int l = 0; l < lines; ++l) {
        const double across = -radius_ + (l + 0.5) * 2 * radius_ / lines;
        auto point = [&](double along) { return axis == 0 ? Vec2(along, across) : Vec2(across, along); };
        double previous_s = -radius_, previous_f = value(point(previous_s));
        for (int k = 1; k <= samples; ++k) {
          const double s = -radius_ + k * 2 * radius_ / samples;
          const double f = value(point(s));
          if ((f < 0) != (previous_f < 0)) out.push_back(point(bisect(point, previous_s, s, previous_f)));
          previous_s = s;
          previous_f = f;
        }
      }
    return out;
  }

 private:
  const CompatibilityRows& rows_;
  double radius_, step_;

  Mat3 matrix(const Vec2& c) const {
    Mat3 m;
    for (int k = 0; k < 3; ++k) m.row(k) = rows_.row(k, c);
    return m;
  }
  double value(const Vec2& c) const { return matrix(c).determinant(); }
  // Jacobi's formula, row by row: d det / dc_x = sum_k det(M with row k replaced by dx_k).
  Vec2 gradient(const Vec2& c) const {
    const Mat3 m = matrix(c);
    Vec2 g(0, 0);
    for (int k = 0; k < 3; ++k) {
      Mat3 mx = m, my = m;
      mx.row(k) = rows_.dx[k];
      my.row(k) = rows_.dy[k];
      g += Vec2(mx.determinant(), my.determinant());
    }
    return g;
  }
  Vec2 tangent(const Vec2& c, const Vec2& previous) const {
    const Vec2 g = gradient(c);
    Vec2 t = Vec2(-g.y(), g.x()) / g.norm();
    return t.dot(previous) < 0 ? Vec2(-t) : t;
  }

  template <class Point>
  double bisect(const Point& point, double a, double b, double fa) const {
    for (int i = 0; i < 60; ++i) {
      const double m = 0.5 * (a + b);
      const double fm = value(point(m));
      if ((fm < 0) == (fa < 0)) {
        a = m;
        fa = fm;
      } else {
        b = m;
      }
    }
    return 0.5 * (a + b);
  }

  // Newton along the gradient back onto the curve.
  std::optional<Vec2> correct(Vec2 c) const {
    for (int i = 0; i < 12; ++i) {
      const Vec2 g = gradient(c);
      const double gg = g.squaredNorm();
      if (!(gg > 0)) return std::nullopt;
      const Vec2 delta = value(c) * g / gg;
      c -= delta;
      if (delta.norm() <= 1e-14 * (1 + c.norm())) return c;
    }
    return std::nullopt;
  }

  bool covered(const std::vector<std::vector<Vec2>>& lines, const Vec2& c) const {
    for (const auto& line : lines)
      for (const Vec2& p : line)
        if ((p - c).norm() < 1.5 * step_) return true;
    return false;
  }

  // Predictor along the tangent, corrector onto the curve; the step halves where the curve
  // turns sharply or the corrector strays, so samples stay on the part being followed.
  std::vector<Vec2> follow(const Vec2& start, Vec2 t, bool& closed) const {
    std::vector<Vec2> points{start};
    const Vec2 t0 = t;
    Vec2 c = start;
    double h = step_, travelled = 0;
    const int max_points = static_cast<int>(40 * radius_ / step_) + 1000;
    while (static_cast<int>(points.size()) < max_points && h > 1e-4 * step_) {
      const Vec2 guess = c + h * t;
      const std::optional<Vec2> next = correct(guess);
      if (!next || (*next - guess).norm() > 0.5 * h) {
        h *= 0.5;
        continue;
      }
      const Vec2 tn = tangent(*next, t);
      if (!tn.allFinite() || tn.dot(t) < std::cos(0.2)) {
        h *= 0.5;
        continue;
      }
      travelled += (*next - c).norm();
      c = *next;
      t = tn;
      if (c.norm() > radius_) break;
      if (travelled > 4 * step_ && (c - start).norm() < step_ && t.dot(t0) > 0) {
        points.push_back(start);
        closed = true;
        break;
      }
      points.push_back(c);
      h = std::min(step_, 2 * h);
    }
    return points;
  }
};

// Rejects motions for which the curves do not exist: no rotation at all, or every position
// a rotation about one common point.
void check_motion(const std::vector<Displacement>& disp) {
  bool turns = false;
  for (const Displacement& t : disp) turns = turns || !t.D.isIdentity(1e-12);
  if (!turns) fail("the body does not turn between the positions (a pure translation): no finite centre points");
  Eigen::MatrixXd a(2 * (disp.size() - 1), 2);
  Eigen::VectorXd b(a.rows());
  for (std::size_t i = 1; i < disp.size(); ++i) {
    a.block<2, 2>(2 * (i - 1), 0) = Mat2::Identity() - disp[i].D;
    b.segment<2>(2 * (i - 1)) = disp[i].d;
  }
  const Vec2 fixed = a.colPivHouseholderQr().solve(b);
  if ((a * fixed - b).norm() <= 1e-10 * (1 + b.norm()))
    fail("the body only turns about one point: every dyad pivoted there works, and no curve exists");
}

// Samples of one traced polyline as pairs; polylines break where the partner is too far.
void add_pairs(const CompatibilityRows& rows, const LocalFrame& frame, bool swap, const std::vector<Vec2>& line,
               std::vector<std::vector<BurmesterPair>>& out) {
  constexpr double far = 1e6;
  std::vector<BurmesterPair> current;
  auto flush = [&] {
    if (current.size() >= 2) out.push_back(current);
    current.clear();
  };
  for (const Vec2& c : line) {
    const std::optional<Vec2> q = partner(rows, c, far);
    if (!q) {
      flush();
      continue;
    }
    BurmesterPair p{frame.to_world(c), frame.to_world(*q)};
    if (swap) std::swap(p.centre, p.circle);
    current.push_back(p);
  }
  flush();
}

double default_radius(const LocalFrame& f) {
  double r = 0;
  for (const Vec2& p : f.points) r = std::max(r, p.norm());
  const double spread = r;
  for (std::size_t i = 0; i < f.points.size(); ++i)
    for (std::size_t j = i + 1; j < f.points.size(); ++j)
      if (const auto p = pole(f, i, j); p && p->norm() < 20 * std::max(spread, 1.0)) r = std::max(r, p->norm());
  return 1.5 * std::max(r, 1.0);
}

// ---- Five positions ------------------------------------------------------------------------

// Polynomials of total degree <= 3 in two variables: c[i][j] multiplies x^i y^j.
struct Cubic2 {
  std::array<std::array<double, 4>, 4> c{};

  static Cubic2 affine(double a0, double ax, double ay) {
    Cubic2 p;
    p.c[0][0] = a0;
    p.c[1][0] = ax;
    p.c[0][1] = ay;
    return p;
  }
  friend Cubic2 operator*(const Cubic2& a, const Cubic2& b) {
    Cubic2 p;
    for (int i = 0; i < 4; ++i)
      for (int j = 0; i + j < 4; ++j)
        for (int k = 0; k < 4; ++k)
          for (int l = 0; k + l < 4; ++l) {
            if (a.c[i][j] == 0 || b.c[k][l] == 0) continue;
            if (i + j + k + l > 3) throw Error(ErrorKind::Internal, "Cubic2: degree above 3");
            p.c[i + k][j + l] += a.c[i][j] * b.c[k][l];
          }
    return p;
  }
  friend Cubic2 operator+(Cubic2 a, const Cubic2& b) {
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) a.c[i][j] += b.c[i][j];
    return a;
  }
  friend Cubic2 operator-(Cubic2 a, const Cubic2& b) {
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) a.c[i][j] -= b.c[i][j];
    return a;
  }
};

// Binary forms f(u) = sum_j f[j] u_x^(n-j) u_y^j of degree n = f.size() - 1.
using BinaryForm = std::vector<Complex>;

BinaryForm homogeneous_part(const Cubic2& p, int k) {
  BinaryForm f(static_cast<std::size_t>(k) + 1);
  for (int j = 0; j <= k; ++j) f[static_cast<std::size_t>(j)] = p.c[k - j][j];
  return f;
}

BinaryForm operator*(const BinaryForm& a, const BinaryForm& b) {
  BinaryForm p(a.size() + b.size() - 1, 0.0);
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = 0; j < b.size(); ++j) p[i + j] += a[i] * b[j];
  return p;
}

BinaryForm operator-(BinaryForm a, const BinaryForm& b) {
  for (std::size_t i = 0; i < a.size(); ++i) a[i] -= b[i];
  return a;
}

// f / (alpha u_x + beta u_y), exact when the linear form divides f. Eliminated from the end
// where the divisor's coefficient is larger, which keeps the recursion stable.
BinaryForm divide(const BinaryForm& f, Complex alpha, Complex beta) {
  const std::size_t n = f.size() - 1;
  BinaryForm g(n);
  if (std::abs(alpha) >= std::abs(beta)) {
    g[0] = f[0] / alpha;
    for (std::size_t j = 1; j < n; ++j) g[j] = (f[j] - beta * g[j - 1]) / alpha;
  } else {
    g[n - 1] = f[n] / beta;
    for (std::size_t j = n - 1; j >= 1; --j) g[j - 1] = (f[j] - alpha * g[j]) / beta;
  }
  return g;
}

Complex evaluate(const BinaryForm& f, const CVec2& u) {
  const std::size_t n = f.size() - 1;
  Complex sum = 0;
  for (std::size_t j = 0; j <= n; ++j)
    sum += f[j] * std::pow(u.x(), static_cast<int>(n - j)) * std::pow(u.y(), static_cast<int>(j));
  return sum;
}

// The roots of a binary form as directions u (complex in general). Dehomogenized at the end
// whose coefficient is larger; exact zeros at the other end are roots on an axis.
std::vector<CVec2> roots(BinaryForm f) {
  double big = 0;
  for (const Complex& a : f) big = std::max(big, std::abs(a));
  const bool in_y = std::abs(f.back()) >= std::abs(f.front());  // t = u_y / u_x
  if (!in_y) std::reverse(f.begin(), f.end());                  // t = u_x / u_y
  auto direction = [&](Complex t) { return in_y ? CVec2(1.0, t) : CVec2(t, 1.0); };
  std::vector<CVec2> out;
  std::size_t low = 0;
  while (low + 1 < f.size() && std::abs(f[low]) <= 1e-14 * big) {
    out.push_back(direction(0.0));
    ++low;
  }
  const int n = static_cast<int>(f.size() - 1 - low);
  if (n <= 0) return out;
  Eigen::MatrixXcd companion = Eigen::MatrixXcd::Zero(n, n);
  for (int j = 0; j < n; ++j) companion(0, j) = -f[f.size() - 2 - static_cast<std::size_t>(j)] / f.back();
  for (int j = 1; j < n; ++j) companion(j, j - 1) = 1.0;
  const Eigen::VectorXcd eigenvalues = linear_algebra::eigenvalues(companion);
  for (int j = 0; j < n; ++j) out.push_back(direction(eigenvalues[j]));
  return out;
}

Cubic2 det3(const std::array<std::array<Cubic2, 3>, 3>& m) {
  return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
         m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

// det of the compatibility rows {k0, k1, k2} at c = origin + v, as a cubic in v.
Cubic2 curve_about(const CompatibilityRows& rows, const std::array<int, 3>& k, const Vec2& origin) {
  std::array<std::array<Cubic2, 3>, 3> m;
  for (int r = 0; r < 3; ++r) {
    const Row3 at = rows.row(k[r], origin);
    for (int col = 0; col < 3; ++col) m[r][col] = Cubic2::affine(at[col], rows.dx[k[r]][col], rows.dy[k[r]][col]);
  }
  return det3(m);
}

struct Solution {
  CVec2 c, q;
};

// Newton's method on E_1..E_4 = 0 in (c, q), complex.
std::optional<Solution> refine(const CompatibilityRows& rows, Solution s) {
  auto residual = [&](const Solution& x) {
    CVec4 e;
    for (int k = 0; k < 4; ++k) {
      const CRow3 r = rows.row(k, x.c);
      e[k] = (r.head<2>() * x.q).value() + r(2);
    }
    return e;
  };
  for (int it = 0; it < 40; ++it) {
    Eigen::Matrix4cd j;
    for (int k = 0; k < 4; ++k) {
      j.block<1, 2>(k, 0) = rows.dc(k, s.q).transpose();
      j.block<1, 2>(k, 2) = rows.row(k, s.c).head<2>();
    }
    const CVec4 delta = linear_algebra::solve_full_pivoting(j, -residual(s));
    if (!delta.allFinite()) return std::nullopt;
    s.c += delta.head<2>();
    s.q += delta.tail<2>();
    const double size = 1 + std::max(s.c.norm(), s.q.norm());
    if (delta.norm() <= 1e-15 * size) break;
  }
  const double size = 1 + std::max(s.c.norm(), s.q.norm());
  if (!(residual(s).cwiseAbs().maxCoeff() <= 1e-11 * size * size)) return std::nullopt;
  return s;
}

double distance(const Solution& a, const Solution& b) {
  return std::sqrt((a.c - b.c).squaredNorm() + (a.q - b.q).squaredNorm());
}

void add_distinct(std::vector<Solution>& found, const Solution& s) {
  const double size = 1 + std::max(s.c.norm(), s.q.norm());
  for (const Solution& f : found)
    if (distance(f, s) <= 1e-7 * size) return;
  found.push_back(s);
}

// The closed route: the centre-point curves of positions {0,1,2,3} and {0,1,2,4} meet in 9
// points: the poles P01, P02, P12, the two circular points at infinity and the 4 Burmester
// centre points. On lines through P01 each curve is s (a s^2 + b s + c) with a, b, c forms of
// degree 3, 2, 1 in the direction u; the two quadratics share a root where their resultant,
// a form of degree 8 in u, vanishes. Dividing out the directions of P02, P12 and the
// circular points leaves a quartic whose 4 roots are the directions of the Burmester points.
std::vector<Solution> closed_form_candidates(const CompatibilityRows& rows, const Vec2& p01, const Vec2& p02,
                                             const Vec2& p12) {
  const Cubic2 f1 = curve_about(rows, {0, 1, 2}, p01), f2 = curve_about(rows, {0, 1, 3}, p01);
  const BinaryForm a1 = homogeneous_part(f1, 3), b1 = homogeneous_part(f1, 2), c1 = homogeneous_part(f1, 1);
  const BinaryForm a2 = homogeneous_part(f2, 3), b2 = homogeneous_part(f2, 2), c2 = homogeneous_part(f2, 1);
  const BinaryForm ac = a1 * c2 - a2 * c1, ab = a1 * b2 - a2 * b1, bc = b1 * c2 - b2 * c1;
  BinaryForm resultant = ac * ac - ab * bc;
  const Complex i(0, 1);
  resultant = divide(resultant, 1.0, i);   // u_x + i u_y
  resultant = divide(resultant, 1.0, -i);  // u_x - i u_y
  for (const Vec2& w : {Vec2(p02 - p01), Vec2(p12 - p01)}) resultant = divide(resultant, -w.y(), w.x());

  std::vector<Solution> out;
  for (const CVec2& u : roots(resultant)) {
    const Complex A1 = evaluate(a1, u), B1 = evaluate(b1, u), C1 = evaluate(c1, u);
    const Complex A2 = evaluate(a2, u), B2 = evaluate(b2, u), C2 = evaluate(c2, u);
    // The common root of A s^2 + B s + C from either elimination, the better conditioned.
    const Complex den1 = A1 * B2 - A2 * B1, den2 = A1 * C2 - A2 * C1;
    const Complex s = std::abs(den1) >= std::abs(den2) ? -(A1 * C2 - A2 * C1) / den1 : -(B1 * C2 - B2 * C1) / den2;
    const CVec2 c = p01.cast<Complex>() + s * u;
    if (!c.allFinite()) continue;
    Eigen::Matrix<Complex, 4, 3> m;
    for (int k = 0; k < 4; ++k) m.row(k) = rows.row(k, c);
    const Eigen::Vector3cd v = linear_algebra::smallest_right_singular_vector(m);
    if (std::abs(v.z()) <= 1e-12 * v.norm()) continue;  // moving pivot at infinity
    if (auto refined = refine(rows, {c, v.head<2>() / v.z()})) out.push_back(*refined);
  }
  return out;
}

// The same solutions from the homotopy solver (6 paths of the bilinear system); used when
// the closed route loses a root (two Burmester points in one direction from P01, say).
std::vector<Solution> homotopy_candidates(const CompatibilityRows& rows) {
  std::vector<Polynomial> equations;
  const Polynomial cx = Polynomial::variable(4, 0), cy = Polynomial::variable(4, 1);
  const Polynomial qx = Polynomial::variable(4, 2), qy = Polynomial::variable(4, 3);
  for (int k = 0; k < 4; ++k) {
    auto entry = [&](int col) {
      return Polynomial::constant(4, rows.base[k][col]) + cx * rows.dx[k][col] + cy * rows.dy[k][col];
    };
    equations.push_back(entry(0) * qx + entry(1) * qy + entry(2));
  }
  SolverOptions options;
  options.threads = 1;
  const SolveResult result = solve_linear_product(PolynomialSystem(equations), {{0, 1}, {2, 3}}, options);
  std::vector<Solution> out;
  for (const Endpoint& e : result.endpoints)
    if (e.kind == EndpointKind::Finite)
      if (auto refined = refine(rows, {CVec2(e.x[0], e.x[1]), CVec2(e.x[2], e.x[3])})) out.push_back(*refined);
  return out;
}

// The three positions with the most different angles (for the poles P01, P02, P12) first.
std::array<std::size_t, 5> five_position_order(const std::array<BodyPose, 5>& poses) {
  std::array<std::size_t, 5> best{0, 1, 2, 3, 4};
  double best_score = -1;
  for (std::size_t a = 0; a < 5; ++a)
    for (std::size_t b = a + 1; b < 5; ++b)
      for (std::size_t c = b + 1; c < 5; ++c) {
        auto gap = [&](std::size_t i, std::size_t j) {
          return std::abs(std::sin(0.5 * (poses[i].angle - poses[j].angle)));
        };
        const double score = std::min({gap(a, b), gap(a, c), gap(b, c)});
        if (score > best_score) {
          best_score = score;
          best = {a, b, c, 0, 0};
          std::size_t k = 3;
          for (std::size_t r = 0; r < 5; ++r)
            if (r != a && r != b && r != c) best[k++] = r;
        }
      }
  if (best_score < 1e-6) fail("five positions need three whose angles all differ");
  return best;
}

}  // namespace

// ---- Public API ----------------------------------------------------------------------------

Eigen::Vector2d centre_point(const std::array<BodyPose, 3>& poses, const Eigen::Vector2d& circle) {
  check_poses(poses);
  if (!circle.allFinite()) fail("the circle point is not finite");
  const LocalFrame frame(poses);
  const std::vector<Displacement> disp = displacements(frame);
  const Vec2 q = frame.to_local(circle);
  return frame.to_world(circumcentre({q, disp[1].apply(q), disp[2].apply(q)}, "circle point", "centre point"));
}

Eigen::Vector2d circle_point(const std::array<BodyPose, 3>& poses, const Eigen::Vector2d& centre) {
  check_poses(poses);
  if (!centre.allFinite()) fail("the centre point is not finite");
  const LocalFrame frame(poses);
  // |T_i q - c| = |q - T_i^-1 c|: the circle point is the circumcentre of the fixed pivot's
  // positions seen from the body (the inverted motion).
  const std::vector<Displacement> inv = inverted(displacements(frame));
  const Vec2 c = frame.to_local(centre);
  return frame.to_world(
      circumcentre({c, inv[1].apply(c), inv[2].apply(c)}, "centre point (seen from the body)", "circle point"));
}

FourBarDesign three_position_design(const std::array<BodyPose, 3>& poses, PivotChoice given,
                                    const Eigen::Vector2d& input_pivot, const Eigen::Vector2d& output_pivot) {
  check_poses(poses);
  const bool moving = given == PivotChoice::Moving;
  const char* kind = moving ? "moving" : "fixed";
  double size = 0;
  for (const BodyPose& p : poses) size = std::max(size, p.point.norm());
  size = std::max({size, input_pivot.norm(), output_pivot.norm()});
  if ((input_pivot - output_pivot).norm() <= 1e-12 * size) fail("the two given ", kind, " pivots coincide");
  BurmesterPair in, out;
  if (moving) {
    in = {centre_point(poses, input_pivot), input_pivot};
    out = {centre_point(poses, output_pivot), output_pivot};
  } else {
    in = {input_pivot, circle_point(poses, input_pivot)};
    out = {output_pivot, circle_point(poses, output_pivot)};
  }
  const char* other = moving ? "fixed" : "moving";
  if ((moving ? (in.centre - out.centre) : (in.circle - out.circle)).norm() <= 1e-12 * size)
    fail("the two dyads have the same ", other, " pivot: no four-bar");
  if ((in.centre - in.circle).norm() <= 1e-12 * size) fail("the input link has zero length");
  if ((out.centre - out.circle).norm() <= 1e-12 * size) fail("the output link has zero length");
  return design_from_pairs(in, out, poses[0].point);
}

BurmesterCurves four_position_curves(const std::array<BodyPose, 4>& poses, const CurveOptions& options) {
  check_poses(poses);
  if (!std::isfinite(options.radius) || options.radius < 0) fail("the window radius must be finite and not negative");
  if (!std::isfinite(options.step) || options.step < 0) fail("the sampling step must be finite and not negative");
  const LocalFrame frame(poses);
  const std::vector<Displacement> disp = displacements(frame);
  check_motion(disp);

  if (options.radius > kMaxWindowRadius * frame.scale)
    fail("the window radius ", options.radius, " is more than 10^6 times the size of the poses (", frame.scale,
         ", the RMS distance of the reference points from their centroid): the curves cannot be traced in it");
  const double radius = options.radius > 0 ? options.radius / frame.scale : default_radius(frame);
  const double step = options.step > 0 ? options.step / frame.scale : radius / 300;
  if (step > radius / 4) fail("the sampling step must be below a quarter of the window radius");
  if (radius / step > 1e5) fail("the sampling step is too small for the window (more than 10^5 steps per radius)");

  std::vector<Vec2> poles;
  for (std::size_t i = 0; i < 4; ++i)
    for (std::size_t j = i + 1; j < 4; ++j)
      if (const auto p = pole(frame, i, j)) poles.push_back(*p);

  BurmesterCurves out;
  out.window_centre = frame.origin;
  out.window_radius = radius * frame.scale;
  const CompatibilityRows rows(disp);
  const CurveTracer centres(rows, radius, step);
  for (const auto& line : centres.trace(centres.seeds(poles))) add_pairs(rows, frame, false, line, out.centre_curve);
  // The circle-point curve is the centre-point curve of the inverted motion; the poles of
  // the inverted motion are the poles moved back to the first position.
  const CompatibilityRows inverse_rows(inverted(disp));
  std::vector<Vec2> inverse_poles;
  for (std::size_t i = 0; i < 4; ++i)
    for (std::size_t j = i + 1; j < 4; ++j)
      if (const auto p = pole(frame, i, j)) {
        const Mat2 back = rotation(frame.angles[0] - frame.angles[i]);
        inverse_poles.push_back(back * (*p - frame.points[i]) + frame.points[0]);
      }
  const CurveTracer circles(inverse_rows, radius, step);
  for (const auto& line : circles.trace(circles.seeds(inverse_poles)))
    add_pairs(inverse_rows, frame, true, line, out.circle_curve);
  return out;
}

FivePositionResult five_position_burmester(const std::array<BodyPose, 5>& poses) {
  check_poses(poses);
  const std::array<std::size_t, 5> order = five_position_order(poses);
  std::array<BodyPose, 5> sorted;
  for (std::size_t k = 0; k < 5; ++k) sorted[k] = poses[order[k]];
  const LocalFrame frame(sorted);
  const std::vector<Displacement> disp = displacements(frame);
  check_motion(disp);
  const CompatibilityRows rows(disp);

  std::vector<Solution> found;
  for (const Solution& s : closed_form_candidates(rows, *pole(frame, 0, 1), *pole(frame, 0, 2), *pole(frame, 1, 2)))
    add_distinct(found, s);
  if (found.size() < 4) {
    std::vector<Solution> more;
    for (const Solution& s : homotopy_candidates(rows)) add_distinct(more, s);
    if (more.size() > found.size()) found = std::move(more);
  }

  FivePositionResult result;
  // Moving pivots come out in the first of the sorted positions; the caller's first
  // position is the body's displacement from there.
  const Mat2 back = rotation(poses[0].angle - sorted[0].angle);
  for (const Solution& s : found) {
    const double size = 1 + std::max(s.c.norm(), s.q.norm());
    const bool real = std::max(s.c.imag().cwiseAbs().maxCoeff(), s.q.imag().cwiseAbs().maxCoeff()) <= 1e-8 * size;
    if (!real) {
      ++result.complex_points;
      continue;
    }
    const Vec2 c = s.c.real(), q = s.q.real();
    // A body point that never moves (on the fixed pivot) is no dyad.
    if ((c - q).norm() <= 1e-9 * size) continue;
    const Vec2 circle = back * (frame.to_world(q) - sorted[0].point) + poses[0].point;
    result.points.push_back({frame.to_world(c), circle});
  }
  for (int a = 0; a < static_cast<int>(result.points.size()); ++a)
    for (int b = a + 1; b < static_cast<int>(result.points.size()); ++b) {
      BurmesterDesign d;
      d.design = design_from_pairs(result.points[a], result.points[b], poses[0].point);
      d.input = a;
      d.output = b;
      const std::vector<int> signs = branch_signs(d.design, poses);
      d.one_branch = std::all_of(signs.begin(), signs.end(), [&](int s) { return s != 0 && s == signs[0]; });
      result.designs.push_back(d);
    }
  return result;
}

PolynomialSystem five_position_system(const std::array<BodyPose, 5>& poses) {
  check_poses(poses);
  std::vector<Polynomial> equations;
  const Polynomial cx = Polynomial::variable(4, 0), cy = Polynomial::variable(4, 1);
  const Polynomial qx = Polynomial::variable(4, 2), qy = Polynomial::variable(4, 3);
  const Mat2 r0 = rotation(poses[0].angle);
  for (std::size_t i = 1; i < 5; ++i) {
    const Mat2 D = rotation(poses[i].angle) * r0.transpose();
    const Vec2 d = poses[i].point - D * poses[0].point;
    // Written out bilinear, q.(I - D^T) c + q.D^T d + |d|^2/2 - d.c, so that no rounding
    // leaves the cancelled |q|^2 terms behind.
    const Mat2 A = Mat2::Identity() - D.transpose();
    const Vec2 b = D.transpose() * d;
    const Polynomial ax = cx * A(0, 0) + cy * A(0, 1), ay = cx * A(1, 0) + cy * A(1, 1);
    equations.push_back(qx * ax + qy * ay + qx * b.x() + qy * b.y() - cx * d.x() - cy * d.y() +
                        Complex(0.5 * d.squaredNorm()));
  }
  return PolynomialSystem(equations);
}

FourBarDesign design_from_pairs(const BurmesterPair& input, const BurmesterPair& output,
                                const Eigen::Vector2d& coupler_point) {
  FourBarDesign d;
  d.ground_a = input.centre;
  d.ground_b = output.centre;
  d.moving_a = input.circle;
  d.moving_b = output.circle;
  d.coupler_point = coupler_point;
  return d;
}

std::vector<int> branch_signs(const FourBarDesign& design, std::span<const BodyPose> poses) {
  std::vector<int> signs;
  if (poses.empty()) return signs;
  const Mat2 r0 = rotation(poses[0].angle);
  for (const BodyPose& p : poses) {
    const Mat2 D = rotation(p.angle) * r0.transpose();
    const Vec2 a = D * (design.moving_a - poses[0].point) + p.point;
    const Vec2 b = D * (design.moving_b - poses[0].point) + p.point;
    const double side = cross(design.ground_b - a, b - a);
    signs.push_back(side > 0 ? 1 : side < 0 ? -1 : 0);
  }
  return signs;
}

}  // namespace nbar::synthesis
