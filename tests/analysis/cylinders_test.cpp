// A cylinder's rod leaving its barrel over the sweep, found by nbar check.
#include "example_models.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <string>

#include "nbar/analysis/cylinders.hpp"
#include "nbar/analysis/summary.hpp"
#include "nbar/io/model_file.hpp"

namespace nbar {
namespace {

// The dump-truck tipper as it once was: barrel C0-D 700 mm, rod E-G 600 mm, stroke 900 to
// 2100 mm. The piston end G is at (cylinder - 600) mm from C0 along the axis, so it reaches the
// mouth D at 1300 mm and is 2100 - 600 - 700 = 800 mm out at the end. With 121 samples 10 mm
// apart, 1300 mm is step 40 (G exactly at D) and the first step out is 41.
std::string tipper(double barrel, double rod, double to) {
  const double ux = 829.156198 / 900, uy = 350.0 / 900;
  const double d = barrel, g = 900 - rod;
  return fmt::format(
      "units: {{length: mm, angle: deg}}\n"
      "points:\n  H: [4000, 1150]\n  C0: [1500, 800]\n  F: [-200, 1150]\n  T: [-200, 2300]\n"
      "  E: [2329.156198, 1150]\n  D: [{:.9f}, {:.9f}]\n  G: [{:.9f}, {:.9f}]\n"
      "ground: [H, C0]\nbodies:\n  bed: [H, F, T, E]\n  barrel: [C0, D]\n  rod: [E, G]\n"
      "sliders:\n  - {{body: rod, point: E, along: [C0, D]}}\n"
      "drivers:\n  - {{name: cylinder, distance: [C0, E], from: 900, to: {}, speed: 50 mm/s}}\n"
      "sweep: {{steps: 121}}\n",
      1500 + d * ux, 800 + d * uy, 1500 + g * ux, 800 + g * uy, to);
}

TEST(Cylinders, TheRodLeavingItsBarrelIsWarnedAtTheFirstStepOutWithHowFarItGets) {
  const io::LoadedModel file = io::parse_model(tipper(700, 600, 2100));
  const Mechanism mech(file.model);
  ASSERT_TRUE(has_cylinder(file.model));
  const ModelSummary summary = summarize(mech);
  ASSERT_EQ(summary.warnings.size(), 1u);
  const Warning& w = summary.warnings[0];
  EXPECT_EQ(w.code, "rod_leaves_barrel");
  EXPECT_EQ(w.step, 41);
  EXPECT_NE(w.message.find("piston end G leaves the barrel C0-D (700 mm long) at step 41 (cylinder = 1310 mm)"),
            std::string::npos)
      << w.message;
  EXPECT_NE(w.message.find("800 mm out of it"), std::string::npos) << w.message;
}

TEST(Cylinders, ARodThatStaysInItsBarrelGetsNoWarning) {
  // 860 mm each, 900 to 1700 mm: G from 40 to 840 mm, inside the 860 mm barrel.
  const io::LoadedModel file = io::parse_model(tipper(860, 860, 1700));
  EXPECT_TRUE(cylinder_warnings(Mechanism(file.model)).empty());
  // A little further, to 1730 mm, G reaches 870 mm: out by 10 mm.
  const io::LoadedModel longer = io::parse_model(tipper(860, 860, 1730));
  const auto warnings = cylinder_warnings(Mechanism(longer.model));
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].message.find("10 mm out of it"), std::string::npos) << warnings[0].message;
  // The example itself.
  const io::LoadedModel example = io::load_model_file(std::string(NBAR_EXAMPLES_DIR) + "/dump-truck-tipper.yaml");
  EXPECT_TRUE(cylinder_warnings(Mechanism(example.model)).empty());
}

TEST(Cylinders, ASliderOnAGroundGuideOrWithABlockIsNoCylinder) {
  for (const char* name : {"machine-18.yaml", "inverted-slider-crank-shaper.yaml", "slider-crank-offset.yaml"}) {
    EXPECT_FALSE(has_cylinder(test_support::example_model(name))) << name;
  }
}

}  // namespace
}  // namespace nbar
