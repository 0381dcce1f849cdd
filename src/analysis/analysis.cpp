#include "nbar/analysis/analysis.hpp"

#include "nbar/analysis/columns.hpp"
#include "nbar/analysis/summary.hpp"
#include "nbar/analysis/table_stream.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

#include "nbar/dynamics/dynamics_table.hpp"
#include "nbar/kinematics/continuation.hpp"
#include "nbar/model/units.hpp"
#include "overflow.hpp"

namespace nbar {

namespace {

void check_options(const AnalysisOptions& options) {
  check_derivative_order(options.order);
  if (options.steps && *options.steps < 1) throw Error(ErrorKind::BadInput, "a sweep needs at least one step");
  if (options.max_steps < 1) throw Error(ErrorKind::BadInput, "the limit on a sweep's steps must be at least 1");
  if (options.stress && (options.sections < kMinSectionsPerLink || options.sections > kMaxSectionsPerLink))
    throw Error(ErrorKind::BadInput, "stresses need " + std::to_string(kMinSectionsPerLink) + " to " +
                                         std::to_string(kMaxSectionsPerLink) + " sections per link, not " +
                                         std::to_string(options.sections));
  if (options.stress && (!std::isfinite(options.fe.mesh_size) || options.fe.mesh_size < 0.0))
    throw Error(ErrorKind::BadInput, "the mesh size must be a positive length (or 0 for the default)");
}

SweepResult run_sweep_stage(const Mechanism& mech, const AnalysisOptions& options) {
  SweepOptions sweep;
  sweep.steps = options.steps;
  sweep.max_steps = options.max_steps;
  sweep.order = options.dynamics || options.stress ? std::max(options.order, 2) : options.order;
  sweep.condition = options.condition;
  std::vector<Warning> before = check_before_sweep(mech);
  SweepResult result = run_sweep(mech, sweep, options.control);
  result.warnings.insert(result.warnings.begin(), before.begin(), before.end());
  return result;
}

// One sample's inverse dynamics, checked and counted into the stage's summary.
DynamicsResult solve_dynamics_sample(DynamicsStage& stage, const Model& m, const Sample& sample) {
  DynamicsResult r = stage.solver->solve(sample);
  detail::check_finite_dynamics(m, sample, r);
  stage.unique = stage.unique && r.unique;
  stage.max_residual = std::max(stage.max_residual, r.residual);
  return r;
}

void add_dynamics_warnings(DynamicsStage& stage, const Model& m);

DynamicsStage run_dynamics_stage(const Analysis& analysis, const AnalysisOptions& options) {
  DynamicsStage stage;
  stage.solver = std::make_shared<const InverseDynamics>(analysis.mechanism);
  const auto& samples = analysis.sweep.samples;
  stage.samples.reserve(samples.size());
  for (std::size_t i = 0; i < samples.size(); ++i) {
    options.control.checkpoint("dynamics", static_cast<long>(i), static_cast<long>(samples.size()));
    stage.samples.push_back(solve_dynamics_sample(stage, analysis.model(), samples[i]));
  }
  add_dynamics_warnings(stage, analysis.model());
  return stage;
}

void add_dynamics_warnings(DynamicsStage& stage, const Model& m) {
  bool kinetics = !m.gravity.isZero() || !m.point_loads.empty() || !m.torques.empty() || !m.springs.empty();
  for (const Body& b : m.bodies) kinetics = kinetics || mass_properties(b).mass > 0.0;
  if (!kinetics)
    stage.warnings.push_back({"no_kinetics", -1,
                              "the model has no masses or loads (no `mass`, material, gravity, forces, torques or "
                              "springs): every joint force and driver effort is zero"});
  if (!stage.unique)
    stage.warnings.push_back(
        {"forces_not_unique", -1,
         "the mechanism has redundant constraints: its joint forces are not unique (statically indeterminate); "
         "the minimum-norm set is given"});
}

// Said at the first body, where a shape would be given.
[[noreturn]] void no_shaped_link() {
  throw Error(ErrorKind::InvalidModel,
              "no link has a shape (`shape:` or `bar:` with a thickness), so there is nothing to compute stresses in",
              EntityRef{EntityRef::Kind::Body, 0});
}

StressStage run_beam_stress(const Analysis& analysis, const AnalysisOptions& options) {
  StressStage stage;
  stage.links = std::make_shared<const LinkStress>(analysis.dynamics->solver, options.sections);
  bool any = false;
  for (std::size_t b = 0; b < analysis.model().bodies.size(); ++b)
    any = any || stage.links->analysed(static_cast<int>(b));
  if (!any) no_shaped_link();
  stage.peaks = stress_peaks(*stage.links, analysis.sweep, analysis.dynamics->samples, options.control);
  detail::check_finite_stress(analysis.model(), analysis.sweep.samples, stage.peaks);
  return stage;
}

StressStage run_fe_stress(const Analysis& analysis, const AnalysisOptions& options) {
  StressStage stage;
  stage.method = StressMethod::fe;
  stage.fe = std::make_shared<const LinkFe>(analysis.dynamics->solver, options.fe, options.control);
  bool any = false;
  for (std::size_t b = 0; b < analysis.model().bodies.size(); ++b) any = any || stage.fe->analysed(static_cast<int>(b));
  if (!any) no_shaped_link();
  stage.fe_peaks = fe_peaks(*stage.fe, analysis.sweep, analysis.dynamics->samples, options.control);
  for (const FePeak& p : stage.fe_peaks)
    if (!std::isfinite(p.von_mises))
      throw Error(ErrorKind::InvalidModel,
                  "the finite-element stress in body '" + analysis.model().bodies[p.body].name +
                      "' is too large to compute with: check its loads, masses and material",
                  EntityRef{EntityRef::Kind::Body, p.body});
  return stage;
}

StressStage run_stress_stage(const Analysis& analysis, const AnalysisOptions& options) {
  return options.stress_method == StressMethod::fe ? run_fe_stress(analysis, options)
                                                   : run_beam_stress(analysis, options);
}

}  // namespace

std::vector<TransmissionExtremes> transmission_extremes(const Analysis& analysis) {
  const Mechanism& mech = *analysis.mechanism;
  std::vector<TransmissionExtremes> out;
  if (analysis.sweep.samples.empty()) return out;
  for (const FourBarLoop& loop : mech.four_bar_loops()) out.push_back({loop.name});
  for (const Sample& sample : analysis.sweep.samples) {
    const std::vector<Eigen::Vector2d> points = point_positions(mech, sample.taylor.col(0));
    for (std::size_t l = 0; l < out.size(); ++l) {
      const double mu = transmission_angle(mech.four_bar_loops()[l], points);
      const double from_dead_point = std::min(mu, std::numbers::pi - mu);
      TransmissionExtremes& e = out[l];
      const bool first = e.min_step < 0;
      if (first || mu < e.min) e.min = mu, e.min_step = sample.step;
      if (first || mu > e.max) e.max = mu, e.max_step = sample.step;
      if (first || from_dead_point < e.design) e.design = from_dead_point, e.design_step = sample.step;
    }
  }
  return out;
}

std::vector<Warning> Analysis::warnings() const {
  std::vector<Warning> all = sweep.warnings;
  if (dynamics) all.insert(all.end(), dynamics->warnings.begin(), dynamics->warnings.end());
  return all;
}

std::shared_ptr<const Mechanism> with_sweep_options(std::shared_ptr<const Mechanism> mechanism,
                                                    const AnalysisOptions& options) {
  if ((!options.at_limits && !options.cycles) || mechanism->model().drivers.empty()) return mechanism;
  Model model = mechanism->model();
  if (options.at_limits) model.drivers[0].at_limits = *options.at_limits;
  if (options.cycles) model.drivers[0].cycles = *options.cycles;
  return std::make_shared<const Mechanism>(std::move(model));
}

Analysis analyse(std::shared_ptr<const Mechanism> mechanism, const AnalysisOptions& options) {
  check_options(options);
  Analysis analysis;
  analysis.mechanism = with_sweep_options(std::move(mechanism), options);
  analysis.sweep = run_sweep_stage(*analysis.mechanism, options);
  if (options.dynamics || options.stress) analysis.dynamics = run_dynamics_stage(analysis, options);
  if (options.stress) analysis.stress = run_stress_stage(analysis, options);
  return analysis;
}

ResultTable result_table(const Analysis& analysis, const ColumnsOnRequest& extra) {
  ResultTable table = make_table(*analysis.mechanism, analysis.sweep, extra);
  if (analysis.dynamics)
    append_dynamics_columns(*analysis.dynamics->solver, analysis.sweep, analysis.dynamics->samples, table);
  zero_numerical_noise(table);
  return table;
}

ColumnTable result_columns(const Analysis& analysis, const ColumnsOnRequest& extra) {
  ColumnTable table = make_column_table(*analysis.mechanism, analysis.sweep, extra);
  if (analysis.dynamics)
    append_dynamics_columns(*analysis.dynamics->solver, analysis.sweep, analysis.dynamics->samples, table);
  zero_numerical_noise(table);
  return table;
}

ResultTable section_profile_table(const Analysis& analysis, int body, int step) {
  const Model& m = analysis.model();
  if (!analysis.stress) throw Error(ErrorKind::BadInput, "section profiles need the stress stage");
  if (!analysis.stress->links)
    throw Error(ErrorKind::BadInput, "section profiles are the beam method's: the finite elements cut no sections");
  if (body < 0 || body >= static_cast<int>(m.bodies.size()) || !analysis.stress->links->analysed(body))
    throw Error(
        ErrorKind::BadInput,
        "'" + (body >= 0 && body < static_cast<int>(m.bodies.size()) ? m.bodies[body].name : std::to_string(body)) +
            "' has no shape to cut");
  const int steps = static_cast<int>(analysis.sweep.samples.size());
  if (step < 0 || step >= steps)
    throw Error(ErrorKind::BadInput,
                "step " + std::to_string(step) + " is not a solved step (0 to " + std::to_string(steps - 1) + ")");
  const auto profile = analysis.stress->links->profile(analysis.dynamics->samples[step], body);
  ResultTable t;
  t.columns = {"x", "area", "N", "V", "M", "sigma_right", "sigma_left", "tau", "von_mises"};
  const std::string len = m.units.length;
  t.units = {len, len + "^2", "N", "N", "N m", "MPa", "MPa", "MPa", "MPa"};
  const double unit = m.units.length_scale;
  for (const SectionStress& sec : profile)
    t.rows.push_back({sec.position / unit, sec.area / (unit * unit), sec.axial, sec.shear, sec.moment,
                      to_megapascal(sec.sigma_low), to_megapascal(sec.sigma_high), to_megapascal(sec.tau_max),
                      to_megapascal(sec.von_mises)});
  zero_numerical_noise(t);
  const Sample& at = analysis.sweep.samples[step];
  std::string inputs;
  for (std::size_t d = 0; d < m.drivers.size(); ++d)
    inputs += m.drivers[d].name + " = " + format_driver_value(m, static_cast<int>(d), at.driver_values[d]) + ", ";
  std::ostringstream time;
  time << at.time;
  t.title = "Sections of " + m.bodies[body].name + " at step " + std::to_string(step) + " (" + inputs +
            "t = " + time.str() + " s): x from " + m.points[m.bodies[body].points[0]].name + " towards " +
            m.points[m.bodies[body].points[1]].name;
  return t;
}

// TableStream: the pipeline of analyse() with a sink on the sweep, each sample's dynamics solved
// as it comes and its row filled at once.
struct TableStream::Pass {
  std::function<void(const double* full_row)> row;
};

TableStream::TableStream(std::shared_ptr<const Mechanism> mechanism, const AnalysisOptions& options,
                         ColumnsOnRequest extra)
    : mechanism_(with_sweep_options(std::move(mechanism), options)), options_(options), extra_(std::move(extra)) {
  check_options(options_);
  if (options_.stress) throw Error(ErrorKind::BadInput, "stresses need the whole sweep: use analyse");
  if (options_.dynamics) dynamics_ = std::make_shared<const InverseDynamics>(mechanism_);
  name_columns();
}

TableStream::~TableStream() = default;

void TableStream::name_columns() {
  const int order = options_.dynamics ? std::max(options_.order, 2) : options_.order;
  const KinematicRows kinematic(*mechanism_, order, extra_);
  columns_.clear();
  units_.clear();
  kinematic.name_columns(columns_, units_);
  on_request_ = kinematic.on_request();
  if (dynamics_) {
    for (ColumnName& c : dynamics_columns(*dynamics_)) {
      columns_.push_back(std::move(c.name));
      units_.push_back(std::move(c.unit));
    }
  }
  all_units_ = units_;
  picked_.clear();
  for (std::size_t c = 0; c < columns_.size(); ++c) picked_.push_back(c);
}

void TableStream::select(const std::vector<std::string>& patterns) {
  if (!measured_ && extra_.empty()) {
    extra_ = columns_on_request(*mechanism_, patterns);
    if (!extra_.empty()) name_columns();
  }
  const std::vector<std::size_t> picked = pick_columns(columns_, patterns, on_request_);
  std::vector<std::string> columns, units;
  std::vector<std::size_t> indices;
  for (std::size_t c : picked) {
    columns.push_back(columns_[c]);
    units.push_back(units_[c]);
    indices.push_back(picked_[c]);
  }
  columns_ = std::move(columns);
  units_ = std::move(units);
  picked_ = std::move(indices);
}

void TableStream::run(Pass& pass) {
  const Mechanism& mech = *mechanism_;
  const int order = options_.dynamics ? std::max(options_.order, 2) : options_.order;
  KinematicRows kinematic(mech, order, extra_);
  const std::size_t kinematic_columns = kinematic.column_count();
  std::vector<double> row(all_units_.size());
  dynamics_stage_.reset();
  std::optional<DynamicsRows> dynamic;
  if (dynamics_) {
    dynamics_stage_.emplace();
    dynamics_stage_->solver = dynamics_;
    dynamic.emplace(*dynamics_);
  }
  SweepOptions sweep;
  sweep.steps = options_.steps;
  sweep.max_steps = options_.max_steps;
  sweep.order = order;
  sweep.condition = options_.condition || extra_.condition;
  ++passes_;
  if (!before_sweep_) before_sweep_ = check_before_sweep(mech);
  sweep_ = run_sweep(mech, sweep, options_.control, [&](const Sample& s) {
    kinematic.fill(s, row.data());
    if (dynamic) {
      const DynamicsResult r = solve_dynamics_sample(*dynamics_stage_, mech.model(), s);
      dynamic->fill(s, r, row.data() + kinematic_columns);
    }
    pass.row(row.data());
  });
  sweep_.warnings.insert(sweep_.warnings.begin(), before_sweep_->begin(), before_sweep_->end());
  if (dynamics_stage_) add_dynamics_warnings(*dynamics_stage_, mech.model());
}

void TableStream::measure() {
  // zero_numerical_noise's scales: per column the largest finite size, then per unit the largest
  // over its columns; unitless columns keep a threshold of 0.
  const std::size_t n = all_units_.size();
  std::vector<double> column_max(n, 0.0);
  const std::size_t kept_values = kept_rows_budget_ / sizeof(double);
  kept_rows_.clear();
  rows_kept_ = n > 0;
  Pass pass;
  pass.row = [&](const double* row) {
    for (std::size_t c = 0; c < n; ++c)
      if (std::isfinite(row[c])) column_max[c] = std::max(column_max[c], std::abs(row[c]));
    if (!rows_kept_) return;
    if (kept_rows_.size() + n > kept_values) {
      rows_kept_ = false;
      std::vector<double>().swap(kept_rows_);
      return;
    }
    kept_rows_.insert(kept_rows_.end(), row, row + n);
  };
  run(pass);
  threshold_.assign(n, 0.0);
  for (std::size_t c = 0; c < n; ++c) {
    if (all_units_[c].empty()) continue;
    double scale = 0.0;
    const bool requested = c < on_request_.size() && on_request_[c];
    for (std::size_t other = 0; other < n; ++other)
      if (all_units_[other] == all_units_[c] && (requested || !(other < on_request_.size() && on_request_[other])))
        scale = std::max(scale, column_max[other]);
    threshold_[c] = kNoiseRelative * scale;
  }
  measured_ = true;
}

void TableStream::rows(const std::function<void(const double* row)>& sink) {
  if (!measured_) measure();
  std::vector<double> out(picked_.size());
  auto hand_out = [&](const double* row) {
    for (std::size_t i = 0; i < picked_.size(); ++i) {
      const double v = row[picked_[i]];
      out[i] = std::abs(v) <= threshold_[picked_[i]] ? 0.0 : v;
    }
    sink(out.data());
  };
  if (rows_kept_) {
    const std::size_t n = all_units_.size();
    for (std::size_t start = 0; start + n <= kept_rows_.size(); start += n) hand_out(kept_rows_.data() + start);
    return;
  }
  Pass pass;
  pass.row = hand_out;
  run(pass);
}

std::vector<Warning> TableStream::warnings() const {
  std::vector<Warning> all = sweep_.warnings;
  if (dynamics_stage_) all.insert(all.end(), dynamics_stage_->warnings.begin(), dynamics_stage_->warnings.end());
  return all;
}

}  // namespace nbar
