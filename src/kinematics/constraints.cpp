#include "kinematics/constraints.hpp"

#include "kinematics/mechanism.hpp"

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
  std::vector<DriverDoubles> d(drivers.size());
  for (std::size_t i = 0; i < drivers.size(); ++i)
    d[i] = {drivers[i].value.value(), drivers[i].cos.value(), drivers[i].sin.value()};
  auto drv = [&](int i) -> const DriverDoubles& { return d[i]; };
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
  const int terms = k + 1;
  rhs.resize(mech.row_count());
  auto point = [&](int i) {
    Vec<Series> r{Series(terms), Series(terms)};
    const int col = mech.column_of(i);
    if (col < 0) {
      const Eigen::Vector2d& p = mech.model().points[i].position;
      r.x[0] = p.x();
      r.y[0] = p.y();
      return r;
    }
    for (int j = 0; j < k; ++j) {  // coefficient k stays zero
      r.x[j] = coefficients(col, j);
      r.y[j] = coefficients(col + 1, j);
    }
    return r;
  };
  std::vector<DriverState> truncated(drivers.size());
  for (std::size_t i = 0; i < drivers.size(); ++i)
    truncated[i] = {drivers[i].value.head(terms), drivers[i].cos.head(terms), drivers[i].sin.head(terms)};
  auto drv = [&](int i) -> const DriverState& { return truncated[i]; };
  const auto& rows = mech.rows();
  for (int i = 0; i < mech.row_count(); ++i) rhs[i] = residual<Series>(rows[i], point, drv)[k];
}

}  // namespace nbar
