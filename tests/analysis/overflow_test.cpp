// Overflow is an error about the input that caused it, from the library itself, so that every
// front-end (CLI, server, Python) reports it alike (issue 16, items 5-8 and 11).
#include "nbar/analysis/analysis.hpp"
#include "nbar/io/model_file.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <limits>
#include <memory>
#include <sstream>
#include <string>

namespace nbar {
namespace {

using ::testing::HasSubstr;

const std::string kBase = "points: {O: [0, 0], A: [1, 0]}\nground: [O]\n";

std::shared_ptr<const Mechanism> compile(const std::string& text) {
  return std::make_shared<const Mechanism>(io::parse_model(text).model);
}

// The error `run` throws: its kind, entity and message.
template <typename Run>
Error error_of(Run run) {
  try {
    run();
  } catch (const Error& e) {
    return e;
  }
  ADD_FAILURE() << "no error";
  return Error(ErrorKind::BadInput, "none");
}

TEST(Overflow, AHugeDriverAccelerationIsAnErrorAtTheDriverNotNanDerivatives) {
  const auto mech =
      compile(kBase + "bodies: {crank: [O, A]}\ndrivers: [{angle: crank, from: 0, to: 90, accel: 1e300}]\n");
  AnalysisOptions options;
  options.order = 2;
  const Analysis ok = analyse(mech, options);  // accelerations of 1e300 are still numbers
  EXPECT_TRUE(ok.sweep.samples.back().taylor.allFinite());
  options.order = 5;
  const Error e = error_of([&] { analyse(mech, options); });
  EXPECT_EQ(e.kind(), ErrorKind::InvalidModel);
  EXPECT_EQ(e.where().kind, EntityRef::Kind::Driver);
  EXPECT_EQ(e.where().index, 0);
  EXPECT_THAT(e.message(), HasSubstr("4th derivatives of the mechanism overflow"));
}

TEST(Overflow, AMassThatOverflowsIsRejectedAtTheBody) {
  for (const std::string body :
       {"{points: [O, A], bar: {width: 0.1}, thickness: 1e306, material: steel}", "{points: [O, A], mass: 1e308}"}) {
    const Error e = error_of([&] {
      compile(kBase + "gravity: [0, -9.81]\nbodies:\n  crank: " + body +
              "\ndrivers: [{angle: crank, from: 0, to: 90}]\n");
    });
    // Found while reading: placed at the body, line 5 of the text.
    EXPECT_EQ(e.kind(), ErrorKind::InvalidModel) << body;
    EXPECT_EQ(e.mark().line, 5) << body;
    EXPECT_EQ(e.mark().column, 3) << body;
    EXPECT_THAT(e.message(), HasSubstr("too large to compute with")) << body;
  }
}

TEST(Overflow, AnOverflowBlamesTheInputThatCausedIt) {
  const std::string drivers = "drivers: [{angle: crank, from: 0, to: 90}]\n";
  const std::string bar = "{points: [O, A], bar: {width: 0.1}, thickness: 0.01, material: steel}";
  // Gravity of 1e308 overflows the weight of a 0.8 kg bar: gravity is to blame, not the thickness.
  const Error heavy =
      error_of([&] { compile(kBase + "gravity: [0, -1e308]\nbodies:\n  crank: " + bar + "\n" + drivers); });
  EXPECT_THAT(heavy.message(), HasSubstr("(its mass times gravity) is too large to compute with: check `gravity`"));
  EXPECT_THAT(heavy.message(), testing::Not(HasSubstr("thickness")));
  // A bar 1e300 wide: its outline is too large, not flat.
  const Error wide = error_of([&] {
    compile(kBase + "bodies:\n  crank: {points: [O, A], bar: {width: 1e300}, thickness: 0.01, material: steel}\n" +
            drivers);
  });
  EXPECT_THAT(wide.message(), HasSubstr("is too large to compute with (its area overflows)"));
  EXPECT_THAT(wide.message(), testing::Not(HasSubstr("zero area")));
}

TEST(Overflow, AHugeForceIsAnErrorAtTheForceWhenStressesOverflow) {
  const auto mech = compile(kBase +
                            "bodies:\n  crank: {points: [O, A], bar: {width: 0.1}, thickness: 0.01, material: steel}\n"
                            "forces: [{point: A, body: crank, force: [1e300, 1e300]}]\n"
                            "drivers: [{angle: crank, from: 0, to: 90}]\nsweep: {steps: 5}\n");
  AnalysisOptions options;
  options.stress = true;
  const Error e = error_of([&] { analyse(mech, options); });
  EXPECT_EQ(e.where().kind, EntityRef::Kind::PointLoad);
  EXPECT_EQ(e.where().index, 0);
  EXPECT_THAT(e.message(), HasSubstr("the stresses in body 'crank' overflow"));
}

TEST(Overflow, ASpeedTooSmallToMeanAMotionIsRejectedAtTheDriver) {
  const Error e = error_of(
      [&] { compile(kBase + "bodies: {crank: [O, A]}\ndrivers: [{angle: crank, from: 0, to: 90, speed: 1e-308}]\n"); });
  EXPECT_EQ(e.mark().line, 4);  // the driver's line
  EXPECT_THAT(e.message(), HasSubstr("the speed is too small"));
}

TEST(Overflow, ASpeedWhosePowersOverflowIsRejectedAtTheDriver) {
  // At 1e150 rad/s omega^2 * L passes 1e300 and the sweep stopped "at a singular position".
  const Error speed = error_of([&] {
    compile(kBase + "bodies: {crank: [O, A]}\ndrivers: [{angle: crank, from: 0, to: 90, speed: 1e150 rad/s}]\n");
  });
  EXPECT_EQ(speed.mark().line, 4);
  EXPECT_THAT(speed.message(), HasSubstr("the speed is too large to compute with (its size must be at most 1e30"));
  // A free driver's initial speed as well: at 1e300 rad/s a simulation's rows were NaN.
  const Error initial = error_of([&] {
    compile(kBase + "bodies: {crank: [O, A]}\ndrivers: [{angle: crank, free: true, initial_speed: 1e300}]\n");
  });
  EXPECT_EQ(initial.mark().line, 4);
  EXPECT_THAT(initial.message(), HasSubstr("the initial speed is too large to compute with"));
  // The largest speed still solves to the fifth derivative: the crank tip's is omega^5 on 1 m.
  const auto fast = compile(kBase +
                            "bodies: {crank: [O, A]}\ndrivers: [{angle: crank, from: 0, to: 90, speed: 1e30 rad/s}]\n"
                            "sweep: {steps: 3}\n");
  AnalysisOptions options;
  options.order = 5;
  const Analysis a = analyse(fast, options);
  ASSERT_TRUE(a.sweep.complete);
  ASSERT_EQ(a.sweep.samples.size(), 3u);
  for (const Sample& sample : a.sweep.samples) EXPECT_TRUE(sample.taylor.allFinite());
  EXPECT_NEAR(a.sweep.samples[1].derivative(5).norm() / 1e150, 1.0, 1e-9);
}

TEST(SweepSize, ATimeSweepOfMoreSamplesThanAnIntHoldsIsLimitedWithoutOverflow) {
  const auto mech = compile(kBase +
                            "bodies: {crank: [O, A]}\ndrivers: [{angle: crank, law: \"1e-6*t\"}]\n"
                            "sweep: {duration: 2147483647, step: 1}\n");
  AnalysisOptions options;
  options.max_steps = std::numeric_limits<int>::max();
  const Error e = error_of([&] { analyse(mech, options); });
  EXPECT_EQ(e.where().kind, EntityRef::Kind::Sweep);
  EXPECT_THAT(e.message(), HasSubstr("the sweep asks for 2147483648 steps, more than the limit of 2147483647"));
}

TEST(SweepSize, TheModelsSweepIsLimitedAtTheSweepAndAnOptionAsBadInput) {
  const auto mech = compile(kBase +
                            "bodies: {crank: [O, A]}\ndrivers: [{angle: crank, from: 0, to: 360}]\n"
                            "sweep: {steps: 1000000000}\n");
  const Error model = error_of([&] { analyse(mech, {}); });
  EXPECT_EQ(model.kind(), ErrorKind::InvalidModel);
  EXPECT_EQ(model.where().kind, EntityRef::Kind::Sweep);
  EXPECT_THAT(model.message(), HasSubstr("the sweep asks for 1000000000 steps, more than the limit of 10000000"));
  AnalysisOptions options;
  options.steps = 20;
  options.max_steps = 10;
  const Error option = error_of([&] { analyse(mech, options); });
  EXPECT_EQ(option.kind(), ErrorKind::BadInput);
  options.max_steps = 20;
  EXPECT_EQ(analyse(mech, options).sweep.samples.size(), 20u);
}

TEST(SweepSize, ATimeSweepTooLongToCountIsRejectedAtTheSweep) {
  const Error e = error_of([&] {
    compile(kBase +
            "bodies: {crank: [O, A]}\ndrivers: [{angle: crank, law: \"t\"}]\nsweep: {duration: 1e300, step: 1e-10}\n");
  });
  EXPECT_EQ(e.mark().line, 5);  // the sweep's line
  EXPECT_THAT(e.message(), HasSubstr("more samples than nbar can count"));
}

TEST(SweepSize, ALawThatTurnsTooFarIsRejectedAtTheLawsText) {
  // 1e12 deg/s for 2 s: 5.56e9 turns, beyond the 1000 turns a sweep may follow.
  const Error e = error_of([&] {
    compile(kBase +
            "bodies: {crank: [O, A]}\ndrivers: [{angle: crank, law: \"1e12*t\"}]\nsweep: {duration: 2, step: 0.5}\n");
  });
  EXPECT_EQ(e.mark().line, 4);
  EXPECT_EQ(e.mark().column, 31);  // the law's text, not the driver's mapping at column 11
  EXPECT_THAT(e.message(), HasSubstr("turns 5.56e+09 times over the sweep"));
  // 179000 deg/s for 2 s is 994 turns: within the limit.
  EXPECT_NO_THROW(compile(kBase + "bodies: {crank: [O, A]}\ndrivers: [{angle: crank, law: \"179000*t\"}]\n"
                                  "sweep: {duration: 2, step: 0.5}\n"));
}

TEST(LawLocation, AForcesUndefinedFyIsReportedAtItsText) {
  const io::LoadedModel loaded = io::parse_model(kBase +
                                                 "bodies: {crank: {points: [O, A], mass: 1}}\n"
                                                 "drivers: [{angle: crank, law: \"90*t\"}]\n"
                                                 "forces: [{point: A, body: crank, fx: 1, fy: \"log(t-1)\"}]\n"
                                                 "sweep: {duration: 2, step: 0.5}\n");
  AnalysisOptions options;
  options.dynamics = true;
  const Error e = error_of([&] { analyse(std::make_shared<const Mechanism>(loaded.model), options); });
  EXPECT_EQ(e.where().kind, EntityRef::Kind::PointLoad);
  EXPECT_EQ(e.where().law, 1);  // fy
  const Error at = io::located(loaded.source, e);
  EXPECT_EQ(at.mark().line, 5);
  EXPECT_EQ(at.mark().column, 45);  // the quote before log(t-1), not the force's mapping at column 9
  EXPECT_THAT(e.message(), HasSubstr("law 'log(t-1)' is undefined at t = "));
}

TEST(LawLocation, ALawUndefinedWhereTheSweepGoesBetweenSamplesIsAnErrorAtTheLaw) {
  // The wiper's law, defined at every sample of a quarter-second sweep but not for t in (0.3,
  // 0.45): the big first steps are shortened, and the tracker asks for the law at t = 0.375.
  std::ifstream file(std::string(NBAR_EXAMPLES_DIR) + "/fourbar-oscillating.yaml");
  std::stringstream text;
  text << file.rdbuf();
  std::string model = text.str();
  const std::string law = "30*sin(2*pi*t)\"", step = "step: 0.01";
  ASSERT_NE(model.find(law), std::string::npos);
  ASSERT_NE(model.find(step), std::string::npos);
  model.replace(model.find(law), law.size(), "30*sin(2*pi*t) + 0*sqrt((t-0.3)*(t-0.45))\"");
  model.replace(model.find(step), step.size(), "step: 0.25");
  const io::LoadedModel loaded = io::parse_model(model, "wiper.yaml");
  const Error e = error_of([&] { analyse(std::make_shared<const Mechanism>(loaded.model), AnalysisOptions{}); });
  // Not a stop at a limit position located at the sweep, as before.
  EXPECT_EQ(e.kind(), ErrorKind::UndefinedLaw);
  EXPECT_EQ(e.where().kind, EntityRef::Kind::Driver);
  EXPECT_THAT(e.message(), HasSubstr("is undefined at t = 0.375, which the sweep passes between steps 1 and 2"));
  const Error at = io::located(loaded.source, e);
  EXPECT_EQ(at.mark().line, 21);
  EXPECT_EQ(at.mark().column, 25);
}

}  // namespace
}  // namespace nbar
