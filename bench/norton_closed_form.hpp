// Norton's closed form of the four-bar (Design of Machinery, eqs. 4.10, 6.18, 7.12), written
// straight in C++ for one mechanism: the reference the general engine is timed against.
#pragma once

#include <cmath>

namespace nbar_bench {

// Link lengths a (crank), b (coupler), c (output), d (frame along +x from the crank pivot).
struct NortonFourBar {
  double a, b, c, d;
  bool crossed = false;  // which root of the position equations: false = open branch

  struct Pose {
    double theta3, theta4, omega3, omega4, alpha3, alpha4;
    // The crank pin A and the coupler-output pin B: positions, velocities, accelerations.
    double ax, ay, avx, avy, aax, aay, bx, by, bvx, bvy, bax, bay;
  };

  // The crank at theta2 turning at omega2 with angular acceleration alpha2.
  Pose solve(double theta2, double omega2, double alpha2) const {
    Pose p;
    const double s2 = std::sin(theta2), c2 = std::cos(theta2);
    const double k1 = d / a, k2 = d / c, k3 = (a * a - b * b + c * c + d * d) / (2 * a * c);
    const double k4 = d / b, k5 = (c * c - d * d - a * a - b * b) / (2 * a * b);
    const double A = c2 - k1 - k2 * c2 + k3, B = -2 * s2, C = k1 - (k2 + 1) * c2 + k3;
    const double D = c2 - k1 + k4 * c2 + k5, E = -2 * s2, F = k1 + (k4 - 1) * c2 + k5;
    const double sign = crossed ? 1.0 : -1.0;
    p.theta4 = 2 * std::atan2(-B + sign * std::sqrt(B * B - 4 * A * C), 2 * A);
    p.theta3 = 2 * std::atan2(-E + sign * std::sqrt(E * E - 4 * D * F), 2 * D);
    const double s3 = std::sin(p.theta3), c3 = std::cos(p.theta3);
    const double s4 = std::sin(p.theta4), c4 = std::cos(p.theta4);
    p.omega3 = a * omega2 / b * std::sin(p.theta4 - theta2) / std::sin(p.theta3 - p.theta4);
    p.omega4 = a * omega2 / c * std::sin(theta2 - p.theta3) / std::sin(p.theta4 - p.theta3);
    const double Aa = c * s4, Ba = b * s3, Da = c * c4, Ea = b * c3;
    const double Ca =
        a * alpha2 * s2 + a * omega2 * omega2 * c2 + b * p.omega3 * p.omega3 * c3 - c * p.omega4 * p.omega4 * c4;
    const double Fa =
        a * alpha2 * c2 - a * omega2 * omega2 * s2 - b * p.omega3 * p.omega3 * s3 + c * p.omega4 * p.omega4 * s4;
    const double det = Aa * Ea - Ba * Da;
    p.alpha3 = (Ca * Da - Aa * Fa) / det;
    p.alpha4 = (Ca * Ea - Ba * Fa) / det;
    p.ax = a * c2;
    p.ay = a * s2;
    p.avx = -a * omega2 * s2;
    p.avy = a * omega2 * c2;
    p.aax = -a * (alpha2 * s2 + omega2 * omega2 * c2);
    p.aay = a * (alpha2 * c2 - omega2 * omega2 * s2);
    p.bx = d + c * c4;
    p.by = c * s4;
    p.bvx = -c * p.omega4 * s4;
    p.bvy = c * p.omega4 * c4;
    p.bax = -c * (p.alpha4 * s4 + p.omega4 * p.omega4 * c4);
    p.bay = c * (p.alpha4 * c4 - p.omega4 * p.omega4 * s4);
    return p;
  }
};

}  // namespace nbar_bench
