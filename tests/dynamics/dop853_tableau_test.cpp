// The coefficients of DOP853 (src/dynamics/dop853_tableau.hpp) against the conditions they must
// meet: each stage's weights sum to its node; the eighth-order weights integrate polynomials up to
// degree 7 exactly (and not degree 8); the fifth- and third-order error estimates vanish on
// polynomials up to degree 4 and 2; the continuous extension of order 7 reproduces the integral of
// a polynomial of degree 6 anywhere on the step (and not of degree 7). A wrong digit in a
// coefficient breaks one of them.
#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "dynamics/dop853_tableau.hpp"

namespace {

using namespace nbar::dop853;

// The stages of y' = t^power from t0 over h: they do not depend on y.
std::array<double, kStagesExtended> stages_of_power(int power, double t0, double h) {
  std::array<double, kStagesExtended> k{};
  for (int j = 0; j < kStagesExtended; ++j) k[j] = std::pow(t0 + c[j] * h, power);
  return k;
}

// y(t0 + theta h) by the continuous extension of the step of y' = t^power from y(t0) = t0^(p+1)/(p+1).
double extension_of_power(int power, double t0, double h, double theta) {
  const std::array<double, kStagesExtended> k = stages_of_power(power, t0, h);
  const double y0 = std::pow(t0, power + 1) / (power + 1);
  double y1 = y0;
  for (int j = 0; j < kStages; ++j) y1 += h * a[kStages][j] * k[j];
  std::array<double, kExtension> r{};
  r[0] = y1 - y0;
  r[1] = h * k[0] - r[0];
  r[2] = 2 * r[0] - h * (k[kStages] + k[0]);
  for (int i = 0; i < kExtension - 3; ++i)
    for (int j = 0; j < kStagesExtended; ++j) r[3 + i] += h * d[i][j] * k[j];
  double sum = 0.0;
  for (int i = kExtension - 1; i >= 0; --i) sum = (i % 2 == 0 ? theta : 1 - theta) * (r[i] + sum);
  return y0 + sum;
}

TEST(Dop853Tableau, EachStagesWeightsSumToItsNode) {
  for (int i = 1; i < kStagesExtended; ++i) {
    double sum = 0.0, size = 0.0;
    for (int j = 0; j < i; ++j) {
      sum += a[i][j];
      size += std::abs(a[i][j]);
    }
    EXPECT_NEAR(sum, c[i], 4 * size * 2.2e-16) << "stage " << i;  // the weights' rounding
  }
}

TEST(Dop853Tableau, TheWeightsIntegratePolynomialsUpToDegreeSeven) {
  for (int degree = 0; degree <= 8; ++degree) {
    double sum = 0.0;
    for (int j = 0; j < kStages; ++j) sum += a[kStages][j] * std::pow(c[j], degree);
    if (degree <= 7)
      EXPECT_NEAR(sum, 1.0 / (degree + 1), 1e-15) << "degree " << degree;
    else
      EXPECT_GT(std::abs(sum - 1.0 / (degree + 1)), 1e-6) << "eighth order only";
  }
}

TEST(Dop853Tableau, TheErrorEstimatesVanishOnLowDegrees) {
  for (int degree = 0; degree <= 5; ++degree) {
    double fifth = 0.0, third = 0.0;
    for (int j = 0; j < kStages; ++j) {
      fifth += e5_weights[j] * std::pow(c[j], degree);
      third += e3_weights[j] * std::pow(c[j], degree);
    }
    if (degree <= 4)
      EXPECT_NEAR(fifth, 0.0, 1e-15) << "degree " << degree;
    else
      EXPECT_GT(std::abs(fifth), 1e-5);
    if (degree <= 2)
      EXPECT_NEAR(third, 0.0, 1e-15) << "degree " << degree;
    else
      EXPECT_GT(std::abs(third), 1e-3);
  }
}

TEST(Dop853Tableau, TheContinuousExtensionIsOfOrderSeven) {
  const double t0 = 0.3, h = 0.7;
  for (int power = 0; power <= 7; ++power) {
    for (const double theta : {0.0, 0.37, 0.5, 0.81, 1.0}) {
      const double exact = std::pow(t0 + theta * h, power + 1) / (power + 1);
      const double error = std::abs(extension_of_power(power, t0, h, theta) - exact);
      if (power <= 6) {
        EXPECT_LT(error, 1e-13) << "power " << power << ", theta " << theta;  // weights of up to 500
      } else if (theta != 0.0 && theta != 1.0) {
        EXPECT_GT(error, 1e-7) << "seventh order only: power " << power << ", theta " << theta;
      }
    }
  }
}

}  // namespace
