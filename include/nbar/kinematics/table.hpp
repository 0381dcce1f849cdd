// The sweep as a table of named columns in the model's units: the one shape every front-end
// (CSV, JSON, web, Python) shows, so column names and units are decided in one place.
#pragma once

#include <Eigen/Core>

#include <string>
#include <vector>

#include "nbar/kinematics/sweep.hpp"

namespace nbar {

struct ResultTable {
  std::vector<std::string> columns;
  std::vector<std::string> units;  // per column: "mm", "deg/s^2", "s", "" for counts
  std::vector<std::vector<double>> rows;
};

// step, t, one column per driver, then for every point P.x, P.y, P.vx, P.vy, P.ax, P.ay,
// P.jx, P.jy, P.d4x, ... up to the sweep's order, then for every body with an angle
// B.angle, B.omega, B.alpha, B.jerk, B.d4, B.d5 (the angle unwrapped over the sweep), then
// the transmission angle of every four-bar loop as <input>-<coupler>-<output>.mu.
ResultTable make_table(const Mechanism& mech, const SweepResult& sweep);

// The same columns stored column by column, every column contiguous (samples x columns,
// column-major): what front-ends hand out without copying (Python's numpy arrays).
struct ColumnTable {
  std::vector<std::string> columns;
  std::vector<std::string> units;
  Eigen::MatrixXd values;
};
ColumnTable make_column_table(const Mechanism& mech, const SweepResult& sweep);
// The columns matching `patterns` (as select_columns), in the order of the patterns.
ColumnTable select_columns(const ColumnTable& table, const std::vector<std::string>& patterns);

// The columns matching any of `patterns` (exact names, or globs with '*' such as
// "rocker.*"), in the order of the patterns. Throws std::invalid_argument naming a pattern
// that matches nothing.
ResultTable select_columns(const ResultTable& table, const std::vector<std::string>& patterns);

// Whether `text` matches `pattern`, where '*' stands for any run of characters.
bool glob_match(const std::string& pattern, const std::string& text);

}  // namespace nbar
