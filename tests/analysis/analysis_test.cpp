// The analysis pipeline: each stage runs once, in order, and what it keeps agrees with the
// stages run one by one; the column catalogue agrees with the tables; errors have kinds.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>

#include "nbar/analysis/analysis.hpp"
#include "nbar/analysis/columns.hpp"
#include "nbar/analysis/summary.hpp"
#include "nbar/dynamics/dynamics_table.hpp"
#include "nbar/io/model_file.hpp"
#include "nbar/render/report.hpp"

namespace nbar {
namespace {

std::shared_ptr<const Mechanism> example(const std::string& name) {
  return std::make_shared<const Mechanism>(io::load_model_file(std::string(NBAR_EXAMPLES_DIR) + "/" + name).model);
}

AnalysisOptions with_stress(int steps) {
  AnalysisOptions o;
  o.steps = steps;
  o.stress = true;
  o.sections = 60;
  return o;
}

TEST(Analysis, ReportSolvesTheDynamicsOfEverySampleOnce) {
  const auto mech = example("fourbar-steel-bars.yaml");
  const ModelSummary summary = summarize(*mech);
  AnalysisOptions options = render::report_analysis_options(summary);
  ASSERT_TRUE(options.dynamics);
  ASSERT_TRUE(options.stress);
  options.steps = 19;
  const long before = InverseDynamics::solve_count();
  const Analysis analysis = analyse(mech, options);
  render::ReportOptions report;
  report.frames = 8;
  const std::string html = render::html_report(analysis, summary, report);
  EXPECT_EQ(InverseDynamics::solve_count() - before, 19);
  EXPECT_NE(html.find("id=\"stresses\""), std::string::npos);
}

TEST(Analysis, TableAgreesWithTheStagesRunOneByOne) {
  const auto mech = example("compressor-myszka-kinetics.yaml");
  AnalysisOptions options;
  options.steps = 25;
  options.order = 3;
  options.dynamics = true;
  const ResultTable table = result_table(analyse(mech, options));

  SweepOptions sweep_options;
  sweep_options.steps = 25;
  sweep_options.order = 3;
  const SweepResult sweep = run_sweep(*mech, sweep_options);
  const InverseDynamics dynamics(mech);
  std::vector<DynamicsResult> results;
  for (const Sample& s : sweep.samples) results.push_back(dynamics.solve(s));
  ResultTable expected = make_table(*mech, sweep);
  append_dynamics_columns(dynamics, sweep, results, expected);

  ASSERT_EQ(table.columns, expected.columns);
  ASSERT_EQ(table.units, expected.units);
  ASSERT_EQ(table.rows.size(), 25u);
  for (std::size_t r = 0; r < table.rows.size(); ++r) EXPECT_EQ(table.rows[r], expected.rows[r]) << "row " << r;
}

TEST(Analysis, StressPeakIsTheLargestOfEveryProfile) {
  const auto mech = example("fourbar-steel-bars.yaml");
  const Analysis analysis = analyse(mech, with_stress(13));
  ASSERT_TRUE(analysis.stress);
  ASSERT_FALSE(analysis.stress->peaks.empty());
  for (const StressPeak& peak : analysis.stress->peaks) {
    double largest = 0.0;
    int at = -1;
    for (int step = 0; step < 13; ++step) {
      const ResultTable profile = section_profile_table(analysis, peak.body, step);
      const std::size_t vm = profile.columns.size() - 1;
      ASSERT_EQ(profile.columns[vm], "von_mises");
      for (const auto& row : profile.rows)
        if (row[vm] > largest) {
          largest = row[vm];
          at = step;
        }
    }
    EXPECT_DOUBLE_EQ(peak.at.von_mises / 1e6, largest) << analysis.model().bodies[peak.body].name;
    EXPECT_EQ(peak.step, at);
  }
}

TEST(Analysis, OutlivesTheCallersMechanism) {
  auto mech = example("fourbar-steel-bars.yaml");
  const std::weak_ptr<const Mechanism> watch = mech;
  Analysis analysis = analyse(std::move(mech), with_stress(7));
  EXPECT_FALSE(watch.expired());  // the analysis keeps it alive
  const ResultTable profile = section_profile_table(analysis, analysis.stress->peaks[0].body, 3);
  EXPECT_GT(profile.rows.size(), 50u);
}

TEST(Columns, CatalogueNamesTheTableColumnsWithTheirUnits) {
  const auto mech = example("compressor-myszka-kinetics.yaml");
  AnalysisOptions options;
  options.steps = 3;
  options.order = 4;
  options.dynamics = true;
  const ResultTable table = result_table(analyse(mech, options));
  const std::vector<ColumnInfo> catalogue = column_catalogue(*mech, 4, true);
  ASSERT_EQ(column_names(catalogue), table.columns);
  for (std::size_t c = 0; c < catalogue.size(); ++c) EXPECT_EQ(catalogue[c].unit, table.units[c]) << table.columns[c];
  const auto find = [&](const std::string& name) {
    return *std::find_if(catalogue.begin(), catalogue.end(), [&](const ColumnInfo& i) { return i.name == name; });
  };
  EXPECT_EQ(find("crank").order, 0);
  EXPECT_EQ(find("C.vx").order, 1);
  EXPECT_EQ(find("C.d4x").order, 4);
  EXPECT_EQ(find("crank.torque").stage, Stage::Dynamics);
  EXPECT_EQ(find("crank.alpha").stage, Stage::Sweep);
}

TEST(Columns, NeedsSayWhichStagesAndOrder) {
  const auto mech = example("compressor-myszka-kinetics.yaml");
  ColumnNeeds n = column_needs(*mech, {"crank.torque", "crank"});
  EXPECT_TRUE(n.dynamics);
  EXPECT_EQ(n.order, 2);
  EXPECT_EQ(n.unmatched, -1);
  n = column_needs(*mech, {"C.jx"});
  EXPECT_FALSE(n.dynamics);
  EXPECT_EQ(n.order, 3);
  n = column_needs(*mech, {"C.d5*", "C.x"});
  EXPECT_EQ(n.order, 5);
  n = column_needs(*mech, {"crank", "C.jx"}, 2);  // an order given is kept
  EXPECT_EQ(n.unmatched, 1);
  EXPECT_NE(n.message.find("no column matches 'C.jx'"), std::string::npos);
  n = column_needs(*mech, {"nothing*"});
  EXPECT_EQ(n.unmatched, 0);
  EXPECT_NE(n.message.find("with inverse dynamics also: "), std::string::npos);
}

ErrorKind kind_of(const std::function<void()>& run) {
  try {
    run();
  } catch (const Error& e) {
    return e.kind();
  }
  ADD_FAILURE() << "no nbar::Error thrown";
  return ErrorKind::BadInput;
}

TEST(Analysis, ErrorsHaveKinds) {
  const auto kinematic = example("fourbar-crank-rocker.yaml");
  EXPECT_EQ(kind_of([&] { analyse(kinematic, with_stress(5)); }), ErrorKind::InvalidModel);
  AnalysisOptions order9;
  order9.order = 9;
  EXPECT_EQ(kind_of([&] { analyse(kinematic, order9); }), ErrorKind::BadInput);

  const auto steel = example("fourbar-steel-bars.yaml");
  const Analysis analysis = analyse(steel, with_stress(5));
  EXPECT_EQ(kind_of([&] { section_profile_table(analysis, analysis.stress->peaks[0].body, 5); }), ErrorKind::BadInput);
}

TEST(Analysis, CancelledByTokenOrProgress) {
  const auto mech = example("fourbar-steel-bars.yaml");
  AnalysisOptions options = with_stress(200);
  options.control.token.cancel();
  EXPECT_EQ(kind_of([&] { analyse(mech, options); }), ErrorKind::Cancelled);

  AnalysisOptions stop_in_dynamics = with_stress(200);
  long dynamics_calls = 0;
  stop_in_dynamics.control.on_progress = [&](const Progress& p) {
    if (std::string(p.stage) == "dynamics") ++dynamics_calls;
    return std::string(p.stage) != "dynamics" || p.done < 10;
  };
  EXPECT_EQ(kind_of([&] { analyse(mech, stop_in_dynamics); }), ErrorKind::Cancelled);
  EXPECT_EQ(dynamics_calls, 11);
}

TEST(Summary, CountsClassifiesAndDecidesKineticsOnce) {
  const ModelSummary four_bar = summarize(*example("fourbar-crank-rocker.yaml"));
  EXPECT_EQ(four_bar.mobility.dof, 1);
  EXPECT_EQ(four_bar.mobility.grubler, 1);
  ASSERT_EQ(four_bar.loops.size(), 1u);
  EXPECT_EQ(four_bar.loops[0].grashof.kind, GrashofClass::CrankRocker);
  EXPECT_TRUE(four_bar.assembly);
  EXPECT_FALSE(four_bar.has_kinetics());
  EXPECT_EQ(render::report_analysis_options(four_bar).dynamics, false);

  const ModelSummary steel = summarize(*example("fourbar-steel-bars.yaml"));
  EXPECT_TRUE(steel.has_kinetics());
  EXPECT_TRUE(steel.has_stress_links);
  for (const BodySummary& b : steel.bodies) EXPECT_GT(b.mass.mass, 0.0) << b.name;

  const ModelSummary redundant = summarize(*example("parallelogram-redundant.yaml"));
  EXPECT_EQ(redundant.redundant.size(), 1u);
  EXPECT_EQ(redundant.mobility.grubler, 0);
  EXPECT_EQ(redundant.mobility.dof, 1);
}

// The crank-rocker with its crank lengthened from 80 to 130 mm: s + l = p + q within the
// drawing's rounding, and the crank folds against the coupler near 180 deg.
std::shared_ptr<const Mechanism> long_crank(const std::string& units, const std::string& to) {
  return std::make_shared<const Mechanism>(
      io::parse_model("units: {length: mm, angle: " + units +
                      "}\n"
                      "points: {O2: [0, 0], O4: [200, 0], A: [80, 0], B: [181.25, 148.823511]}\n"
                      "ground: [O2, O4]\n"
                      "bodies: {crank: [O2, A], coupler: [A, B], rocker: [O4, B]}\n"
                      "lengths: {crank: 130, rocker: 150}\n"
                      "drivers: [{angle: crank, from: 0, to: " +
                      to + "}]\n")
          .model);
}

TEST(Summary, WarnsOfASweepPastTheInputsToggles) {
  const ModelSummary s = summarize(*long_crank("deg", "360"));
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_EQ(s.warnings[0].code, "input_limited");
  EXPECT_EQ(s.warnings[0].step, -1);
  EXPECT_NE(s.warnings[0].message.find("the sweep asks crank to turn 360 deg, from 0 deg to 360 deg, but loop "
                                       "crank-coupler-rocker lets it turn only between -179.99"),
            std::string::npos)
      << s.warnings[0].message;
  // The sweep does stop there.
  const Analysis a = analyse(long_crank("deg", "360"), {});
  EXPECT_FALSE(a.sweep.complete);
  // Within the range: no warning.
  EXPECT_TRUE(summarize(*long_crank("deg", "170")).warnings.empty());
  // A crank that turns fully: none either.
  EXPECT_TRUE(summarize(*example("fourbar-crank-rocker.yaml")).warnings.empty());
}

TEST(Summary, WarnsOfManyTurnsAndNamesTheUnit) {
  const ModelSummary s = summarize(*long_crank("rad", "360"));
  ASSERT_FALSE(s.warnings.empty());
  EXPECT_EQ(s.warnings[0].code, "many_turns");
  EXPECT_NE(s.warnings[0].message.find("the sweep turns crank 57.3 times, from 0 rad to 360 rad (the model's angle "
                                       "unit is rad"),
            std::string::npos)
      << s.warnings[0].message;
  EXPECT_TRUE(summarize(*long_crank("rad", "2")).warnings.empty());
}

TEST(Analysis, DynamicsOfAModelWithoutMassesOrLoadsSaysSo) {
  AnalysisOptions o;
  o.steps = 3;
  o.dynamics = true;
  const Analysis bare = analyse(example("fourbar-crank-rocker.yaml"), o);
  ASSERT_EQ(bare.warnings().size(), 1u);
  EXPECT_EQ(bare.warnings()[0].code, "no_kinetics");
  EXPECT_TRUE(analyse(example("fourbar-steel-bars.yaml"), o).warnings().empty());
}

}  // namespace
}  // namespace nbar
