#include "nbar/kinematics/constraints.hpp"

#include "nbar/kinematics/mechanism.hpp"

namespace nbar {

namespace {

// A 2-vector over doubles (positions) or Series (Taylor coefficients); one template serves both.
template <class V>
struct Vec {
  V x, y;
};
template <class V>
Vec<V> operator-(const Vec<V>& a, const Vec<V>& b) {
  return {a.x - b.x, a.y - b.y};
}
template <class V>
V cross(const Vec<V>& a, const Vec<V>& b) {
  return a.x * b.y - a.y * b.x;
}
template <class V>
V dot(const Vec<V>& a, const Vec<V>& b) {
  return a.x * b.x + a.y * b.y;
}

// Rotates w by the angle whose cosine and sine are c, s.
template <class V, class C>
Vec<V> rotate(const Vec<V>& w, const C& c, const C& s) {
  return {c * w.x - s * w.y, s * w.x + c * w.y};
}

// The residual of one row. `point(i)` gives a point's position, `drv` the driver's state.
template <class V, class PointFn, class DriverFn>
V residual(const Constraint& c, PointFn&& point, DriverFn&& drv) {
  switch (c.type) {
    case ConstraintType::Distance: {
      const Vec<V> u = point(c.p[1]) - point(c.p[0]);
      return (dot(u, u) - c.a * c.a) * c.scale;
    }
    case ConstraintType::RigidX:
    case ConstraintType::RigidY: {
      const Vec<V> ri = point(c.p[0]);
      const Vec<V> u = point(c.p[1]) - ri;
      const Vec<V> rk = point(c.p[2]);
      if (c.type == ConstraintType::RigidX) return rk.x - ri.x - c.a * u.x + c.b * u.y;
      return rk.y - ri.y - c.a * u.y - c.b * u.x;
    }
    case ConstraintType::PointOnLine: {
      const Vec<V> ri = point(c.p[0]);
      return cross(point(c.p[2]) - ri, point(c.p[1]) - ri) * c.scale;
    }
    case ConstraintType::Orientation: {
      const Vec<V> v = point(c.p[1]) - point(c.p[0]);
      const Vec<V> w = point(c.p[3]) - point(c.p[2]);
      return cross(v, rotate(w, c.a, c.b)) * c.scale;
    }
    case ConstraintType::DriveAngle: {
      const auto& d = drv(c.driver);
      const Vec<V> u = point(c.p[1]) - point(c.p[0]);
      return (u.x * d.sin - u.y * d.cos) * c.scale;
    }
    case ConstraintType::DriveRelativeAngle: {
      const auto& d = drv(c.driver);
      const Vec<V> u = point(c.p[1]) - point(c.p[0]);
      const Vec<V> w = point(c.p[3]) - point(c.p[2]);
      return cross(u, rotate(w, d.cos, d.sin)) * c.scale;
    }
    case ConstraintType::DriveDistance: {
      const auto& d = drv(c.driver);
      const Vec<V> u = point(c.p[1]) - point(c.p[0]);
      return (dot(u, u) - d.value * d.value) * c.scale;
    }
    case ConstraintType::DriveSlide: {
      const auto& d = drv(c.driver);
      const Vec<V> ri = point(c.p[0]);
      return dot(point(c.p[2]) - ri, point(c.p[1]) - ri) * (1.0 / c.a) - d.value;
    }
  }
  return V{};
}

struct DriverDoubles {
  double value, cos, sin;
};

// Gradient of one row with respect to its (up to four) points.
std::array<Eigen::Vector2d, 4> gradient(const Constraint& c, const Mechanism& mech, const Eigen::VectorXd& q,
                                        const DriverDoubles& d) {
  std::array<Eigen::Vector2d, 4> g{Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero(),
                                   Eigen::Vector2d::Zero()};
  auto r = [&](int slot) { return mech.point_position(c.p[slot], q); };
  auto perp_grad = [](const Eigen::Vector2d& other) {  // d(a x b)/da = (b.y, -b.x)
    return Eigen::Vector2d(other.y(), -other.x());
  };
  switch (c.type) {
    case ConstraintType::Distance:
    case ConstraintType::DriveDistance: {
      const Eigen::Vector2d u = r(1) - r(0);
      g[1] = 2.0 * c.scale * u;
      g[0] = -g[1];
      break;
    }
    case ConstraintType::RigidX:
      g[2] = {1.0, 0.0};
      g[1] = {-c.a, c.b};
      g[0] = {c.a - 1.0, -c.b};
      break;
    case ConstraintType::RigidY:
      g[2] = {0.0, 1.0};
      g[1] = {-c.b, -c.a};
      g[0] = {c.b, c.a - 1.0};
      break;
    case ConstraintType::PointOnLine: {
      const Eigen::Vector2d e = r(2) - r(0), w = r(1) - r(0);
      g[2] = c.scale * perp_grad(w);   // d/de of e x w
      g[1] = -c.scale * perp_grad(e);  // d/dw of e x w = -(e.y, -e.x)
      g[0] = -g[2] - g[1];
      break;
    }
    case ConstraintType::Orientation:
    case ConstraintType::DriveRelativeAngle: {
      const double cs = c.type == ConstraintType::Orientation ? c.a : d.cos;
      const double sn = c.type == ConstraintType::Orientation ? c.b : d.sin;
      const Eigen::Vector2d v = r(1) - r(0), w = r(3) - r(2);
      const Eigen::Vector2d z(cs * w.x() - sn * w.y(), sn * w.x() + cs * w.y());
      const Eigen::Vector2d dv = c.scale * perp_grad(z);
      const Eigen::Vector2d dz = -c.scale * perp_grad(v);
      const Eigen::Vector2d dw(cs * dz.x() + sn * dz.y(), -sn * dz.x() + cs * dz.y());  // R^T dz
      g[1] = dv;
      g[0] = -dv;
      g[3] = dw;
      g[2] = -dw;
      break;
    }
    case ConstraintType::DriveAngle:
      g[1] = c.scale * Eigen::Vector2d(d.sin, -d.cos);
      g[0] = -g[1];
      break;
    case ConstraintType::DriveSlide: {
      const Eigen::Vector2d e = r(2) - r(0), w = r(1) - r(0);
      g[2] = w / c.a;
      g[1] = e / c.a;
      g[0] = -g[2] - g[1];
      break;
    }
  }
  return g;
}

}  // namespace

DriverState make_driver_state(const Series& value, bool angular) {
  DriverState s;
  s.value = value;
  if (angular) {
    sincos(value, s.sin, s.cos);
  } else {
    s.sin = Series(value.terms());
    s.cos = Series(value.terms());
  }
  return s;
}

void evaluate_residuals(const Mechanism& mech, const Eigen::VectorXd& q, const std::vector<DriverState>& drivers,
                        Eigen::VectorXd& phi) {
  phi.resize(mech.row_count());
  auto point = [&](int i) {
    const Eigen::Vector2d r = mech.point_position(i, q);
    return Vec<double>{r.x(), r.y()};
  };
  auto drv = [&](int i) {
    return DriverDoubles{drivers[i].value.value(), drivers[i].cos.value(), drivers[i].sin.value()};
  };
  const auto& rows = mech.rows();
  for (int i = 0; i < mech.row_count(); ++i) phi[i] = residual<double>(rows[i], point, drv);
}

void evaluate_jacobian(const Mechanism& mech, const Eigen::VectorXd& q, const std::vector<DriverState>& drivers,
                       std::vector<double>& values) {
  values.assign(mech.jacobian_pattern().size(), 0.0);
  const auto& rows = mech.rows();
  for (int i = 0; i < mech.row_count(); ++i) {
    const Constraint& c = rows[i];
    DriverDoubles d{0.0, 1.0, 0.0};
    if (c.is_driver()) {
      const DriverState& s = drivers[c.driver];
      d = {s.value.value(), s.cos.value(), s.sin.value()};
    }
    const auto g = gradient(c, mech, q, d);
    for (int slot = 0; slot < 4; ++slot) {
      const int e = mech.entry_index(i, slot);
      if (e < 0) continue;
      values[e] += g[slot].x();
      values[e + 1] += g[slot].y();
    }
  }
}

void evaluate_series_remainder(const Mechanism& mech, const Eigen::MatrixXd& coefficients, int k,
                               const std::vector<DriverState>& drivers, Eigen::VectorXd& rhs) {
  // Only coefficient k of each row is needed, and every row is at most bilinear in q, so it is
  // a short convolution of lower coefficients (q's coefficient k counts as zero). Written out
  // per row rather than through Series arithmetic: this runs every step, for every order.
  rhs.resize(mech.row_count());
  const auto& points = mech.model().points;
  auto coefficient = [&](int point, int j) -> Eigen::Vector2d {
    const int col = mech.column_of(point);
    if (col < 0) return j == 0 ? points[point].position : Eigen::Vector2d::Zero();
    if (j >= k) return Eigen::Vector2d::Zero();
    return {coefficients(col, j), coefficients(col + 1, j)};
  };
  auto diff = [&](int from, int to, int j) -> Eigen::Vector2d { return coefficient(to, j) - coefficient(from, j); };
  auto term = [](const Series& s, int j) { return j < s.terms() ? s[j] : 0.0; };
  auto cross2 = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); };
  const auto& rows = mech.rows();
  for (int r = 0; r < mech.row_count(); ++r) {
    const Constraint& c = rows[r];
    const auto& p = c.p;
    double v = 0.0;
    switch (c.type) {
      case ConstraintType::Distance:
      case ConstraintType::DriveDistance:
        for (int j = 1; j < k; ++j) v += diff(p[0], p[1], j).dot(diff(p[0], p[1], k - j));
        if (c.type == ConstraintType::DriveDistance) {
          const Series& s = drivers[c.driver].value;
          for (int j = 0; j <= k; ++j) v -= term(s, j) * term(s, k - j);
        }
        v *= c.scale;
        break;
      case ConstraintType::RigidX:
      case ConstraintType::RigidY:
        break;  // linear in q: coefficient k depends on q_k alone
      case ConstraintType::PointOnLine:
        for (int j = 1; j < k; ++j) v += cross2(diff(p[0], p[2], j), diff(p[0], p[1], k - j));
        v *= c.scale;
        break;
      case ConstraintType::Orientation:
        for (int j = 1; j < k; ++j) {
          const Eigen::Vector2d w = diff(p[2], p[3], k - j);
          v += cross2(diff(p[0], p[1], j), Eigen::Vector2d(c.a * w.x() - c.b * w.y(), c.b * w.x() + c.a * w.y()));
        }
        v *= c.scale;
        break;
      case ConstraintType::DriveAngle: {
        const DriverState& d = drivers[c.driver];
        for (int j = 0; j < k; ++j) {
          const Eigen::Vector2d u = diff(p[0], p[1], j);
          v += u.x() * term(d.sin, k - j) - u.y() * term(d.cos, k - j);
        }
        v *= c.scale;
        break;
      }
      case ConstraintType::DriveRelativeAngle: {
        // u x z with z = R(theta) w: both factors carry coefficients of q and of the driver.
        const DriverState& d = drivers[c.driver];
        for (int j = 0; j < k; ++j) {
          Eigen::Vector2d z = Eigen::Vector2d::Zero();
          for (int l = 0; l <= k - j; ++l) {
            const Eigen::Vector2d w = diff(p[2], p[3], k - j - l);
            const double cs = term(d.cos, l), sn = term(d.sin, l);
            z += Eigen::Vector2d(cs * w.x() - sn * w.y(), sn * w.x() + cs * w.y());
          }
          v += cross2(diff(p[0], p[1], j), z);
        }
        v *= c.scale;
        break;
      }
      case ConstraintType::DriveSlide:
        for (int j = 1; j < k; ++j) v += diff(p[0], p[2], j).dot(diff(p[0], p[1], k - j));
        v = v / c.a - term(drivers[c.driver].value, k);
        break;
    }
    rhs[r] = v;
  }
}

}  // namespace nbar
