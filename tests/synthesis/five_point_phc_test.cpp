// Cross-check against an independent solver: PHCpack (`phc -b`, Debian package phcpack),
// with its own start system and tracker, on the primer's form of one instance.
#include <gtest/gtest.h>

#include <unistd.h>

#include <random>

#include "nbar/synthesis/five_point.hpp"
#include "phc_support.hpp"

namespace nbar::synthesis {
namespace {

TEST(FivePointPhcpackTest, SameThirtySixSolutionsAsPhcpack) {
  if (!phc::available()) GTEST_SKIP() << "phc not installed (apt-get install phcpack)";
  FivePointTask t;  // pivots (0, 0) and (1, 0): the task's frame is the primer's
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> u(-1.0, 2.0);
  for (auto& p : t.points) p = {u(rng), u(rng)};
  const std::vector<std::string> names{"c1", "s1", "c2", "s2", "c3", "s3", "c4", "s4", "x1", "x2", "y1", "y2"};
  const auto dir =
      std::filesystem::temp_directory_path() / std::string("nbar-phc-test-").append(std::to_string(::getpid()));
  const auto theirs = phc::solve(five_point_system(t.points), names, dir);
  std::filesystem::remove_all(dir);
  ASSERT_TRUE(theirs.has_value());
  EXPECT_EQ(theirs->reported_regular, 36);
  ASSERT_EQ(theirs->regular.size(), 36u);

  const FivePointResult ours = solve_five_point(t);
  ASSERT_EQ(ours.solutions.size(), 36u);
  double worst = 0;
  for (const auto& s : theirs->regular) {
    double best = INFINITY;
    for (const auto& o : ours.solutions) {
      double d = 0;
      for (int i = 0; i < 4; ++i) {
        d = std::max(d, std::abs(o.cos_rotation[i] - s.at(names[2 * i])));
        d = std::max(d, std::abs(o.sin_rotation[i] - s.at(names[2 * i + 1])));
      }
      for (int k = 0; k < 2; ++k) {
        d = std::max(d, std::abs(o.moving_a[k] - s.at(names[8 + k])));
        d = std::max(d, std::abs(o.moving_b[k] - s.at(names[10 + k])));
      }
      best = std::min(best, d);
    }
    worst = std::max(worst, best);
  }
  std::printf("[ accuracy ] five-point vs PHCpack: every one of its 36 solutions within %.1e of ours\n", worst);
  EXPECT_LT(worst, 1e-8);
}

}  // namespace
}  // namespace nbar::synthesis
