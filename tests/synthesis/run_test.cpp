// Synthesis through the library: the same ranked designs the CLI prints, the ranking rule, the
// JSON the CLI and the server give, and runs that are cancelled or run out of time.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "apps/cli_support.hpp"
#include "nbar/io/synthesis_task.hpp"
#include "nbar/io/synthesis_writer.hpp"
#include "nbar/synthesis/run.hpp"

namespace nbar::synthesis {
namespace {

const std::string kFivePoint = std::string(NBAR_EXAMPLES_DIR) + "/synthesis/five-point-crank-rocker.yaml";

ErrorKind kind_of(const std::function<void()>& run) {
  try {
    run();
  } catch (const Error& e) {
    return e.kind();
  }
  ADD_FAILURE() << "no nbar::Error";
  return ErrorKind::BadInput;
}

TEST(RunSynthesis, GivesTheDesignsTheCommandLinePrints) {
  const SynthesisTask task = io::load_synthesis_task(kFivePoint);
  const SynthesisOutcome outcome = run_synthesis(task);
  EXPECT_EQ(outcome.rows.size(), 36u);
  const std::vector<int> shown = shown_rows(outcome, false, 20);
  ASSERT_FALSE(shown.empty());

  const auto cli = nbar::cli_test::nbar("synth five-point " + kFivePoint + " --format json");
  ASSERT_EQ(cli.code, 0) << cli.err;
  const nlohmann::json printed = nlohmann::json::parse(cli.out);
  ASSERT_EQ(printed["designs"].size(), shown.size());
  for (std::size_t k = 0; k < shown.size(); ++k) {
    const DesignRow& row = outcome.rows[shown[k]];
    const auto& design = printed["designs"][k];
    EXPECT_EQ(design["lengths"]["frame"].get<double>(), row.check.frame);
    EXPECT_EQ(design["lengths"]["coupler"].get<double>(), row.check.coupler);
    EXPECT_EQ(design["pivots"]["moving_a"][0].get<double>(), row.design.moving_a.x());
  }
  // And the writer gives the very text the command prints.
  io::SynthesisListing listing;
  listing.shown = shown;
  EXPECT_EQ(io::synthesis_json(task, outcome, listing), cli.out);
}

// A fixed pivot on one of the five target points (the task's pivot a at the origin, a point tapped
// on the drawn crank pivot there) is said in a note; the bundled task, whose points are clear of
// its pivots, has no such note.
TEST(RunSynthesis, APivotOnATargetPointIsNoted) {
  const SynthesisTask task = io::parse_synthesis_task(R"(task: five-point
units: {length: mm, angle: deg}
pivots: {a: [0, 0], b: [200, 0]}
points: [[-74.772, 20.544], [-3.664, 70.026], [44.303, 194.508], [0, 0], [-90.203, 97.034]]
)");
  const auto is_pivot_note = [](const std::string& n) { return n.starts_with("pivot "); };
  const SynthesisOutcome outcome = run_synthesis(task);
  ASSERT_EQ(std::count_if(outcome.notes.begin(), outcome.notes.end(), is_pivot_note), 1)
      << fmt::format("{}", outcome.notes);
  EXPECT_NE(std::find(outcome.notes.begin(), outcome.notes.end(),
                      "pivot a is at target point 4 (0, 0 mm): the coupler point would pass through a fixed pivot, "
                      "which only a degenerate linkage does; move the pivot or the point"),
            outcome.notes.end());
  const SynthesisOutcome clear = run_synthesis(io::load_synthesis_task(kFivePoint));
  EXPECT_EQ(std::count_if(clear.notes.begin(), clear.notes.end(), is_pivot_note), 0);
}

// A nine-point run stops at its own budget with the designs found by then and a note that says
// so (the bundled task takes seconds; a budget of a microsecond leaves nothing to find).
TEST(RunSynthesis, ANinePointRunPastItsBudgetSaysWhatItFound) {
  const SynthesisTask task =
      io::load_synthesis_task(std::string(NBAR_EXAMPLES_DIR) + "/synthesis/nine-point-crank-rocker.yaml");
  SynthesisRunOptions options;
  options.nine_point_budget = 1e-6;
  const SynthesisOutcome outcome = run_synthesis(task, options);
  EXPECT_TRUE(outcome.rows.empty());
  const std::string notes = fmt::format("{}", fmt::join(outcome.notes, " | "));
  EXPECT_NE(notes.find("0 of 1442 orbits"), std::string::npos) << notes;
  EXPECT_NE(notes.find("the solve stopped at its time budget of 1e-06 s"), std::string::npos) << notes;
  EXPECT_EQ(SynthesisRunOptions{}.nine_point_budget, kDefaultNinePointBudget);
}

TEST(RunSynthesis, ShownRowsPutDefectFreeRealDesignsFirstAndObeyTop) {
  const SynthesisOutcome outcome = run_synthesis(io::load_synthesis_task(kFivePoint));
  const std::vector<int> clean = shown_rows(outcome, false, 0);
  for (int i : clean) {
    EXPECT_TRUE(outcome.rows[i].real);
    EXPECT_TRUE(outcome.rows[i].check.defect_free());
  }
  const std::vector<int> all = shown_rows(outcome, true, 0);
  EXPECT_EQ(all.size(), outcome.rows.size());
  bool complex_seen = false;
  for (int i : all) {
    if (!outcome.rows[i].real) complex_seen = true;
    EXPECT_FALSE(complex_seen && outcome.rows[i].real) << "a real design after a complex one";
  }
  EXPECT_EQ(shown_rows(outcome, true, 5).size(), 5u);
}

TEST(RunSynthesis, JsonHasTheDocumentedKeys) {
  const SynthesisTask task = io::load_synthesis_task(std::string(NBAR_EXAMPLES_DIR) + "/synthesis/function-log10.yaml");
  const SynthesisOutcome outcome = run_synthesis(task);
  io::SynthesisListing listing;
  listing.shown = shown_rows(outcome, true, 0);
  const nlohmann::json j = nlohmann::json::parse(io::synthesis_json(task, outcome, listing));
  for (const char* key : {"task", "name", "method", "units", "error_unit", "solutions", "notes", "designs"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["task"], "function");
  ASSERT_EQ(j["designs"].size(), 1u);
  for (const char* key : {"rank", "grashof", "lengths", "defects", "targets", "structural_error"})
    EXPECT_TRUE(j["designs"][0].contains(key)) << key;
}

TEST(RunSynthesis, CancelledOrOutOfTimeStopsQuickly) {
  const SynthesisTask task = io::load_synthesis_task(kFivePoint);
  SynthesisRunOptions cancelled;
  cancelled.control.token.cancel();
  auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(kind_of([&] { run_synthesis(task, cancelled); }), ErrorKind::Cancelled);

  SynthesisRunOptions hurried;
  hurried.threads = 1;
  hurried.control.token.set_time_budget(std::chrono::microseconds(200));
  EXPECT_EQ(kind_of([&] { run_synthesis(task, hurried); }), ErrorKind::Cancelled);

  // Asked to stop by the progress callback after the first path.
  SynthesisRunOptions asked;
  asked.threads = 1;
  int paths_seen = 0;
  asked.control.on_progress = [&](const Progress& p) {
    if (std::string(p.stage) == "paths" && p.done > 0) ++paths_seen;
    return paths_seen < 1;
  };
  EXPECT_EQ(kind_of([&] { run_synthesis(task, asked); }), ErrorKind::Cancelled);
  EXPECT_LE(paths_seen, 2);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_LT(seconds, 0.5);
}

TEST(RunSynthesis, TaskDataTheSolverRejectsIsAnInvalidModelAtTheTask) {
  SynthesisTask task = io::load_synthesis_task(kFivePoint);
  task.pivot_b = task.pivot_a;  // coincident pivots
  try {
    run_synthesis(task);
    FAIL() << "accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::InvalidModel);
    EXPECT_EQ(e.file(), kFivePoint);
  }
}

// A window the centre-point curve does not cross yields no dyads, and a note says why rather
// than an unexplained "0 solutions".
TEST(RunSynthesis, FourPosesWithNoCurveInTheWindowSayWhy) {
  SynthesisTask task =
      io::load_synthesis_task(std::string(NBAR_EXAMPLES_DIR) + "/synthesis/burmester-four-positions.yaml");
  task.curves.radius = 1;  // mm, about the poses' centroid, where the curve does not pass
  const SynthesisOutcome outcome = run_synthesis(task);
  EXPECT_TRUE(outcome.rows.empty());
  ASSERT_EQ(outcome.notes.size(), 1u);
  EXPECT_EQ(outcome.notes[0].rfind("no part of the centre-point curve was traced within the window (radius 1 mm", 0),
            0u)
      << outcome.notes[0];
  EXPECT_NE(outcome.notes[0].find("leave `curves: {radius}` out"), std::string::npos) << outcome.notes[0];
}

}  // namespace
}  // namespace nbar::synthesis
