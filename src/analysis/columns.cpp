#include "nbar/analysis/columns.hpp"

#include <algorithm>
#include <unordered_map>

#include "nbar/dynamics/dynamics_table.hpp"
#include "nbar/dynamics/inverse_dynamics.hpp"
#include "nbar/kinematics/table.hpp"

namespace nbar {

namespace {

std::vector<ColumnInfo> kinematic_columns(const Mechanism& mech, int order, const ColumnsOnRequest& extra = {}) {
  SweepResult empty;
  empty.order = order;
  const ResultTable table = make_table(mech, empty, extra);
  std::unordered_map<std::string, std::size_t> index;
  std::vector<ColumnInfo> out;
  for (std::size_t c = 0; c < table.columns.size(); ++c) {
    index.emplace(table.columns[c], c);
    out.push_back({table.columns[c], table.units[c], Stage::Sweep, order});
  }
  // A column's order is the lowest at which the table has it.
  for (int k = order - 1; k >= 0; --k) {
    empty.order = k;
    for (const std::string& name : make_table(mech, empty, extra).columns) out[index.at(name)].order = k;
  }
  return out;
}

std::vector<ColumnInfo> dynamic_columns(const Mechanism& mech) {
  // A non-owning pointer: the solver lives only in this function, while `mech` is alive.
  const InverseDynamics structure(std::shared_ptr<const Mechanism>(std::shared_ptr<const void>(), &mech));
  std::vector<ColumnInfo> out;
  for (const ColumnName& c : dynamics_columns(structure)) out.push_back({c.name, c.unit, Stage::Dynamics, 2});
  return out;
}

bool any_matches(const std::vector<std::string>& names, const std::string& pattern) {
  return std::any_of(names.begin(), names.end(), [&](const std::string& n) { return column_matches(pattern, n); });
}

// The names of only the columns on request of `extra`, at `order`.
std::vector<std::string> names_on_request(const Mechanism& mech, int order, const ColumnsOnRequest& extra) {
  const KinematicRows rows(mech, order, extra);
  std::vector<std::string> columns, units, out;
  rows.name_columns(columns, units);
  const std::vector<bool> flags = rows.on_request();
  for (std::size_t c = 0; c < columns.size(); ++c)
    if (flags[c]) out.push_back(columns[c]);
  return out;
}

std::string join(const std::vector<std::string>& items) {
  std::string s;
  for (std::size_t i = 0; i < items.size(); ++i) s += (i ? ", " : "") + items[i];
  return s;
}

}  // namespace

std::vector<ColumnInfo> column_catalogue(const Mechanism& mech, int max_order, bool with_dynamics) {
  check_derivative_order(max_order);
  std::vector<ColumnInfo> out = kinematic_columns(mech, max_order);
  if (with_dynamics) {
    const std::vector<ColumnInfo> dynamic = dynamic_columns(mech);
    out.insert(out.end(), dynamic.begin(), dynamic.end());
  }
  return out;
}

ColumnsOnRequest every_column_on_request(const Mechanism& mech) {
  const Model& m = mech.model();
  ColumnsOnRequest extra;
  for (std::size_t b = 0; b < m.bodies.size(); ++b) {
    const MassProperties mass = mass_properties(m.bodies[b]);
    if (!(mass.mass > 0.0)) continue;
    // The centre of mass in the body's frame, as the inverse dynamics places it (BodyMotion::point).
    const BodyFrame frame = body_frame(m, static_cast<int>(b));
    RidingPoint cg{m.bodies[b].name + ".cg", frame.origin, frame.origin, frame.origin, 0.0, 0.0};
    const Eigen::Vector2d offset = mass.cg - m.points[frame.origin].position;
    if (frame.from >= 0) {
      const Eigen::Vector2d direction = m.points[frame.to].position - m.points[frame.from].position;
      cg.from = frame.from;
      cg.to = frame.to;
      cg.along = offset.dot(direction) / direction.squaredNorm();
      cg.across = (direction.x() * offset.y() - direction.y() * offset.x()) / direction.squaredNorm();
    }
    extra.points.push_back(std::move(cg));
  }
  extra.design_transmission = !mech.four_bar_loops().empty();
  extra.condition = true;
  return extra;
}

ColumnsOnRequest columns_on_request(const Mechanism& mech, const std::vector<std::string>& patterns) {
  ColumnsOnRequest asked;
  if (patterns.empty()) return asked;
  std::vector<std::string> ordinary = column_names(kinematic_columns(mech, kMaxDerivativeOrder));
  for (const std::string& name : column_names(dynamic_columns(mech))) ordinary.push_back(name);
  std::vector<std::string> open;  // the patterns that may ask for columns on request
  for (const std::string& p : patterns)
    if (!any_matches(ordinary, p)) open.push_back(p);
  if (open.empty()) return asked;
  // Whether an open pattern names any of the columns `only` gives.
  const auto asks_for = [&](const ColumnsOnRequest& only) {
    const std::vector<std::string> names = names_on_request(mech, kMaxDerivativeOrder, only);
    return std::any_of(open.begin(), open.end(), [&](const std::string& p) { return any_matches(names, p); });
  };
  const ColumnsOnRequest every = every_column_on_request(mech);
  for (const RidingPoint& point : every.points)
    if (asks_for({{point}, false, false})) asked.points.push_back(point);
  asked.design_transmission = every.design_transmission && asks_for({{}, true, false});
  asked.condition = asks_for({{}, false, true});
  return asked;
}

std::vector<std::string> column_names(const std::vector<ColumnInfo>& columns) {
  std::vector<std::string> names;
  for (const ColumnInfo& c : columns) names.push_back(c.name);
  return names;
}

bool column_matches(const std::string& pattern, const std::string& name) { return glob_match(pattern, name); }

std::string default_abscissa(const Model& model) {
  // A rocking input goes back and forth: against time its oscillation shows.
  const bool rocks = !model.drivers.empty() && model.drivers[0].at_limits == AtLimits::Reverse;
  return model.drivers.empty() || model.has_time_law() || rocks ? std::string("t") : model.drivers[0].name;
}

ColumnNeeds column_needs(const Mechanism& mech, const std::vector<std::string>& patterns, std::optional<int> order,
                         bool dynamics) {
  if (order) check_derivative_order(*order);
  const ColumnsOnRequest extra = every_column_on_request(mech);
  const std::vector<std::string> all_kinematic = column_names(kinematic_columns(mech, kMaxDerivativeOrder, extra));
  const std::vector<std::string> dynamic = column_names(dynamic_columns(mech));
  ColumnNeeds needs;
  needs.dynamics = dynamics;
  std::vector<std::string> kinematic_patterns;
  for (const std::string& p : patterns) {
    if (!any_matches(all_kinematic, p) && any_matches(dynamic, p))
      needs.dynamics = true;
    else
      kinematic_patterns.push_back(p);
  }
  needs.order = order.value_or(2);
  if (!order) {
    for (int k = 2; k <= kMaxDerivativeOrder; ++k) {
      const std::vector<std::string> names = column_names(kinematic_columns(mech, k, extra));
      if (std::all_of(kinematic_patterns.begin(), kinematic_patterns.end(),
                      [&](const std::string& p) { return any_matches(names, p); })) {
        needs.order = k;
        break;
      }
    }
  }
  if (needs.dynamics) needs.order = std::max(needs.order, 2);
  std::vector<std::string> available = column_names(kinematic_columns(mech, needs.order));
  if (needs.dynamics) available.insert(available.end(), dynamic.begin(), dynamic.end());
  const std::vector<std::string> on_request = names_on_request(mech, needs.order, extra);
  needs.condition = columns_on_request(mech, patterns).condition;
  for (std::size_t i = 0; i < patterns.size(); ++i) {
    if (any_matches(available, patterns[i]) || any_matches(on_request, patterns[i])) continue;
    needs.unmatched = static_cast<int>(i);
    std::vector<std::string> every = available;
    if (!needs.dynamics) every.insert(every.end(), dynamic.begin(), dynamic.end());
    needs.message = no_column_message(patterns[i], every) + "; the columns are: " + join(available);
    if (!needs.dynamics && !dynamic.empty()) needs.message += "; with inverse dynamics also: " + join(dynamic);
    break;
  }
  return needs;
}

}  // namespace nbar
