// The fallbacks of model/double_text.hpp (strtod and snprintf, for the WebAssembly build's libc++,
// which has no floating-point std::from_chars or std::to_chars) read every text as
// std::from_chars does (the same value bit for bit, the same end and the same error) and write
// every number as std::to_chars does.
#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "model/double_text.hpp"

namespace nbar {
namespace {

TEST(ParseDouble, TheFallbackReadsAsFromChars) {
  const char* texts[] = {"0",
                         "-0",
                         "1",
                         "250",
                         "3.14159265358979323846",
                         "-2.5e-3",
                         "1e308",
                         "4.9e-324",
                         "2.2250738585072014e-308",
                         "0.1",
                         ".5",
                         "5.",
                         "1e",
                         "1e+",
                         "12abc",
                         "7 mm",
                         "1,5",
                         "1e400",
                         "-1e400",
                         "1e-400",
                         "-1e-400",
                         "1e-320",
                         "inf",
                         "-Infinity",
                         "nan",
                         "0x1A",
                         "-0x10",
                         "+1",
                         " 1",
                         "-",
                         "",
                         "abc",
                         "1.7976931348623157e308",
                         "123456789012345678901234567890"};
  for (const char* text : texts) {
    SCOPED_TRACE(text);
    const char* last = text + std::strlen(text);
    double expected = 42.0, got = 42.0;
    const std::from_chars_result reference = std::from_chars(text, last, expected);
    const std::from_chars_result fallback = parse_double_by_strtod(text, last, got);
    EXPECT_EQ(fallback.ec, reference.ec);
    EXPECT_EQ(fallback.ptr - text, reference.ptr - text);
    if (reference.ec == std::errc() && expected == expected) {
      EXPECT_EQ(std::memcmp(&got, &expected, sizeof got), 0) << got << " vs " << expected;
    } else if (reference.ec == std::errc()) {
      EXPECT_NE(got, got);  // nan
    } else {
      EXPECT_EQ(got, 42.0);  // left alone
    }
  }
}

TEST(WriteDouble, TheFallbackWritesAsToChars) {
  std::vector<double> values = {0.0,
                                1.0,
                                -1.0,
                                0.1,
                                1e-5,
                                123456789012.0,
                                1234567890123.0,
                                1e21,
                                5e-324,
                                std::numeric_limits<double>::max(),
                                std::numeric_limits<double>::infinity(),
                                -std::numeric_limits<double>::infinity(),
                                std::nan(""),
                                2.0 / 3.0,
                                99.99999999999};
  std::mt19937_64 random(35);
  std::uniform_real_distribution<double> mantissa(-10.0, 10.0);
  std::uniform_int_distribution<int> exponent(-30, 30);
  for (int i = 0; i < 10000; ++i) values.push_back(mantissa(random) * std::pow(10.0, exponent(random)));
  for (const double v : values) {
    for (const int precision : {6, 12, 17}) {
      char expected[64], got[64];
      char* expected_end =
          std::to_chars(expected, expected + sizeof expected, v, std::chars_format::general, precision).ptr;
      char* got_end = write_double_general_by_snprintf(got, got + sizeof got, v, precision);
      ASSERT_EQ(std::string(got, got_end), std::string(expected, expected_end)) << v << " at precision " << precision;
    }
  }
}

}  // namespace
}  // namespace nbar
