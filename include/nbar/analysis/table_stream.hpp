// The result table of a sweep row by row, without keeping the sweep: for writers of long
// sweeps (the CSV of `nbar solve`), whose memory then does not grow with the number of samples.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "nbar/analysis/analysis.hpp"

namespace nbar {

// The rows of result_table(analyse(mechanism, options)), bit for bit, handed out one at a
// time. The noise made exact 0 (zero_numerical_noise) is measured against the largest value of
// each unit over the whole sweep, which is known only at its end. measure() runs the pipeline
// once, keeping those sizes (and raising every error analyse would, before any row is out) and
// the rows themselves while they fit in kept_rows_budget() bytes; rows() then hands the kept
// rows out. A sweep too long for the budget runs a second time in rows(), each row handed out
// as it is solved, so memory stays bounded. Both passes are the same deterministic
// computation, so they give the same numbers.
class TableStream {
 public:
  // Throws Error(BadInput) for options out of range and for the stress stage (its peaks need
  // the whole sweep: use analyse).
  // `extra`: the columns on request to compute as well (columns_on_request), for a select()
  // after measure() to find.
  TableStream(std::shared_ptr<const Mechanism> mechanism, const AnalysisOptions& options, ColumnsOnRequest extra = {});
  ~TableStream();
  TableStream(const TableStream&) = delete;
  TableStream& operator=(const TableStream&) = delete;

  // Every column (the selected ones after select()).
  const std::vector<std::string>& columns() const { return columns_; }
  const std::vector<std::string>& units() const { return units_; }
  // Keeps only the columns matching `patterns`, as select_columns does, adding first the columns
  // on request they name (columns_on_request). Throws Error(ErrorKind::BadInput) naming a
  // pattern that matches nothing. Call it once, before measure().
  void select(const std::vector<std::string>& patterns);

  // The first pass. Throws Error as analyse does.
  void measure();
  // Every row (columns().size() values) to `sink`, in sweep order: the kept rows, or a second
  // pass when the first could not keep them.
  void rows(const std::function<void(const double* row)>& sink);

  // Bytes of rows the first pass may keep (default 4 MiB: about 12 000 rows of a four-bar's
  // 43 columns); 0 always runs twice. Set before measure().
  void set_kept_rows_budget(std::size_t bytes) { kept_rows_budget_ = bytes; }
  std::size_t kept_rows_budget() const { return kept_rows_budget_; }
  // How many times the pipeline ran (1 or 2 once rows() is done).
  int passes() const { return passes_; }

  // Of the last pass: the sweep (complete, stop reason, warnings, solved; no samples kept) and
  // the warnings of every stage, as Analysis::warnings().
  const SweepResult& sweep() const { return sweep_; }
  std::vector<Warning> warnings() const;

 private:
  struct Pass;
  void run(Pass& pass);
  void name_columns();

  std::shared_ptr<const Mechanism> mechanism_;
  AnalysisOptions options_;
  std::shared_ptr<const InverseDynamics> dynamics_;
  std::vector<std::string> columns_, units_;
  std::vector<std::string> all_units_;
  ColumnsOnRequest extra_;
  std::vector<bool> on_request_;     // per column of the whole table
  std::vector<std::size_t> picked_;  // columns kept, in the order asked
  std::vector<double> threshold_;    // per column of the whole table: noise below this is 0
  bool measured_ = false;
  std::size_t kept_rows_budget_ = std::size_t{4} << 20;
  std::vector<double> kept_rows_;  // the first pass's rows, every column, when they fit
  bool rows_kept_ = false;
  int passes_ = 0;
  // check_before_sweep's warnings, found on the first pass (a law undefined in the sweep is
  // refused there); every pass's sweep carries them.
  std::optional<std::vector<Warning>> before_sweep_;
  SweepResult sweep_;
  std::optional<DynamicsStage> dynamics_stage_;  // its summary only (no samples)
};

}  // namespace nbar
