#include "nbar/kinematics/mechanism.hpp"

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>

#include <algorithm>
#include <cmath>
#include <map>

namespace nbar {

namespace {

// Dense rank analysis is cubic (70 ms at 600 coordinates); beyond this many coordinates a
// sparse LU of the driven system first tries to prove it regular (the common case).
constexpr int kDenseAnalysisLimit = 100;
constexpr double kRankTolerance = 1e-9;

double angle_of(const Eigen::Vector2d& u) { return std::atan2(u.y(), u.x()); }

std::string point_pair(const Model& m, int i, int j) { return m.points[i].name + "-" + m.points[j].name; }

}  // namespace

Mechanism::Mechanism(Model model) : model_(std::move(model)) {
  validate(model_);
  if (model_.bodies.empty()) throw ModelError({EntityRef::Kind::Model, -1}, "the model has no moving bodies");

  // Natural coordinates: x, y of every point not fixed to the frame.
  column_.assign(model_.points.size(), -1);
  for (std::size_t i = 0; i < model_.points.size(); ++i) {
    if (!model_.points[i].ground) {
      column_[i] = n_;
      n_ += 2;
    }
  }
  q_drawn_.resize(n_);
  Eigen::Vector2d lo = model_.points.front().position, hi = lo;
  for (std::size_t i = 0; i < model_.points.size(); ++i) {
    const Eigen::Vector2d& p = model_.points[i].position;
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
    if (column_[i] >= 0) q_drawn_.segment<2>(column_[i]) = p;
  }
  length_scale_ = (hi - lo).norm();
  for (const Body& b : model_.bodies)
    if (b.length) length_scale_ = std::max(length_scale_, *b.length);
  if (!(length_scale_ > 0.0))
    throw ModelError({EntityRef::Kind::Model, -1}, "all points coincide: the model has no size");

  build_rows();
  build_pattern();
  loops_ = find_four_bar_loops(model_);
  analyse_mobility();
}

Eigen::Vector2d Mechanism::point_position(int point, const Eigen::VectorXd& q) const {
  const int col = column_[point];
  if (col < 0) return model_.points[point].position;
  return q.segment<2>(col);
}

void Mechanism::build_rows() {
  const auto& pts = model_.points;
  auto pos = [&](int i) -> const Eigen::Vector2d& { return pts[i].position; };
  auto all_fixed = [&](std::initializer_list<int> ids) {
    return std::all_of(ids.begin(), ids.end(), [&](int i) { return column_[i] < 0; });
  };

  for (std::size_t bi = 0; bi < model_.bodies.size(); ++bi) {
    const Body& body = model_.bodies[bi];
    const EntityRef src{EntityRef::Kind::Body, static_cast<int>(bi)};
    if (body.points.size() < 2) continue;
    const int i = body.points[0], j = body.points[1];
    const Eigen::Vector2d u = pos(j) - pos(i);
    if (!all_fixed({i, j})) {
      Constraint c;
      c.type = ConstraintType::Distance;
      c.p = {i, j, -1, -1};
      c.a = body.length.value_or(u.norm());
      c.scale = 1.0 / (2.0 * c.a);
      c.label = "length of " + body.name + " (" + point_pair(model_, i, j) + ")";
      c.source = src;
      rows_.push_back(c);
    }
    // Further points by two linear equations in the frame of the first two: they hold for
    // collinear points too, where a distance equation would be singular.
    const double uu = u.squaredNorm();
    for (std::size_t s = 2; s < body.points.size(); ++s) {
      const int k = body.points[s];
      if (all_fixed({i, j, k})) continue;
      const Eigen::Vector2d d = pos(k) - pos(i);
      Constraint c;
      c.p = {i, j, k, -1};
      c.a = d.dot(u) / uu;
      c.b = (-u.y() * d.x() + u.x() * d.y()) / uu;
      c.source = src;
      c.type = ConstraintType::RigidX;
      c.label = "shape of " + body.name + " (" + pts[k].name + ", x)";
      rows_.push_back(c);
      c.type = ConstraintType::RigidY;
      c.label = "shape of " + body.name + " (" + pts[k].name + ", y)";
      rows_.push_back(c);
    }
  }

  for (std::size_t si = 0; si < model_.sliders.size(); ++si) {
    const Slider& s = model_.sliders[si];
    const EntityRef src{EntityRef::Kind::Slider, static_cast<int>(si)};
    const int i = s.along[0], j = s.along[1];
    const Eigen::Vector2d w = pos(j) - pos(i);
    const Body& body = model_.bodies[s.body];
    if (!all_fixed({i, j, s.point})) {
      Constraint c;
      c.type = ConstraintType::PointOnLine;
      c.p = {i, j, s.point, -1};
      c.scale = 1.0 / w.norm();
      c.label = pts[s.point].name + " of " + body.name + " on the line " + point_pair(model_, i, j);
      c.source = src;
      rows_.push_back(c);
    }
    if (body.points.size() >= 2) {
      const int bi = body.points[0], bj = body.points[1];
      if (!all_fixed({bi, bj, i, j})) {
        const double phi0 = angle_of(pos(bj) - pos(bi)) - angle_of(w);
        Constraint c;
        c.type = ConstraintType::Orientation;
        c.p = {bi, bj, i, j};
        c.a = std::cos(phi0);
        c.b = std::sin(phi0);
        c.scale = 1.0 / w.norm();
        c.label = "orientation of " + body.name + " along " + point_pair(model_, i, j);
        c.source = src;
        rows_.push_back(c);
      }
    }
  }

  for (std::size_t si = 0; si < model_.slots.size(); ++si) {
    const Slot& s = model_.slots[si];
    const int i = s.along[0], j = s.along[1];
    if (all_fixed({i, j, s.point})) continue;
    Constraint c;
    c.type = ConstraintType::PointOnLine;
    c.p = {i, j, s.point, -1};
    c.scale = 1.0 / (pos(j) - pos(i)).norm();
    c.label = pts[s.point].name + " in the slot " + point_pair(model_, i, j);
    c.source = {EntityRef::Kind::Slot, static_cast<int>(si)};
    rows_.push_back(c);
  }

  constraint_rows_ = static_cast<int>(rows_.size());

  for (std::size_t di = 0; di < model_.drivers.size(); ++di) {
    const Driver& d = model_.drivers[di];
    Constraint c;
    c.driver = static_cast<int>(di);
    c.source = {EntityRef::Kind::Driver, static_cast<int>(di)};
    c.label = "driver " + d.name;
    double drawn = 0.0;
    switch (d.kind) {
      case DriverKind::Angle: {
        const Body& body = model_.bodies[d.body];
        const int i = body.points[0], j = body.points[1];
        const Eigen::Vector2d u = pos(j) - pos(i);
        if (d.relative_to < 0) {
          c.type = ConstraintType::DriveAngle;
          c.p = {i, j, -1, -1};
          drawn = angle_of(u);
        } else {
          const Body& ref = model_.bodies[d.relative_to];
          const int m = ref.points[0], n = ref.points[1];
          const Eigen::Vector2d w = pos(n) - pos(m);
          c.type = ConstraintType::DriveRelativeAngle;
          c.p = {i, j, m, n};
          c.scale = 1.0 / w.norm();
          drawn = std::atan2(w.x() * u.y() - w.y() * u.x(), w.dot(u));
        }
        break;
      }
      case DriverKind::Distance: {
        const int i = d.points[0], j = d.points[1];
        drawn = (pos(j) - pos(i)).norm();
        c.type = ConstraintType::DriveDistance;
        c.p = {i, j, -1, -1};
        c.scale = 1.0 / (2.0 * std::max(drawn, 1e-3 * length_scale_));
        break;
      }
      case DriverKind::Slide: {
        const Slider& s = model_.sliders[d.slider];
        const int i = s.along[0], j = s.along[1];
        const Eigen::Vector2d w = pos(j) - pos(i);
        c.type = ConstraintType::DriveSlide;
        c.p = {i, j, s.point, -1};
        c.a = w.norm();
        drawn = (pos(s.point) - pos(i)).dot(w) / c.a;
        break;
      }
    }
    driver_drawn_.push_back(drawn);
    rows_.push_back(c);
  }
}

void Mechanism::build_pattern() {
  entry_.assign(rows_.size(), {-1, -1, -1, -1});
  for (std::size_t r = 0; r < rows_.size(); ++r) {
    for (int slot = 0; slot < 4; ++slot) {
      const int p = rows_[r].p[slot];
      if (p < 0 || column_[p] < 0) continue;
      entry_[r][slot] = static_cast<int>(pattern_.size());
      pattern_.push_back({static_cast<int>(r), column_[p]});
      pattern_.push_back({static_cast<int>(r), column_[p] + 1});
    }
  }
}

PairCount count_pairs(const Model& m) {
  std::vector<int> links_at(m.points.size(), 0);
  for (std::size_t i = 0; i < m.points.size(); ++i) links_at[i] = m.points[i].ground ? 1 : 0;
  for (const Body& b : m.bodies)
    for (int p : b.points) ++links_at[p];
  PairCount c;
  c.links = static_cast<int>(m.bodies.size()) + 1;
  c.lower_pairs = static_cast<int>(m.sliders.size());
  for (int k : links_at) c.lower_pairs += std::max(0, k - 1);
  c.higher_pairs = static_cast<int>(m.slots.size());
  c.dof = 3 * (c.links - 1) - 2 * c.lower_pairs - c.higher_pairs;
  return c;
}

void Mechanism::analyse_mobility() {
  MobilityReport& r = mobility_;
  r.coordinates = n_;
  r.constraint_rows = constraint_rows_;
  r.grubler = count_pairs(model_).dof;

  std::vector<DriverState> drivers;
  for (std::size_t d = 0; d < model_.drivers.size(); ++d)
    drivers.push_back(make_driver_state(Series(1, driver_drawn_[d]), model_.drivers[d].is_angular()));
  std::vector<double> values;
  evaluate_jacobian(*this, q_drawn_, drivers, values);
  const int m = row_count();
  const int drivers_count = static_cast<int>(model_.drivers.size());

  if (n_ > kDenseAnalysisLimit && m == n_) {
    // Large square systems: a regular sparse LU proves full rank, hence no redundancy.
    Eigen::SparseMatrix<double> J(m, n_);
    std::vector<Eigen::Triplet<double>> t;
    for (std::size_t e = 0; e < pattern_.size(); ++e) t.emplace_back(pattern_[e].row, pattern_[e].col, values[e]);
    J.setFromTriplets(t.begin(), t.end());
    Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
    lu.compute(J);
    if (lu.info() == Eigen::Success) {
      r.rank = constraint_rows_;
      r.dof = n_ - constraint_rows_;
      r.reciprocal_condition = 1.0;  // not estimated for sparse systems
      return;
    }
  }

  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(m, n_);
  for (std::size_t e = 0; e < pattern_.size(); ++e) J(pattern_[e].row, pattern_[e].col) += values[e];

  // Columns of Phi_q^T are rows of Phi_q: the pivoting picks an independent set of constraints.
  Eigen::MatrixXd Jc = J.topRows(constraint_rows_);
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(Jc.transpose());
  qr.setThreshold(kRankTolerance);
  r.rank = constraint_rows_ == 0 ? 0 : static_cast<int>(qr.rank());
  r.dof = n_ - r.rank;
  if (constraint_rows_ > 0) {
    const auto& perm = qr.colsPermutation().indices();
    for (int c = r.rank; c < constraint_rows_; ++c) r.redundant.push_back(perm[c]);
    std::sort(r.redundant.begin(), r.redundant.end());
  }

  const std::string counts = "the mechanism has " + std::to_string(r.dof) + " degree" + (r.dof == 1 ? "" : "s") +
                             " of freedom (Gruebler-Kutzbach count: " + std::to_string(r.grubler) + ") but " +
                             std::to_string(drivers_count) + " driver" + (drivers_count == 1 ? " is" : "s are") +
                             " given";
  if (r.dof != drivers_count) {
    std::string hint;
    if (r.grubler == drivers_count)
      hint = "; the drawn pose may be a singular (toggle or flat) position: draw the mechanism in a general pose";
    else if (drivers_count < r.dof)
      hint = "; add one driver per free input";
    else
      hint = "; remove drivers, or check for missing joints";
    throw ModelError({EntityRef::Kind::Model, -1}, counts + hint);
  }

  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> full(J.transpose());
  full.setThreshold(kRankTolerance);
  if (full.rank() < n_) {
    // Find the first driver whose row depends on the constraints and the drivers before it.
    for (int d = 0; d < drivers_count; ++d) {
      Eigen::ColPivHouseholderQR<Eigen::MatrixXd> partial(J.topRows(constraint_rows_ + d + 1).transpose());
      partial.setThreshold(kRankTolerance);
      if (partial.rank() < r.rank + d + 1)
        throw ModelError({EntityRef::Kind::Driver, d},
                         "driver '" + model_.drivers[d].name +
                             "' does not move the mechanism independently: what it drives is already fixed by the "
                             "joints or by the other drivers");
    }
  }
  if (m == n_) {
    Eigen::PartialPivLU<Eigen::MatrixXd> lu(J);
    r.reciprocal_condition = lu.rcond();
  } else {
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(J);
    const auto& s = svd.singularValues();
    r.reciprocal_condition = s(0) > 0 ? s(s.size() - 1) / s(0) : 0.0;
  }
}

}  // namespace nbar
