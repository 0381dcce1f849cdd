#include "explain_expr.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <initializer_list>

namespace nbar::explain_detail {

namespace {

using K = Ex::Kind;

E make(Ex e) { return std::make_shared<const Ex>(std::move(e)); }

// Concatenation by appending: g++ 12 warns (-Wrestrict, a false positive) on some
// `literal + std::string` chains.
std::string cat(std::initializer_list<std::string> parts) {
  std::string out;
  for (const auto& p : parts) out.append(p);
  return out;
}

bool is_num(const E& e) { return e->kind == K::Num; }

// Text of a factor: sums and negative numbers in parentheses.
std::string text_factor(const E& e) {
  if (e->kind == K::Sum || (e->kind == K::Num && e->value < 0)) return cat({"(", text(e), ")"});
  return text(e);
}
std::string latex_factor(const E& e) {
  if (e->kind == K::Sum || (e->kind == K::Num && e->value < 0)) return cat({"\\left(", latex(e), "\\right)"});
  return latex(e);
}

template <class Factor, class Number>
std::string render_sum(const Ex& s, Factor factor, Number numeral, const std::string& times) {
  std::string out;
  bool first = true;
  for (const auto& [c, t] : s.terms) {
    const std::string body = std::abs(c) == 1.0 ? factor(t) : numeral(std::abs(c)) + times + factor(t);
    out += first ? (c < 0 ? "-" : "") : (c < 0 ? " - " : " + ");
    out += body;
    first = false;
  }
  if (s.value != 0.0 || first) {
    if (first)
      out += numeral(s.value);
    else
      out += (s.value < 0 ? " - " : " + ") + numeral(std::abs(s.value));
  }
  return out;
}

}  // namespace

E num(double v) {
  Ex e;
  e.kind = K::Num;
  e.value = v == 0.0 ? 0.0 : v;
  return make(std::move(e));
}

E sym(std::string text, std::string latex) {
  Ex e;
  e.kind = K::Sym;
  e.text = std::move(text);
  e.latex = std::move(latex);
  return make(std::move(e));
}

E sum(const std::vector<std::pair<double, E>>& terms) {
  Ex s;
  s.kind = K::Sum;
  for (const auto& [c, t] : terms) {
    if (c == 0.0) continue;
    if (is_num(t)) {
      s.value += c * t->value;
    } else if (t->kind == K::Sum && c == 1.0) {
      for (const auto& inner : t->terms) s.terms.push_back(inner);
      s.value += t->value;
    } else if (t->kind == K::Sum && t->value == 0.0 && t->terms.size() == 1) {
      s.terms.push_back({c * t->terms[0].first, t->terms[0].second});
    } else {
      s.terms.push_back({c, t});
    }
  }
  if (s.terms.empty()) return num(s.value);
  if (s.terms.size() == 1 && s.value == 0.0 && s.terms[0].first == 1.0) return s.terms[0].second;
  return make(std::move(s));
}

E scale(const E& e, double c) {
  if (c == 0.0) return num(0.0);
  if (is_num(e)) return num(c * e->value);
  if (c == 1.0) return e;
  return sum({{c, e}});
}

E mul(const E& a, const E& b) {
  if (is_num(a)) return scale(b, a->value);
  if (is_num(b)) return scale(a, b->value);
  Ex p;
  p.kind = K::Prod;
  p.a = a;
  p.b = b;
  return make(std::move(p));
}

E sq(const E& e) {
  Ex s;
  s.kind = K::Square;
  s.a = e;
  return make(std::move(s));
}

E call(bool sine, const E& arg) {
  Ex f;
  f.kind = sine ? K::Sin : K::Cos;
  f.a = arg;
  return make(std::move(f));
}

bool is_zero(const E& e) { return is_num(e) && e->value == 0.0; }

std::string text(const E& e) {
  switch (e->kind) {
    case K::Num: return number(e->value);
    case K::Sym: return e->text;
    case K::Sum:
      return render_sum(
          *e, text_factor, [](double v) { return number(v); }, "*");
    case K::Prod: return cat({text_factor(e->a), "*", text_factor(e->b)});
    case K::Square: {
      const bool bare = e->a->kind == K::Sym || (e->a->kind == K::Num && e->a->value >= 0);
      return bare ? cat({text(e->a), "^2"}) : cat({"(", text(e->a), ")^2"});
    }
    case K::Sin: return cat({"sin(", text(e->a), ")"});
    case K::Cos: return cat({"cos(", text(e->a), ")"});
  }
  return {};
}

std::string latex(const E& e) {
  switch (e->kind) {
    case K::Num: return latex_number(e->value);
    case K::Sym: return e->latex;
    case K::Sum:
      return render_sum(
          *e, latex_factor, [](double v) { return latex_number(v); }, "\\,");
    case K::Prod: return cat({latex_factor(e->a), "\\,", latex_factor(e->b)});
    case K::Square: {
      const bool bare = e->a->kind == K::Sym || (e->a->kind == K::Num && e->a->value >= 0);
      return bare ? cat({"{", latex(e->a), "}^{2}"}) : cat({"\\left(", latex(e->a), "\\right)^{2}"});
    }
    case K::Sin:
    case K::Cos: {
      const std::string f = e->kind == K::Sin ? "\\sin " : "\\cos ";
      return e->a->kind == K::Sym ? cat({f, latex(e->a)}) : cat({f, "\\left(", latex(e->a), "\\right)"});
    }
  }
  return {};
}

std::string plain_name(const std::string& name) {
  std::string out;
  for (char ch : name) {
    const bool ok = (ch >= 'A' && ch <= 'Z') || (ch >= 'a' && ch <= 'z') || (ch >= '0' && ch <= '9') || ch == '_';
    out += ok ? ch : '_';
  }
  return out;
}

std::string tex_escape(const std::string& s) {
  std::string out;
  for (char ch : s) {
    if (ch == '_' || ch == '#' || ch == '%' || ch == '&' || ch == '$' || ch == '{' || ch == '}')
      out += std::string("\\") + ch;
    else if (ch == '\\' || ch == '^' || ch == '~')
      out += "{-}";
    else
      out += ch;
  }
  return out;
}

std::string latex_name(const std::string& name) {
  int letters = 0;
  for (char ch : name)
    if ((ch >= 'A' && ch <= 'Z') || (ch >= 'a' && ch <= 'z')) ++letters;
  const std::string out = tex_escape(name);
  return letters > 1 ? "\\mathrm{" + out + "}" : out;
}

std::string number(double v, int digits) {
  if (!std::isfinite(v)) return v != v ? "nan" : (v > 0 ? "inf" : "-inf");
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  std::string s = buf;
  // Rounding can leave a lone minus sign on a zero ("-0"): drop it.
  bool all_zero = true;
  for (char ch : s) {
    if (ch == 'e') break;
    if (ch >= '1' && ch <= '9') all_zero = false;
  }
  if (all_zero) return "0";
  return s;
}

std::string latex_number(double v, int digits) {
  const std::string s = number(v, digits);
  const auto e = s.find('e');
  if (e == std::string::npos) return s;
  const std::string mantissa = s.substr(0, e);
  int exponent = std::atoi(s.c_str() + e + 1);
  return (mantissa == "1"    ? ""
          : mantissa == "-1" ? "-"
                             : mantissa + " \\times ") +
         "10^{" + std::to_string(exponent) + "}";
}

}  // namespace nbar::explain_detail
