// The stored generic instance of the nine-point problem: its parameters and one solution of
// each of its 1442 orbits, as written by nbar-nine-point-start into data/nine_point_start.inc
// (base64 of little-endian doubles: the orbit count, the 16 parameters, then per orbit the
// dyads' 8 coordinates; the rotations follow from them and Newton polishes all).
#include <Eigen/LU>

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>

#include "nbar/model/diagnostics.hpp"
#include "nbar/synthesis/nine_point_start.hpp"

namespace nbar::synthesis {
namespace {

const char* const kStartLines[] = {
#include "data/nine_point_start.inc"
};

constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

std::vector<double> decode(const std::string& text) {
  std::string bytes;
  std::uint32_t buffer = 0;
  int bits = 0;
  for (char c : text) {
    const char* at = std::strchr(kAlphabet, c);
    if (c == '=' || c == '\0' || !at) continue;
    buffer = (buffer << 6) | static_cast<std::uint32_t>(at - kAlphabet);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      bytes.push_back(static_cast<char>((buffer >> bits) & 0xFF));
    }
  }
  std::vector<double> values(bytes.size() / 8);
  for (size_t i = 0; i < values.size(); ++i) {
    std::uint64_t word = 0;
    for (int k = 0; k < 8; ++k) word |= std::uint64_t(static_cast<unsigned char>(bytes[8 * i + k])) << (8 * k);
    std::memcpy(&values[i], &word, sizeof word);  // std::bit_cast, which emscripten's libc++ 14 lacks
  }
  return values;
}

std::string encode(const std::vector<double>& values) {
  std::string bytes;
  for (double v : values) {
    std::uint64_t word = 0;
    std::memcpy(&word, &v, sizeof word);
    for (int k = 0; k < 8; ++k) bytes.push_back(static_cast<char>((word >> (8 * k)) & 0xFF));
  }
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    std::uint32_t chunk = 0;
    const size_t n = std::min<size_t>(3, bytes.size() - i);
    for (size_t k = 0; k < 3; ++k) chunk = (chunk << 8) | (k < n ? static_cast<unsigned char>(bytes[i + k]) : 0u);
    for (size_t k = 0; k < 4; ++k) out.push_back(k <= n ? kAlphabet[(chunk >> (18 - 6 * k)) & 63] : '=');
  }
  return out;
}

// The rotations of position i from the dyads: both circle equations are linear in (t, tb).
CVector with_rotations(const CVector& dyads, const CVector& p) {
  CVector s(24);
  s.tail<8>() = dyads;
  for (int i = 0; i < 8; ++i) {
    const Complex d = p[i], db = p[8 + i];
    Eigen::Matrix2cd m;
    Eigen::Vector2cd r;
    for (int dyad = 0; dyad < 2; ++dyad) {
      const Complex x = dyads[4 * dyad], xb = dyads[4 * dyad + 1], a = dyads[4 * dyad + 2], ab = dyads[4 * dyad + 3];
      m(dyad, 0) = x * (db - ab);
      m(dyad, 1) = xb * (d - a);
      r[dyad] = -(d * db - d * ab - a * db + x * ab + a * xb);
    }
    const Eigen::Vector2cd t = m.partialPivLu().solve(r);
    s[i] = t[0];
    s[8 + i] = t[1];
  }
  return s;
}

CVector polished(const CVector& affine, const CVector& p) {
  const ParameterizedSystem& f = nine_point_system();
  CVector v = f.from_affine(affine), step;
  for (int k = 0; k < 4; ++k) {
    if (!f.linear_solve(v, p, nullptr, step)) break;
    v -= step;
  }
  return f.to_affine(v);
}

}  // namespace

const NinePointStart& nine_point_start() {
  static const NinePointStart start = [] {
    std::string text;
    for (const char* line : kStartLines) text += line;
    const std::vector<double> values = decode(text);
    NinePointStart s;
    if (values.size() < 33) return s;
    const auto count = static_cast<size_t>(values[0]);
    if (values.size() != 33 + 16 * count) throw Error(ErrorKind::Internal, "nine_point_start.inc is damaged");
    s.parameters.resize(16);
    for (int k = 0; k < 16; ++k) s.parameters[k] = {values[1 + 2 * k], values[2 + 2 * k]};
    for (size_t n = 0; n < count; ++n) {
      CVector dyads(8);
      for (int k = 0; k < 8; ++k) dyads[k] = {values[33 + 16 * n + 2 * k], values[34 + 16 * n + 2 * k]};
      s.representatives.push_back(polished(with_rotations(dyads, s.parameters), s.parameters));
    }
    s.closed = true;
    return s;
  }();
  return start;
}

std::string encode_nine_point_start(const NinePointStart& start) {
  std::vector<double> values{static_cast<double>(start.representatives.size())};
  for (int k = 0; k < 16; ++k) {
    values.push_back(start.parameters[k].real());
    values.push_back(start.parameters[k].imag());
  }
  for (const auto& r : start.representatives)
    for (int k = 16; k < 24; ++k) {
      values.push_back(r[k].real());
      values.push_back(r[k].imag());
    }
  const std::string text = encode(values);
  std::string out;
  for (size_t i = 0; i < text.size(); i += 96) {
    out.push_back('"');
    out.append(text, i, 96);
    out.append("\",\n");
  }
  return out;
}

}  // namespace nbar::synthesis
