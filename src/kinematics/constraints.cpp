#include "constraints.hpp"

#include "nbar/kinematics/mechanism.hpp"

#include <cmath>
#include <limits>
#include <type_traits>

namespace nbar {

namespace {

struct Xy {
  double x, y;
};
Xy operator-(Xy a, Xy b) { return {a.x - b.x, a.y - b.y}; }
Xy operator+(Xy a, Xy b) { return {a.x + b.x, a.y + b.y}; }
double cross(Xy a, Xy b) { return a.x * b.y - a.y * b.x; }
double dot(Xy a, Xy b) { return a.x * b.x + a.y * b.y; }
// w turned by the angle whose cosine and sine are c, s.
Xy rotate(Xy w, double c, double s) { return {c * w.x - s * w.y, s * w.x + c * w.y}; }
// d(a x b)/da = (b.y, -b.x).
Xy perp(Xy b) { return {b.y, -b.x}; }

// A point's coordinates: a column of q, or fixed ones (CompiledRow::at).
struct Points {
  const double* q;
  const double* fixed;
  Xy operator()(int at) const { return at >= 0 ? point<false>(at) : point<true>(at); }
  // The same for a point known, when compiled, to be fixed (Fixed) or to move.
  template <bool Fixed>
  Xy point(int at) const {
    const double* p = Fixed ? fixed + ~at : q + at;
    return {p[0], p[1]};
  }
};

// f(F0, F1), std::bool_constant each: whether a group's first and second points are fixed
// (RowGroup::fixed).
template <class F>
void with_fixed_points(int fixed, F&& f) {
  switch (fixed) {
    case 0: return f(std::false_type{}, std::false_type{});
    case 1: return f(std::true_type{}, std::false_type{});
    case 2: return f(std::false_type{}, std::true_type{});
    default: return f(std::true_type{}, std::true_type{});
  }
}

struct DriverValues {
  double value = 0.0, cos = 1.0, sin = 0.0;
};
DriverValues driver_values(const CompiledRow& c, const std::vector<DriverState>& drivers) {
  if (c.driver < 0) return {};
  const DriverState& d = drivers[static_cast<std::size_t>(c.driver)];
  return {d.value.value(), d.cos.value(), d.sin.value()};
}

[[gnu::always_inline]] inline double residual(const CompiledRow& c, const Points& r, const DriverValues& d) {
  const auto& at = c.at;
  switch (c.type) {
    case ConstraintType::Distance: {
      const Xy u = r(at[1]) - r(at[0]);
      return (dot(u, u) - c.a * c.a) * c.scale;
    }
    case ConstraintType::RigidX: {
      const Xy ri = r(at[0]), u = r(at[1]) - ri;
      return r(at[2]).x - ri.x - c.a * u.x + c.b * u.y;
    }
    case ConstraintType::RigidY: {
      const Xy ri = r(at[0]), u = r(at[1]) - ri;
      return r(at[2]).y - ri.y - c.a * u.y - c.b * u.x;
    }
    case ConstraintType::PointOnLine: {
      const Xy ri = r(at[0]);
      return cross(r(at[2]) - ri, r(at[1]) - ri) * c.scale;
    }
    case ConstraintType::Orientation:
      return cross(r(at[1]) - r(at[0]), rotate(r(at[3]) - r(at[2]), c.a, c.b)) * c.scale;
    case ConstraintType::DriveAngle: {
      const Xy u = r(at[1]) - r(at[0]);
      return (u.x * d.sin - u.y * d.cos) * c.scale;
    }
    case ConstraintType::DriveRelativeAngle:
      return cross(r(at[1]) - r(at[0]), rotate(r(at[3]) - r(at[2]), d.cos, d.sin)) * c.scale;
    case ConstraintType::DriveDistance: {
      const Xy u = r(at[1]) - r(at[0]);
      return (dot(u, u) - d.value * d.value) * c.scale;
    }
    case ConstraintType::DriveSlide: {
      const Xy ri = r(at[0]);
      return dot(r(at[2]) - ri, r(at[1]) - ri) * (1.0 / c.a) - d.value;
    }
  }
  return 0.0;
}

// Gradient of one row with respect to its (up to four) points.
[[gnu::always_inline]] inline std::array<Xy, 4> gradient(const CompiledRow& c, const Points& r, const DriverValues& d) {
  std::array<Xy, 4> g{};
  const auto& at = c.at;
  switch (c.type) {
    case ConstraintType::Distance:
    case ConstraintType::DriveDistance: {
      const Xy u = r(at[1]) - r(at[0]);
      g[1] = {2.0 * c.scale * u.x, 2.0 * c.scale * u.y};
      g[0] = {-g[1].x, -g[1].y};
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
      const Xy ri = r(at[0]), e = r(at[2]) - ri, w = r(at[1]) - ri;
      const Xy de = perp(w), dw = perp(e);  // d/de of e x w, and minus d/dw
      g[2] = {c.scale * de.x, c.scale * de.y};
      g[1] = {-c.scale * dw.x, -c.scale * dw.y};
      g[0] = {-g[2].x - g[1].x, -g[2].y - g[1].y};
      break;
    }
    case ConstraintType::Orientation:
    case ConstraintType::DriveRelativeAngle: {
      const bool fixed = c.type == ConstraintType::Orientation;
      const double cs = fixed ? c.a : d.cos, sn = fixed ? c.b : d.sin;
      const Xy v = r(at[1]) - r(at[0]), z = rotate(r(at[3]) - r(at[2]), cs, sn);
      const Xy dv = perp(z), pv = perp(v);
      const Xy dz = {-c.scale * pv.x, -c.scale * pv.y};
      const Xy dw = {cs * dz.x + sn * dz.y, -sn * dz.x + cs * dz.y};  // R^T dz
      g[1] = {c.scale * dv.x, c.scale * dv.y};
      g[0] = {-g[1].x, -g[1].y};
      g[3] = dw;
      g[2] = {-dw.x, -dw.y};
      break;
    }
    case ConstraintType::DriveAngle:
      g[1] = {c.scale * d.sin, -c.scale * d.cos};
      g[0] = {-g[1].x, -g[1].y};
      break;
    case ConstraintType::DriveSlide: {
      const Xy ri = r(at[0]), e = r(at[2]) - ri, w = r(at[1]) - ri;
      g[2] = {w.x / c.a, w.y / c.a};
      g[1] = {e.x / c.a, e.y / c.a};
      g[0] = {-g[2].x - g[1].x, -g[2].y - g[1].y};
      break;
    }
  }
  return g;
}

// Coefficient j of a point's Taylor series, with coefficients k and beyond taken as zero: from
// the columns of q's series, or the fixed coordinates (their own at j = 0, zero after).
struct Coefficients {
  const double* series;  // column-major, n rows
  Eigen::Index n;
  const double* fixed;
  int k;
  Xy operator()(int at, int j) const {
    if (j >= k) return {0.0, 0.0};
    if (j > 0) return rate(at, j);
    return at >= 0 ? position<false>(at) : position<true>(at);
  }
  Xy difference(int from, int to, int j) const { return (*this)(to, j) - (*this)(from, j); }
  // Coefficient j for 0 < j < k, where a fixed point's is zero: what the loops over j >= 1 read.
  Xy rate(int at, int j) const { return at < 0 ? rate<true>(at, j) : rate<false>(at, j); }
  Xy rate_difference(int from, int to, int j) const { return rate(to, j) - rate(from, j); }
  // The same for points known, when compiled, to be fixed or to move (0 < k).
  template <bool Fixed>
  Xy position(int at) const {
    const double* p = Fixed ? fixed + ~at : series + at;
    return {p[0], p[1]};
  }
  template <bool Fixed>
  Xy rate(int at, int j) const {
    if constexpr (Fixed) {
      return {0.0, 0.0};
    } else {
      const double* p = series + j * n + at;
      return {p[0], p[1]};
    }
  }
  template <bool FromFixed, bool ToFixed>
  Xy rate_difference(int from, int to, int j) const {
    return rate<ToFixed>(to, j) - rate<FromFixed>(from, j);
  }
};

double term(const Series& s, int j) { return j < s.terms() ? s[j] : 0.0; }

// Coefficient k of one row with q's coefficient k taken as zero: every row is at most bilinear
// in q, so a short convolution of lower coefficients.
double remainder(const CompiledRow& c, const Coefficients& q, int k, const std::vector<DriverState>& drivers) {
  const auto& at = c.at;
  double v = 0.0;
  switch (c.type) {
    case ConstraintType::Distance:
    case ConstraintType::DriveDistance:
      for (int j = 1; j < k; ++j) v += dot(q.difference(at[0], at[1], j), q.difference(at[0], at[1], k - j));
      if (c.type == ConstraintType::DriveDistance) {
        const Series& s = drivers[static_cast<std::size_t>(c.driver)].value;
        for (int j = 0; j <= k; ++j) v -= term(s, j) * term(s, k - j);
      }
      return v * c.scale;
    case ConstraintType::RigidX:
    case ConstraintType::RigidY: return 0.0;  // linear in q: coefficient k depends on q_k alone
    case ConstraintType::PointOnLine:
      for (int j = 1; j < k; ++j) v += cross(q.difference(at[0], at[2], j), q.difference(at[0], at[1], k - j));
      return v * c.scale;
    case ConstraintType::Orientation:
      for (int j = 1; j < k; ++j)
        v += cross(q.difference(at[0], at[1], j), rotate(q.difference(at[2], at[3], k - j), c.a, c.b));
      return v * c.scale;
    case ConstraintType::DriveAngle: {
      const DriverState& d = drivers[static_cast<std::size_t>(c.driver)];
      for (int j = 0; j < k; ++j) {
        const Xy u = q.difference(at[0], at[1], j);
        v += u.x * term(d.sin, k - j) - u.y * term(d.cos, k - j);
      }
      return v * c.scale;
    }
    case ConstraintType::DriveRelativeAngle: {
      // u x z with z = R(theta) w: both factors carry coefficients of q and of the driver.
      const DriverState& d = drivers[static_cast<std::size_t>(c.driver)];
      for (int j = 0; j < k; ++j) {
        Xy z{0.0, 0.0};
        for (int l = 0; l <= k - j; ++l)
          z = z + rotate(q.difference(at[2], at[3], k - j - l), term(d.cos, l), term(d.sin, l));
        v += cross(q.difference(at[0], at[1], j), z);
      }
      return v * c.scale;
    }
    case ConstraintType::DriveSlide:
      for (int j = 1; j < k; ++j) v += dot(q.difference(at[0], at[2], j), q.difference(at[0], at[1], k - j));
      return v / c.a - term(drivers[static_cast<std::size_t>(c.driver)].value, k);
  }
  return 0.0;
}

}  // namespace

// The rows of one type run together (Mechanism::Equations::compiled is grouped so): the two commonest,
// a body's length and a crank's angle, in loops of their own with nothing to dispatch, compiled
// for which of their points are fixed (RowGroup::fixed); the others through the general functions
// above.
template <class Group>
void for_each_group(const Mechanism& mech, Group&& group) {
  const CompiledRow* rows = mech.equations().compiled.data();
  for (const RowGroup& g : mech.equations().groups) group(g, rows + g.first, rows + g.last);
}

namespace {

// A row whose gradient is -g at its first point and g at its second, written into the Jacobian's
// values where those points move (a fixed point has no entries).
template <bool FirstFixed, bool SecondFixed>
void put_pair(double* out, const CompiledRow& c, Xy g) {
  if constexpr (!FirstFixed) {
    out[c.entry[0]] = -g.x;
    out[c.entry[0] + 1] = -g.y;
  }
  if constexpr (!SecondFixed) {
    out[c.entry[1]] = g.x;
    out[c.entry[1] + 1] = g.y;
  }
}

[[gnu::always_inline]] inline void put_gradient(double* out, const CompiledRow& c, const Points& r,
                                                const DriverValues& d) {
  const std::array<Xy, 4> g = gradient(c, r, d);
  for (std::size_t slot = 0; slot < 4; ++slot) {
    const int e = c.entry[slot];
    if (e < 0) continue;
    out[e] = g[slot].x;
    out[e + 1] = g[slot].y;
  }
}

// The residuals (WithResiduals, into `residuals`, returning the largest |row|) and the Jacobian's
// values (WithJacobian, into `jacobian`) in one pass over the rows: a row's points are read once
// for both, and each row's formulas are written once for the three evaluations below.
template <bool WithResiduals, bool WithJacobian>
double evaluate_rows(const Mechanism& mech, const Eigen::VectorXd& q, const std::vector<DriverState>& drivers,
                     double* residuals, double* jacobian) {
  const Points r{q.data(), mech.equations().fixed_coordinates.data()};
  // The largest |row| found on the way (a second pass over the rows cost a tenth of a four-bar
  // step); a NaN anywhere is kept aside and makes it infinite.
  double largest = 0.0;
  bool nan = false;
  const auto put = [&](int row, double value) {
    residuals[row] = value;
    const double size = std::abs(value);
    largest = size > largest ? size : largest;
    nan |= std::isnan(value);
  };
  for_each_group(mech, [&](const RowGroup& group, const CompiledRow* first, const CompiledRow* last) {
    switch (group.type) {
      case ConstraintType::Distance:
        return with_fixed_points(group.fixed, [&](auto first_fixed, auto second_fixed) {
          constexpr bool F0 = decltype(first_fixed)::value, F1 = decltype(second_fixed)::value;
          for (const CompiledRow* c = first; c != last; ++c) {
            const Xy u = r.point<F1>(c->at[1]) - r.point<F0>(c->at[0]);
            if constexpr (WithResiduals) put(c->row, (dot(u, u) - c->a * c->a) * c->scale);
            if constexpr (WithJacobian) {
              const double f = 2.0 * c->scale;
              put_pair<F0, F1>(jacobian, *c, {f * u.x, f * u.y});
            }
          }
        });
      case ConstraintType::DriveAngle:
        return with_fixed_points(group.fixed, [&](auto first_fixed, auto second_fixed) {
          constexpr bool F0 = decltype(first_fixed)::value, F1 = decltype(second_fixed)::value;
          for (const CompiledRow* c = first; c != last; ++c) {
            const DriverState& d = drivers[static_cast<std::size_t>(c->driver)];
            if constexpr (WithResiduals) {
              const Xy u = r.point<F1>(c->at[1]) - r.point<F0>(c->at[0]);
              put(c->row, (u.x * d.sin.value() - u.y * d.cos.value()) * c->scale);
            }
            if constexpr (WithJacobian)
              put_pair<F0, F1>(jacobian, *c, {c->scale * d.sin.value(), -c->scale * d.cos.value()});
          }
        });
      default:
        for (const CompiledRow* c = first; c != last; ++c) {
          const DriverValues d = driver_values(*c, drivers);
          if constexpr (WithResiduals) put(c->row, residual(*c, r, d));
          if constexpr (WithJacobian) put_gradient(jacobian, *c, r, d);
        }
    }
  });
  return nan ? std::numeric_limits<double>::infinity() : largest;
}

double* sized_residuals(const Mechanism& mech, Eigen::VectorXd& phi) {
  const auto rows = static_cast<Eigen::Index>(mech.equations().compiled.size());
  if (phi.size() != rows) phi.resize(rows);
  return phi.data();
}

// Every pattern entry belongs to one (row, point) slot, so each is written once.
double* sized_jacobian(const Mechanism& mech, std::vector<double>& values) {
  values.resize(mech.equations().pattern.size());
  return values.data();
}

}  // namespace

double evaluate_residuals(const Mechanism& mech, const Eigen::VectorXd& q, const std::vector<DriverState>& drivers,
                          Eigen::VectorXd& phi) {
  return evaluate_rows<true, false>(mech, q, drivers, sized_residuals(mech, phi), nullptr);
}

double evaluate_residuals_and_jacobian(const Mechanism& mech, const Eigen::VectorXd& q,
                                       const std::vector<DriverState>& drivers, Eigen::VectorXd& phi,
                                       std::vector<double>& values) {
  return evaluate_rows<true, true>(mech, q, drivers, sized_residuals(mech, phi), sized_jacobian(mech, values));
}

void evaluate_jacobian(const Mechanism& mech, const Eigen::VectorXd& q, const std::vector<DriverState>& drivers,
                       std::vector<double>& values) {
  evaluate_rows<false, true>(mech, q, drivers, nullptr, sized_jacobian(mech, values));
}

namespace {

// evaluate_series_remainder for coefficient K known when compiled (the sums over j unroll), or
// with K = 0 for `runtime_k`. Kept out of line: inlined, the four instantiations share one frame
// and its register saves, which every step then pays even when it needs only one of them.
template <int K>
[[gnu::noinline]] void remainder_of_order(const Mechanism& mech, const Eigen::MatrixXd& coefficients, int runtime_k,
                                          const std::vector<DriverState>& drivers, Eigen::VectorXd& rhs) {
  const int k = K > 0 ? K : runtime_k;
  const auto& rows = mech.equations().compiled;
  if (rhs.size() != static_cast<Eigen::Index>(rows.size())) rhs.resize(static_cast<Eigen::Index>(rows.size()));
  double* out = rhs.data();
  const Coefficients q{coefficients.data(), coefficients.rows(), mech.equations().fixed_coordinates.data(), k};
  for_each_group(mech, [&](const RowGroup& group, const CompiledRow* first, const CompiledRow* last) {
    switch (group.type) {
      case ConstraintType::Distance:
        // The first coefficient is linear in q_1 alone (no sum: 0 * scale, which is +0, every scale
        // being positive); the k-th, sum over j of u_j . u_(k-j).
        if (k == 1) {
          for (const CompiledRow* c = first; c != last; ++c) out[c->row] = 0.0;
          return;
        }
        return with_fixed_points(group.fixed, [&](auto first_fixed, auto second_fixed) {
          constexpr bool F0 = decltype(first_fixed)::value, F1 = decltype(second_fixed)::value;
          for (const CompiledRow* c = first; c != last; ++c) {
            const int from = c->at[0], to = c->at[1];
            double v = 0.0;
            for (int j = 1; j < k; ++j)
              v += dot(q.rate_difference<F0, F1>(from, to, j), q.rate_difference<F0, F1>(from, to, k - j));
            out[c->row] = v * c->scale;
          }
        });
      case ConstraintType::RigidX:
      case ConstraintType::RigidY:
        for (const CompiledRow* c = first; c != last; ++c) out[c->row] = 0.0;  // linear in q
        return;
      case ConstraintType::DriveAngle:
        // (u x (cos, sin)) coefficient k: sum over j < k of u_j against the driver's k - j.
        return with_fixed_points(group.fixed, [&](auto first_fixed, auto second_fixed) {
          constexpr bool F0 = decltype(first_fixed)::value, F1 = decltype(second_fixed)::value;
          for (const CompiledRow* c = first; c != last; ++c) {
            const DriverState& d = drivers[static_cast<std::size_t>(c->driver)];
            const int from = c->at[0], to = c->at[1];
            const Xy u0 = q.position<F1>(to) - q.position<F0>(from);
            double v = 0.0;  // added to, not started from, the first term: a -0 product stays +0
            v += u0.x * term(d.sin, k) - u0.y * term(d.cos, k);
            for (int j = 1; j < k; ++j) {
              const Xy u = q.rate_difference<F0, F1>(from, to, j);
              v += u.x * term(d.sin, k - j) - u.y * term(d.cos, k - j);
            }
            out[c->row] = v * c->scale;
          }
        });
      default:
        for (const CompiledRow* c = first; c != last; ++c) out[c->row] = remainder(*c, q, k, drivers);
    }
  });
}

}  // namespace

void evaluate_series_remainder(const Mechanism& mech, const Eigen::MatrixXd& coefficients, int k,
                               const std::vector<DriverState>& drivers, Eigen::VectorXd& rhs) {
  switch (k) {  // a sweep's velocities, accelerations and jerks
    case 1: return remainder_of_order<1>(mech, coefficients, k, drivers, rhs);
    case 2: return remainder_of_order<2>(mech, coefficients, k, drivers, rhs);
    case 3: return remainder_of_order<3>(mech, coefficients, k, drivers, rhs);
    default: return remainder_of_order<0>(mech, coefficients, k, drivers, rhs);
  }
}

}  // namespace nbar
