#include "nbar/model/units.hpp"

#include <cctype>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string_view>
#include <vector>

#include "nbar/model/diagnostics.hpp"

namespace nbar {

std::optional<double> length_unit_scale(const std::string& unit) {
  if (unit == "m") return 1.0;
  if (unit == "mm") return 1e-3;
  if (unit == "cm") return 1e-2;
  if (unit == "in") return 0.0254;
  if (unit == "ft") return 0.3048;
  return std::nullopt;
}

std::optional<double> angle_unit_scale(const std::string& unit) {
  if (unit == "deg") return std::numbers::pi / 180.0;
  if (unit == "rad") return 1.0;
  return std::nullopt;
}

std::optional<Units> Units::make(const std::string& length, const std::string& angle) {
  auto ls = length_unit_scale(length);
  auto as = angle_unit_scale(angle);
  if (!ls || !as) return std::nullopt;
  Units u;
  u.length = length;
  u.angle = angle;
  u.length_scale = *ls;
  u.angle_scale = *as;
  return u;
}

namespace {

std::string trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return std::string(s);
}

}  // namespace

Quantity parse_rate(const std::string& text, int order) {
  const std::string s = trim(text);
  std::size_t used = 0;
  double number = 0.0;
  try {
    number = std::stod(s, &used);
  } catch (const std::exception&) {
    throw Error(ErrorKind::BadInput, "expected a number followed by a unit, got '" + text + "'");
  }
  if (!std::isfinite(number)) throw Error(ErrorKind::BadInput, "'" + text + "' is not a finite number");
  std::string unit = trim(std::string_view(s).substr(used));
  // Accept "s2", "s^2", "s²" alike for accelerations.
  const std::string per = order == 1 ? "/s" : "/s^2";
  auto strip_per_time = [&](std::string& u) -> bool {
    for (const std::string& suffix :
         order == 1 ? std::vector<std::string>{"/s"} : std::vector<std::string>{"/s^2", "/s2", "/s\u00b2"}) {
      if (u.size() > suffix.size() && u.compare(u.size() - suffix.size(), suffix.size(), suffix) == 0) {
        u.erase(u.size() - suffix.size());
        return true;
      }
    }
    return false;
  };
  // Units are case-sensitive; a unit that only differs in case gets the right spelling.
  std::string lower = unit;
  for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (lower != unit) {
    const std::string suggestion = s.substr(0, used) + " " + lower;
    bool fits = true;
    try {
      parse_rate(suggestion, order);
    } catch (const Error&) {
      fits = false;
    }
    if (fits)
      throw Error(ErrorKind::BadInput, "'" + text + "': units are case-sensitive: did you mean '" + suggestion + "'?");
  }
  Quantity q;
  if (order == 1 && unit == "rpm") {
    q.value_si = number * 2.0 * std::numbers::pi / 60.0;
    q.angular = true;
    return q;
  }
  std::string base = unit;
  if (!strip_per_time(base)) {
    throw Error(ErrorKind::BadInput,
                "'" + text + "' needs a unit per time such as " +
                    (order == 1 ? std::string("rpm, rad/s, deg/s or m/s") : std::string("rad/s^2, deg/s^2 or m/s^2")));
  }
  if (auto a = angle_unit_scale(base)) {
    q.value_si = number * *a;
    q.angular = true;
  } else if (base == "rev") {
    q.value_si = number * 2.0 * std::numbers::pi;
    q.angular = true;
  } else if (auto l = length_unit_scale(base)) {
    q.value_si = number * *l;
    q.angular = false;
  } else {
    throw Error(ErrorKind::BadInput, "unknown unit '" + unit + "' in '" + text + "' (use rpm, rad" + per + ", deg" +
                                         per + ", rev" + per + ", m" + per + ", mm" + per + ", in" + per + "...)");
  }
  return q;
}

}  // namespace nbar
