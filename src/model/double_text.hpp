// Doubles to and from text as std::from_chars and std::to_chars do them, also with a standard
// library that has neither for floating point: libc++ 14, emscripten's. There strtod reads (its
// result is correctly rounded too) and snprintf writes, both in the "C" locale, the only one
// emscripten has.
#pragma once

#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <system_error>

namespace nbar {

// The fallback, compiled everywhere so that the tests hold it to std::from_chars where both exist.
inline std::from_chars_result parse_double_by_strtod(const char* first, const char* last, double& value) {
  std::string text(first, last);
  const std::size_t sign = !text.empty() && text.front() == '-' ? 1 : 0;
  if (text.size() <= sign) return {first, std::errc::invalid_argument};
  // strtod's extras: leading space, '+', and hexadecimal numbers ("0x1" is the 0 of it to from_chars).
  const unsigned char lead = static_cast<unsigned char>(text[sign]);
  if (!std::isdigit(lead) && lead != '.' && std::tolower(lead) != 'i' && std::tolower(lead) != 'n')
    return {first, std::errc::invalid_argument};
  if (lead == '0' && text.size() > sign + 1 && std::tolower(static_cast<unsigned char>(text[sign + 1])) == 'x')
    text.resize(sign + 1);
  errno = 0;
  char* end = nullptr;
  const double read = std::strtod(text.c_str(), &end);
  if (end == text.c_str()) return {first, std::errc::invalid_argument};
  const char* past = first + (end - text.c_str());
  if (errno == ERANGE && (std::isinf(read) || read == 0)) return {past, std::errc::result_out_of_range};
  value = read;
  return {past, std::errc()};
}

// As std::from_chars: no leading space or '+', '.' as the decimal point whatever the locale, the
// end of the number returned, out of range reported and the value left alone.
inline std::from_chars_result parse_double(const char* first, const char* last, double& value) {
#if defined(__cpp_lib_to_chars)
  return std::from_chars(first, last, value);
#else
  return parse_double_by_strtod(first, last, value);
#endif
}

// printf's %.<precision>g, as std::to_chars(first, last, value, std::chars_format::general,
// precision) writes it; [first, last) must have room for the number and a NUL.
inline char* write_double_general_by_snprintf(char* first, char* last, double value, int precision) {
  const int written = std::snprintf(first, static_cast<std::size_t>(last - first), "%.*g", precision, value);
  return first + written;
}

inline char* write_double_general(char* first, char* last, double value, int precision) {
#if defined(__cpp_lib_to_chars)
  return std::to_chars(first, last, value, std::chars_format::general, precision).ptr;
#else
  return write_double_general_by_snprintf(first, last, value, precision);
#endif
}

}  // namespace nbar
