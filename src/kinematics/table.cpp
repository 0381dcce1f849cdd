#include "nbar/kinematics/table.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <stdexcept>

#include "constraints.hpp"
#include "nbar/model/diagnostics.hpp"
#include "rocking.hpp"
#include "workspace.hpp"

namespace nbar {

namespace {

const char* const kPointSuffix[] = {"", "v", "a", "j", "d4", "d5"};
const char* const kAngleName[] = {"angle", "omega", "alpha", "jerk", "d4", "d5"};

std::string per_time(const std::string& unit, int order) {
  if (order == 0) return unit;
  if (order == 1) return unit + "/s";
  return unit + "/s^" + std::to_string(order);
}

// The multiple of 2 pi that brings `angle` closest to `reference`.
double unwrap(double angle, double reference) {
  const double two_pi = 2.0 * std::numbers::pi;
  return angle + two_pi * std::round((reference - angle) / two_pi);
}

}  // namespace

KinematicRows::KinematicRows(const Mechanism& mech, int order, ColumnsOnRequest extra)
    : mech_(mech), order_(order), extra_(std::move(extra)) {
  const Model& m = mech.model();
  for (std::size_t b = 0; b < m.bodies.size(); ++b)
    if (m.bodies[b].points.size() >= 2) angled_.push_back(static_cast<int>(b));
  for (std::size_t p = 0; p < m.points.size(); ++p)
    if (!m.points[p].guide_direction) shown_.push_back(static_cast<int>(p));
  previous_.assign(m.bodies.size(), 0.0);
  started_.assign(m.bodies.size(), false);
  positions_.resize(m.points.size());
  mu_.resize(mech.four_bar_loops().size());
  rocks_ =
      std::any_of(m.drivers.begin(), m.drivers.end(), [](const Driver& d) { return d.at_limits == AtLimits::Reverse; });
}

void KinematicRows::name_columns(std::vector<std::string>& columns, std::vector<std::string>& units) const {
  const Model& m = mech_.model();
  const Units& u = m.units;
  auto add = [&](std::string name, std::string unit) {
    columns.push_back(std::move(name));
    units.push_back(std::move(unit));
  };
  auto add_point = [&](const std::string& name) {
    for (int k = 0; k <= order_; ++k) {
      add(name + "." + kPointSuffix[k] + "x", per_time(u.length, k));
      add(name + "." + kPointSuffix[k] + "y", per_time(u.length, k));
    }
  };
  add("step", "");
  add("t", "s");
  for (const Driver& d : m.drivers) add(d.name, d.is_angular() ? u.angle : u.length);
  if (rocks_) add("reversals", "");
  for (int p : shown_) add_point(m.points[p].name);
  for (int b : angled_)
    for (int k = 0; k <= order_; ++k) add(m.bodies[b].name + "." + kAngleName[k], per_time(u.angle, k));
  for (const FourBarLoop& loop : mech_.four_bar_loops()) add(loop.name + ".mu", u.angle);
  for (const RidingPoint& p : extra_.points) add_point(p.name);
  if (extra_.design_transmission)
    for (const FourBarLoop& loop : mech_.four_bar_loops()) add(loop.name + ".mu_design", u.angle);
  if (extra_.condition) add("cond", "");
}

std::size_t KinematicRows::own_column_count() const {
  const Model& m = mech_.model();
  return 2 + m.drivers.size() + (rocks_ ? 1 : 0) + 2 * (order_ + 1) * shown_.size() + (order_ + 1) * angled_.size() +
         mech_.four_bar_loops().size();
}

std::size_t KinematicRows::column_count() const {
  return own_column_count() + 2 * (order_ + 1) * extra_.points.size() +
         (extra_.design_transmission ? mech_.four_bar_loops().size() : 0) + (extra_.condition ? 1 : 0);
}

std::vector<bool> KinematicRows::on_request() const {
  std::vector<bool> flags(column_count(), true);
  std::fill_n(flags.begin(), own_column_count(), false);
  return flags;
}

void KinematicRows::fill(const Sample& s, double* out, std::ptrdiff_t stride) {
  const Model& m = mech_.model();
  const Units& u = m.units;
  if (!first_done_) {
    // A body driven by an absolute angle starts at its driver's value, not at atan2's range.
    for (std::size_t d = 0; d < m.drivers.size(); ++d) {
      const Driver& drv = m.drivers[d];
      if (drv.kind == DriverKind::Angle && drv.relative_to < 0) {
        previous_[drv.body] = s.driver_values[d];
        started_[drv.body] = true;
      }
    }
    first_done_ = true;
  }
  std::ptrdiff_t j = 0;
  auto put = [&](double v) { out[stride * j++] = v; };
  put(s.step);
  put(s.time);
  for (std::size_t d = 0; d < m.drivers.size(); ++d)
    put(s.driver_values[d] / (m.drivers[d].is_angular() ? u.angle_scale : u.length_scale));
  if (rocks_) put(s.reversals);
  std::array<double, Series::kCapacity> x{}, y{};
  for (int p : shown_) {
    point_derivatives(mech_, s, p, x.data(), y.data());
    for (int k = 0; k <= order_; ++k) {
      put(x[k] / u.length_scale);
      put(y[k] / u.length_scale);
    }
  }
  for (int b : angled_) {
    body_angle_derivatives(mech_, s, b, x.data());
    if (s.body_angles.size() > static_cast<std::size_t>(b))
      x[0] = unwrap(x[0], s.body_angles[b]);  // the turns its maker followed
    else if (started_[b])
      x[0] = unwrap(x[0], previous_[b]);
    previous_[b] = x[0];
    started_[b] = true;
    for (int k = 0; k <= order_; ++k) put(x[k] / u.angle_scale);
  }
  if (!mech_.four_bar_loops().empty()) {
    q_ = s.taylor.col(0);
    for (std::size_t i = 0; i < positions_.size(); ++i) positions_[i] = mech_.point_position(static_cast<int>(i), q_);
    for (std::size_t l = 0; l < mu_.size(); ++l) {
      mu_[l] = transmission_angle(mech_.four_bar_loops()[l], positions_);
      put(mu_[l] / u.angle_scale);
    }
  }
  fill_on_request(s, out + stride * j, stride);
}

void KinematicRows::fill_on_request(const Sample& s, double* out, std::ptrdiff_t stride) {
  const double length_scale = mech_.model().units.length_scale;
  std::ptrdiff_t j = 0;
  auto put = [&](double v) { out[stride * j++] = v; };
  // Every derivative of a riding point is the same combination of its frame points' derivatives.
  std::array<double, Series::kCapacity> ox{}, oy{}, fx{}, fy{}, tx{}, ty{};
  for (const RidingPoint& p : extra_.points) {
    point_derivatives(mech_, s, p.origin, ox.data(), oy.data());
    point_derivatives(mech_, s, p.from, fx.data(), fy.data());
    point_derivatives(mech_, s, p.to, tx.data(), ty.data());
    for (int k = 0; k <= order_; ++k) {
      const double dx = tx[k] - fx[k], dy = ty[k] - fy[k];
      put((ox[k] + p.along * dx - p.across * dy) / length_scale);
      put((oy[k] + p.along * dy + p.across * dx) / length_scale);
    }
  }
  if (extra_.design_transmission)
    for (const double mu : mu_) put(std::min(mu, std::numbers::pi - mu) / mech_.model().units.angle_scale);
  if (extra_.condition) put(condition_of(s));
}

// The sweep's own estimate when it made one (SweepOptions::condition); else the same estimate from
// the sample's pose, factorised here, so that rows built from a sweep run without it (an analysis
// asked for other columns first) give the number and not a nan.
double KinematicRows::condition_of(const Sample& s) {
  if (!std::isnan(s.reciprocal_condition)) return 1.0 / s.reciprocal_condition;
  if (!s.positions().allFinite()) return std::numeric_limits<double>::quiet_NaN();
  if (!condition_state_) condition_state_ = std::make_shared<State>(mech_);
  State& state = *condition_state_;
  state.q = s.positions();
  state.drivers.resize(s.driver_values.size());
  for (std::size_t d = 0; d < s.driver_values.size(); ++d)
    state.drivers[d] = make_driver_state(Series(1, s.driver_values[d]), mech_.model().drivers[d].is_angular());
  if (!factorize_jacobian(mech_, state)) return HUGE_VAL;  // singular: a limit or a change point
  return 1.0 / sample_condition(state);
}

ResultTable make_table(const Mechanism& mech, const SweepResult& sweep, const ColumnsOnRequest& extra) {
  ResultTable t;
  KinematicRows rows(mech, sweep.order, extra);
  rows.name_columns(t.columns, t.units);
  if (!extra.empty()) t.on_request = rows.on_request();
  t.rows.reserve(sweep.samples.size());
  for (const Sample& s : sweep.samples) {
    std::vector<double> row(t.columns.size());
    rows.fill(s, row.data(), 1);
    t.rows.push_back(std::move(row));
  }
  return t;
}

ColumnTable make_column_table(const Mechanism& mech, const SweepResult& sweep, const ColumnsOnRequest& extra) {
  ColumnTable t;
  KinematicRows rows(mech, sweep.order, extra);
  rows.name_columns(t.columns, t.units);
  if (!extra.empty()) t.on_request = rows.on_request();
  const auto samples = static_cast<std::ptrdiff_t>(sweep.samples.size());
  t.values.resize(samples, static_cast<Eigen::Index>(t.columns.size()));
  for (std::ptrdiff_t r = 0; r < samples; ++r) rows.fill(sweep.samples[r], t.values.data() + r, samples);
  return t;
}

namespace {

bool is_on_request(const std::vector<bool>& on_request, std::size_t column) {
  return column < on_request.size() && on_request[column];
}

// For every column, the largest size of a value of its unit; 0 for unitless columns. A column on
// request counts only for the columns on request, so that asking for one changes no other.
template <class ValueAt>
std::vector<double> unit_scales(const std::vector<std::string>& units, const std::vector<bool>& on_request,
                                std::size_t rows, ValueAt value_at) {
  std::vector<double> column_max(units.size(), 0.0);
  for (std::size_t c = 0; c < units.size(); ++c)
    for (std::size_t r = 0; r < rows; ++r)
      if (std::isfinite(value_at(r, c))) column_max[c] = std::max(column_max[c], std::abs(value_at(r, c)));
  std::vector<double> scale(units.size(), 0.0);
  for (std::size_t c = 0; c < units.size(); ++c) {
    if (units[c].empty()) continue;
    for (std::size_t other = 0; other < units.size(); ++other)
      if (units[other] == units[c] && (is_on_request(on_request, c) || !is_on_request(on_request, other)))
        scale[c] = std::max(scale[c], column_max[other]);
  }
  return scale;
}

template <class ValueAt>
void zero_below_scales(const std::vector<std::string>& units, const std::vector<bool>& on_request, std::size_t rows,
                       ValueAt value_at) {
  const std::vector<double> scale = unit_scales(units, on_request, rows, value_at);
  for (std::size_t c = 0; c < units.size(); ++c) {
    const double threshold = kNoiseRelative * scale[c];
    for (std::size_t r = 0; r < rows; ++r)
      if (std::abs(value_at(r, c)) <= threshold) value_at(r, c) = 0.0;
  }
}

}  // namespace

void zero_numerical_noise(ResultTable& table) {
  zero_below_scales(table.units, table.on_request, table.rows.size(),
                    [&](std::size_t r, std::size_t c) -> double& { return table.rows[r][c]; });
}

void zero_numerical_noise(ColumnTable& table) {
  zero_below_scales(table.units, table.on_request, static_cast<std::size_t>(table.values.rows()),
                    [&](std::size_t r, std::size_t c) -> double& {
                      return table.values(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c));
                    });
}

bool glob_match(const std::string& pattern, const std::string& text) {
  std::size_t p = 0, t = 0, star = std::string::npos, mark = 0;
  while (t < text.size()) {
    if (p < pattern.size() && pattern[p] == '*') {
      star = p++;
      mark = t;
    } else if (p < pattern.size() && pattern[p] == text[t]) {
      ++p;
      ++t;
    } else if (star != std::string::npos) {
      p = star + 1;
      t = ++mark;
    } else {
      return false;
    }
  }
  while (p < pattern.size() && pattern[p] == '*') ++p;
  return p == pattern.size();
}

std::optional<std::string> column_suggestion(const std::string& pattern, const std::vector<std::string>& columns) {
  const auto lower = [](std::string text) {
    for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return text;
  };
  const std::string folded = lower(pattern);
  for (const std::string& column : columns)
    if (glob_match(folded, lower(column))) return column;
  return std::nullopt;
}

std::string no_column_message(const std::string& pattern, const std::vector<std::string>& columns) {
  std::string message = "no column matches '" + pattern + "'";
  if (auto close = column_suggestion(pattern, columns)) message += " (did you mean '" + *close + "'?)";
  return message;
}

// Which columns the patterns pick, in the order of the patterns, each once.
std::vector<std::size_t> pick_columns(const std::vector<std::string>& columns, const std::vector<std::string>& patterns,
                                      const std::vector<bool>& on_request) {
  std::vector<std::size_t> picked;
  // Only a pattern that matches no ordinary column reaches the columns on request.
  auto pick = [&](const std::string& pattern, bool requested) {
    bool any = false;
    for (std::size_t c = 0; c < columns.size(); ++c) {
      if (is_on_request(on_request, c) != requested || !glob_match(pattern, columns[c])) continue;
      any = true;
      if (std::find(picked.begin(), picked.end(), c) == picked.end()) picked.push_back(c);
    }
    return any;
  };
  for (const std::string& pattern : patterns)
    if (!pick(pattern, false) && !pick(pattern, true))
      throw Error(ErrorKind::BadInput, no_column_message(pattern, columns));
  return picked;
}

ResultTable select_columns(const ResultTable& table, const std::vector<std::string>& patterns) {
  const std::vector<std::size_t> picked = pick_columns(table.columns, patterns, table.on_request);
  ResultTable out;
  for (std::size_t c : picked) {
    out.columns.push_back(table.columns[c]);
    out.units.push_back(table.units[c]);
    if (!table.on_request.empty()) out.on_request.push_back(is_on_request(table.on_request, c));
  }
  for (const auto& row : table.rows) {
    std::vector<double> r;
    r.reserve(picked.size());
    for (std::size_t c : picked) r.push_back(row[c]);
    out.rows.push_back(std::move(r));
  }
  return out;
}

ColumnTable select_columns(const ColumnTable& table, const std::vector<std::string>& patterns) {
  const std::vector<std::size_t> picked = pick_columns(table.columns, patterns, table.on_request);
  ColumnTable out;
  out.values.resize(table.values.rows(), static_cast<Eigen::Index>(picked.size()));
  for (std::size_t i = 0; i < picked.size(); ++i) {
    out.columns.push_back(table.columns[picked[i]]);
    out.units.push_back(table.units[picked[i]]);
    if (!table.on_request.empty()) out.on_request.push_back(is_on_request(table.on_request, picked[i]));
    out.values.col(static_cast<Eigen::Index>(i)) = table.values.col(static_cast<Eigen::Index>(picked[i]));
  }
  return out;
}

}  // namespace nbar
