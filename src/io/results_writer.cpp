#include "io/results_writer.hpp"

#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <string>
#include <vector>

namespace nbar::io {

void write_csv(std::ostream& out, const ResultTable& table) {
  for (std::size_t c = 0; c < table.columns.size(); ++c) out << (c ? "," : "") << table.columns[c];
  out << '\n';
  std::string line;
  for (const auto& row : table.rows) {
    line.clear();
    for (std::size_t c = 0; c < row.size(); ++c) {
      if (c) line += ',';
      // Adding 0.0 turns -0 into 0, which nobody wants to read.
      line += fmt::format("{:.12g}", row[c] + 0.0);
    }
    out << line << '\n';
  }
}

void write_text_table(std::ostream& out, const ResultTable& table) {
  const std::size_t n = table.columns.size();
  std::vector<std::vector<std::string>> cells(table.rows.size());
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
  auto line = [&](auto cell) {
    std::string s;
    for (std::size_t c = 0; c < n; ++c) s += fmt::format("{}{:>{}}", c ? "  " : "", cell(c), width[c]);
    out << s << '\n';
  };
  line([&](std::size_t c) { return table.columns[c]; });
  line([&](std::size_t c) { return table.units[c].empty() ? std::string() : "[" + table.units[c] + "]"; });
  for (std::size_t r = 0; r < cells.size(); ++r) line([&](std::size_t c) { return cells[r][c]; });
}

void write_json(std::ostream& out, const Mechanism& mech, const SweepResult& sweep, const ResultTable& table) {
  const Model& m = mech.model();
  const MobilityReport& mob = mech.mobility();
  nlohmann::ordered_json j;
  j["model"] = m.name;
  j["units"] = {{"length", m.units.length}, {"angle", m.units.angle}, {"time", "s"}};
  nlohmann::ordered_json redundant = nlohmann::json::array();
  for (int r : mob.redundant) redundant.push_back(mech.rows()[r].label);
  j["dof"] = {{"gruebler", mob.grubler}, {"mobility", mob.dof}, {"redundant_constraints", redundant}};
  nlohmann::ordered_json loops = nlohmann::json::array();
  for (std::size_t l = 0; l < mech.four_bar_loops().size(); ++l)
    loops.push_back({{"loop", mech.four_bar_loops()[l].name}, {"branch", sweep.branches[l]}});
  j["branches"] = loops;
  j["order"] = sweep.order;
  j["complete"] = sweep.complete;
  if (!sweep.complete) j["stop_reason"] = sweep.stop_reason;
  j["warnings"] = sweep.warnings;
  j["max_residual"] = sweep.max_residual / m.units.length_scale;
  j["columns"] = table.columns;
  j["column_units"] = table.units;
  j["rows"] = table.rows;
  out << j.dump(1) << '\n';
}

}  // namespace nbar::io
