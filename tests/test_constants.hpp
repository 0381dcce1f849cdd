// Constants many test files use, defined once: a test program compiles its files in unity
// batches, one unit each, where a file-private copy in each file would be defined twice.
#pragma once

#include <numbers>

namespace nbar::test_constants {

inline constexpr double kPi = std::numbers::pi;
inline constexpr double kDeg = kPi / 180.0;  // one degree in radians

}  // namespace nbar::test_constants
