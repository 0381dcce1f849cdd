#include "nbar/io/results_writer.hpp"

#include "json_text.hpp"
#include "model/double_text.hpp"
#include "nbar/model/diagnostics.hpp"
#include "nbar/model/units.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

namespace nbar::io {

namespace {

// Room for one number: sign, 12 digits, point, exponent ("-1.23456789012e-308").
constexpr std::size_t kNumberRoom = 32;
constexpr std::size_t kCsvBlock = 1 << 20;

// A name as one CSV field (RFC 4180): names may hold commas and quotes ("a,b" is a valid point
// name), which would otherwise split the header into more fields than the rows have.
std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) (quoted += c) += c == '"' ? "\"" : "";
  return quoted + '"';
}

}  // namespace

CsvWriter::CsvWriter(std::ostream& out, const std::vector<std::string>& columns)
    : out_(out), columns_(columns.size()), buffer_(kCsvBlock + kNumberRoom * (columns.size() + 1)) {
  std::string header;
  for (std::size_t c = 0; c < columns.size(); ++c) (header += (c ? "," : "")) += csv_field(columns[c]);
  header += '\n';
  out_.write(header.data(), static_cast<std::streamsize>(header.size()));
}

CsvWriter::~CsvWriter() { flush(); }

void CsvWriter::row(const double* values) {
  char* p = buffer_.data() + used_;
  char* const end = buffer_.data() + buffer_.size();
  for (std::size_t c = 0; c < columns_; ++c) {
    if (c) *p++ = ',';
    // Adding 0.0 turns -0 into 0, which nobody wants to read.
    p = write_double_general(p, end, values[c] + 0.0, 12);
  }
  *p++ = '\n';
  used_ = static_cast<std::size_t>(p - buffer_.data());
  if (used_ >= kCsvBlock) flush();
}

void CsvWriter::flush() {
  if (used_ > 0) out_.write(buffer_.data(), static_cast<std::streamsize>(used_));
  used_ = 0;
}

void write_csv(std::ostream& out, const ResultTable& table) {
  CsvWriter csv(out, table.columns);
  for (const auto& row : table.rows) csv.row(row.data());
}

void write_text_table(std::ostream& out, const ResultTable& table, std::size_t line_width) {
  const std::size_t n = table.columns.size();
  std::vector<std::vector<std::string>> cells(table.rows.size());
  if (!table.title.empty()) out << table.title << '\n';
  std::vector<std::size_t> width(n, 0);
  for (std::size_t c = 0; c < n; ++c) {
    const std::string unit = table.units[c].empty() ? "" : "[" + table.units[c] + "]";
    width[c] = std::max(table.columns[c].size(), unit.size());
  }
  for (std::size_t r = 0; r < table.rows.size(); ++r) {
    for (std::size_t c = 0; c < n; ++c) {
      cells[r].push_back(fmt::format("{:.6g}", table.rows[r][c] + 0.0));
      width[c] = std::max(width[c], cells[r].back().size());
    }
  }
  // Column groups that fit line_width, each led by the first column (step) again.
  if (n == 0) return;
  std::vector<std::vector<std::size_t>> groups{{0}};
  std::size_t used = width[0];
  for (std::size_t c = 1; c < n; ++c) {
    if (line_width > 0 && groups.back().size() > 1 && used + 2 + width[c] > line_width) {
      groups.push_back({0});
      used = width[0];
    }
    groups.back().push_back(c);
    used += 2 + width[c];
  }
  for (std::size_t g = 0; g < groups.size(); ++g) {
    if (g) out << '\n';
    const auto line = [&](auto cell) {
      std::string s;
      for (std::size_t i = 0; i < groups[g].size(); ++i) {
        const std::size_t c = groups[g][i];
        s += fmt::format("{}{:>{}}", i ? "  " : "", cell(c), width[c]);
      }
      out << s << '\n';
    };
    line([&](std::size_t c) { return table.columns[c]; });
    line([&](std::size_t c) { return table.units[c].empty() ? std::string() : "[" + table.units[c] + "]"; });
    for (std::size_t r = 0; r < cells.size(); ++r) line([&](std::size_t c) { return cells[r][c]; });
  }
}

namespace {

std::vector<std::string> messages(const std::vector<Warning>& warnings) {
  std::vector<std::string> out;
  for (const Warning& w : warnings) out.push_back(w.message);
  return out;
}

}  // namespace

namespace {

// A loop's transmission angle over the sweep, in the model's angle unit: its extremes and its
// design value (the smallest of min(mu, 180 deg - mu)), each with its step.
nlohmann::ordered_json transmission_json(const TransmissionExtremes& mu, double angle_scale) {
  return {{"min", mu.min / angle_scale}, {"min_step", mu.min_step},           {"max", mu.max / angle_scale},
          {"max_step", mu.max_step},     {"design", mu.design / angle_scale}, {"design_step", mu.design_step}};
}

}  // namespace

void write_json(std::ostream& out, const Analysis& analysis, const ResultTable& table, const DynamicsStage* dynamics) {
  const Mechanism& mech = *analysis.mechanism;
  const SweepResult& sweep = analysis.sweep;
  const Model& m = mech.model();
  const MobilityReport& mob = mech.mobility();
  nlohmann::ordered_json j;
  j["model"] = m.name;
  if (!table.title.empty()) j["title"] = table.title;
  j["units"] = {{"length", m.units.length}, {"angle", m.units.angle}, {"time", "s"}};
  nlohmann::ordered_json redundant = nlohmann::json::array();
  for (int r : mob.redundant) redundant.push_back(mech.row_label(r));
  j["dof"] = {{"gruebler", mob.grubler}, {"mobility", mob.dof}, {"redundant_constraints", redundant}};
  nlohmann::ordered_json loops = nlohmann::json::array();
  const std::vector<TransmissionExtremes> mu = transmission_extremes(analysis);
  for (std::size_t l = 0; l < mech.four_bar_loops().size(); ++l) {
    nlohmann::ordered_json loop = {{"loop", mech.four_bar_loops()[l].name}, {"branch", sweep.branches[l]}};
    if (l < mu.size()) loop["transmission_angle"] = transmission_json(mu[l], m.units.angle_scale);
    loops.push_back(loop);
  }
  j["branches"] = loops;
  j["order"] = sweep.order;
  j["complete"] = sweep.complete;
  // Always there, so that readers need not test for it: null for a sweep that ran to its end.
  j["stop_reason"] = sweep.complete ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(sweep.stop_reason);
  j["warnings"] = messages(sweep.warnings);
  j["max_residual"] = sweep.max_residual / m.units.length_scale;
  if (std::any_of(m.drivers.begin(), m.drivers.end(),
                  [](const Driver& d) { return d.at_limits == AtLimits::Reverse; })) {
    nlohmann::ordered_json turns = nlohmann::json::array();
    for (const Reversal& r : sweep.reversals)
      turns.push_back({{"after_step", r.after_step},
                       {"t", r.time},
                       {m.drivers[0].name,
                        r.driver_value / (m.drivers[0].is_angular() ? m.units.angle_scale : m.units.length_scale)},
                       {"involved", r.involved},
                       {"at_sample", r.at_sample}});
    j["reversals"] = turns;
  }
  if (dynamics) {
    j["dynamics"] = {{"units", "forces N, torques N m, energies J, whatever the model's length unit"},
                     {"unique", dynamics->unique},
                     {"max_residual", dynamics->max_residual},
                     {"warnings", messages(dynamics->warnings)}};
  }
  j["columns"] = table.columns;
  j["column_units"] = table.units;
  j["rows"] = table.rows;
  out << json_text(j, 1) << '\n';
}

void write_table(std::ostream& out, const std::string& format, const Analysis& analysis, const ResultTable& table,
                 const DynamicsStage* dynamics, std::size_t line_width) {
  if (format == "json")
    write_json(out, analysis, table, dynamics);
  else if (format == "table")
    write_text_table(out, table, line_width);
  else if (format == "csv")
    write_csv(out, table);
  else
    throw Error(ErrorKind::BadInput, "a table is written as csv, table or json, not '" + format + "'");
}

namespace {

// The step, time and every driver's value at a peak.
void append_input_columns(const Model& m, std::vector<std::pair<std::string, std::string>>& columns) {
  columns.insert(columns.end(), {{"step", ""}, {"t", "s"}});
  for (const Driver& d : m.drivers) columns.push_back({d.name, d.is_angular() ? m.units.angle : m.units.length});
}
void append_input_values(const Model& m, const SweepResult& sweep, int step, std::vector<double>& row) {
  const Sample* at = step >= 0 ? &sweep.samples[step] : nullptr;
  row.push_back(static_cast<double>(step));
  row.push_back(at ? at->time : 0.0);
  for (std::size_t d = 0; d < m.drivers.size(); ++d)
    row.push_back(at ? at->driver_values[d] / (m.drivers[d].is_angular() ? m.units.angle_scale : m.units.length_scale)
                     : 0.0);
}

// A table of one peak per link: von Mises, the inputs at its step, then the method's columns.
ResultTable peak_table_columns(const Model& m, const std::vector<std::pair<std::string, std::string>>& own) {
  std::vector<std::pair<std::string, std::string>> columns = {{"von_mises", "MPa"}};
  append_input_columns(m, columns);
  columns.insert(columns.end(), own.begin(), own.end());
  ResultTable t;
  for (const auto& [name, unit] : columns) {
    t.columns.push_back(name);
    t.units.push_back(unit);
  }
  return t;
}

ResultTable beam_peak_table(const Analysis& analysis) {
  const Model& m = analysis.model();
  const double length = m.units.length_scale;
  ResultTable t = peak_table_columns(m, {{"x", m.units.length},
                                         {"y", m.units.length},
                                         {"sigma", "MPa"},
                                         {"tau", "MPa"},
                                         {"N", "N"},
                                         {"V", "N"},
                                         {"M", "N m"},
                                         {"safety_factor", ""}});
  for (const StressPeak& p : analysis.stress->peaks) {
    std::vector<double> row = {to_megapascal(p.at.von_mises)};
    append_input_values(m, analysis.sweep, p.step, row);
    for (double v :
         {p.at.where.x() / length, p.at.where.y() / length, to_megapascal(p.at.sigma), to_megapascal(p.at.tau),
          p.at.axial, p.at.shear, p.at.moment, p.safety_factor.value_or(std::numeric_limits<double>::quiet_NaN())})
      row.push_back(v);
    t.rows.push_back(std::move(row));
  }
  return t;
}

// A flat peak's arc as the body's frame sees it (the frame of the peak's x and y): its ends'
// angles about the hole's centre, degrees in [0, 360).
struct FlatArcInBody {
  double from_deg, to_deg, length;
};
FlatArcInBody flat_arc_in_body(const Model& m, int body, const fe::FlatArc& arc) {
  const Eigen::Vector2d centre = body_frame_point(m, body, arc.centre);
  const auto angle = [&](const Eigen::Vector2d& plate_point) {
    const Eigen::Vector2d arm = body_frame_point(m, body, plate_point) - centre;
    const double deg = std::atan2(arm.y(), arm.x()) * 180.0 / std::numbers::pi;
    return deg < 0.0 ? deg + 360.0 : deg;
  };
  return {angle(arc.from_at), angle(arc.to_at), arc.length};
}

ResultTable fe_peak_table(const Analysis& analysis) {
  const Model& m = analysis.model();
  const double length = m.units.length_scale;
  ResultTable t = peak_table_columns(m, {{"x", m.units.length},
                                         {"y", m.units.length},
                                         {"safety_factor", ""},
                                         {"nodes", ""},
                                         {"elements", ""},
                                         {"mesh_size", m.units.length},
                                         {"min_angle", "deg"},
                                         {"unbalance", ""},
                                         {"reaction", ""},
                                         {"flat_from", "deg"},
                                         {"flat_to", "deg"},
                                         {"flat_arc", m.units.length}});
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  for (const FePeak& p : analysis.stress->fe_peaks) {
    std::vector<double> row = {to_megapascal(p.von_mises)};
    append_input_values(m, analysis.sweep, p.step, row);
    const Eigen::Vector2d where = body_frame_point(m, p.body, p.at);
    const FlatArcInBody flat = p.flat ? flat_arc_in_body(m, p.body, *p.flat) : FlatArcInBody{nan, nan, nan};
    for (double v :
         {where.x() / length, where.y() / length, p.safety_factor.value_or(nan), static_cast<double>(p.nodes),
          static_cast<double>(p.elements), p.mesh_size / length, p.min_angle_deg, p.load_unbalance, p.support_reaction,
          flat.from_deg, flat.to_deg, flat.length / length})
      row.push_back(v);
    t.rows.push_back(std::move(row));
  }
  return t;
}

}  // namespace

void write_stress_report(std::ostream& out, const std::string& format, const Analysis& analysis) {
  const Model& m = analysis.model();
  const bool fe = analysis.stress->method == StressMethod::fe;
  const ResultTable t = fe ? fe_peak_table(analysis) : beam_peak_table(analysis);
  std::vector<std::string> names;
  if (fe)
    for (const FePeak& p : analysis.stress->fe_peaks) names.push_back(m.bodies[p.body].name);
  else
    for (const StressPeak& p : analysis.stress->peaks) names.push_back(m.bodies[p.body].name);
  if (format == "json") {
    nlohmann::ordered_json j;
    j["model"] = m.name;
    if (fe) j["method"] = "fe";
    j["units"] = {{"stress", "MPa"}, {"force", "N"}, {"moment", "N m"}, {"length", m.units.length}};
    nlohmann::ordered_json bodies = nlohmann::json::array();
    for (std::size_t i = 0; i < names.size(); ++i) {
      nlohmann::ordered_json b;
      b["body"] = names[i];
      for (std::size_t c = 0; c < t.columns.size(); ++c) {
        const double v = t.rows[i][c];
        // Counts are whole numbers in JSON ("step": 12, not 12.0).
        const bool count = t.columns[c] == "step" || t.columns[c] == "reversals" || t.columns[c] == "nodes" ||
                           t.columns[c] == "elements";
        if (!std::isfinite(v))
          b[t.columns[c]] = nullptr;
        else if (count && v == std::floor(v) && std::abs(v) < 9e15)
          b[t.columns[c]] = static_cast<long long>(v);
        else
          b[t.columns[c]] = v;
      }
      bodies.push_back(b);
    }
    j["links"] = bodies;
    out << json_text(j, 1) << '\n';
    return;
  }
  // Text and CSV: the body's name first; a missing safety factor (no yield strength) is blank.
  std::vector<std::vector<std::string>> cells;
  cells.push_back({"body"});
  for (const auto& c : t.columns) cells.back().push_back(c);
  if (format != "csv") {
    cells.push_back({""});
    for (const auto& u : t.units) cells.back().push_back(u.empty() ? "" : "[" + u + "]");
  }
  for (std::size_t i = 0; i < names.size(); ++i) {
    cells.push_back({names[i]});
    for (double v : t.rows[i]) cells.back().push_back(std::isfinite(v) ? fmt::format("{:.6g}", v + 0.0) : "");
  }
  if (format == "csv") {
    for (const auto& row : cells) {
      for (std::size_t c = 0; c < row.size(); ++c) out << (c ? "," : "") << csv_field(row[c]);
      out << '\n';
    }
    return;
  }
  std::vector<std::size_t> width(cells[0].size(), 0);
  for (const auto& row : cells)
    for (std::size_t c = 0; c < row.size(); ++c) width[c] = std::max(width[c], row[c].size());
  for (const auto& row : cells) {
    std::string line;
    for (std::size_t c = 0; c < row.size(); ++c)
      line += c == 0 ? fmt::format("{:<{}}", row[c], width[c]) : fmt::format("  {:>{}}", row[c], width[c]);
    out << line << '\n';
  }
}

void write_simulation_json(std::ostream& out, const Mechanism& mechanism, const Simulation& simulation,
                           const ResultTable& table) {
  const Model& m = mechanism.model();
  const SimulationStatistics& stats = simulation.statistics;
  nlohmann::ordered_json j;
  j["model"] = m.name;
  j["units"] = {{"length", m.units.length}, {"angle", m.units.angle}, {"time", "s"}, {"energy", "J"}};
  nlohmann::ordered_json free = nlohmann::json::array();
  for (int d : simulation.free_drivers) free.push_back(m.drivers[d].name);
  j["free_drivers"] = free;
  j["complete"] = simulation.complete;
  j["stop_reason"] =
      simulation.complete ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(simulation.stop_reason);
  if (!simulation.complete) {  // only then, so that a complete run's answer keeps its keys
    j["cancelled"] = simulation.cancelled;
    j["time_reached"] = simulation.time_reached();
  }
  j["integrator"] = {{"method", kSimulationMethod},
                     {"accepted_steps", stats.accepted_steps},
                     {"rejected_steps", stats.rejected_steps},
                     {"evaluations", stats.evaluations},
                     {"smallest_step", stats.smallest_step},
                     {"largest_step", stats.largest_step}};
  j["constraint_drift"] = {{"position", stats.drift.position / m.units.length_scale},
                           {"velocity", stats.drift.velocity / m.units.length_scale},
                           {"acceleration", stats.drift.acceleration / m.units.length_scale}};
  j["largest_energy_error"] = stats.largest_energy_error;
  nlohmann::ordered_json events = nlohmann::json::array();
  for (const SimulationEvent& event : simulation.events)
    events.push_back({{"kind", event.kind == SimulationEvent::Kind::toggle ? "toggle" : "stop_when"},
                      {"time", event.time},
                      {"row", event.row},
                      {"message", event.message}});
  j["events"] = events;
  put_warnings(j, simulation.warnings);
  j["columns"] = table.columns;
  j["column_units"] = table.units;
  j["rows"] = table.rows;
  out << json_text(j, 1) << '\n';
}

namespace {

std::string percent_text(double fraction) { return fmt::format("{:.3g}", 100 * fraction); }

// The study's verdict, one sentence.
std::string convergence_verdict(const FeConvergence& c) {
  if (c.converged)
    return "converged: every peak changed by less than " + percent_text(c.tolerance) + " % on the last mesh";
  return "not converged to " + percent_text(c.tolerance) + " %: " + c.stopped;
}

void write_fe_convergence_json(std::ostream& out, const Analysis& analysis, const FeConvergence& c) {
  const Model& m = analysis.model();
  nlohmann::ordered_json j;
  j["model"] = m.name;
  j["method"] = "fe";
  j["units"] = {{"stress", "MPa"}, {"length", m.units.length}, {"change", "%"}};
  j["tolerance"] = 100 * c.tolerance;
  j["converged"] = c.converged;
  j["stopped"] = c.converged ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(c.stopped);
  nlohmann::ordered_json meshes = nlohmann::json::array();
  for (const FeConvergence::Mesh& mesh : c.meshes) {
    nlohmann::ordered_json links = nlohmann::json::array();
    for (std::size_t k = 0; k < mesh.peaks.size(); ++k) {
      const FePeak& p = mesh.peaks[k];
      const Eigen::Vector2d where = body_frame_point(m, p.body, p.at);
      nlohmann::ordered_json link;
      link["body"] = m.bodies[p.body].name;
      link["mesh_size"] = p.mesh_size / m.units.length_scale;
      link["nodes"] = p.nodes;
      link["elements"] = p.elements;
      link["von_mises"] = to_megapascal(p.von_mises);
      link["step"] = p.step;
      link["x"] = where.x() / m.units.length_scale;
      link["y"] = where.y() / m.units.length_scale;
      link["change"] =
          mesh.change.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(100 * mesh.change[k]);
      links.push_back(link);
    }
    meshes.push_back({{"refinement", mesh.refinement}, {"links", links}});
  }
  j["meshes"] = meshes;
  out << json_text(j, 1) << '\n';
}

}  // namespace

void write_fe_convergence(std::ostream& out, const std::string& format, const Analysis& analysis,
                          const FeConvergence& c) {
  if (format == "json") return write_fe_convergence_json(out, analysis, c);
  const Model& m = analysis.model();
  std::vector<std::vector<std::string>> cells{{"mesh", "body", "mesh_size", "nodes", "von_mises", "change"}};
  if (format != "csv") cells.push_back({"", "", "[" + m.units.length + "]", "", "[MPa]", "[%]"});
  for (std::size_t i = 0; i < c.meshes.size(); ++i) {
    const FeConvergence::Mesh& mesh = c.meshes[i];
    for (std::size_t k = 0; k < mesh.peaks.size(); ++k) {
      const FePeak& p = mesh.peaks[k];
      cells.push_back({std::to_string(i + 1), m.bodies[p.body].name,
                       fmt::format("{:.6g}", p.mesh_size / m.units.length_scale), std::to_string(p.nodes),
                       fmt::format("{:.6g}", to_megapascal(p.von_mises)),
                       mesh.change.empty() ? "" : fmt::format("{:.3f}", 100 * mesh.change[k])});
    }
  }
  if (format == "csv") {
    for (const auto& row : cells) {
      for (std::size_t col = 0; col < row.size(); ++col) out << (col ? "," : "") << csv_field(row[col]);
      out << '\n';
    }
    return;
  }
  out << "Finite-element peaks, refining every plate's mesh (element sizes halved each time):\n";
  std::vector<std::size_t> width(cells[0].size(), 0);
  for (const auto& row : cells)
    for (std::size_t col = 0; col < row.size(); ++col) width[col] = std::max(width[col], row[col].size());
  for (const auto& row : cells) {
    std::string line;
    for (std::size_t col = 0; col < row.size(); ++col)
      line += col == 1 ? fmt::format("  {:<{}}", row[col], width[col])
                       : fmt::format("{}{:>{}}", col ? "  " : "", row[col], width[col]);
    line.erase(line.find_last_not_of(' ') + 1);  // the first mesh has no change
    out << line << '\n';
  }
  out << convergence_verdict(c) << '\n';
}

}  // namespace nbar::io
