// Units the user reads and writes; the core computes in SI (m, rad, s).
#pragma once

#include <optional>
#include <string>

namespace nbar {

struct Units {
  std::string length = "m";                   // m | mm | cm | in | ft
  std::string angle = "deg";                  // deg | rad
  double length_scale = 1.0;                  // metres per length unit
  double angle_scale = 0.017453292519943295;  // radians per angle unit

  static std::optional<Units> make(const std::string& length, const std::string& angle);
  double to_si_length(double v) const { return v * length_scale; }
  double to_si_angle(double v) const { return v * angle_scale; }
};

// Stresses are computed in Pa and shown in MPa. A division, not a multiplication by 1e-6, so
// that printed values stay what they always were.
inline constexpr double kPascalPerMegapascal = 1e6;
inline double to_megapascal(double pascal) { return pascal / kPascalPerMegapascal; }

std::optional<double> length_unit_scale(const std::string& unit);  // metres per unit
std::optional<double> angle_unit_scale(const std::string& unit);   // radians per unit

// A rate or its derivative written as "<number> <unit>", e.g. "1750 rpm", "10 rad/s",
// "-90 deg/s", "0.5 m/s", "2 rad/s^2". `order` is 1 for speeds and 2 for accelerations.
// Returns the value in SI (rad/s^order or m/s^order) and whether it is angular.
struct Quantity {
  double value_si = 0.0;
  bool angular = false;
};
// Throws Error(ErrorKind::BadInput) with a readable reason when the text is not such a quantity.
Quantity parse_rate(const std::string& text, int order);

}  // namespace nbar
