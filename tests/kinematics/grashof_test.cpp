// Grashof's classification at its boundary: which links turn fully must not depend on which of
// several equal links compares smallest after rounding.
#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "nbar/kinematics/loops.hpp"

namespace nbar {
namespace {

constexpr double kTolerance = 1e-9;

// Each length moved by at most a few units in the last place, every way round.
std::array<double, 4> nudged(std::array<double, 4> len, int pattern) {
  for (int i = 0; i < 4; ++i) {
    const int steps = (pattern >> (2 * i)) % 4 - 1;  // -1, 0, 1 or 2 ulps
    for (int k = 0; k < std::abs(steps); ++k) len[i] = std::nextafter(len[i], steps > 0 ? 1e9 : 0.0);
  }
  return len;
}

void expect_change_point(std::array<double, 4> len, bool input_turns, bool output_turns) {
  for (int pattern = 0; pattern < 256; ++pattern) {
    const auto l = nudged(len, pattern);
    const GrashofReport r = classify_grashof(l[0], l[1], l[2], l[3], kTolerance);
    SCOPED_TRACE(::testing::Message() << "lengths " << l[0] << " " << l[1] << " " << l[2] << " " << l[3]);
    EXPECT_EQ(r.kind, GrashofClass::ChangePoint);
    EXPECT_EQ(r.margin, 0.0);
    EXPECT_EQ(r.input_turns_fully, input_turns);
    EXPECT_EQ(r.output_turns_fully, output_turns);
  }
}

// A parallelogram (frame 200, cranks 50): both cranks turn fully relative to the frame.
TEST(Grashof, ParallelogramTurnsBothCranksWhicheverComparesSmallest) {
  expect_change_point({0.2, 0.05, 0.2, 0.05}, true, true);
}

// A rhombus (the scissor lift's all-600 mm loop): every link is a shortest one.
TEST(Grashof, RhombusTurnsBothCranks) { expect_change_point({0.6, 0.6, 0.6, 0.6}, true, true); }

// A kite with its two short links next to each other at the input's pivot: frame and input are
// the shortest, so input and output both turn fully relative to the frame.
TEST(Grashof, KiteWithShortFrameAndInputTurnsBoth) { expect_change_point({0.1, 0.1, 0.3, 0.3}, true, true); }

// A kite whose short links are input and coupler: only the input turns fully relative to the frame.
TEST(Grashof, KiteWithShortInputAndCouplerTurnsTheInputOnly) { expect_change_point({0.3, 0.1, 0.1, 0.3}, true, false); }

// Away from the boundary the classes are textbook ones (Norton, table 2-4).
TEST(Grashof, ClassesAwayFromTheBoundary) {
  EXPECT_EQ(classify_grashof(0.4, 0.1, 0.35, 0.3, kTolerance).kind, GrashofClass::CrankRocker);
  EXPECT_EQ(classify_grashof(0.1, 0.4, 0.35, 0.3, kTolerance).kind, GrashofClass::DoubleCrank);
  EXPECT_EQ(classify_grashof(0.4, 0.35, 0.1, 0.3, kTolerance).kind, GrashofClass::DoubleRocker);
  EXPECT_EQ(classify_grashof(0.4, 0.2, 0.35, 0.1, kTolerance).kind, GrashofClass::CrankRocker);
  const GrashofReport non = classify_grashof(0.5, 0.2, 0.25, 0.1, kTolerance);
  EXPECT_EQ(non.kind, GrashofClass::TripleRocker);
  EXPECT_NEAR(non.margin, (0.2 + 0.25) - (0.1 + 0.5), 1e-15);
  EXPECT_FALSE(non.input_turns_fully);
  EXPECT_FALSE(non.output_turns_fully);
}

}  // namespace
}  // namespace nbar
