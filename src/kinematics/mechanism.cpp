#include "nbar/kinematics/mechanism.hpp"

#include <Eigen/Dense>
#include <Eigen/OrderingMethods>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <Eigen/SparseQR>

#include <algorithm>
#include <cmath>
#include <map>

#include "constraints.hpp"
#include "model/linear_algebra.hpp"

namespace nbar {

namespace {

// Dense rank analysis is cubic (70 ms at 600 coordinates); beyond this many coordinates a
// sparse LU of the driven system first tries to prove it regular (the common case).
constexpr int kDenseAnalysisLimit = 100;
// Beyond this many coordinates the rank analysis is sparse (a rank-revealing sparse QR, Eigen's
// SparseQR) and the diagnosis of a wrong number of drivers gives counts, not the body at fault.
constexpr int kDenseRankLimit = 600;
constexpr double kRankTolerance = 1e-9;

double angle_of(const Eigen::Vector2d& u) { return std::atan2(u.y(), u.x()); }

std::string point_pair(const Model& m, int i, int j) { return m.points[i].name + "-" + m.points[j].name; }

// The rows are built once per model, by kind of joint. A row whose points are all fixed to the
// frame holds by itself and is left out.
bool all_fixed(const std::vector<int>& column, std::initializer_list<int> ids) {
  return std::all_of(ids.begin(), ids.end(), [&](int i) { return column[i] < 0; });
}

// Each body's length (its first two points), and its further points by two linear equations in
// the frame of the first two: they hold for collinear points too, where a distance equation
// would be singular.
void add_body_rows(const Model& model, const std::vector<int>& column, std::vector<Constraint>& rows) {
  const auto& pts = model.points;
  auto pos = [&](int i) -> const Eigen::Vector2d& { return pts[i].position; };
  for (std::size_t bi = 0; bi < model.bodies.size(); ++bi) {
    const Body& body = model.bodies[bi];
    const EntityRef src{EntityRef::Kind::Body, static_cast<int>(bi)};
    if (body.points.size() < 2) continue;
    const int i = body.points[0], j = body.points[1];
    const Eigen::Vector2d u = pos(j) - pos(i);
    if (!all_fixed(column, {i, j})) {
      Constraint c;
      c.type = ConstraintType::Distance;
      c.p = {i, j, -1, -1};
      c.a = body.length.value_or(u.norm());
      c.scale = 1.0 / (2.0 * c.a);
      c.label = "length of " + body.name + " (" + point_pair(model, i, j) + ")";
      c.source = src;
      rows.push_back(c);
    }
    const double uu = u.squaredNorm();
    for (std::size_t s = 2; s < body.points.size(); ++s) {
      const int k = body.points[s];
      if (all_fixed(column, {i, j, k})) continue;
      const Eigen::Vector2d d = pos(k) - pos(i);
      Constraint c;
      c.p = {i, j, k, -1};
      c.a = d.dot(u) / uu;
      c.b = (-u.y() * d.x() + u.x() * d.y()) / uu;
      c.source = src;
      c.type = ConstraintType::RigidX;
      c.label = "shape of " + body.name + " (" + pts[k].name + ", x)";
      rows.push_back(c);
      c.type = ConstraintType::RigidY;
      c.label = "shape of " + body.name + " (" + pts[k].name + ", y)";
      rows.push_back(c);
    }
  }
}

// A slider: its point on the guide line, and its body's orientation along the line.
void add_slider_rows(const Model& model, const std::vector<int>& column, std::vector<Constraint>& rows) {
  const auto& pts = model.points;
  auto pos = [&](int i) -> const Eigen::Vector2d& { return pts[i].position; };
  for (std::size_t si = 0; si < model.sliders.size(); ++si) {
    const Slider& s = model.sliders[si];
    const EntityRef src{EntityRef::Kind::Slider, static_cast<int>(si)};
    const int i = s.along[0], j = s.along[1];
    const Eigen::Vector2d w = pos(j) - pos(i);
    const Body& body = model.bodies[s.body];
    if (!all_fixed(column, {i, j, s.point})) {
      Constraint c;
      c.type = ConstraintType::PointOnLine;
      c.p = {i, j, s.point, -1};
      c.scale = 1.0 / w.norm();
      c.label = pts[s.point].name + " of " + body.name + " on the line " + point_pair(model, i, j);
      c.source = src;
      rows.push_back(c);
    }
    if (body.points.size() >= 2) {
      const int bi = body.points[0], bj = body.points[1];
      if (!all_fixed(column, {bi, bj, i, j})) {
        const double phi0 = angle_of(pos(bj) - pos(bi)) - angle_of(w);
        Constraint c;
        c.type = ConstraintType::Orientation;
        c.p = {bi, bj, i, j};
        c.a = std::cos(phi0);
        c.b = std::sin(phi0);
        c.scale = 1.0 / w.norm();
        c.label = "orientation of " + body.name + " along " + point_pair(model, i, j);
        c.source = src;
        rows.push_back(c);
      }
    }
  }
}

// A slot: its point on the line.
void add_slot_rows(const Model& model, const std::vector<int>& column, std::vector<Constraint>& rows) {
  const auto& pts = model.points;
  auto pos = [&](int i) -> const Eigen::Vector2d& { return pts[i].position; };
  for (std::size_t si = 0; si < model.slots.size(); ++si) {
    const Slot& s = model.slots[si];
    const int i = s.along[0], j = s.along[1];
    if (all_fixed(column, {i, j, s.point})) continue;
    Constraint c;
    c.type = ConstraintType::PointOnLine;
    c.p = {i, j, s.point, -1};
    c.scale = 1.0 / (pos(j) - pos(i)).norm();
    c.label = pts[s.point].name + " in the slot " + point_pair(model, i, j);
    c.source = {EntityRef::Kind::Slot, static_cast<int>(si)};
    rows.push_back(c);
  }
}

// Positions converge to this fraction of the linkage's size (Mechanism::tolerance).
constexpr double kRelativeTolerance = 1e-12;
// A point that rides along (linkage_points) loosens the tolerance only when it lies further than
// 1 / kFarPointShare times the linkage's size: the rounding of its own rows grows with its
// distance (about 1e-16 of it), and beyond that they could not meet a tolerance of 1e-12 of the
// linkage.
constexpr double kFarPointShare = 1e-3;

// Which points make the linkage: every point a constraint between two links or a driver reads,
// not those that only ride along. A point rides along when it is a further point (the third or
// later) of one body and of nothing else: its two rows fix it in that body's frame and no other
// row reads it, so it moves with the linkage without shaping it (a coupler point, a centre of
// mass placed as a point). Its distance must not set the tolerance of the joints' equations: a
// centre of mass drawn 470 m from a 5 m linkage loosened the joints from 2e-13 to 1.4e-12 m when
// the whole drawing set it (issue 37).
std::vector<bool> linkage_points(const Model& model) {
  const std::size_t count = model.points.size();
  std::vector<int> bodies_of(count, 0);
  std::vector<bool> in_linkage(count, false);
  for (const Body& body : model.bodies) {
    for (std::size_t s = 0; s < body.points.size(); ++s) {
      ++bodies_of[body.points[s]];
      if (s < 2) in_linkage[body.points[s]] = true;  // the body's frame
    }
  }
  for (std::size_t i = 0; i < count; ++i)
    if (bodies_of[i] > 1) in_linkage[i] = true;  // a joint between bodies
  const auto mark = [&](int point) {
    if (point >= 0) in_linkage[point] = true;
  };
  for (const Slider& s : model.sliders) {
    mark(s.point);
    mark(s.along[0]);
    mark(s.along[1]);
  }
  for (const Slot& s : model.slots) {
    mark(s.point);
    mark(s.along[0]);
    mark(s.along[1]);
  }
  for (const Driver& d : model.drivers) {
    mark(d.points[0]);
    mark(d.points[1]);
  }
  // A point on the frame and on a body is a joint with the frame.
  for (std::size_t i = 0; i < count; ++i)
    if (model.points[i].ground && bodies_of[i] > 0) in_linkage[i] = true;
  return in_linkage;
}

// The diagonal of the bounding box of the drawn points marked in `which` (0 when none are).
double drawn_extent(const Model& model, const std::vector<bool>& which) {
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(HUGE_VAL), hi = -lo;
  bool any = false;
  for (std::size_t i = 0; i < model.points.size(); ++i) {
    if (!which[i]) continue;
    lo = lo.cwiseMin(model.points[i].position);
    hi = hi.cwiseMax(model.points[i].position);
    any = true;
  }
  return any ? (hi - lo).norm() : 0.0;
}

// Driver `di`'s row, and its value in the drawn pose (`drawn`).
Constraint driver_row(const Model& model, int di, double length_scale, double& drawn) {
  auto pos = [&](int i) -> const Eigen::Vector2d& { return model.points[i].position; };
  const Driver& d = model.drivers[di];
  Constraint c;
  c.driver = di;
  c.source = {EntityRef::Kind::Driver, di};
  c.label = "driver " + d.name;
  drawn = 0.0;
  switch (d.kind) {
    case DriverKind::Angle: {
      const Body& body = model.bodies[d.body];
      const int i = body.points[0], j = body.points[1];
      const Eigen::Vector2d u = pos(j) - pos(i);
      if (d.relative_to < 0) {
        c.type = ConstraintType::DriveAngle;
        c.p = {i, j, -1, -1};
        drawn = angle_of(u);
      } else {
        const Body& ref = model.bodies[d.relative_to];
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
      c.scale = 1.0 / (2.0 * std::max(drawn, 1e-3 * length_scale));
      break;
    }
    case DriverKind::Slide: {
      const Slider& s = model.sliders[d.slider];
      const int i = s.along[0], j = s.along[1];
      const Eigen::Vector2d w = pos(j) - pos(i);
      c.type = ConstraintType::DriveSlide;
      c.p = {i, j, s.point, -1};
      c.a = w.norm();
      drawn = (pos(s.point) - pos(i)).dot(w) / c.a;
      break;
    }
  }
  return c;
}

}  // namespace

Mechanism::Mechanism(Model model) : Mechanism(std::move(model), true) {}

MobilityReport Mechanism::joint_mobility(Model model) { return Mechanism(std::move(model), false).mobility_; }

Mechanism::Mechanism(Model model, bool check_drivers) : model_(std::move(model)), check_drivers_(check_drivers) {
  // Before the validation, whose checks also grow with the size.
  const auto moving =
      std::count_if(model_.points.begin(), model_.points.end(), [](const Point& p) { return !p.ground; });
  if (moving > kMaxMovingPoints)
    throw ModelError({EntityRef::Kind::Model, -1}, "the model has " + std::to_string(moving) +
                                                       " moving points; nbar analyses at most " +
                                                       std::to_string(kMaxMovingPoints));
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
  for (std::size_t i = 0; i < model_.points.size(); ++i)
    if (column_[i] >= 0) q_drawn_.segment<2>(column_[i]) = model_.points[i].position;
  const std::vector<bool> in_linkage = linkage_points(model_);
  length_scale_ = drawn_extent(model_, in_linkage);
  drawing_size_ = drawn_extent(model_, std::vector<bool>(model_.points.size(), true));
  for (const Body& b : model_.bodies) {
    if (!b.length) continue;
    length_scale_ = std::max(length_scale_, *b.length);
    drawing_size_ = std::max(drawing_size_, *b.length);
  }
  // A model whose linkage points all coincide (a single-point slider block, say) is measured by
  // its whole drawing.
  if (!(length_scale_ > 0.0)) length_scale_ = drawing_size_;
  if (!(length_scale_ > 0.0))
    throw ModelError({EntityRef::Kind::Model, -1}, "all points coincide: the model has no size");
  tolerance_ = kRelativeTolerance * std::max(length_scale_, kFarPointShare * drawing_size_);

  auto equations = std::make_shared<Equations>();
  build_rows(*equations);
  build_pattern(*equations);
  equations_ = std::move(equations);
  // The mobility first: a model with the wrong number of drivers is rejected before the loop
  // search, whose cost grows with the number of bodies joined at one point.
  analyse_mobility();
  loops_ = find_four_bar_loops(model_);
}

const std::string& Mechanism::row_label(int row) const { return equations_->rows[row].label; }

void Mechanism::build_rows(Equations& equations) {
  std::vector<Constraint>& rows = equations.rows;
  add_body_rows(model_, column_, rows);
  add_slider_rows(model_, column_, rows);
  add_slot_rows(model_, column_, rows);
  constraint_rows_ = static_cast<int>(rows.size());
  for (std::size_t di = 0; di < model_.drivers.size(); ++di) {
    double drawn = 0.0;
    rows.push_back(driver_row(model_, static_cast<int>(di), length_scale_, drawn));
    driver_drawn_.push_back(drawn);
  }
  row_count_ = static_cast<int>(rows.size());
}

void Mechanism::build_pattern(Equations& equations) const {
  const std::vector<Constraint>& rows = equations.rows;
  std::vector<double>& fixed_xy = equations.fixed_coordinates;
  std::vector<CompiledRow>& compiled = equations.compiled;
  std::vector<JacobianEntry>& pattern = equations.pattern;
  fixed_xy.assign(2 * model_.points.size(), 0.0);
  for (std::size_t i = 0; i < model_.points.size(); ++i) {
    fixed_xy[2 * i] = model_.points[i].position.x();
    fixed_xy[2 * i + 1] = model_.points[i].position.y();
  }
  equations.entry.assign(rows.size(), {-1, -1, -1, -1});
  compiled.assign(rows.size(), CompiledRow{});
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const Constraint& c = rows[r];
    CompiledRow& k = compiled[r];
    k.type = c.type;
    k.row = static_cast<int>(r);
    k.driver = c.driver;
    k.a = c.a;
    k.b = c.b;
    k.scale = c.scale;
    for (int slot = 0; slot < 4; ++slot) {
      const int p = c.p[slot];
      if (p < 0) continue;
      k.at[slot] = column_[p] >= 0 ? column_[p] : ~(2 * p);
      if (column_[p] < 0) continue;
      equations.entry[r][slot] = k.entry[slot] = static_cast<int>(pattern.size());
      pattern.push_back({static_cast<int>(r), column_[p]});
      pattern.push_back({static_cast<int>(r), column_[p] + 1});
    }
  }
  const auto fixed_points = [](const CompiledRow& c) {
    if (c.type != ConstraintType::Distance && c.type != ConstraintType::DriveAngle) return 0;
    return (c.at[0] < 0 ? 1 : 0) | (c.at[1] < 0 ? 2 : 0);
  };
  std::stable_sort(compiled.begin(), compiled.end(), [&](const CompiledRow& a, const CompiledRow& b) {
    return a.type != b.type ? a.type < b.type : fixed_points(a) < fixed_points(b);
  });
  std::vector<RowGroup>& groups = equations.groups;
  groups.clear();
  for (std::size_t r = 0; r < compiled.size(); ++r) {
    const int fixed = fixed_points(compiled[r]);
    if (groups.empty() || groups.back().type != compiled[r].type || groups.back().fixed != fixed)
      groups.push_back({compiled[r].type, fixed, static_cast<int>(r), static_cast<int>(r)});
    groups.back().last = static_cast<int>(r) + 1;
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

namespace {

// Places where a body is joined to the rest: points it shares with the ground or other bodies,
// sliders on it, slots its points run in.
std::vector<std::string> joint_places(const Model& model, int body) {
  std::vector<std::string> places;
  for (int p : model.bodies[body].points) {
    bool shared = model.points[p].ground;
    for (std::size_t o = 0; o < model.bodies.size() && !shared; ++o)
      if (static_cast<int>(o) != body)
        shared =
            std::find(model.bodies[o].points.begin(), model.bodies[o].points.end(), p) != model.bodies[o].points.end();
    if (shared) places.push_back(model.points[p].name);
  }
  for (const Slider& s : model.sliders)
    if (s.body == body) places.push_back("slider at " + model.points[s.point].name);
  for (const Slot& s : model.slots)
    if (std::find(model.bodies[body].points.begin(), model.bodies[body].points.end(), s.point) !=
        model.bodies[body].points.end())
      places.push_back("slot at " + model.points[s.point].name);
  return places;
}

// Where there are more drivers than degrees of freedom, the row most likely put on by mistake:
// the first that depends on the rows before it (Gram-Schmidt). When the joints alone lock the
// mechanism (`drivers_first`), the rows are taken drivers first, then the constraints in the
// model's order, and the row found is a constraint (a slider on the wrong body...); otherwise
// the constraints come first, their own redundancies are passed over, and the row is a driver.
int first_dependent_row(const Eigen::MatrixXd& J, int constraint_rows, bool drivers_first) {
  std::vector<int> order;
  for (int c = 0; c < constraint_rows; ++c) order.push_back(c);
  for (int d = constraint_rows; d < static_cast<int>(J.rows()); ++d)
    order.insert(drivers_first ? order.begin() + (d - constraint_rows) : order.end(), d);
  std::vector<Eigen::VectorXd> basis;
  for (int row : order) {
    Eigen::VectorXd v = J.row(row).transpose();
    const double norm = v.norm();
    if (!(norm > 0.0)) continue;  // a row that touches no moving point
    for (int pass = 0; pass < 2; ++pass)
      for (const Eigen::VectorXd& b : basis) v -= b.dot(v) * b;
    if (v.norm() <= kRankTolerance * norm) {
      if (drivers_first || row >= constraint_rows) return row;
      continue;  // a redundant constraint, as in a parallelogram with a third crank
    }
    basis.push_back(v / v.norm());
  }
  return -1;
}

// The body that moves when the drivers are held: of those the null space of every row moves,
// the one joined to the rest at the fewest places (the last such in the model), or -1.
int free_body(const Eigen::MatrixXd& J, const Model& model, const std::vector<int>& column) {
  Eigen::FullPivLU<Eigen::MatrixXd> lu(J);
  lu.setThreshold(kRankTolerance);
  const Eigen::MatrixXd kernel = lu.kernel();
  if (kernel.cols() == 0 || kernel.isZero()) return -1;
  int best = -1, best_joints = 0;
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    double moves = 0.0;
    for (int p : model.bodies[b].points)
      if (column[p] >= 0) moves = std::max(moves, kernel.middleRows(column[p], 2).norm());
    if (moves <= 1e-6 * kernel.norm()) continue;
    const int joints = static_cast<int>(joint_places(model, static_cast<int>(b)).size());
    if (best < 0 || joints <= best_joints) {
      best = static_cast<int>(b);
      best_joints = joints;
    }
  }
  return best;
}

std::string joints_of(const Model& model, int body) {
  const std::vector<std::string> places = joint_places(model, body);
  if (places.empty()) return "it is joined to nothing";
  std::string s = "it is joined to the rest only at ";
  for (std::size_t i = 0; i < places.size(); ++i)
    s += (i == 0 ? "" : i + 1 == places.size() ? " and " : ", ") + places[i];
  return s;
}

// Whether a sparse LU of the square Jacobian (its `values` on `pattern`) succeeds: then it is
// regular, of full rank.
bool sparse_lu_regular(const std::vector<JacobianEntry>& pattern, const std::vector<double>& values, int m, int n) {
  Eigen::SparseMatrix<double> J(m, n);
  std::vector<Eigen::Triplet<double>> t;
  for (std::size_t e = 0; e < pattern.size(); ++e) t.emplace_back(pattern[e].row, pattern[e].col, values[e]);
  J.setFromTriplets(t.begin(), t.end());
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
  lu.compute(J);
  return lu.info() == Eigen::Success;
}

// The dof differs from the number of drivers: says why, naming the body left free or the row
// (a constraint or a driver) most likely put on by mistake.
[[noreturn]] void refuse_driver_count(const Mechanism& mech, const std::vector<int>& column, const Eigen::MatrixXd& J,
                                      const MobilityReport& r, int drivers_count) {
  const Model& model = mech.model();
  const std::string counts = "the mechanism has " + std::to_string(r.dof) + " degree" + (r.dof == 1 ? "" : "s") +
                             " of freedom (Gruebler-Kutzbach count: " + std::to_string(r.grubler) + ") but " +
                             std::to_string(drivers_count) + " driver" + (drivers_count == 1 ? " is" : "s are") +
                             " given";
  if (r.grubler == drivers_count)
    throw ModelError({EntityRef::Kind::Model, -1},
                     counts +
                         "; the drawn pose may be a singular (toggle or flat) position: draw the mechanism "
                         "in a general pose");
  if (drivers_count < r.dof) {
    const int body = drivers_count > 0 ? free_body(J, model, column) : -1;
    if (body >= 0)
      throw ModelError({EntityRef::Kind::Body, body},
                       counts + "; body '" + model.bodies[body].name + "' can still move with the drivers held (" +
                           joints_of(model, body) +
                           "): give it a joint, a slider or a driver, or add one driver per free input");
    throw ModelError({EntityRef::Kind::Model, -1}, counts + "; add one driver per free input");
  }
  // Joints that lock the mechanism by themselves: a constraint is at fault; otherwise a driver.
  const int row = first_dependent_row(J, r.constraint_rows, r.dof == 0);
  if (row >= 0) {
    const Constraint& c = mech.equations().rows[row];
    std::string why;
    if (c.is_driver())
      why = "driver '" + model.drivers[c.driver].name +
            "' moves what the joints and the drivers before it already fix: remove it";
    else
      why = "'" + c.label + "' is already fixed by the drivers and the joints before it: " +
            (c.source.kind == EntityRef::Kind::Slider ? std::string("is the slider on the right body?")
             : c.source.kind == EntityRef::Kind::Slot
                 ? std::string("is the slot where it should be?")
                 : "is a joint of body '" + model.bodies[c.source.index].name + "' too many?") +
            " (or remove drivers)";
    throw ModelError(c.source, counts + "; " + why);
  }
  throw ModelError({EntityRef::Kind::Model, -1}, counts + "; remove drivers, or check for missing joints");
}

// With the right number of drivers, Phi_q must still have full column rank: else the first
// driver whose row depends on the constraints and the drivers before it is at fault.
void check_drivers_independent(const Model& model, const Eigen::MatrixXd& J, int constraint_rows, int constraint_rank) {
  const int drivers_count = static_cast<int>(model.drivers.size());
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> full(J.transpose());
  full.setThreshold(kRankTolerance);
  if (full.rank() < J.cols()) {
    for (int d = 0; d < drivers_count; ++d) {
      Eigen::ColPivHouseholderQR<Eigen::MatrixXd> partial(J.topRows(constraint_rows + d + 1).transpose());
      partial.setThreshold(kRankTolerance);
      if (partial.rank() < constraint_rank + d + 1)
        throw ModelError({EntityRef::Kind::Driver, d},
                         "driver '" + model.drivers[d].name +
                             "' does not move the mechanism independently: what it drives is already fixed by the "
                             "joints or by the other drivers");
    }
  }
}

// The reciprocal condition of Phi_q: LU's estimate when square, else the ratio of the extreme
// singular values.
double reciprocal_condition(const Eigen::MatrixXd& J) {
  if (J.rows() == J.cols()) {
    Eigen::PartialPivLU<Eigen::MatrixXd> lu(J);
    return lu.rcond();
  }
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(J);
  const auto& s = svd.singularValues();
  return s(0) > 0 ? s(s.size() - 1) / s(0) : 0.0;
}

}  // namespace

std::string Mechanism::mobility_counts(bool at_least) const {
  const MobilityReport& r = mobility_;
  const int drivers = static_cast<int>(model_.drivers.size());
  return "the mechanism has " + std::string(at_least ? "at least " : "") + std::to_string(r.dof) + " degree" +
         (r.dof == 1 ? "" : "s") + " of freedom (Gruebler-Kutzbach count: " + std::to_string(r.grubler) + ") but " +
         std::to_string(drivers) + " driver" + (drivers == 1 ? " is" : "s are") + " given";
}

// Large models: every factorisation sparse. The constraint rows alone give the rank and the
// redundant rows; then the driven system must have full column rank.
void Mechanism::analyse_mobility_sparse(const std::vector<double>& values) {
  MobilityReport& r = mobility_;
  const int drivers = static_cast<int>(model_.drivers.size());
  // The rank is at most the number of constraint rows: too few drivers shows in the counts,
  // before any factorisation.
  if (check_drivers_ && n_ - constraint_rows_ > drivers) {
    r.dof = n_ - constraint_rows_;
    throw ModelError({EntityRef::Kind::Model, -1}, mobility_counts(true) + "; add one driver per free input");
  }
  using Sparse = Eigen::SparseMatrix<double>;
  const auto transposed = [&](int rows) {
    // Phi_q^T: columns are rows of Phi_q, so that the pivoting picks independent rows.
    Sparse jt(n_, rows);
    std::vector<Eigen::Triplet<double>> t;
    const std::vector<JacobianEntry>& pattern = equations_->pattern;
    for (std::size_t e = 0; e < pattern.size(); ++e)
      if (pattern[e].row < rows) t.emplace_back(pattern[e].col, pattern[e].row, values[e]);
    jt.setFromTriplets(t.begin(), t.end());
    jt.makeCompressed();
    return jt;
  };
  Eigen::SparseQR<Sparse, Eigen::COLAMDOrdering<int>> qr;
  qr.setPivotThreshold(kRankTolerance);
  qr.compute(transposed(constraint_rows_));
  r.rank = constraint_rows_ == 0 ? 0 : static_cast<int>(qr.rank());
  r.dof = n_ - r.rank;
  const auto& perm = qr.colsPermutation().indices();
  for (int c = r.rank; c < constraint_rows_; ++c) r.redundant.push_back(perm[c]);
  std::sort(r.redundant.begin(), r.redundant.end());
  if (!check_drivers_) return;
  if (r.dof != drivers) {
    throw ModelError({EntityRef::Kind::Model, -1},
                     mobility_counts(false) + (drivers < r.dof ? "; add one driver per free input"
                                                               : "; remove drivers, or check for missing joints"));
  }
  Eigen::SparseQR<Sparse, Eigen::COLAMDOrdering<int>> full;
  full.setPivotThreshold(kRankTolerance);
  full.compute(transposed(row_count()));
  if (full.rank() < n_)
    throw ModelError({EntityRef::Kind::Model, -1},
                     "the drivers do not move the mechanism independently: what one drives is already fixed by the "
                     "joints or by the other drivers");
  r.reciprocal_condition = 1.0;  // not estimated for sparse systems
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

  // Large square systems: a regular sparse LU proves full rank, hence no redundancy.
  if (n_ > kDenseAnalysisLimit && m == n_ && sparse_lu_regular(equations_->pattern, values, m, n_)) {
    r.rank = constraint_rows_;
    r.dof = n_ - constraint_rows_;
    r.reciprocal_condition = 1.0;  // not estimated for sparse systems
    return;
  }

  if (n_ > kDenseRankLimit) {
    analyse_mobility_sparse(values);
    return;
  }

  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(m, n_);
  const std::vector<JacobianEntry>& pattern = equations_->pattern;
  for (std::size_t e = 0; e < pattern.size(); ++e) J(pattern[e].row, pattern[e].col) += values[e];

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

  if (!check_drivers_) return;
  if (r.dof != drivers_count) refuse_driver_count(*this, column_, J, r, drivers_count);
  check_drivers_independent(model_, J, constraint_rows_, r.rank);
  r.reciprocal_condition = reciprocal_condition(J);
}

}  // namespace nbar
