// The synthesis requests, one per method (five-point, nine-point, Burmester, function, path fit):
// what `nbar synth METHOD`, the web API's /api/synth/METHOD and Python's nbar.synth ask. The task
// itself is a document every front-end reads with io::parse_synthesis_task (a task file's text, the
// command line's task options written as one, the JSON body's `task`, Python's dict); the request
// owns the rest: which options the method takes, their ranges and defaults, the designs listed and
// the answer written.
//
//   const SynthesisRequest synth = SynthesisRequest::read(SynthesisKind::FivePoint, options);
//   SynthesisOutcome outcome = run_synthesis(task, synth.run_options());
//   std::cout << synth.answer(task, outcome);      // the table, or the JSON
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "nbar/io/synthesis_writer.hpp"
#include "nbar/request/options.hpp"
#include "nbar/synthesis/run.hpp"
#include "nbar/synthesis/task.hpp"

namespace nbar::request {

struct SynthesisRequest {
  static constexpr int kDefaultTop = 20;
  static constexpr int kMaxThreads = 1024;

  synthesis::SynthesisKind kind = synthesis::SynthesisKind::FivePoint;
  std::string format = "table";  // table or json
  bool all = false;              // defective designs and (five-point) complex solutions too
  int top = kDefaultTop;         // at most this many designs, best first; 0: every one
  unsigned threads = 0;          // 0: every hardware thread
  std::uint64_t seed = 1;        // methods with random starts (five-point, nine-point, path)

  // The options `kind` takes: every method the listing's and the threads'; the seed only the
  // methods whose solvers draw random numbers.
  static const std::vector<OptionRule>& rules(synthesis::SynthesisKind kind);
  // Refuses an option the method does not take (OptionError naming it and the ones it takes).
  static SynthesisRequest read(synthesis::SynthesisKind kind, const Options& options);

  synthesis::SynthesisRunOptions run_options() const;
  // The designs listed (shown_rows with `all` and `top`), exported to `export_dir` when given.
  io::SynthesisListing listing(const synthesis::SynthesisOutcome& outcome, const std::string& export_dir = {}) const;
  // The answer in `format`: the ranked table or the JSON document.
  std::string answer(const synthesis::SynthesisTask& task, const synthesis::SynthesisOutcome& outcome,
                     const io::SynthesisListing& listing) const;
};

}  // namespace nbar::request
