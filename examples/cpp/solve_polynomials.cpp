// Using nbar's homotopy continuation solver from C++: all solutions of a small polynomial
// system, by a total-degree and by a linear-product (two-group) start system.
//   build/examples/cpp/solve-polynomials
#include <cstdio>

#include "nbar/synthesis/solve.hpp"

int main() {
  using namespace nbar::synthesis;
  const int n = 2;
  const Polynomial x = Polynomial::variable(n, 0), y = Polynomial::variable(n, 1);
  // A circle and a hyperbola: x^2 + y^2 = 4, x y = 1 (four real intersections).
  const PolynomialSystem f({x * x + y * y - 4.0, x * y - 1.0});

  SolverOptions options;
  options.seed = 7;
  const SolveResult r = solve_total_degree(f, options);
  std::printf("total degree: %ld paths\n", total_degree_count(f));
  for (const Endpoint& e : r.endpoints) {
    const char* kind = e.kind == EndpointKind::Finite       ? "finite"
                       : e.kind == EndpointKind::AtInfinity ? "at infinity"
                                                            : "failed";
    std::printf("  path %d: %s%s%s", e.path, kind, e.singular ? ", singular" : "", e.real ? ", real" : "");
    if (e.kind == EndpointKind::Finite)
      std::printf("  x = %+.12f%+.12fi  y = %+.12f%+.12fi  residual %.1e  condition %.1e", e.x[0].real(), e.x[0].imag(),
                  e.x[1].real(), e.x[1].imag(), e.residual, e.condition);
    std::printf("\n");
  }
  // Grouping {x}{y}: the first equation has degree 2 in each group, the second 1: 4 paths too
  // here, but far fewer than the total degree for systems like the five-point problem.
  std::printf("linear product {x}{y}: %ld paths, %zu real solutions\n", multihomogeneous_count(f, {{0}, {1}}),
              solve_linear_product(f, {{0}, {1}}, options).solutions(true).size());
  return 0;
}
