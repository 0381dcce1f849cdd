// The time budget reaches every computation of every endpoint: sweeps, dynamics, stresses,
// synthesis, animation frames (GIF, SVG, HTML, MP4), the report and the explanation. Each case
// runs twice through ServerConfig::on_progress: once letting everything run (200, and the
// stage it is about was checked), once stopping at that stage (504, as a passed deadline
// answers). Then a budget too small for anything: every computing endpoint answers 504.
#include <mutex>
#include <set>

#include "nbar/render/animation.hpp"
#include "web/web_support.hpp"

namespace nbar::web_test {
namespace {

struct Case {
  std::string path;
  Json body;
  std::string stage;  // the checkpoint that must stop it
};

std::vector<Case> cases() {
  const auto fourbar = [](Json options) {
    return with_model("examples/fourbar-crank-rocker.yaml", std::move(options));
  };
  const auto steel = [](Json options) { return with_model("examples/fourbar-steel-bars.yaml", std::move(options)); };
  std::vector<Case> out = {
      {"/api/solve", fourbar({{"steps", 37}}), "sweep"},
      {"/api/solve", steel({{"steps", 37}, {"dynamics", true}}), "dynamics"},
      {"/api/stress", steel({{"steps", 13}}), "stress"},
      {"/api/synth/five-point", with_task("examples/synthesis/five-point-crank-rocker.yaml"), "paths"},
      {"/api/synth/five-point", with_task("examples/synthesis/five-point-crank-rocker.yaml"), "checking"},
      {"/api/synth/burmester", with_task("examples/synthesis/burmester-five-positions.yaml"), "checking"},
      {"/api/synth/function", with_task("examples/synthesis/function-log10.yaml"), "checking"},
      {"/api/render", fourbar({{"kind", "draw"}, {"at", 30}}), "pose"},
      {"/api/render", fourbar({{"kind", "plot"}, {"y", "rocker.angle"}}), "sweep"},
      {"/api/render", fourbar({{"kind", "animate"}, {"format", "gif"}, {"frames", 12}}), "frames"},
      {"/api/render", fourbar({{"kind", "animate"}, {"format", "svg"}, {"frames", 12}}), "frames"},
      {"/api/render", fourbar({{"kind", "animate"}, {"format", "html"}, {"frames", 12}}), "frames"},
      {"/api/report", steel({{"steps", 37}, {"frames", 12}}), "frames"},
      {"/api/report", steel({{"steps", 37}, {"frames", 12}}), "report"},
      {"/api/explain", fourbar({{"step", 3}, {"steps", 13}}), "sweep"},
      {"/api/explain", fourbar({{"step", 3}, {"steps", 13}}), "explain"},
  };
  if (render::Animation::program_available("ffmpeg"))
    out.push_back({"/api/render", fourbar({{"kind", "animate"}, {"format", "mp4"}, {"frames", 12}}), "frames"});
  return out;
}

TEST(WebCancellation, EveryStageOfEveryEndpointStopsWhenToldTo) {
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.path + " " + c.body.value("kind", "") + " " + c.body.value("format", "") + " at " + c.stage);
    std::mutex mutex;  // synthesis calls the hook from its path-tracking threads
    std::set<std::string> seen;
    ServerConfig config = test_config();
    config.on_progress = [&](const Progress& p) {
      const std::lock_guard lock(mutex);
      seen.insert(p.stage);
      return true;
    };
    const ApiResponse whole = post(c.path, c.body, config);
    ASSERT_EQ(whole.status, 200) << whole.body.substr(0, 400);
    EXPECT_TRUE(seen.count(c.stage)) << "the computation never checked '" << c.stage << "'";

    int stops = 0;
    config.on_progress = [&](const Progress& p) {
      const std::lock_guard lock(mutex);
      if (p.stage != c.stage) return true;
      ++stops;
      return false;
    };
    const ApiResponse stopped = post(c.path, c.body, config);
    EXPECT_EQ(stopped.status, 504) << stopped.body.substr(0, 400);
    EXPECT_EQ(error_of(stopped)["kind"], "time_budget_exceeded");
    EXPECT_GE(stops, 1);
    // The slot is given back.
    EXPECT_EQ(config.jobs->in_use() + config.light_jobs->in_use(), 0);
  }
}

TEST(WebCancellation, ABudgetTooSmallForAnythingStopsEveryComputingEndpoint) {
  ServerConfig config = test_config();
  config.limits.time_budget_seconds = 1e-9;
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.path + " " + c.body.value("kind", "") + " " + c.body.value("format", ""));
    const ApiResponse r = post(c.path, c.body, config);
    EXPECT_EQ(r.status, 504) << r.body.substr(0, 400);
    EXPECT_EQ(error_of(r)["kind"], "time_budget_exceeded");
    EXPECT_NE(error_of(r)["message"].get<std::string>().find("time budget"), std::string::npos);
  }
  // Reading and checking the model count against the budget too; what computes nothing (the
  // static answers) is still answered.
  const ApiResponse check = post("/api/check", with_model("examples/fourbar-crank-rocker.yaml"), config);
  EXPECT_EQ(check.status, 504) << check.body.substr(0, 400);
  EXPECT_EQ(error_of(check)["kind"], "time_budget_exceeded");
  EXPECT_EQ(call("GET", "/api/health", "", config).status, 200);
}

}  // namespace
}  // namespace nbar::web_test
