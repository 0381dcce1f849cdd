// Writing a sweep's results as CSV or JSON.
#pragma once

#include <ostream>

#include <string>
#include <vector>

#include "nbar/analysis/analysis.hpp"
#include "nbar/dynamics/forward_dynamics.hpp"
#include "nbar/kinematics/table.hpp"

namespace nbar::io {

// Header line of column names, then one line per sample; values in the model's units.
void write_csv(std::ostream& out, const ResultTable& table);

// The same CSV written a row at a time, as rows come (TableStream): each number with 12
// significant digits as printf's %.12g (std::to_chars), -0 written 0, into a buffer handed to
// the stream in large blocks. write_csv writes with it, so both give the same bytes.
class CsvWriter {
 public:
  CsvWriter(std::ostream& out, const std::vector<std::string>& columns);
  ~CsvWriter();  // flushes
  CsvWriter(const CsvWriter&) = delete;
  CsvWriter& operator=(const CsvWriter&) = delete;
  void row(const double* values);
  void flush();

 private:
  std::ostream& out_;
  std::size_t columns_;
  std::vector<char> buffer_;
  std::size_t used_ = 0;
};

// Aligned columns for people reading a terminal, with a units line under the names. With a
// line_width (characters, 0: no limit), a table wider than that is written as groups of
// columns one under the other, each group led by the first column (step) and fitting the width.
void write_text_table(std::ostream& out, const ResultTable& table, std::size_t line_width = 0);
// The width text tables are wrapped to where there is no terminal to ask (the web API), and
// the CLI's when $COLUMNS says nothing.
constexpr std::size_t kTextTableWidth = 80;

// The table's columns and rows, plus units per column, the degrees of freedom, the assembly
// branch of every four-bar loop, the sweep's residual and warnings. With `dynamics`, also
// whether the joint forces are unique, the equations' residual and their warnings.
void write_json(std::ostream& out, const Analysis& analysis, const ResultTable& table,
                const DynamicsStage* dynamics = nullptr);

// The table in `format`: "csv" (write_csv), "table" (write_text_table) or "json" (write_json with
// `dynamics`); throws Error(ErrorKind::BadInput) for another format.
void write_table(std::ostream& out, const std::string& format, const Analysis& analysis, const ResultTable& table,
                 const DynamicsStage* dynamics = nullptr, std::size_t line_width = 0);

// The largest von Mises stress of every link over the sweep, where and when, and its safety
// factor: format "table", "csv" or "json". Stresses in MPa, forces in N, moments in N m,
// positions in the model's length unit (x along the link from its first point to its second,
// y to the left of that line).
// Needs the analysis's stress stage. By finite elements (StressMethod::fe) the columns are the
// peak's von Mises, step, time, drivers, x, y, safety factor, then the mesh (nodes, elements,
// mesh_size, min_angle) and the numerical checks (unbalance, reaction: relative, ~0), and the
// JSON says "method": "fe".
void write_stress_report(std::ostream& out, const std::string& format, const Analysis& analysis);

// A convergence study of the finite-element peaks (nbar stress --method fe --converge): per mesh
// and link, the refinement (1, 2, 4...: the element sizes divided by it), the element size far
// from holes, the nodes, the peak von Mises (MPa) and its change from the mesh before (%); then
// whether every change fell below the tolerance, or why the study stopped. Format "table",
// "csv" or "json".
void write_fe_convergence(std::ostream& out, const std::string& format, const Analysis& analysis,
                          const FeConvergence& convergence);

// A simulation (nbar simulate) as JSON: the model, units, the free drivers, whether it ran to its
// end (and why not), the integrator's statistics and the largest constraint drift and energy
// error, the events met (kind, time, row, message), then the table's columns, units and rows.
void write_simulation_json(std::ostream& out, const Mechanism& mechanism, const Simulation& simulation,
                           const ResultTable& table);

}  // namespace nbar::io
