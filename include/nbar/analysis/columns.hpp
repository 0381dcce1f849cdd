// The column catalogue: every column an analysis of a mechanism can give, with its unit, the
// stage that computes it and the derivative order it needs, so that a front-end asking for
// columns by name or glob (`nbar plot --y`, the web UI, Python) learns which stages to run
// without solving anything.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "nbar/kinematics/mechanism.hpp"
#include "nbar/kinematics/table.hpp"

namespace nbar {

enum class Stage { Sweep, Dynamics, Stress };

struct ColumnInfo {
  std::string name, unit;
  Stage stage = Stage::Sweep;
  int order = 0;  // the sweep order the column needs (dynamics columns need 2)
};

// In table order: the kinematic columns up to `max_order`, then, when `with_dynamics`, the
// inverse-dynamics columns.
std::vector<ColumnInfo> column_catalogue(const Mechanism& mechanism, int max_order = 5, bool with_dynamics = true);

std::vector<std::string> column_names(const std::vector<ColumnInfo>& columns);

// Every column a table can have on request: the centre of mass of every body with mass, as the
// riding point B.cg (columns B.cg.x, B.cg.y, B.cg.vx, ... as a point's), and `cond`.
ColumnsOnRequest every_column_on_request(const Mechanism& mechanism);
// Those that `patterns` name: a pattern that matches no ordinary column (kinematic, of any order,
// or dynamic) asks for the columns on request it matches ("coupler.cg.*", "*.cg.x", "cond"), and
// the others are left out of the table; a pattern such as "coupler.*" asks for none of them.
ColumnsOnRequest columns_on_request(const Mechanism& mechanism, const std::vector<std::string>& patterns);

// Whether a column name matches a pattern: an exact name, or a glob with '*'.
bool column_matches(const std::string& pattern, const std::string& name);

// What a request for columns needs. A pattern that matches only dynamics columns switches
// dynamics on; the columns on request count as there (but are not listed in `message`); without a given order, the
// lowest order from 2 up that has every kinematic pattern's columns. `unmatched` is the index of the first pattern that
// matches no column the analysis would then have (-1 when all match), and `message` says so and lists them.
struct ColumnNeeds {
  int order = 2;
  bool dynamics = false;
  bool condition = false;  // a pattern asks for `cond`: AnalysisOptions::condition
  int unmatched = -1;
  std::string message;
};
ColumnNeeds column_needs(const Mechanism& mechanism, const std::vector<std::string>& patterns,
                         std::optional<int> order = std::nullopt, bool dynamics = false);

// The column results are best plotted against by default: time, `t`, for a sweep in time (a
// driver with a time law) or a model without drivers; otherwise the first driver's column.
std::string default_abscissa(const Model& model);

}  // namespace nbar
