// A driver's motion law: an arithmetic expression in the time t, e.g. "30*sin(2*pi*t)".
// Parsed once, then evaluated either as a number or as a truncated Taylor series in t,
// which gives the driver's value, speed, acceleration, jerk... exactly.
#pragma once

#include <memory>
#include <string>
#include <string_view>

#include "nbar/model/diagnostics.hpp"
#include "nbar/model/series.hpp"

namespace nbar {

class Expression;  // the parsed tree, defined in law.cpp

// Thrown for a malformed expression (an invalid model's law); `column` is the 0-based offset in
// the text. The readers of model and task files catch it to point at the law's place in the file.
class LawSyntaxError : public Error {
 public:
  LawSyntaxError(int column, const std::string& message) : Error(ErrorKind::InvalidModel, message), column_(column) {}
  int column() const { return column_; }

 private:
  int column_;
};

class Law {
 public:
  // Grammar: numbers, t, pi, e, + - * / ^ (right associative), unary minus, parentheses,
  // functions sin cos tan exp log sqrt abs asin acos atan sinh cosh tanh log10.
  // `scale` multiplies the result (model units -> SI). `variable` names the variable (t for a
  // driver's law, x for a synthesis task's function); messages use that name.
  static Law parse(const std::string& text, double scale = 1.0, std::string_view variable = "t");

  // Both throw Error(ErrorKind::UndefinedLaw) where the law (or a derivative asked for) has no finite value.
  double value(double t) const;
  // Taylor series of the law around t0 with `terms` coefficients.
  Series series(double t0, int terms) const;
  const std::string& text() const { return text_; }

 private:
  std::shared_ptr<const Expression> root_;
  std::string text_;
  std::string variable_ = "t";
  double scale_ = 1.0;
};

}  // namespace nbar
