// The analysis pipeline: each stage runs once, in order, and what it keeps agrees with the
// stages run one by one; the column catalogue agrees with the tables; errors have kinds.
#include "example_models.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>

#include "nbar/analysis/analysis.hpp"
#include "nbar/analysis/columns.hpp"
#include "nbar/analysis/summary.hpp"
#include "nbar/dynamics/dynamics_table.hpp"
#include "nbar/io/model_file.hpp"
#include "nbar/kinematics/sweep.hpp"
#include "nbar/render/report.hpp"

namespace nbar {
namespace {

using test_support::example_mechanism;

AnalysisOptions with_stress(int steps) {
  AnalysisOptions o;
  o.steps = steps;
  o.stress = true;
  o.sections = 60;
  return o;
}

TEST(Analysis, ReportSolvesTheDynamicsOfEverySampleOnce) {
  const auto mech = example_mechanism("fourbar-steel-bars.yaml");
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
  const auto mech = example_mechanism("compressor-myszka-kinetics.yaml");
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
  zero_numerical_noise(expected);

  ASSERT_EQ(table.columns, expected.columns);
  ASSERT_EQ(table.units, expected.units);
  ASSERT_EQ(table.rows.size(), 25u);
  for (std::size_t r = 0; r < table.rows.size(); ++r) EXPECT_EQ(table.rows[r], expected.rows[r]) << "row " << r;
}

TEST(Analysis, StressPeakIsTheLargestOfEveryProfile) {
  const auto mech = example_mechanism("fourbar-steel-bars.yaml");
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
  auto mech = example_mechanism("fourbar-steel-bars.yaml");
  const std::weak_ptr<const Mechanism> watch = mech;
  Analysis analysis = analyse(std::move(mech), with_stress(7));
  EXPECT_FALSE(watch.expired());  // the analysis keeps it alive
  const ResultTable profile = section_profile_table(analysis, analysis.stress->peaks[0].body, 3);
  EXPECT_GT(profile.rows.size(), 50u);
}

TEST(Columns, CatalogueNamesTheTableColumnsWithTheirUnits) {
  const auto mech = example_mechanism("compressor-myszka-kinetics.yaml");
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
  const auto mech = example_mechanism("compressor-myszka-kinetics.yaml");
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
  n = column_needs(*mech, {"crank", "C.X"});  // case folded: did you mean
  EXPECT_EQ(n.unmatched, 1);
  EXPECT_EQ(n.message.rfind("no column matches 'C.X' (did you mean 'C.x'?); the columns are: step, t, crank,", 0), 0u)
      << n.message;
  EXPECT_EQ(no_column_message("CRANK.TOR*", {"crank", "crank.torque"}),
            "no column matches 'CRANK.TOR*' (did you mean 'crank.torque'?)");
  EXPECT_EQ(no_column_message("zz", {"crank"}), "no column matches 'zz'");
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
  const auto kinematic = example_mechanism("fourbar-crank-rocker.yaml");
  EXPECT_EQ(kind_of([&] { analyse(kinematic, with_stress(5)); }), ErrorKind::InvalidModel);
  AnalysisOptions order9;
  order9.order = 9;
  EXPECT_EQ(kind_of([&] { analyse(kinematic, order9); }), ErrorKind::BadInput);

  const auto steel = example_mechanism("fourbar-steel-bars.yaml");
  const Analysis analysis = analyse(steel, with_stress(5));
  EXPECT_EQ(kind_of([&] { section_profile_table(analysis, analysis.stress->peaks[0].body, 5); }), ErrorKind::BadInput);
}

// Every entry point that takes a derivative order refuses one past 5: the column catalogue built
// its tables from it and crashed at 6 (Python's Model.columns(order=6)).
TEST(Analysis, OrdersAndSectionsOutOfRangeAreBadInput) {
  const auto mech = example_mechanism("fourbar-crank-rocker.yaml");
  EXPECT_EQ(kind_of([&] { column_catalogue(*mech, 6); }), ErrorKind::BadInput);
  EXPECT_EQ(kind_of([&] { column_catalogue(*mech, -1); }), ErrorKind::BadInput);
  EXPECT_EQ(kind_of([&] { column_needs(*mech, {"P.x"}, 6, false); }), ErrorKind::BadInput);
  EXPECT_GT(column_catalogue(*mech, kMaxDerivativeOrder).size(), column_catalogue(*mech, 2).size());

  const auto steel = example_mechanism("fourbar-steel-bars.yaml");
  AnalysisOptions too_fine = with_stress(5);
  too_fine.sections = kMaxSectionsPerLink + 1;
  EXPECT_EQ(kind_of([&] { analyse(steel, too_fine); }), ErrorKind::BadInput);
  AnalysisOptions no_steps;
  no_steps.max_steps = 0;
  EXPECT_EQ(kind_of([&] { analyse(mech, no_steps); }), ErrorKind::BadInput);
}

// A budget past what the clock counts (infinite, or 1e12 s) is none: converted, it wrapped into
// the past and cancelled every run at once.
TEST(Analysis, AnEndlessTimeBudgetNeverCancels) {
  for (const double seconds : {HUGE_VAL, 1e300, 1e12, 1e10}) {
    CancelToken token;
    token.set_time_budget(std::chrono::duration<double>(seconds));
    EXPECT_FALSE(token.cancelled()) << seconds;
  }
  CancelToken spent;
  spent.set_time_budget(std::chrono::duration<double>(-1.0));
  EXPECT_TRUE(spent.cancelled());
  AnalysisOptions options;
  options.control.token.set_time_budget(std::chrono::duration<double>(HUGE_VAL));
  EXPECT_TRUE(analyse(example_mechanism("fourbar-crank-rocker.yaml"), options).complete());
}

TEST(Analysis, CancelledByTokenOrProgress) {
  const auto mech = example_mechanism("fourbar-steel-bars.yaml");
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
  const ModelSummary four_bar = summarize(*example_mechanism("fourbar-crank-rocker.yaml"));
  EXPECT_EQ(four_bar.mobility.dof, 1);
  EXPECT_EQ(four_bar.mobility.grubler, 1);
  ASSERT_EQ(four_bar.loops.size(), 1u);
  EXPECT_EQ(four_bar.loops[0].grashof.kind, GrashofClass::CrankRocker);
  EXPECT_TRUE(four_bar.assembly);
  EXPECT_FALSE(four_bar.has_kinetics());
  EXPECT_EQ(render::report_analysis_options(four_bar).dynamics, false);

  const ModelSummary steel = summarize(*example_mechanism("fourbar-steel-bars.yaml"));
  EXPECT_TRUE(steel.has_kinetics());
  EXPECT_TRUE(steel.has_stress_links);
  for (const BodySummary& b : steel.bodies) EXPECT_GT(b.mass.mass, 0.0) << b.name;

  const ModelSummary redundant = summarize(*example_mechanism("parallelogram-redundant.yaml"));
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
  EXPECT_TRUE(summarize(*example_mechanism("fourbar-crank-rocker.yaml")).warnings.empty());
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

// A plate drawn where its body is not (a DXF part in its own frame, here turned 90 degrees)
// is said with how far the point is off it; pins in holes, on the edge or inside are not.
std::shared_ptr<const Mechanism> crank_with_plate(const std::string& outline) {
  return std::make_shared<const Mechanism>(io::parse_model("units: {length: mm, angle: deg}\n"
                                                           "points: {O: [0, 0], A: [80, 0]}\n"
                                                           "ground: [O]\n"
                                                           "bodies:\n"
                                                           "  crank:\n"
                                                           "    points: [O, A]\n"
                                                           "    shape: {outline: " +
                                                           outline +
                                                           ", holes: [{at: O, radius: 4}]}\n"
                                                           "    thickness: 5\n"
                                                           "    material: steel\n"
                                                           "drivers: [{angle: crank, from: 0, to: 360}]\n")
                                               .model);
}

TEST(Summary, WarnsOfABodysPointOffItsPlate) {
  // A slot 80 mm long drawn along y: A at (80, 0) is 70 mm from its right side, x = 10.
  const auto turned = crank_with_plate("[[-10, 0, {bulge: 1}], [10, 0], [10, 80, {bulge: 1}], [-10, 80]]");
  const ModelSummary s = summarize(*turned);
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_EQ(s.warnings[0].code, "point_off_plate");
  EXPECT_NE(s.warnings[0].message.find("point A of body crank lies 70 mm outside its plate, which spans x from -10 to "
                                       "10 and y from -10 to 90 mm"),
            std::string::npos)
      << s.warnings[0].message;
  // Every command that sweeps says it too.
  const std::vector<Warning> before = check_before_sweep(*turned);
  ASSERT_EQ(before.size(), 1u);
  EXPECT_EQ(before[0].code, "point_off_plate");
  // A pin on the plate's edge, or inside it, is where it should be.
  EXPECT_TRUE(summarize(*crank_with_plate("[[-10, -10], [80, -10], [80, 10], [-10, 10]]")).warnings.empty());
  EXPECT_TRUE(summarize(*crank_with_plate("[[-10, -10], [90, -10], [90, 10], [-10, 10]]")).warnings.empty());
}

// Stroke, dead centres and time ratio of an offset slider-crank against the closed forms
// (Norton): stroke = sqrt((l+r)^2 - e^2) - sqrt((l-r)^2 - e^2); the crank lies along the rod at
// asin(e/(l+r)) (outer) and pi + asin(e/(l-r)) (inner), measured from the guide's direction.
TEST(Summary, SliderCrankStrokeDeadCentresAndTimeRatio) {
  const auto mech = example_mechanism("slider-crank-offset.yaml");
  const ModelSummary s = summarize(*mech);
  ASSERT_EQ(s.slider_cranks.size(), 1u);
  const SliderCrankSummary& f = s.slider_cranks[0];
  EXPECT_EQ(f.crank, "crank");
  EXPECT_EQ(f.rod, "rod");
  const double r = 0.050, e = 0.025, l = std::hypot(0.228255435 - 0.050, 0.025);
  EXPECT_NEAR(f.crank_length, r, 1e-12);
  EXPECT_NEAR(f.rod_length, l, 1e-12);
  EXPECT_NEAR(f.offset, e, 1e-12);
  ASSERT_TRUE(f.crank_turns_fully);
  EXPECT_NEAR(f.stroke, std::sqrt((l + r) * (l + r) - e * e) - std::sqrt((l - r) * (l - r) - e * e), 1e-12);
  const double outer = std::asin(e / (l + r)), inner = std::numbers::pi + std::asin(e / (l - r));
  EXPECT_NEAR(f.outer_dead_centre, outer, 1e-12);
  EXPECT_NEAR(f.inner_dead_centre, inner, 1e-12);
  EXPECT_NEAR(f.outstroke_turn, 2 * std::numbers::pi + outer - inner, 1e-12);
  EXPECT_NEAR(f.time_ratio, (inner - outer) / (2 * std::numbers::pi + outer - inner), 1e-12);
  EXPECT_NE(f.description.find("stroke 101.0"), std::string::npos) << f.description;

  // In line: the stroke is twice the crank and both strokes take 180 deg.
  const ModelSummary centred = summarize(*example_mechanism("slider-crank-centred.yaml"));
  ASSERT_EQ(centred.slider_cranks.size(), 1u);
  EXPECT_NEAR(centred.slider_cranks[0].stroke, 2 * centred.slider_cranks[0].crank_length, 1e-12);
  EXPECT_NEAR(centred.slider_cranks[0].time_ratio, 1.0, 1e-12);
}

// A crank-rocker's limits (Norton): the crank and the coupler in line, |O2 B| = b + a stretched
// and b - a folded, so the crank angle is acos((r^2 + d^2 - c^2) / (2 r d)) from the frame (plus
// 180 deg folded) and B lies at r along it; the time ratio is the longer crank turn between the
// two over the shorter. The example: frame 200 along +x, crank 80, coupler 180, rocker 150 mm.
TEST(Summary, CrankRockerSwingAndTimeRatio) {
  const ModelSummary s = summarize(*example_mechanism("fourbar-crank-rocker.yaml"));
  ASSERT_EQ(s.loops.size(), 1u);
  ASSERT_TRUE(s.loops[0].rocker);
  const RockerSwing& r = *s.loops[0].rocker;
  // The drawing's lengths (B is drawn to 6 decimals of mm: 80, 180, 150, 200 to about 1e-6).
  const GrashofReport& g = s.loops[0].grashof;
  const double a = g.input, b = g.coupler, c = g.output, d = g.frame, pi = std::numbers::pi;
  EXPECT_NEAR(a + b + c + d, 0.61, 1e-8);
  const auto crank_at = [&](double reach) { return std::acos((reach * reach + d * d - c * c) / (2 * reach * d)); };
  const auto rocker_at = [&](double reach, double direction) {
    return std::atan2(reach * std::sin(direction), reach * std::cos(direction) - d);
  };
  const double stretched = crank_at(b + a), folded = crank_at(b - a) + pi;
  EXPECT_NEAR(r.crank_stretched, stretched, 1e-12);
  EXPECT_NEAR(r.crank_folded, folded, 1e-12);
  EXPECT_NEAR(r.rocker_stretched, rocker_at(b + a, stretched), 1e-12);
  EXPECT_NEAR(r.rocker_folded, rocker_at(b - a, folded - pi), 1e-12);
  EXPECT_NEAR(r.turn_to_stretched, stretched + 2 * pi - folded, 1e-12);
  EXPECT_NEAR(r.time_ratio, (2 * pi - r.turn_to_stretched) / r.turn_to_stretched, 1e-12);
  EXPECT_NE(r.description.find("swings 65.921 deg"), std::string::npos) << r.description;
}

// Over a crank's full turn the transmission angle's extremes and its design value (the
// smallest of mu and 180 deg - mu) come from the closed form; a 36 001-step sweep of the whole
// turn, measured by the analysis, finds the same to its step (mu is flat at its extremes).
TEST(Summary, TransmissionOverTheCranksFullTurnIsTheSweepsExtremes) {
  for (const char* name : {"fourbar-crank-rocker.yaml", "fourbar-double-crank.yaml"}) {
    const auto mech = example_mechanism(name);
    const ModelSummary s = summarize(*mech);
    ASSERT_EQ(s.loops.size(), 1u) << name;
    ASSERT_TRUE(s.loops[0].transmission_over_turn) << name;
    const TransmissionOverTurn& t = *s.loops[0].transmission_over_turn;
    AnalysisOptions options;
    options.steps = 36001;
    const Analysis analysis = analyse(mech, options);
    ASSERT_TRUE(analysis.complete()) << name;
    const std::vector<TransmissionExtremes> swept = transmission_extremes(analysis);
    ASSERT_EQ(swept.size(), 1u);
    EXPECT_NEAR(t.min, swept[0].min, 1e-7) << name;
    EXPECT_NEAR(t.max, swept[0].max, 1e-7) << name;
    EXPECT_NEAR(t.design, swept[0].design, 1e-7) << name;
    // The start's value lies inside the range (the crank-rocker starts at its minimum, which the
    // two compute by different formulas: to rounding), and the design value is never above it.
    EXPECT_LE(t.min, s.loops[0].transmission_angle + 1e-15);
    EXPECT_GE(t.max, s.loops[0].transmission_angle - 1e-15);
    EXPECT_LE(t.design, std::min(t.min, std::numbers::pi - t.max) + 1e-15);
  }
  // A rocker input has no full turn: its design value would be the toggles' 0.
  EXPECT_FALSE(summarize(*example_mechanism("fourbar-double-rocker.yaml")).loops[0].transmission_over_turn);
}

// The limits are the extremes of the rocker's angle over a fine sweep of the machine's crank;
// a loop whose input is moved by the rest of the machine (it may only swing) has none.
TEST(Summary, CrankRockerLimitsAreTheSweepsExtremes) {
  const auto mech = example_mechanism("machine-18.yaml");
  const ModelSummary s = summarize(*mech);
  const SweepResult sweep = run_sweep(*mech, {.steps = 36001, .order = 0});
  ASSERT_TRUE(sweep.complete) << sweep.stop_reason;
  int checked = 0;
  for (const LoopSummary& l : s.loops) {
    if (!l.rocker) continue;
    double low = 1e9, high = -1e9;
    const double middle = 0.5 * (l.rocker->rocker_stretched + l.rocker->rocker_folded);
    for (const Sample& sample : sweep.samples) {
      const double angle =
          middle + std::remainder(body_angle_motion(*mech, sample, l.loop.output)[0] - middle, 2 * std::numbers::pi);
      low = std::min(low, angle);
      high = std::max(high, angle);
    }
    EXPECT_NEAR(std::min(l.rocker->rocker_stretched, l.rocker->rocker_folded), low, 1e-7) << l.loop.name;
    EXPECT_NEAR(std::max(l.rocker->rocker_stretched, l.rocker->rocker_folded), high, 1e-7) << l.loop.name;
    ++checked;
  }
  EXPECT_EQ(checked, 1) << "rocker1's loop has a driven crank; rocker4's input, rocker3, is moved by the machine";
}

// The crank-shaper's own description: forward 227.2 deg, return 132.8 deg of crank turn. Closed
// form: limits where the crank is perpendicular to the arm, 2 acos(r/d) apart; swing 2 asin(r/d).
TEST(Summary, QuickReturnSwingAndTimeRatio) {
  const ModelSummary s = summarize(*example_mechanism("inverted-slider-crank-shaper.yaml"));
  ASSERT_EQ(s.quick_returns.size(), 1u);
  const QuickReturnSummary& q = s.quick_returns[0];
  EXPECT_EQ(q.crank, "crank");
  EXPECT_EQ(q.arm, "arm");
  EXPECT_NEAR(q.swing, 2 * std::asin(100.0 / 250.0), 1e-12);
  EXPECT_NEAR(q.fast_turn * 180 / std::numbers::pi, 132.8, 0.05);
  EXPECT_NEAR(q.slow_turn * 180 / std::numbers::pi, 227.2, 0.05);
  EXPECT_NEAR(q.time_ratio, (2 * std::numbers::pi - 2 * std::acos(0.4)) / (2 * std::acos(0.4)), 1e-12);
  // The ram's slider is driven by the arm, a rocker: not a slider-crank.
  EXPECT_TRUE(s.slider_cranks.empty());
}

// A Grashof double-rocker (frame 40, input 30, coupler 20, output 35): the input turns only
// while the diagonal from its pin to the output's pivot is between |20 - 35| and 20 + 35; by
// the law of cosines, between acos(2275/2400) and acos(-525/2400) from the frame line.
TEST(Summary, FourBarToggleInputAngles) {
  const auto mech = std::make_shared<const Mechanism>(
      io::parse_model("units: {length: mm, angle: deg}\n"
                      "points: {O: [0, 0], A: [15, 25.980762113533157], B: [33.17477564823534, 34.328068872980296], "
                      "Q: [40, 0]}\n"
                      "ground: [O, Q]\n"
                      "bodies: {input: [O, A], coupler: [A, B], output: [Q, B]}\n"
                      "drivers:\n  - {angle: input, from: 60, to: 90}\n")
          .model);
  const ModelSummary s = summarize(*mech);
  ASSERT_EQ(s.loops.size(), 1u);
  ASSERT_TRUE(s.loops[0].toggle_from && s.loops[0].toggle_to);
  EXPECT_NEAR(*s.loops[0].toggle_from, std::acos(2275.0 / 2400.0), 1e-9);
  EXPECT_NEAR(*s.loops[0].toggle_to, std::acos(-525.0 / 2400.0), 1e-9);
  // A crank-rocker's crank turns fully: no toggles.
  const ModelSummary crank_rocker = summarize(*example_mechanism("fourbar-crank-rocker.yaml"));
  ASSERT_FALSE(crank_rocker.loops.empty());
  EXPECT_FALSE(crank_rocker.loops[0].toggle_from);
}

// A loop whose longest link is longer than the other three cannot close: said plainly.
TEST(Summary, ALoopThatCannotCloseSaysSo) {
  const auto mech =
      std::make_shared<const Mechanism>(io::parse_model("units: {length: mm}\n"
                                                        "points: {O: [0, 0], A: [40, 0], B: [60, 40], Q: [200, 0]}\n"
                                                        "ground: [O, Q]\n"
                                                        "bodies: {crank: [O, A], coupler: [A, B], rocker: [Q, B]}\n"
                                                        "lengths: {coupler: 50, rocker: 50}\n"
                                                        "drivers:\n  - {angle: crank, from: 0, to: 360}\n")
                                            .model);
  const ModelSummary s = summarize(*mech);
  ASSERT_TRUE(s.assembly_error);
  EXPECT_NE(s.assembly_error->message().find(
                "crank 40 + coupler 50 + rocker 50 < frame 200 mm: loop crank-coupler-rocker cannot close"),
            std::string::npos)
      << s.assembly_error->message();
}

// Where the exact value is 0 (the piston's velocity at dead centre, a constant-speed crank's
// angular acceleration), the tables say 0, not rounding noise; real values are untouched.
TEST(Analysis, TablesWriteExactZerosForNumericalNoise) {
  AnalysisOptions options;
  options.steps = 13;  // every 30 deg
  const Analysis a = analyse(example_mechanism("compressor-myszka.yaml"), options);
  const ResultTable table = result_table(a);
  const ColumnTable columns = result_columns(a);
  const auto column = [&](const std::string& name) {
    return static_cast<std::size_t>(std::find(table.columns.begin(), table.columns.end(), name) -
                                    table.columns.begin());
  };
  const std::size_t vx = column("C.vx"), alpha = column("crank.alpha"), crank = column("crank");
  ASSERT_LT(alpha, table.columns.size());
  for (std::size_t r = 0; r < table.rows.size(); ++r) {
    EXPECT_EQ(table.rows[r][alpha], 0.0) << "row " << r;
    for (std::size_t c = 0; c < table.columns.size(); ++c)
      EXPECT_EQ(table.rows[r][c], columns.values(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)));
  }
  // Dead centres at 0 and 180 deg: v = 0 exactly; at 90 deg v = -r omega (r = 0.75 in, 1750 rpm).
  EXPECT_EQ(table.rows[0][vx], 0.0);
  EXPECT_EQ(table.rows[6][vx], 0.0);
  EXPECT_EQ(table.rows[12][vx], 0.0);
  EXPECT_NEAR(table.rows[6][crank], 180.0, 1e-12);
  EXPECT_NEAR(table.rows[3][vx], -0.75 * 1750 * 2 * std::numbers::pi / 60, 1e-9);

  // The rule itself: per unit, relative to the largest value of that unit.
  ResultTable t;
  t.columns = {"step", "a", "b", "c"};
  t.units = {"", "mm/s", "mm/s", "N"};
  t.rows = {{1e-20, 1000.0, 1e-10, 1e-14}, {2, -2e-9, 5e-8, 2e-14}};
  zero_numerical_noise(t);
  // mm/s: the scale is 1000 (column a), so 1e-10 is noise but -2e-9 is not; N: small but all alike.
  EXPECT_EQ(t.rows[0], (std::vector<double>{1e-20, 1000.0, 0.0, 1e-14}));
  EXPECT_EQ(t.rows[1], (std::vector<double>{2, -2e-9, 5e-8, 2e-14}));
}

// A single pose is a sweep of one step, from the model file (`from` alone, `steps: 1`) or from
// the options, for from/to sweeps and time sweeps alike.
TEST(Analysis, OneStepIsOnePose) {
  const std::string four_bar =
      "points: {O: [0, 0], A: [10, 0], B: [30, 20], Q: [40, 0]}\n"
      "ground: [O, Q]\n"
      "bodies: {crank: [O, A], coupler: [A, B], rocker: [Q, B]}\n";
  const auto single = std::make_shared<const Mechanism>(
      io::parse_model(four_bar + "drivers:\n  - {angle: crank, from: 60}\nsweep: {steps: 1}\n").model);
  const Analysis a = analyse(single, AnalysisOptions{});
  ASSERT_EQ(a.sweep.samples.size(), 1u);
  EXPECT_TRUE(a.sweep.complete);
  EXPECT_NEAR(a.sweep.samples[0].driver_values[0], 60 * std::numbers::pi / 180, 1e-15);

  const auto timed = std::make_shared<const Mechanism>(
      io::parse_model(four_bar + "drivers:\n  - {angle: crank, law: 10*t}\nsweep: {duration: 2, steps: 1}\n").model);
  const Analysis t = analyse(timed, AnalysisOptions{});
  ASSERT_EQ(t.sweep.samples.size(), 1u);
  EXPECT_EQ(t.sweep.samples[0].time, 0.0);

  AnalysisOptions one;
  one.steps = 1;
  EXPECT_EQ(analyse(example_mechanism("fourbar-crank-rocker.yaml"), one).sweep.samples.size(), 1u);
  one.steps = 0;
  EXPECT_THROW(analyse(example_mechanism("fourbar-crank-rocker.yaml"), one), Error);
}

TEST(Analysis, DynamicsOfAModelWithoutMassesOrLoadsSaysSo) {
  AnalysisOptions o;
  o.steps = 3;
  o.dynamics = true;
  const Analysis bare = analyse(example_mechanism("fourbar-crank-rocker.yaml"), o);
  ASSERT_EQ(bare.warnings().size(), 1u);
  EXPECT_EQ(bare.warnings()[0].code, "no_kinetics");
  EXPECT_TRUE(analyse(example_mechanism("fourbar-steel-bars.yaml"), o).warnings().empty());
}

}  // namespace
}  // namespace nbar
