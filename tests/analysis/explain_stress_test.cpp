// The stresses at an explained pose (Explanation::stresses): a cantilever's against beam theory,
// and a steel four-bar's against the stress stage's section profile at that step of its sweep.
#include "example_models.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <string>

#include "io/explain_writer.hpp"
#include "nbar/analysis/analysis.hpp"
#include "nbar/analysis/explain.hpp"
#include "nbar/io/model_file.hpp"

namespace nbar {
namespace {

using test_support::example_mechanism;

// A straight steel bar O-A, 300 x 20 x 5 mm, held at O by its driver and loaded across at A by
// 250 N; turned so slowly (0.001 rpm) that its inertia is 1e-12 of the load.
const char* kCantilever = R"(
units: {length: mm, angle: deg}
points: {O: [0, 0], A: [300, 0]}
ground: [O]
bodies:
  bar: {points: [O, A], bar: {width: 20, margin: 15}, thickness: 5, material: steel}
forces:
  - {point: A, body: bar, force: [0, 250]}
drivers:
  - {angle: bar, from: 0, to: 1, speed: 0.001 rpm}
sweep: {steps: 2}
)";

TEST(ExplainStresses, CantileverRootMatchesBeamTheory) {
  const auto mech = std::make_shared<const Mechanism>(io::parse_model(kCantilever).model);
  const Explanation ex = explain(mech, {});
  ASSERT_EQ(ex.stresses.size(), 1u);
  const StressPeak& peak = ex.stresses[0];
  EXPECT_EQ(peak.step, 0);
  // sigma = M c / I with M = P (L - x) at the section found, c = w / 2, I = t w^3 / 12; the
  // shear's sqrt(3) tau = sqrt(3) 1.5 P / (w t) is far below it.
  const double P = 250.0, L = 0.3, w = 0.02, t = 0.005, x = peak.at.position;
  const double sigma = P * (L - x) * (w / 2) / (t * w * w * w / 12.0);
  EXPECT_LT(x, 0.01 * L);  // at the root
  EXPECT_NEAR(peak.at.von_mises, sigma, 1e-6 * sigma);
  EXPECT_GT(peak.at.von_mises, 70e6);  // 250 N x 0.3 m over 1.667e-10 m^3 = 75 MPa at x = 0
  // Steel's yield strength (the material catalogue's 250 MPa) over it.
  ASSERT_TRUE(peak.safety_factor);
  EXPECT_NEAR(*peak.safety_factor, 250e6 / peak.at.von_mises, 1e-9);
  // The text and the JSON say it in MPa at x in mm.
  const std::string text = render_explanation(ex, ExplainFormat::Text);
  EXPECT_NE(text.find("10. Stresses at this pose"), std::string::npos);
  const auto json = io::explanation_json(ex);
  ASSERT_EQ(json["stresses"].size(), 1u);
  EXPECT_NEAR(json["stresses"][0]["von_mises"].get<double>(), sigma / 1e6, 1e-6 * sigma / 1e6);
  EXPECT_NEAR(json["stresses"][0]["at"].get<double>(), x * 1000, 1e-9);
  EXPECT_EQ(json["stresses"][0]["unit"], "MPa");
}

// At a step of a loaded, moving four-bar, each link's stress is the largest von Mises of the stress
// stage's section profile at that step (what `nbar stress --section-profile LINK --step K` lists).
TEST(ExplainStresses, FourBarMatchesSectionProfileAtTheStep) {
  const auto mech = example_mechanism("fourbar-steel-bars.yaml");
  AnalysisOptions options;
  options.stress = true;
  const Analysis analysis = analyse(mech, options);
  for (const int step : {0, 90, 217}) {
    ExplainOptions asked;
    asked.step = step;
    const Explanation ex = explain(mech, asked);
    ASSERT_EQ(ex.stresses.size(), 3u);
    for (const StressPeak& peak : ex.stresses) {
      const ResultTable profile = section_profile_table(analysis, peak.body, step);
      const auto vm = std::find(profile.columns.begin(), profile.columns.end(), "von_mises") - profile.columns.begin();
      double largest = 0.0;
      for (const auto& row : profile.rows) largest = std::max(largest, std::abs(row[vm]));
      EXPECT_GT(largest, 1.0) << "step " << step;  // MPa: a loaded link
      EXPECT_NEAR(peak.at.von_mises / 1e6, largest, 1e-9 * largest) << "step " << step << " body " << peak.body;
    }
  }
}

// A model with no shaped link has no stresses at its poses, and no section for them.
TEST(ExplainStresses, NoneWithoutShapes) {
  const auto mech = example_mechanism("fourbar-crank-rocker.yaml");
  const Explanation ex = explain(mech, {});
  EXPECT_TRUE(ex.stresses.empty());
  EXPECT_EQ(render_explanation(ex, ExplainFormat::Text).find("Stresses at this pose"), std::string::npos);
}

}  // namespace
}  // namespace nbar
