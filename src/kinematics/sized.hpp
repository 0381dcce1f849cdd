// The sizes a sweep step is compiled for: a square system of 1 to 4 moving points (2, 4, 6 or 8
// coordinates) runs instantiations of the step's code with its size known when compiled, so that
// its loops over coordinates unroll; any other size runs the instantiation for N = 0, which reads
// the size at run time. The arithmetic is the same in every instantiation, bit for bit.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <type_traits>
#include <utility>

namespace nbar {

// f(std::integral_constant<int, N>{}) with N = n when n is 2, 4, 6 or 8, else N = 0.
template <class F>
decltype(auto) with_coordinate_count(int n, F&& f) {
  switch (n) {
    case 2: return std::forward<F>(f)(std::integral_constant<int, 2>{});
    case 4: return std::forward<F>(f)(std::integral_constant<int, 4>{});
    case 6: return std::forward<F>(f)(std::integral_constant<int, 6>{});
    case 8: return std::forward<F>(f)(std::integral_constant<int, 8>{});
    default: return std::forward<F>(f)(std::integral_constant<int, 0>{});
  }
}

// Copies n numbers between arrays that do not overlap, N of them when N > 0: then a few moves in
// line, where std::copy_n of a known size still calls memmove, a call costlier than the copy.
template <int N>
void copy_numbers(const double* from, std::ptrdiff_t n, double* to) {
  if constexpr (N > 0) {
    std::memcpy(to, from, N * sizeof(double));
  } else {
    std::copy_n(from, n, to);
  }
}

}  // namespace nbar
