#include "nbar/model/law.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <sstream>
#include <string_view>
#include <utility>
#include <vector>

#include "model/double_text.hpp"
#include "nbar/model/diagnostics.hpp"

namespace nbar {

namespace {

enum class Op : std::uint8_t {
  kNumber,
  kTime,
  kAdd,
  kSub,
  kMul,
  kDiv,
  kPow,
  kNeg,
  // Functions of one argument; kept contiguous so that is_function() is a range test.
  kSin,
  kCos,
  kTan,
  kExp,
  kLog,
  kSqrt,
  kAbs,
  kAsin,
  kAcos,
  kAtan,
  kSinh,
  kCosh,
  kTanh,
  kLog10,
};

constexpr bool is_function(Op op) { return op >= Op::kSin && op <= Op::kLog10; }

struct FunctionName {
  std::string_view name;
  Op op;
};

constexpr FunctionName kFunctions[] = {
    {"sin", Op::kSin},   {"cos", Op::kCos},   {"tan", Op::kTan},   {"exp", Op::kExp},     {"log", Op::kLog},
    {"sqrt", Op::kSqrt}, {"abs", Op::kAbs},   {"asin", Op::kAsin}, {"acos", Op::kAcos},   {"atan", Op::kAtan},
    {"sinh", Op::kSinh}, {"cosh", Op::kCosh}, {"tanh", Op::kTanh}, {"log10", Op::kLog10},
};

// A constant of the same kind as `like`: a double, or a series with as many terms.
inline double constant(double v, double /*like*/) { return v; }
inline Series constant(double v, const Series& like) { return Series(like.terms(), v); }

inline double absolute(double x) { return std::fabs(x); }

// Near a zero of x, |x| is smooth only if x keeps its sign on both sides, i.e. if its first
// nonzero coefficient belongs to an even power; then |x| is just +-x. An odd leading power
// (|s|, |s^3|) leaves the derivatives of that order and above undefined.
Series absolute(const Series& x) {
  if (x[0] != 0.0) return x[0] > 0.0 ? x : -x;
  for (int m = 1; m < x.terms(); ++m) {
    if (x[m] == 0.0) continue;
    if (m % 2 == 1) throw Error(ErrorKind::UndefinedLaw, "abs is not differentiable at 0");
    return x[m] > 0.0 ? x : -x;
  }
  // x vanishes to the order kept, hence so does |x|.
  return x;
}

template <class S>
S apply_function(Op op, const S& x) {
  // Block-scope using-declarations pick std:: for double; argument-dependent lookup adds the
  // nbar:: overloads for Series.
  using std::acos, std::asin, std::atan, std::cos, std::cosh, std::exp, std::log, std::sin, std::sinh, std::sqrt,
      std::tan, std::tanh;
  switch (op) {
    case Op::kSin: return sin(x);
    case Op::kCos: return cos(x);
    case Op::kTan: return tan(x);
    case Op::kExp: return exp(x);
    case Op::kLog: return log(x);
    case Op::kSqrt: return sqrt(x);
    case Op::kAbs: return absolute(x);
    case Op::kAsin: return asin(x);
    case Op::kAcos: return acos(x);
    case Op::kAtan: return atan(x);
    case Op::kSinh: return sinh(x);
    case Op::kCosh: return cosh(x);
    case Op::kTanh: return tanh(x);
    case Op::kLog10: return log(x) / std::numbers::ln10;
    default: break;
  }
  assert(false && "not a function");
  return x;
}

// Either operand may be a plain double (a folded constant): S op double is cheaper than
// S op S for a series, and the same thing for a double.
template <class A, class B>
auto apply_binary(Op op, const A& a, const B& b) {
  switch (op) {
    case Op::kAdd: return a + b;
    case Op::kSub: return a - b;
    case Op::kMul: return a * b;
    case Op::kDiv: return a / b;
    default: break;
  }
  assert(false && "not an arithmetic operator");
  return a + b;
}

std::string quoted_text(std::string_view s) {
  // Appending rather than "'" + std::string(s) sidesteps a GCC 12 -Wrestrict false positive.
  std::string q;
  q.reserve(s.size() + 2);
  q += '\'';
  q += s;
  q += '\'';
  return q;
}

std::string format_time(double t) {
  std::ostringstream out;
  out.precision(12);
  out << t;
  return out.str();
}

std::string ordinal(int k) {
  const char* suffix = "th";
  if (k % 100 < 11 || k % 100 > 13) {
    if (k % 10 == 1) suffix = "st";
    if (k % 10 == 2) suffix = "nd";
    if (k % 10 == 3) suffix = "rd";
  }
  return std::to_string(k) + suffix;
}

}  // namespace

// The parsed law as a flat post-order array of nodes: children always precede their parent,
// and the root is the last node. Subtrees without t are folded into a single number while
// parsing, so evaluation never recomputes constants like 2*pi.
class Expression {
 public:
  struct Node {
    Op op;
    bool has_t;
    int a;         // first operand (index into nodes_), or -1
    int b;         // second operand, or -1
    double value;  // kNumber only
  };

  int add_leaf(Op op, double value) {
    nodes_.push_back(Node{op, op == Op::kTime, -1, -1, value});
    return static_cast<int>(nodes_.size()) - 1;
  }

  int add(Op op, int a, int b = -1) {
    const bool has_t = nodes_[a].has_t || (b >= 0 && nodes_[b].has_t);
    if (!has_t) {
      // Folded operands are single number nodes at the end of the array; replace them by the
      // result so that the tree holds no dead nodes.
      const double v = fold(op, nodes_[a].value, b >= 0 ? nodes_[b].value : 0.0);
      nodes_.resize(static_cast<std::size_t>(a));
      return add_leaf(Op::kNumber, v);
    }
    nodes_.push_back(Node{op, true, a, b, 0.0});
    return static_cast<int>(nodes_.size()) - 1;
  }

  template <class S>
  S evaluate(const S& t) const {
    return eval(static_cast<int>(nodes_.size()) - 1, t);
  }

 private:
  static double fold(Op op, double a, double b) {
    if (op == Op::kNeg) return -a;
    if (op == Op::kPow) return std::pow(a, b);
    if (is_function(op)) return apply_function(op, a);
    return apply_binary(op, a, b);
  }

  template <class S>
  S eval(int i, const S& t) const {
    const Node& n = nodes_[static_cast<std::size_t>(i)];
    switch (n.op) {
      case Op::kNumber: return constant(n.value, t);
      case Op::kTime: return t;
      case Op::kNeg: return -eval(n.a, t);
      case Op::kPow: {
        const Node& exponent = nodes_[static_cast<std::size_t>(n.b)];
        using std::pow;
        // A constant exponent keeps integer powers of negative bases defined, e.g. (t-1)^2
        // for t < 1, which exp(p log x) would not.
        if (exponent.op == Op::kNumber) return pow(eval(n.a, t), exponent.value);
        return pow(eval(n.a, t), eval(n.b, t));
      }
      case Op::kAdd:
      case Op::kSub:
      case Op::kMul:
      case Op::kDiv: {
        const Node& left = nodes_[static_cast<std::size_t>(n.a)];
        const Node& right = nodes_[static_cast<std::size_t>(n.b)];
        if (left.op == Op::kNumber) return S(apply_binary(n.op, left.value, eval(n.b, t)));
        if (right.op == Op::kNumber) return S(apply_binary(n.op, eval(n.a, t), right.value));
        return S(apply_binary(n.op, eval(n.a, t), eval(n.b, t)));
      }
      default: return apply_function(n.op, eval(n.a, t));
    }
  }

  std::vector<Node> nodes_;
};

namespace {

class Parser {
 public:
  Parser(std::string_view text, std::string_view variable) : text_(text), variable_(variable) {}

  Expression parse() {
    skip_space();
    if (at_end()) throw LawSyntaxError(0, "empty law");
    parse_expr();
    skip_space();
    if (!at_end()) {
      const char c = text_[pos_];
      if (c == ')') fail("unmatched ')'");
      if (std::isalnum(static_cast<unsigned char>(c)) || c == '(' || c == '_') {
        fail("unexpected " + describe_here() + " (use '*' to multiply)");
      }
      fail("unexpected " + describe_here());
    }
    return std::move(expr_);
  }

 private:
  // Deep enough for any hand-written law, shallow enough to never exhaust the stack.
  static constexpr int kMaxDepth = 200;

  bool at_end() const { return pos_ >= text_.size(); }

  void skip_space() {
    while (!at_end() && std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
  }

  // Skips whitespace and consumes `c` if it is next.
  bool accept(char c) {
    skip_space();
    if (!at_end() && text_[pos_] == c) {
      ++pos_;
      return true;
    }
    return false;
  }

  [[noreturn]] void fail(const std::string& message) const { fail_at(pos_, message); }
  [[noreturn]] static void fail_at(std::size_t column, const std::string& message) {
    throw LawSyntaxError(static_cast<int>(column), message);
  }

  // The offending token for a message, at the current position.
  std::string describe_here() const {
    if (at_end()) return "end of expression";
    std::size_t end = pos_ + 1;
    if (std::isalnum(static_cast<unsigned char>(text_[pos_])) || text_[pos_] == '_') {
      while (end < text_.size() && (std::isalnum(static_cast<unsigned char>(text_[end])) || text_[end] == '_')) {
        ++end;
      }
    }
    return quoted_text(text_.substr(pos_, end - pos_));
  }

  int parse_expr() {
    int left = parse_term();
    for (;;) {
      if (accept('+')) {
        left = expr_.add(Op::kAdd, left, parse_term());
      } else if (accept('-')) {
        left = expr_.add(Op::kSub, left, parse_term());
      } else {
        return left;
      }
    }
  }

  int parse_term() {
    int left = parse_unary();
    for (;;) {
      if (accept('*')) {
        left = expr_.add(Op::kMul, left, parse_unary());
      } else if (accept('/')) {
        left = expr_.add(Op::kDiv, left, parse_unary());
      } else {
        return left;
      }
    }
  }

  // Every level of nesting (parentheses, function calls, signs, exponents) passes through
  // here, so this is where the depth is bounded.
  int parse_unary() {
    if (++depth_ > kMaxDepth) fail("expression nested too deeply");
    int result;
    if (accept('-')) {
      result = expr_.add(Op::kNeg, parse_unary());
    } else if (accept('+')) {
      result = parse_unary();
    } else {
      result = parse_power();
    }
    --depth_;
    return result;
  }

  int parse_power() {
    const int base = parse_primary();
    if (accept('^')) return expr_.add(Op::kPow, base, parse_unary());
    return base;
  }

  int parse_primary() {
    skip_space();
    if (at_end()) fail("unexpected end of expression");
    const char c = text_[pos_];
    if (std::isdigit(static_cast<unsigned char>(c)) || c == '.') return parse_number();
    if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') return parse_name();
    if (c == '(') {
      ++pos_;
      const int inner = parse_expr();
      expect_close();
      return inner;
    }
    fail("unexpected " + describe_here());
  }

  void expect_close() {
    if (!accept(')')) fail("expected ')'");
  }

  int parse_number() {
    const std::size_t start = pos_;
    std::size_t p = pos_;
    auto digit = [&](std::size_t i) { return i < text_.size() && std::isdigit(static_cast<unsigned char>(text_[i])); };
    bool digits = false;
    while (digit(p)) ++p, digits = true;
    if (p < text_.size() && text_[p] == '.') {
      ++p;
      while (digit(p)) ++p, digits = true;
    }
    if (!digits) fail("malformed number");
    // An exponent only if digits follow, so "2e" stays "2" followed by the name e and gets
    // the implicit-multiplication error rather than a confusing number error.
    if (p < text_.size() && (text_[p] == 'e' || text_[p] == 'E')) {
      std::size_t q = p + 1;
      if (q < text_.size() && (text_[q] == '+' || text_[q] == '-')) ++q;
      if (digit(q)) {
        p = q;
        while (digit(p)) ++p;
      }
    }
    double value = 0.0;
    const auto [end, error] = parse_double(text_.data() + start, text_.data() + p, value);
    if (error == std::errc::result_out_of_range) fail("number out of range");
    if (error != std::errc() || end != text_.data() + p) fail("malformed number");
    pos_ = p;
    return expr_.add_leaf(Op::kNumber, value);
  }

  int parse_name() {
    const std::size_t start = pos_;
    while (!at_end() && (std::isalnum(static_cast<unsigned char>(text_[pos_])) || text_[pos_] == '_')) {
      ++pos_;
    }
    const std::string_view name = text_.substr(start, pos_ - start);
    if (name == variable_) return expr_.add_leaf(Op::kTime, 0.0);
    if (name == "pi") return expr_.add_leaf(Op::kNumber, std::numbers::pi);
    if (name == "e") return expr_.add_leaf(Op::kNumber, std::numbers::e);
    for (const FunctionName& f : kFunctions) {
      if (f.name != name) continue;
      if (!accept('(')) fail("expected '(' after " + quoted_text(name));
      const int argument = parse_expr();
      expect_close();
      return expr_.add(f.op, argument);
    }
    skip_space();
    if (!at_end() && text_[pos_] == '(') fail_at(start, "unknown function " + quoted_text(name));
    fail_at(start, "unknown name " + quoted_text(name) + " (the variable is " + std::string(variable_) + ")");
  }

  std::string_view text_;
  std::string_view variable_;
  std::size_t pos_ = 0;
  int depth_ = 0;
  Expression expr_;
};

}  // namespace

Law Law::parse(const std::string& text, double scale, std::string_view variable) {
  Law law;
  law.root_ = std::make_shared<const Expression>(Parser(text, variable).parse());
  law.text_ = text;
  law.variable_ = variable;
  law.scale_ = scale;
  return law;
}

double Law::value(double t) const {
  if (!root_) throw Error(ErrorKind::BadInput, "law evaluated before being parsed");
  const double v = root_->evaluate(t) * scale_;
  if (!std::isfinite(v)) {
    throw Error(ErrorKind::UndefinedLaw,
                "law " + quoted_text(text_) + " is undefined at " + variable_ + " = " + format_time(t));
  }
  return v;
}

Series Law::series(double t0, int terms) const {
  if (!root_) throw Error(ErrorKind::BadInput, "law evaluated before being parsed");
  if (terms < 1 || terms > Series::kCapacity) {
    throw Error(ErrorKind::BadInput,
                "law series needs 1 to " + std::to_string(Series::kCapacity) + " terms, got " + std::to_string(terms));
  }
  Series s;
  try {
    s = root_->evaluate(Series::variable(terms, t0));
  } catch (const Error& e) {  // from an operation that has no derivative there (abs at 0)
    throw Error(ErrorKind::UndefinedLaw,
                "law " + quoted_text(text_) + " at " + variable_ + " = " + format_time(t0) + ": " + e.message());
  }
  s *= scale_;
  if (!std::isfinite(s[0])) {
    throw Error(ErrorKind::UndefinedLaw,
                "law " + quoted_text(text_) + " is undefined at " + variable_ + " = " + format_time(t0));
  }
  for (int k = 1; k < s.terms(); ++k) {
    if (!std::isfinite(s[k])) {
      throw Error(ErrorKind::UndefinedLaw, "law " + quoted_text(text_) + " has no finite " + ordinal(k) + " derivative at " +
                                               variable_ + " = " + format_time(t0));
    }
  }
  return s;
}

}  // namespace nbar
