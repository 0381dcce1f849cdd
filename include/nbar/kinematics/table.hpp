// The sweep as a table of named columns in the model's units: the one shape every front-end
// (CSV, JSON, web, Python) shows, so column names and units are decided in one place.
#pragma once

#include <Eigen/Core>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "nbar/kinematics/sweep.hpp"

namespace nbar {

struct ResultTable {
  std::vector<std::string> columns;
  std::vector<std::string> units;  // per column: "mm", "deg/s^2", "s", "" for counts
  std::vector<std::vector<double>> rows;
  // Per column, whether it is one of the columns given only on request (ColumnsOnRequest); empty,
  // or shorter than `columns`, means the rest are not. Such a column is chosen only by a pattern
  // that matches no other column, and does not move the noise threshold of the others.
  std::vector<bool> on_request;
  // What the table is of, when that is not the sweep: "sections of coupler at step 90 (...)".
  // The text table prints it first and JSON has it as "title"; CSV leaves it out.
  std::string title;
};

// A point fixed to a body that only rides along (a centre of mass): where it is follows from
// the body's frame, origin + along * (to - from) + across * perp(to - from), with the frame's
// points' series, so it costs the solve nothing and cannot change it.
struct RidingPoint {
  std::string name;  // its columns are name.x, name.y, name.vx, ...
  int origin = -1, from = -1, to = -1;
  double along = 0.0, across = 0.0;
};

// Columns a table has only when asked for (analysis/columns.hpp decides from the names asked):
// riding points' columns, as a point's, and `cond`, the condition number of the constraint
// Jacobian at each sample (1 / Sample::reciprocal_condition, the solver's own estimate).
struct ColumnsOnRequest {
  std::vector<RidingPoint> points;
  // Per four-bar loop, <loop>.mu_design: min(mu, pi - mu), how far the loop is from a dead point at
  // that sample; its smallest value over the sweep is the loop's design value (0..90 deg, where
  // the .mu column runs 0..180 deg and its minimum is not the design value when mu passes 90 deg).
  bool design_transmission = false;
  bool condition = false;
  bool empty() const { return points.empty() && !design_transmission && !condition; }
};

// step, t, one column per driver, then for every point (but a guide's direction point) P.x, P.y, P.vx, P.vy, P.ax,
// P.ay, P.jx, P.jy, P.d4x, ... up to the sweep's order, then for every body with an angle B.angle, B.omega, B.alpha,
// B.jerk, B.d4, B.d5 (the angle unwrapped over the sweep), then the transmission angle of every four-bar loop as
// <input>-<coupler>-<output>.mu; then the columns on request: every riding point's as a point's, every loop's
// <loop>.mu_design, and `cond`.
ResultTable make_table(const Mechanism& mech, const SweepResult& sweep, const ColumnsOnRequest& extra = {});

// Those columns for one sample at a time, handed the sweep's samples in order (each body's
// angle is unwrapped against the sample before): what make_table fills its rows with, and what
// writers use to stream a sweep that is not kept. Value j of a row goes to out[j * stride].
// Nothing is allocated per sample.
class KinematicRows {
 public:
  KinematicRows(const Mechanism& mech, int order, ColumnsOnRequest extra = {});
  void name_columns(std::vector<std::string>& columns, std::vector<std::string>& units) const;
  // Per column, as ResultTable::on_request.
  std::vector<bool> on_request() const;
  std::size_t column_count() const;
  void fill(const Sample& sample, double* out, std::ptrdiff_t stride = 1);

 private:
  std::size_t own_column_count() const;
  void fill_on_request(const Sample& sample, double* out, std::ptrdiff_t stride);
  double condition_of(const Sample& sample);

  const Mechanism& mech_;
  int order_;
  ColumnsOnRequest extra_;
  std::vector<int> shown_;  // every point but those that only give a guide its direction
  std::vector<int> angled_;
  std::vector<double> previous_;
  std::vector<bool> started_;
  bool first_done_ = false;
  bool rocks_ = false;  // a rocking driver: a column counts the reversals
  std::vector<Eigen::Vector2d> positions_;
  std::vector<double> mu_;  // each loop's transmission angle at the sample filled last, rad
  Eigen::VectorXd q_;
  std::shared_ptr<State> condition_state_;  // for `cond` of samples the sweep did not estimate
};

// The same columns stored column by column, every column contiguous (samples x columns,
// column-major): what front-ends hand out without copying (Python's numpy arrays).
struct ColumnTable {
  std::vector<std::string> columns;
  std::vector<std::string> units;
  Eigen::MatrixXd values;
  std::vector<bool> on_request;  // as ResultTable::on_request
};
ColumnTable make_column_table(const Mechanism& mech, const SweepResult& sweep, const ColumnsOnRequest& extra = {});
// Numerical noise made exact: a value whose size is at most kNoiseRelative times the largest
// size of any value of the same unit in the table (every column in mm/s, every column in
// deg/s^2, every force in N, ...) over the sweep becomes 0 (the columns on request count only
// for themselves and each other, so asking for them leaves every other value as it was). The position solve stops at
// that relative tolerance (Mechanism::tolerance is 1e-12 of the model's size) and what is smaller cannot be told from
// 0: the 5e-11 mm/s a piston's velocity has at dead centre, or the 4e-16 deg/s^2 of a crank turning at constant speed.
// Unitless columns (step) are left alone. The scale is per unit rather than per column, so that a column that is 0
// throughout (a crank's alpha) is measured against the other columns of its unit, not against its own noise.
constexpr double kNoiseRelative = 1e-12;
void zero_numerical_noise(ResultTable& table);
void zero_numerical_noise(ColumnTable& table);

// The columns matching `patterns` (as select_columns), in the order of the patterns.
ColumnTable select_columns(const ColumnTable& table, const std::vector<std::string>& patterns);

// The columns matching any of `patterns` (exact names, or globs with '*' such as
// "rocker.*"), in the order of the patterns. Throws Error(ErrorKind::BadInput) naming a pattern
// that matches nothing. A pattern that matches any column not on request picks only those
// ("rocker.*" stays rocker's angles); one that matches none picks the columns on request it
// matches ("rocker.cg.*", "*.cg.x", "cond").
ResultTable select_columns(const ResultTable& table, const std::vector<std::string>& patterns);
// The indices of those columns among `columns` (`on_request` as ResultTable's).
std::vector<std::size_t> pick_columns(const std::vector<std::string>& columns, const std::vector<std::string>& patterns,
                                      const std::vector<bool>& on_request = {});

// Whether `text` matches `pattern`, where '*' stands for any run of characters.
bool glob_match(const std::string& pattern, const std::string& text);

// For a pattern that matches no column: the first column it matches when case is ignored
// ("C.X" -> "C.x", "Crank.*" -> "crank.angle"), or nothing.
std::optional<std::string> column_suggestion(const std::string& pattern, const std::vector<std::string>& columns);
// "no column matches 'C.X'", plus " (did you mean 'C.x'?)" when column_suggestion has one.
std::string no_column_message(const std::string& pattern, const std::vector<std::string>& columns);

}  // namespace nbar
