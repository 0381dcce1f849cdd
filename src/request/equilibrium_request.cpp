#include "nbar/request/equilibrium_request.hpp"

#include "request/option_rules.hpp"

namespace nbar::request {

using namespace rule_builders;

const std::vector<OptionRule>& EquilibriumRequest::rules() {
  static const std::vector<OptionRule> rules = {
      choice("format",
             "table (default: the pose, then the stability and the residual), csv (the pose's row) or json "
             "(everything)",
             {"table", "csv", "json"}),
      names("columns", "only these columns of the pose, comma-separated names or globs, e.g. 'crank,B.*'"),
      positive_integer("max_iterations", "most Newton iterations (default 50)"),
  };
  return rules;
}

EquilibriumRequest EquilibriumRequest::read(const Options& options) {
  EquilibriumRequest r;
  r.format = read_text(options, rule_of(rules(), "format")).value_or("table");
  r.columns = read_names(options, rule_of(rules(), "columns"));
  r.max_iterations = static_cast<int>(read_integer(options, rule_of(rules(), "max_iterations")).value_or(50));
  return r;
}

EquilibriumOptions EquilibriumRequest::equilibrium_options() const {
  EquilibriumOptions options;
  options.max_iterations = max_iterations;
  return options;
}

ResultTable EquilibriumRequest::table(const Mechanism& mechanism, const Equilibrium& equilibrium) const {
  ResultTable table = equilibrium_table(mechanism, equilibrium);
  if (columns.empty()) return table;
  try {
    return select_columns(table, columns);
  } catch (const Error& e) {
    throw OptionError("columns", literal(e.message()));
  }
}

}  // namespace nbar::request
