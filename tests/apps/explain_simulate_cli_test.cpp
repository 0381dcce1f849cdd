// `nbar explain --simulate --at T` (the equations of motion printed as JSON, solved here, give
// the accelerations `nbar simulate --to T` reports), and `nbar simulate` interrupted by SIGINT
// (the rows so far written, a nonzero exit and one line saying where it stopped).
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>
#include <nlohmann/json.hpp>

#include <Eigen/Dense>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "apps/cli_support.hpp"

namespace nbar::cli_test {
namespace {

using ::testing::HasSubstr;
using Json = nlohmann::json;

const std::string kReleased = std::string(NBAR_EXAMPLES_DIR) + "/crank-rocker-released.yaml";

Eigen::VectorXd vector_of(const Json& a) {
  Eigen::VectorXd v(static_cast<Eigen::Index>(a.size()));
  for (std::size_t i = 0; i < a.size(); ++i) v(static_cast<Eigen::Index>(i)) = a[i].get<double>();
  return v;
}

Eigen::MatrixXd matrix_of(const Json& a) {
  const std::size_t columns = a.empty() ? 0 : a[0].size();
  Eigen::MatrixXd m(static_cast<Eigen::Index>(a.size()), static_cast<Eigen::Index>(columns));
  for (std::size_t r = 0; r < a.size(); ++r) m.row(static_cast<Eigen::Index>(r)) = vector_of(a[r]).transpose();
  return m;
}

// The printed blocks [M Phi_q^T; Phi_q 0] [q''; lambda] = [Q; gamma], solved here, against the
// accelerations of the points in the last row of `nbar simulate --to 0.5` (mm/s^2 there, m/s^2
// here); Q is the sum of its printed parts.
TEST(ExplainSimulateCli, ThePrintedSystemGivesTheSimulatedAccelerations) {
  const CliRun explained = nbar("explain " + kReleased + " --simulate --at 0.5 --rtol 1e-10 --format json");
  ASSERT_EQ(explained.code, 0) << explained.err;
  const Json e = Json::parse(explained.out);
  const Eigen::MatrixXd M = matrix_of(e["mass"]), J = matrix_of(e["jacobian"]);
  const Eigen::Index n = M.rows(), m = J.rows();
  ASSERT_EQ(n, 6);
  ASSERT_EQ(m, 5);  // three lengths and the coupler's two shape rows; the free crank's row is left out
  Eigen::MatrixXd system = Eigen::MatrixXd::Zero(n + m, n + m);
  system << M, J.transpose(), J, Eigen::MatrixXd::Zero(m, m);
  const Json& forces = e["forces"];
  const Eigen::VectorXd Q = vector_of(forces["gravity"]) + vector_of(forces["given"]) + vector_of(forces["springs"]) +
                            vector_of(forces["friction"]);
  EXPECT_LT((Q - vector_of(forces["total"])).lpNorm<Eigen::Infinity>(), 1e-12 * Q.lpNorm<Eigen::Infinity>());
  Eigen::VectorXd rhs(n + m);
  rhs << Q, vector_of(e["gamma"]);
  const Eigen::VectorXd solution = system.fullPivLu().solve(rhs);

  const CliRun simulated = nbar("simulate " + kReleased + " --to 0.5 --rtol 1e-10 --format json");
  ASSERT_EQ(simulated.code, 0) << simulated.err;
  const Json s = Json::parse(simulated.out);
  const Json& last = s["rows"].back();
  const auto& columns = s["columns"];
  const std::vector<std::string> coordinates = e["coordinates"];
  double largest = 0.0, worst = 0.0;
  for (std::size_t i = 0; i < coordinates.size(); ++i) {
    const std::string& name = coordinates[i];  // "A.x"
    const std::string column = name.substr(0, name.size() - 1) + "a" + name.back();
    const auto at = std::find(columns.begin(), columns.end(), column);
    ASSERT_NE(at, columns.end()) << column;
    const double reported = last[static_cast<std::size_t>(at - columns.begin())].get<double>() / 1000;
    largest = std::max(largest, std::abs(reported));
    worst = std::max(worst, std::abs(solution(static_cast<Eigen::Index>(i)) - reported));
  }
  EXPECT_GT(largest, 0.1);
  EXPECT_LT(worst, 1e-9 * largest) << worst;
  // The text says the same system.
  const CliRun text = nbar("explain " + kReleased + " --simulate --at 0.5 --rtol 1e-10");
  ASSERT_EQ(text.code, 0) << text.err;
  EXPECT_THAT(text.out, HasSubstr("[ Phi_q  0       ] [ lambda ] = [ gamma ]"));
  EXPECT_THAT(text.out, HasSubstr("2. The mass matrix M (kg), constant"));
}

TEST(ExplainSimulateCli, BadTimesAreRefusedByName) {
  const CliRun negative = nbar("explain " + kReleased + " --simulate --at -1");
  EXPECT_EQ(negative.code, 2);
  EXPECT_THAT(negative.err, HasSubstr("--at"));
  const CliRun not_a_number = nbar("explain " + kReleased + " --simulate --at nan");
  EXPECT_EQ(not_a_number.code, 2);
  EXPECT_THAT(not_a_number.err, HasSubstr("--at"));
  const CliRun beyond = nbar("explain " + kReleased + " --simulate --at 1e7");
  EXPECT_EQ(beyond.code, 2);
  EXPECT_THAT(beyond.err, HasSubstr("--at"));
  const CliRun without = nbar("explain " + kReleased + " --at 1");
  EXPECT_EQ(without.code, 2);
  EXPECT_THAT(without.err, HasSubstr("--simulate"));
  const CliRun driven =
      nbar("explain " + std::string(NBAR_EXAMPLES_DIR) + "/fourbar-crank-rocker.yaml --simulate --at 1");
  EXPECT_EQ(driven.code, 1);
  EXPECT_THAT(driven.err, HasSubstr("fourbar-crank-rocker.yaml:"));
  EXPECT_THAT(driven.err, HasSubstr("free: true"));
}

// A long run (5000 s of machine time at rtol 1e-12, a row every 10 ms: minutes of computing)
// interrupted by SIGINT after a second:
// the CSV has the rows up to where it stopped, every one 10 ms after the last, the exit code is
// 5 (cancelled) and standard error says where, in one line.
TEST(SimulateCli, InterruptedBySigintWritesTheRowsSoFar) {
  const ScratchDir scratch("nbar_sigint");
  const std::string csv = scratch.file("run.csv"), err = scratch.file("err.txt");
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    ::signal(SIGINT, SIG_DFL);
    if (!std::freopen(err.c_str(), "w", stderr)) ::_exit(127);
    ::execl(NBAR_CLI_PATH, NBAR_CLI_PATH, "simulate", kReleased.c_str(), "--to", "5000", "--dt", "0.01", "--rtol",
            "1e-12", "--columns", "t,crank", "-o", csv.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(1000));
  ::kill(child, SIGINT);
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status)) << "ended by a signal";
  EXPECT_EQ(WEXITSTATUS(status), 5);
  const std::string message = read_file(err);
  EXPECT_EQ(std::count(message.begin(), message.end(), '\n'), 1) << message;
  EXPECT_THAT(message, HasSubstr("the simulation stopped early: cancelled at t = "));
  std::istringstream rows(read_file(csv));
  std::string line;
  std::getline(rows, line);
  EXPECT_EQ(line, "t,crank");
  int count = 0;
  double previous = -0.01;
  for (; std::getline(rows, line); ++count) {
    const double t = std::stod(line.substr(0, line.find(',')));
    ASSERT_NEAR(t - previous, 0.01, 1e-9) << "row " << count;
    previous = t;
  }
  EXPECT_GT(count, 10);
  EXPECT_LT(previous, 5000.0);
  EXPECT_THAT(message, HasSubstr("at t = " + [&] {
                std::ostringstream s;
                s.precision(9);
                s << previous;
                return s.str();
              }() + " s"));
}

}  // namespace
}  // namespace nbar::cli_test
