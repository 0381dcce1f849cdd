// Number checks for the commands' options. CLI11's own print their limits with std::to_string
// ("Value 0 not in range 0.000000 to 1797693...000000", from a range that starts above 0), let
// NaN through, and call a word out of range: these say what is wrong with the value given.
#pragma once

#include "command_line.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <sstream>
#include <string>

#include "nbar/model/file_errors.hpp"
#include "nbar/request/options.hpp"

namespace nbar::cli {

// The request layer's reading and writing of a typed number.
using request::finite_number;
using request::number_text;

// A finite number for which `accept` holds; otherwise "'abc' is not a number" or the rule.
template <class Accept>
Check number_check(Accept accept, const std::string& rule, const std::string& description) {
  return Check{[accept, rule](std::string& text) -> std::string {
                 const std::optional<double> x = finite_number(text);
                 if (!x) return "'" + text + "' is not a finite number";
                 if (!accept(*x)) return "must be " + rule + ", not " + text;
                 return "";
               },
               description,
               {}};
}

inline Check positive() {
  return number_check([](double x) { return x > 0.0; }, "a positive number", "POSITIVE");
}

inline Check in_range(double low, double high) {
  const std::string span = number_text(low) + " to " + number_text(high);
  // Appended, not "[" + span: g++ 12 at -O3 warns (-Wrestrict) on a string inserted at its front.
  std::string description = "[";
  description += span;
  description += "]";
  return number_check([low, high](double x) { return x >= low && x <= high; }, "from " + span, description);
}

// An output file whose folder exists, checked before the command computes anything.
inline Check output_file() {
  // No description: the help keeps showing the option as TEXT.
  return Check{[](std::string& path) { return output_path_problem(path); }, "", {}};
}

}  // namespace nbar::cli
