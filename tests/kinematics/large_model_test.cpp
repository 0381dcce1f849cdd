// Large models (issue 16, item 4): the sparse rank analysis agrees with the dense one, and a
// model with too few drivers is rejected from the counts, before any factorisation.
#include "nbar/io/model_file.hpp"
#include "nbar/kinematics/mechanism.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

namespace nbar {
namespace {

using ::testing::HasSubstr;

// "P12" (built by appending: g++ 12 warns falsely, -Wrestrict, on numbered("P", i)).
std::string numbered(const char* prefix, int i) { return std::string(prefix).append(std::to_string(i)); }

// A rigid truss: a chain of n links from ground point O, every joint also tied to ground point
// G, plus one brace from P0 to P2 that the others already fix (one redundant row).
std::string braced_truss(int n) {
  std::string text = "points:\n  O: [0, 0]\n  G: [0, 5]\n";
  for (int i = 0; i < n; ++i)
    text += numbered("  P", i) + ": [" + std::to_string(1 + i) + ", " + (i % 2 ? "-0.3" : "0.3") + "]\n";
  text += "ground: [O, G]\nbodies:\n  c0: [O, P0]\n";
  for (int i = 1; i < n; ++i)
    text += numbered("  c", i) + ": [" + numbered("P", i - 1) + ", " + numbered("P", i) + "]\n";
  for (int i = 0; i < n; ++i) text += numbered("  g", i) + ": [G, " + numbered("P", i) + "]\n";
  text += "  brace: [P0, P2]\ndrivers: []\n";
  return text;
}

TEST(LargeModel, SparseAndDenseRankAnalysesFindTheSameRedundancy) {
  for (int n : {20, 400}) {  // 40 coordinates (dense) and 800 (sparse)
    const Mechanism mech(io::parse_model(braced_truss(n)).model);
    const MobilityReport& r = mech.mobility();
    EXPECT_EQ(r.coordinates, 2 * n) << n;
    EXPECT_EQ(r.constraint_rows, 2 * n + 1) << n;
    EXPECT_EQ(r.rank, 2 * n) << n;
    EXPECT_EQ(r.dof, 0) << n;
    EXPECT_EQ(r.redundant.size(), 1u) << n;
  }
}

TEST(LargeModel, TooFewDriversIsRejectedFromTheCounts) {
  std::string text = "points:\n  O: [0, 0]\n";
  const int n = 2000;
  for (int i = 0; i < n; ++i) text += numbered("  P", i) + ": [1, " + std::to_string(i) + "]\n";
  text += "ground: [O]\nbodies:\n";
  for (int i = 0; i < n; ++i) text += numbered("  b", i) + ": [O, " + numbered("P", i) + "]\n";
  text += "drivers: [{angle: b0, from: 0, to: 90}]\n";
  const io::LoadedModel loaded = io::parse_model(text);
  try {
    const Mechanism mech(loaded.model);
    FAIL() << "accepted";
  } catch (const ModelError& e) {
    EXPECT_THAT(e.message(), HasSubstr("at least 2000 degrees of freedom"));
  }
}

TEST(LargeModel, MoreMovingPointsThanTheLimitIsAnError) {
  Model m;
  m.points.push_back({"O", {0, 0}, true});
  for (int i = 0; i <= kMaxMovingPoints; ++i) m.points.push_back({numbered("P", i), {1.0 + i, 0.0}, false});
  Body b;
  b.name = "b";
  b.points = {0, 1};
  m.bodies.push_back(b);
  try {
    const Mechanism mech(m);
    FAIL() << "accepted";
  } catch (const ModelError& e) {
    EXPECT_THAT(e.message(), HasSubstr("nbar analyses at most 20000"));
  }
}

}  // namespace
}  // namespace nbar
