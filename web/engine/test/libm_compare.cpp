// Why the engine's numbers are not bit for bit the native program's (docs/javascript.md, "Same
// answers"): prints, for 200 000 pseudo-random arguments, the bits of the C library's sin, cos,
// tan, atan2, asin, acos, atan, pow, exp, log, sqrt, hypot, cbrt and fmod, so that glibc (g++)
// and musl (emscripten) can be compared line by line:
//   g++ -O2 -std=c++20 libm_compare.cpp -o native && ./native > native.txt
//   em++ -O2 -std=c++20 -sSINGLE_FILE=1 libm_compare.cpp -o wasm.js && node wasm.js > wasm.txt
//   node libm_compare.mjs native.txt wasm.txt
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>

namespace {

std::uint64_t bits_of(double x) {
  std::uint64_t bits = 0;
  std::memcpy(&bits, &x, sizeof bits);
  return bits;
}

// xorshift64: the same arguments on every platform, in [0, 1).
class Arguments {
 public:
  double next() {
    state_ ^= state_ << 13;
    state_ ^= state_ >> 7;
    state_ ^= state_ << 17;
    return static_cast<double>(state_ >> 11) * 0x1.0p-53;
  }

 private:
  std::uint64_t state_ = 88172645463325252ull;
};

}  // namespace

int main() {
  Arguments arguments;
  for (int i = 0; i < 200000; ++i) {
    const double a = (arguments.next() - 0.5) * 20;
    const double b = (arguments.next() - 0.5) * 20;
    const double unit = arguments.next() * 2 - 1;
    const double power = arguments.next() * 4;
    const double results[] = {std::sin(a),
                              std::cos(a),
                              std::tan(a),
                              std::atan2(a, b),
                              std::asin(unit),
                              std::acos(unit),
                              std::atan(a),
                              std::pow(std::fabs(a), power),
                              std::exp(a),
                              std::log(std::fabs(a)),
                              std::sqrt(std::fabs(a)),
                              std::hypot(a, b),
                              std::cbrt(a),
                              std::fmod(a, b)};
    for (double result : results) std::printf("%016llx ", static_cast<unsigned long long>(bits_of(result)));
    std::printf("\n");
  }
}
