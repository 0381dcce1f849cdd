#include "nbar/request/synthesis_request.hpp"

#include <map>
#include <sstream>

#include "request/option_rules.hpp"

namespace nbar::request {

namespace {

using synthesis::SynthesisKind;
using namespace rule_builders;

// A seed is any 32-bit number: the widest every front-end holds exactly (a JSON number and
// Python's int both would hold more, the rules' readers not beyond 2^53).
constexpr double kMaxSeed = 4294967295.0;

std::vector<OptionRule> rules_of(SynthesisKind kind) {
  std::vector<OptionRule> rules{
      choice("format", "table (default) or json", {"table", "json"}),
      flag("all", "also list defective designs and (five-point) complex solutions"),
      integer_rule("top",
                   "list (and export) at most N designs, best first; 0 for all (default " +
                       std::to_string(SynthesisRequest::kDefaultTop) + ")",
                   0, kIntMax),
      integer_rule("threads",
                   "threads for path tracking and for checking the designs (default 0: every hardware thread)", 0,
                   SynthesisRequest::kMaxThreads),
  };
  if (kind == SynthesisKind::FivePoint || kind == SynthesisKind::NinePoint || kind == SynthesisKind::Path)
    rules.push_back(integer_rule(
        "seed", "five-point, nine-point, path: random seed of the homotopy and of path's random starts (default 1)", 0,
        kMaxSeed));
  return rules;
}

}  // namespace

const std::vector<OptionRule>& SynthesisRequest::rules(SynthesisKind kind) {
  static const std::map<SynthesisKind, std::vector<OptionRule>> by_kind = [] {
    std::map<SynthesisKind, std::vector<OptionRule>> out;
    for (const SynthesisKind k : {SynthesisKind::FivePoint, SynthesisKind::Burmester, SynthesisKind::Function,
                                  SynthesisKind::NinePoint, SynthesisKind::Path})
      out.emplace(k, rules_of(k));
    return out;
  }();
  return by_kind.at(kind);
}

SynthesisRequest SynthesisRequest::read(SynthesisKind kind, const Options& options) {
  const std::vector<OptionRule>& r = rules(kind);
  check_known(options, r, synthesis::to_string(kind));
  SynthesisRequest s;
  s.kind = kind;
  s.format = read_text(options, rule_of(r, "format")).value_or("table");
  s.all = read_flag(options, rule_of(r, "all"));
  s.top = static_cast<int>(read_integer(options, rule_of(r, "top")).value_or(kDefaultTop));
  s.threads = static_cast<unsigned>(read_integer(options, rule_of(r, "threads")).value_or(0));
  if (options.has("seed")) s.seed = static_cast<std::uint64_t>(*read_integer(options, rule_of(r, "seed")));
  return s;
}

synthesis::SynthesisRunOptions SynthesisRequest::run_options() const {
  synthesis::SynthesisRunOptions run;
  run.threads = threads;
  run.seed = seed;
  return run;
}

io::SynthesisListing SynthesisRequest::listing(const synthesis::SynthesisOutcome& outcome,
                                               const std::string& export_dir) const {
  io::SynthesisListing l;
  l.shown = synthesis::shown_rows(outcome, all, top);
  l.all = all;
  l.export_dir = export_dir;
  return l;
}

std::string SynthesisRequest::answer(const synthesis::SynthesisTask& task, const synthesis::SynthesisOutcome& outcome,
                                     const io::SynthesisListing& listing) const {
  if (format == "json") return io::synthesis_json(task, outcome, listing);
  std::ostringstream out;
  io::write_synthesis_table(out, task, outcome, listing);
  return out.str();
}

}  // namespace nbar::request
