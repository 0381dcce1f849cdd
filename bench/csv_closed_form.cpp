// The reference of `nbar solve`'s CSV speed: the crank-rocker of examples/fourbar-crank-rocker.yaml
// by Norton's closed form, written with printf as the same 43 columns nbar writes (step, t, the
// crank's angle, x, y, vx, vy, ax, ay of O2, O4, A, B and P, angle, omega and alpha of crank,
// coupler and rocker, the transmission angle), %.12g each, in mm, deg and s.
//   csv_closed_form STEPS FILE
// bench/csv_bench.py times it against nbar in one run.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>

#include "norton_closed_form.hpp"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: csv_closed_form STEPS FILE\n");
    return 2;
  }
  const long steps = std::strtol(argv[1], nullptr, 10);
  std::FILE* out = std::fopen(argv[2], "w");
  if (steps < 2 || !out) {
    std::fprintf(stderr, "csv_closed_form: bad steps or cannot write %s\n", argv[2]);
    return 2;
  }
  constexpr double pi = std::numbers::pi, deg = 180.0 / pi;
  // The example's drawing, mm: O2 (0, 0), O4 (200, 0), A (80, 0), B (181.25, 148.823511),
  // P (77.81169, 121.227931) on the coupler; crank 80, rocker 150, coupler |AB|.
  const double bx0 = 181.25, by0 = 148.823511, px0 = 77.81169, py0 = 121.227931;
  const nbar_bench::NortonFourBar linkage{80.0, std::hypot(bx0 - 80.0, by0), 150.0, 200.0};
  const double theta3_0 = std::atan2(by0, bx0 - 80.0);
  const double p_radius = std::hypot(px0 - 80.0, py0), p_angle = std::atan2(py0, px0 - 80.0) - theta3_0;
  const double omega2 = 4.0 * pi;  // 120 rpm
  const double duration = 2.0 * pi / omega2;

  std::fputs(
      "step,t,crank,O2.x,O2.y,O2.vx,O2.vy,O2.ax,O2.ay,O4.x,O4.y,O4.vx,O4.vy,O4.ax,O4.ay,A.x,A.y,A.vx,A.vy,A.ax,"
      "A.ay,B.x,B.y,B.vx,B.vy,B.ax,B.ay,P.x,P.y,P.vx,P.vy,P.ax,P.ay,crank.angle,crank.omega,crank.alpha,"
      "coupler.angle,coupler.omega,coupler.alpha,rocker.angle,rocker.omega,rocker.alpha,"
      "crank-coupler-rocker.mu\n",
      out);
  double row[43];
  for (long i = 0; i < steps; ++i) {
    const double fraction = static_cast<double>(i) / static_cast<double>(steps - 1);
    const double theta2 = 2.0 * pi * fraction;
    const auto p = linkage.solve(theta2, omega2, 0.0);
    const double angle = p.theta3 + p_angle, cp = p_radius * std::cos(angle), sp = p_radius * std::sin(angle);
    const double mu = std::acos(std::cos(p.theta4 - p.theta3));
    const double values[] = {static_cast<double>(i),
                             fraction * duration,
                             theta2 * deg,
                             0,
                             0,
                             0,
                             0,
                             0,
                             0,
                             200,
                             0,
                             0,
                             0,
                             0,
                             0,
                             p.ax,
                             p.ay,
                             p.avx,
                             p.avy,
                             p.aax,
                             p.aay,
                             p.bx,
                             p.by,
                             p.bvx,
                             p.bvy,
                             p.bax,
                             p.bay,
                             p.ax + cp,
                             p.ay + sp,
                             p.avx - p.omega3 * sp,
                             p.avy + p.omega3 * cp,
                             p.aax - p.alpha3 * sp - p.omega3 * p.omega3 * cp,
                             p.aay + p.alpha3 * cp - p.omega3 * p.omega3 * sp,
                             theta2 * deg,
                             omega2 * deg,
                             0.0,
                             p.theta3 * deg,
                             p.omega3 * deg,
                             p.alpha3 * deg,
                             p.theta4 * deg,
                             p.omega4 * deg,
                             p.alpha4 * deg,
                             mu * deg};
    for (int c = 0; c < 43; ++c) row[c] = values[c];
    for (int c = 0; c < 43; ++c) std::fprintf(out, c ? ",%.12g" : "%.12g", row[c] + 0.0);
    std::fputc('\n', out);
  }
  return std::fclose(out) == 0 ? 0 : 1;
}
