// The request layer (nbar/request): each option read by one rule, whatever front-end filled it,
// with the messages every front-end gives; and what the requests choose from their options.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>

#include "../kinematics/four_bar_closed_form.hpp"
#include "nbar/io/dxf_writer.hpp"
#include "nbar/io/model_file.hpp"
#include "nbar/io/synthesis_task.hpp"
#include "nbar/request/requests.hpp"
#include "nbar/request/synthesis_request.hpp"

namespace nbar::request {
namespace {

using ::testing::HasSubstr;

// The message of the OptionError `read` throws, with keys spelled as the command line does.
template <class Read>
std::string cli_message(Read read) {
  try {
    read();
  } catch (const OptionError& e) {
    return e.spelled(flag_name);
  }
  return "(no error)";
}

template <class Read>
std::string message(Read read) {
  try {
    read();
  } catch (const OptionError& e) {
    return e.message();
  }
  return "(no error)";
}

Options with(const std::string& key, Value value) {
  Options o(std::holds_alternative<std::string>(value) || std::holds_alternative<std::vector<std::string>>(value));
  o.set(key, std::move(value));
  return o;
}

TEST(RequestOptions, ANumberReadsTheSameAsTextAsJsonAndAsPython) {
  // The command line gives text, JSON an integer or a double, Python an int: one answer.
  for (const Value& v : {Value(std::string("3")), Value(3LL), Value(3.0)})
    EXPECT_EQ(SolveRequest::read(with("order", v)).order, 3);
  for (const Value& v : {Value(std::string("9")), Value(9LL), Value(9.0)})
    EXPECT_EQ(message([&] { SolveRequest::read(with("order", v)); }), "order: must be from 0 to 5, not 9");
  EXPECT_EQ(message([] { SolveRequest::read(with("order", std::string("2.5"))); }),
            "order: must be a whole number, not 2.5");
  EXPECT_EQ(message([] { SolveRequest::read(with("order", 2.5)); }), "order: must be a whole number, not 2.5");
  EXPECT_EQ(message([] { SolveRequest::read(with("steps", std::string("abc"))); }),
            "steps: 'abc' is not a finite number");
  EXPECT_EQ(message([] { SolveRequest::read(with("steps", std::string("nan"))); }),
            "steps: 'nan' is not a finite number");
  EXPECT_EQ(message([] { SolveRequest::read(with("steps", 0LL)); }), "steps: must be a positive number, not 0");
  EXPECT_EQ(message([] { SolveRequest::read(with("dynamics", std::string("yes"))); }),
            "dynamics: must be true or false");
  EXPECT_EQ(message([] { SolveRequest::read(with("format", std::string("xml"))); }),
            "format: must be one of csv, json, table, not 'xml'");
}

TEST(RequestOptions, ATextWhereANumberBelongsIsRefusedUnlessEverythingIsText) {
  // JSON's "3" and Python's "3" are texts, not the number the command line's typed 3 is.
  Options json;
  json.set("steps", std::string("3"));
  EXPECT_EQ(message([&] { SolveRequest::read(json); }), "steps: must be a whole number, not the text '3'");
  json.set("steps", 3LL);
  json.set("fps", std::string("24"));
  EXPECT_EQ(message([&] { AnimateRequest::read(json); }), "fps: must be a number, not the text '24'");
  Options typed(true);
  typed.set("steps", std::string("3"));
  EXPECT_EQ(SolveRequest::read(typed).sweep.steps, 3);
}

TEST(RequestOptions, TheCommandLineSpellsEveryKeyItNames) {
  EXPECT_EQ(flag_name("max_steps"), "--max-steps");
  EXPECT_EQ(cli_message([] { StressRequest::read(with("mesh_size", std::string("-1"))); }),
            "--mesh-size: must be a positive number, not -1");
  // A problem that names another option: each front-end spells it, the message keeps the key.
  Options beam_query = with("section_profile", std::string("crank"));
  beam_query.set("at", std::vector<std::string>{"0.5", "0.1"});
  EXPECT_EQ(cli_message([&] { StressRequest::read(beam_query); }),
            "--at reads the finite-element field: give --method fe too");
  EXPECT_EQ(message([&] { StressRequest::read(beam_query); }), "at reads the finite-element field: give method fe too");
  // Braces in text from elsewhere (a name) stay braces.
  EXPECT_EQ(spell_keys(literal("{x} and {{") + " {steps}", flag_name), "{x} and {{ --steps");
}

TEST(RequestOptions, AnUnknownKeyIsNamedWithTheOnesTheRequestTakes) {
  Options o = with("frobnicate", 1LL);
  const std::string m = message([&] { check_known(o, CheckRequest::rules(), "check"); });
  EXPECT_EQ(m, "frobnicate: unknown option of check; it takes: format, at_limits, cycles, max_steps");
  // The web server's rule is the same, with the documents it reads itself (the model's text).
  EXPECT_EQ(known_keys(CheckRequest::rules(), {"model"}),
            (std::vector<std::string>{"model", "format", "at_limits", "cycles", "max_steps"}));
  EXPECT_EQ(unknown_key({"format", "model"}, CheckRequest::rules(), {"model"}), std::nullopt);
  EXPECT_EQ(unknown_key({"format", "modle", "stepz"}, CheckRequest::rules(), {"model"}), "modle");
  EXPECT_EQ(unknown_key({"model"}, CheckRequest::rules()), "model");
}

TEST(RequestOptions, EachSynthesisMethodTakesItsOwnOptions) {
  using synthesis::SynthesisKind;
  const auto keys = [](SynthesisKind kind) { return known_keys(SynthesisRequest::rules(kind)); };
  const std::vector<std::string> run{"format", "all", "top", "threads"};
  std::vector<std::string> seeded = run;
  seeded.push_back("seed");
  EXPECT_EQ(keys(SynthesisKind::FivePoint), seeded);
  EXPECT_EQ(keys(SynthesisKind::NinePoint), seeded);
  EXPECT_EQ(keys(SynthesisKind::Path), seeded);
  EXPECT_EQ(keys(SynthesisKind::Burmester), run);  // no random numbers: no seed
  EXPECT_EQ(keys(SynthesisKind::Function), run);
  const SynthesisRequest defaults = SynthesisRequest::read(SynthesisKind::Path, Options());
  EXPECT_EQ(defaults.top, 20);
  EXPECT_EQ(defaults.threads, 0u);
  EXPECT_EQ(defaults.seed, 1u);
  EXPECT_EQ(defaults.format, "table");
  EXPECT_FALSE(defaults.all);
  // The command line's text and JSON's numbers read alike.
  Options typed;
  typed.set("seed", 4294967295LL);
  typed.set("threads", 3LL);
  typed.set("top", 0LL);
  EXPECT_EQ(SynthesisRequest::read(SynthesisKind::FivePoint, typed).seed, 4294967295u);
  EXPECT_EQ(SynthesisRequest::read(SynthesisKind::FivePoint, with("seed", std::string("12"))).seed, 12u);
  EXPECT_EQ(SynthesisRequest::read(SynthesisKind::FivePoint, typed).run_options().threads, 3u);
  EXPECT_EQ(cli_message([] { SynthesisRequest::read(SynthesisKind::Function, with("threads", 2000LL)); }),
            "--threads: must be from 0 to 1024, not 2000");
  EXPECT_EQ(message([] { SynthesisRequest::read(SynthesisKind::FivePoint, with("seed", 4294967296LL)); }),
            "seed: must be from 0 to 4294967295, not 4294967296");
  EXPECT_EQ(message([] { SynthesisRequest::read(SynthesisKind::Burmester, with("seed", 3LL)); }),
            "seed: unknown option of burmester; it takes: format, all, top, threads");
  EXPECT_EQ(cli_message([] { SynthesisRequest::read(SynthesisKind::Burmester, with("seed", std::string("3"))); }),
            "--seed: unknown option of burmester; it takes: --format, --all, --top, --threads");
  EXPECT_EQ(message([] { SynthesisRequest::read(SynthesisKind::Path, with("format", std::string("csv"))); }),
            "format: must be one of table, json, not 'csv'");
}

TEST(RequestOptions, ASynthesisRequestListsAndWritesItsDesigns) {
  const synthesis::SynthesisTask task =
      io::load_synthesis_task(std::string(NBAR_EXAMPLES_DIR) + "/synthesis/function-log10.yaml");
  Options o = with("all", true);
  o.set("format", std::string("json"));
  const SynthesisRequest every = SynthesisRequest::read(task.kind, o);
  const synthesis::SynthesisOutcome outcome = synthesis::run_synthesis(task, every.run_options());
  const io::SynthesisListing all = every.listing(outcome, "designs");
  EXPECT_TRUE(all.all);
  EXPECT_EQ(all.export_dir, "designs");
  EXPECT_EQ(all.shown, synthesis::shown_rows(outcome, true, 20));
  ASSERT_GE(all.shown.size(), 1u);
  EXPECT_EQ(every.answer(task, outcome, all), io::synthesis_json(task, outcome, all));
  o.set("top", 1LL);
  o.set("format", std::string("table"));
  const SynthesisRequest best = SynthesisRequest::read(task.kind, o);
  EXPECT_EQ(best.listing(outcome).shown, std::vector<int>{all.shown[0]});
  std::ostringstream table;
  io::write_synthesis_table(table, task, outcome, best.listing(outcome));
  EXPECT_EQ(best.answer(task, outcome, best.listing(outcome)), table.str());
  EXPECT_THAT(table.str(), ::testing::StartsWith("function task"));
}

TEST(RequestOptions, ListsOfNamesComeAsOneTextOrAsAList) {
  EXPECT_EQ(SolveRequest::read(with("columns", std::string("crank,B.*"))).columns,
            (std::vector<std::string>{"crank", "B.*"}));
  EXPECT_EQ(SolveRequest::read(with("columns", std::vector<std::string>{"crank", "B.x,B.y"})).columns,
            (std::vector<std::string>{"crank", "B.x", "B.y"}));
  const PlotRequest plot = [] {
    Options o = with("y", std::string("P.y"));
    o.set("y_range", std::vector<std::string>{"-5", "5"});
    return PlotRequest::read(o);
  }();
  ASSERT_TRUE(plot.y_range);
  EXPECT_EQ(plot.y_range->first, -5.0);
  EXPECT_EQ(plot.y_range->second, 5.0);
  Options inverted = with("y", std::string("P.y"));
  inverted.set("y_range", std::vector<double>{5, -5});
  EXPECT_EQ(message([&] { PlotRequest::read(inverted); }), "y_range: LO and HI must be finite numbers with LO < HI");
  Options three = with("y", std::string("P.y"));
  three.set("y_range", std::vector<double>{1, 2, 3});
  EXPECT_EQ(message([&] { PlotRequest::read(three); }), "y_range: must be 2 numbers, not 3");
}

TEST(RequestOptions, EachKindOfPictureHasItsOwnSizeInEveryFrontEnd) {
  EXPECT_EQ(message([] { DrawRequest::read(with("width", 50LL)); }), "width: must be from 100 to 10000, not 50");
  EXPECT_EQ(message([] { AnimateRequest::read(with("width", 9000LL)); }), "width: must be from 64 to 8192, not 9000");
  Options plot = with("y", std::string("P.y"));
  plot.set("height", 100LL);
  EXPECT_EQ(message([&] { PlotRequest::read(plot); }), "height: must be from 150 to 10000, not 100");
  EXPECT_EQ(message([] { AnimateRequest::read(with("fps", 200LL)); }), "fps: must be from 0.1 to 120, not 200");
  const DrawRequest defaults = DrawRequest::read(Options());
  EXPECT_EQ(defaults.picture.width, kDrawingLimits.default_width);
  EXPECT_EQ(defaults.picture.height, kDrawingLimits.default_height);
  EXPECT_EQ(PlotRequest::read(with("y", std::string("P.y"))).height, 520);
}

TEST(RequestOptions, AStepTooLargeForAnIntIsRefusedNotWrapped) {
  EXPECT_EQ(message([] { DrawRequest::read(with("step", 3e9)); }),
            "step: must be from 0 to 2147483647, not 3000000000");
  EXPECT_EQ(message([] { DrawRequest::read(with("step", -1LL)); }), "step: must be 0 or more, not -1");
}

class RequestsOnAModel : public ::testing::Test {
 protected:
  void SetUp() override {
    file_ = io::load_model_file(std::string(NBAR_EXAMPLES_DIR) + "/fourbar-crank-rocker.yaml");
    mechanism_ = std::make_shared<const Mechanism>(file_.model);
  }
  io::LoadedModel file_;
  std::shared_ptr<const Mechanism> mechanism_;
};

TEST_F(RequestsOnAModel, TheMeshSizeIsConvertedFromTheModelsUnitOnce) {
  // The crank-rocker is drawn in mm: 4 (mm) is 0.004 m, whichever front-end gave it.
  Options o = with("method", std::string("fe"));
  o.set("mesh_size", std::string("4"));
  const AnalysisOptions options = StressRequest::read(o).analysis_options(file_.model);
  EXPECT_EQ(options.stress_method, StressMethod::fe);
  EXPECT_DOUBLE_EQ(options.fe.mesh_size, 0.004);
  EXPECT_TRUE(options.stress);
  Options beam = with("mesh_size", 4LL);
  EXPECT_EQ(message([&] { StressRequest::read(beam); }),
            "mesh_size: is the finite elements' element size: give method fe too");
}

// The finite elements' mesh options and the convergence study's tolerance, read for every
// front-end: the edge size converted from the model's unit, the tolerance from % to a fraction.
TEST_F(RequestsOnAModel, TheMeshOptionsAndTheConvergenceTolerance) {
  Options o = with("method", std::string("fe"));
  o.set("edge_size", std::string("0.5"));
  o.set("segments_per_hole", std::string("64"));
  o.set("converge", true);
  o.set("tolerance", std::string("0.5"));
  const StressRequest r = StressRequest::read(o);
  EXPECT_TRUE(r.converge);
  EXPECT_DOUBLE_EQ(r.tolerance, 0.005);
  const AnalysisOptions options = r.analysis_options(file_.model);
  EXPECT_DOUBLE_EQ(options.fe.edge_size, 0.0005);
  EXPECT_EQ(options.fe.segments_per_hole, 64);
  EXPECT_DOUBLE_EQ(StressRequest::read(with("method", std::string("fe"))).tolerance, 0.01);
  EXPECT_EQ(message([&] { StressRequest::read(with("edge_size", 1LL)); }),
            "edge_size: is for finite elements: give method fe too");
  Options few = with("method", std::string("fe"));
  few.set("segments_per_hole", 4LL);
  EXPECT_EQ(message([&] { StressRequest::read(few); }), "segments_per_hole: must be from 8 to 1000000, not 4");
  Options zero = with("method", std::string("fe"));
  zero.set("converge", true);
  zero.set("tolerance", 0.0);
  EXPECT_EQ(message([&] { StressRequest::read(zero); }), "tolerance: must be above 0 %, not 0");
}

TEST_F(RequestsOnAModel, ThePoseDrawnIsTheSampleAskedForOrWhereTheDriverIsAt) {
  Options o = with("steps", 13LL);
  o.set("step", 3LL);
  const DrawRequest at_step = DrawRequest::read(o);
  const Analysis analysis = analyse(mechanism_, at_step.analysis_options(file_.model));
  ASSERT_EQ(analysis.sweep.samples.size(), 13u);
  EXPECT_EQ(at_step.drawn_step(analysis), 3);
  EXPECT_EQ(at_step.pose(analysis).step, 3);
  EXPECT_EQ(DrawRequest::read(with("at", 90LL)).pose(analysis).step, std::nullopt);  // not a sample
  EXPECT_EQ(DrawRequest::read(Options()).pose(analysis).step, 0);  // the start: the crank-rocker is open there
  // 13 samples over the crank's turn: sample 3 is at 90 deg; `at: 90` is the same pose.
  const std::vector<Eigen::Vector2d> by_step = at_step.pose(analysis).points;
  const std::vector<Eigen::Vector2d> by_value = DrawRequest::read(with("at", 90LL)).pose(analysis).points;
  ASSERT_EQ(by_step.size(), by_value.size());
  for (std::size_t i = 0; i < by_step.size(); ++i) EXPECT_LT((by_step[i] - by_value[i]).norm(), 1e-12);
  // The crank pin A of a crank of 80 mm at 90 deg about O2 = (0, 0).
  const int a = file_.model.find_point("A");
  ASSERT_GE(a, 0);
  EXPECT_NEAR(by_step[static_cast<std::size_t>(a)].x(), 0.0, 1e-12);
  EXPECT_NEAR(by_step[static_cast<std::size_t>(a)].y(), 0.080, 1e-12);
  Options past = with("step", 13LL);
  EXPECT_EQ(message([&] { DrawRequest::read(past).pose(analysis); }), "step 13 is not a solved step (0 to 12)");
}

// On a rocking path (`at_limits: reverse`) the double-rocker turns at its toggle +L onto its other
// branch, comes down to -L and turns back onto the drawn one. A step past the first turn draws that
// sample's pose, on the other branch (B across the line A-O4 from where it was drawn); `at` a value
// first met on the way down draws the same pose. The reference is the four-bar's closed form.
TEST(RequestsOnARockingPath, TheStepDrawnPastATurnIsThatSamplesPose) {
  const io::LoadedModel file =
      io::load_model_file(std::string(NBAR_EXAMPLES_DIR) + "/fourbar-double-rocker-rocking.yaml");
  const auto mechanism = std::make_shared<const Mechanism>(file.model);
  const Model& m = file.model;
  const test_support::FourBarClosedForm four_bar(m);
  const double drawn_side = four_bar.drawn_side;
  const auto pin_b = [&](double theta, double side) { return four_bar.pin_b(theta, side); };
  Options o;
  o.set("step", 92LL);  // 201 samples over two cycles of 4 x 99.7151 deg: -87.5 deg on the way down
  const DrawRequest by_step = DrawRequest::read(o);
  const Analysis analysis = analyse(mechanism, by_step.analysis_options(m));
  const Sample& sample = analysis.sweep.samples[92];
  ASSERT_EQ(sample.reversals, 1);
  const double theta = sample.driver_values[0];
  ASSERT_LT(theta, -80 * std::numbers::pi / 180);
  const auto b = static_cast<std::size_t>(m.find_point("B"));
  const DrawRequest::Pose drawn = by_step.pose(analysis);
  EXPECT_EQ(drawn.step, 92);
  EXPECT_LT((drawn.points[b] - pin_b(theta, -drawn_side)).norm(), 1e-12);
  EXPECT_GT((drawn.points[b] - pin_b(theta, drawn_side)).norm(), 0.01);  // not the drawn branch's pose
  Options value;
  value.set("at", theta * 180 / std::numbers::pi);
  const DrawRequest::Pose by_value = DrawRequest::read(value).pose(analysis);
  ASSERT_EQ(by_value.points.size(), drawn.points.size());
  for (std::size_t i = 0; i < drawn.points.size(); ++i) EXPECT_LT((by_value.points[i] - drawn.points[i]).norm(), 1e-12);
}

TEST_F(RequestsOnAModel, ThePlatesLieAsDrawnOrWhereTheDriverIsAt) {
  const ExportRequest drawn = ExportRequest::read(Options());
  EXPECT_EQ(drawn.format, "svg");
  const std::vector<Eigen::Vector2d> as_drawn = drawn.points(*mechanism_);
  ASSERT_EQ(as_drawn.size(), file_.model.points.size());
  for (std::size_t i = 0; i < as_drawn.size(); ++i) EXPECT_EQ(as_drawn[i], file_.model.points[i].position);
  // At 90 deg the crank of 80 mm stands straight up from O2 = (0, 0): its pin A at (0, 0.080) m.
  const std::vector<Eigen::Vector2d> at_90 = ExportRequest::read(with("at", 90LL)).points(*mechanism_);
  const auto a = static_cast<std::size_t>(file_.model.find_point("A"));
  EXPECT_NEAR(at_90[a].x(), 0.0, 1e-12);
  EXPECT_NEAR(at_90[a].y(), 0.080, 1e-12);
  EXPECT_EQ(message([] { ExportRequest::read(with("format", std::string("png"))); }),
            "format: must be one of svg, dxf, not 'png'");
  // The crank-rocker's links have no plates: nothing to cut, in either format.
  try {
    drawn.plates(*mechanism_, as_drawn);
    ADD_FAILURE() << "plates of a model without shapes";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::BadInput);
    EXPECT_THAT(e.message(), HasSubstr("nothing to cut"));
  }
  const io::LoadedModel steel = io::load_model_file(std::string(NBAR_EXAMPLES_DIR) + "/fourbar-steel-bars.yaml");
  const Mechanism bars(steel.model);
  const std::string dxf = ExportRequest::read(with("format", std::string("dxf"))).plates(bars, drawn.points(bars));
  EXPECT_EQ(dxf, io::cutting_dxf(bars, drawn.points(bars)));
  EXPECT_THAT(dxf, ::testing::StartsWith("  0\nSECTION"));
}

TEST_F(RequestsOnAModel, AColumnThatMatchesNothingListsTheColumnsOrSaysItNeedsTheDynamics) {
  Options o = with("steps", 5LL);
  o.set("columns", std::string("nosuch"));
  const SolveRequest solve = SolveRequest::read(o);
  const Analysis analysis = analyse(mechanism_, solve.analysis_options());
  const std::string m = message([&] { solve.table(analysis); });
  EXPECT_THAT(m, HasSubstr("columns: no column matches 'nosuch'; the columns are: step, t, crank, O2.x"));
  o.set("columns", std::string("crank.torque"));
  const SolveRequest torque = SolveRequest::read(o);
  EXPECT_EQ(cli_message([&] { torque.table(analysis); }),
            "--columns: no column matches 'crank.torque': the force and torque columns come from the inverse "
            "dynamics, add --dynamics");
  o.set("columns", std::string("crank,B.x"));
  const ResultTable table = SolveRequest::read(o).table(analysis);
  EXPECT_EQ(table.columns, (std::vector<std::string>{"crank", "B.x"}));
  EXPECT_EQ(table.rows.size(), 5u);
}

TEST_F(RequestsOnAModel, APlotAsksForTheStagesItsColumnsNeed) {
  Options o = with("y", std::string("crank.torque"));
  const AnalysisOptions options = PlotRequest::read(o).analysis_options(*mechanism_);
  EXPECT_TRUE(options.dynamics);
  EXPECT_GE(options.order, 2);
  o.set("y", std::string("rocker.jerk"));
  EXPECT_EQ(PlotRequest::read(o).analysis_options(*mechanism_).order, 3);
  o.set("y", std::string("nosuch"));
  EXPECT_THAT(message([&] { PlotRequest::read(o).analysis_options(*mechanism_); }),
              HasSubstr("y: no column matches 'nosuch'"));
}

}  // namespace
}  // namespace nbar::request

namespace nbar::request {
namespace {

// The centres of mass and `cond` come only when `columns` names them, through every front-end's
// request: the solve's table, its numpy columns, its analysis options and the plot's.
TEST(SolveRequestColumns, ColumnsOnRequestComeOnlyWhenNamed) {
  const auto mech = std::make_shared<const Mechanism>(
      io::load_model_file(std::string(NBAR_EXAMPLES_DIR) + "/fourbar-steel-bars.yaml").model);
  Options options;
  options.set("columns", std::string("crank,coupler.*,coupler.cg.x,cond"));
  options.set("steps", 13LL);
  const SolveRequest solve = SolveRequest::read(options);
  const AnalysisOptions analysis_options = solve.analysis_options();
  EXPECT_TRUE(analysis_options.condition);
  const Analysis analysis = analyse(mech, analysis_options);
  const ResultTable table = solve.table(analysis);
  EXPECT_EQ(table.columns, (std::vector<std::string>{"crank", "coupler.angle", "coupler.omega", "coupler.alpha",
                                                     "coupler.cg.x", "cond"}));
  for (const auto& row : table.rows) EXPECT_TRUE(std::isfinite(row[5]) && row[5] >= 1.0);
  const ColumnTable arrays = solve.columns_of(analysis);
  EXPECT_EQ(arrays.columns, table.columns);
  EXPECT_EQ(arrays.values(6, 4), table.rows[6][4]);

  Options ordinary;
  ordinary.set("columns", std::string("crank,coupler.*"));
  EXPECT_FALSE(SolveRequest::read(ordinary).analysis_options().condition);
  EXPECT_EQ(SolveRequest::read(ordinary).table(analysis).columns.size(), 4u);

  Options plot;
  plot.set("y", std::string("coupler.cg.y,cond"));
  const PlotRequest request = PlotRequest::read(plot);
  EXPECT_TRUE(request.analysis_options(*mech).condition);
}

}  // namespace
}  // namespace nbar::request
