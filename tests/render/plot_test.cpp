// Line plots: round tick values, where the data lands in pixels, gaps, clipping, the legend,
// and `nbar plot` as users run it.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <random>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "nbar/model/diagnostics.hpp"
#include "nbar/render/canvas.hpp"
#include "nbar/render/image_canvas.hpp"
#include "nbar/render/plot.hpp"

namespace {

namespace fs = std::filesystem;
using nbar::render::draw_plot;
using nbar::render::format_ticks;
using nbar::render::nice_ticks;
using nbar::render::PlotFrame;
using nbar::render::PlotSeries;
using nbar::render::PlotSpec;
using nbar::render::SvgCanvas;
using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::Not;

void expect_ticks(const std::vector<double>& got, const std::vector<double>& want) {
  ASSERT_EQ(got.size(), want.size()) << "first " << (got.empty() ? 0.0 : got.front());
  for (std::size_t i = 0; i < want.size(); ++i) {
    const double scale = std::max(std::abs(want.front()), std::abs(want.back()));
    EXPECT_NEAR(got[i], want[i], 1e-12 * scale) << "tick " << i;
  }
}

TEST(NiceTicks, UnitRangeInFifths) { expect_ticks(nice_ticks(0, 1), {0, 0.2, 0.4, 0.6, 0.8, 1}); }

TEST(NiceTicks, FullTurnInHundredsOrFifties) {
  // At most `target` intervals: 50s would take 8 to cover 0..360, so six allow only 100s.
  expect_ticks(nice_ticks(0, 360), {0, 100, 200, 300, 400});
  expect_ticks(nice_ticks(0, 360, 8), {0, 50, 100, 150, 200, 250, 300, 350, 400});
}

TEST(NiceTicks, NegativeRanges) {
  expect_ticks(nice_ticks(-7.3, 2.1), {-8, -6, -4, -2, 0, 2, 4});
  expect_ticks(nice_ticks(-1, -0.5), {-1, -0.9, -0.8, -0.7, -0.6, -0.5});
  expect_ticks(nice_ticks(-360, 0), {-400, -300, -200, -100, 0});
}

TEST(NiceTicks, BoundsInEitherOrder) { expect_ticks(nice_ticks(1, 0), nice_ticks(0, 1)); }

TEST(NiceTicks, TinyRanges) {
  expect_ticks(nice_ticks(0, 1e-9), {0, 2e-10, 4e-10, 6e-10, 8e-10, 1e-9});
  // A nanometre on a metre: the ticks are still exact steps from 1.
  expect_ticks(nice_ticks(1, 1 + 1e-9), {1, 1 + 2e-10, 1 + 4e-10, 1 + 6e-10, 1 + 8e-10, 1 + 1e-9});
}

TEST(NiceTicks, HugeRanges) {
  expect_ticks(nice_ticks(0, 1e12), {0, 2e11, 4e11, 6e11, 8e11, 1e12});
  expect_ticks(nice_ticks(-3e20, 5e20), {-4e20, -2e20, 0, 2e20, 4e20, 6e20});
}

TEST(NiceTicks, EmptyRangeWidenedAroundTheValue) {
  expect_ticks(nice_ticks(0, 0), {-1, -0.5, 0, 0.5, 1});
  expect_ticks(nice_ticks(5, 5), {4.4, 4.6, 4.8, 5, 5.2, 5.4, 5.6});
  expect_ticks(nice_ticks(-200, -200), {-220, -210, -200, -190, -180});
  // Rounding noise counts as no range at all.
  expect_ticks(nice_ticks(200, 200 + 3e-14), {180, 190, 200, 210, 220});
}

TEST(NiceTicks, SingleIntervalAboutZeroTakesTwo) { expect_ticks(nice_ticks(-1, 1, 1), {-1, 0, 1}); }

TEST(NiceTicks, RejectsWhatCannotBeTicked) {
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  EXPECT_THROW(nice_ticks(nan, 1), nbar::Error);
  EXPECT_THROW(nice_ticks(0, inf), nbar::Error);
  EXPECT_THROW(nice_ticks(0, 1e305), nbar::Error);
  EXPECT_THROW(nice_ticks(0, 1, 0), nbar::Error);
}

// Every range: ticks cover it, are evenly spaced by 1, 2 or 5 times a power of ten, and no
// more than the target intervals (over random ranges of all sizes and signs).
TEST(NiceTicks, CoverEvenlyWithRoundSteps) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(-1, 1), exponent(-12, 15), relative(-9, 2);
  std::uniform_int_distribution<int> targets(2, 15);
  for (int trial = 0; trial < 3000; ++trial) {
    const double e = exponent(rng);
    const double a = unit(rng) * std::pow(10.0, e), b = a + std::abs(unit(rng)) * std::pow(10.0, e + relative(rng));
    const int target = targets(rng);
    const std::vector<double> t = nice_ticks(a, b, target);
    ASSERT_GE(t.size(), 2u);
    ASSERT_LE(static_cast<int>(t.size()) - 1, target) << a << " " << b;
    const double step = t[1] - t[0];
    EXPECT_LE(t.front(), a + 1e-6 * step) << a << " " << b;
    EXPECT_GE(t.back(), b - 1e-6 * step) << a << " " << b;
    for (std::size_t i = 1; i < t.size(); ++i) EXPECT_NEAR(t[i] - t[i - 1], step, 1e-4 * step);
    const double mantissa = step / std::pow(10.0, std::floor(std::log10(step) + 1e-4));
    EXPECT_TRUE(std::abs(mantissa - 1) < 1e-4 || std::abs(mantissa - 2) < 1e-4 || std::abs(mantissa - 5) < 1e-4)
        << "step " << step;
  }
}

TEST(FormatTicks, FixedWithTheDecimalsTheStepNeeds) {
  EXPECT_THAT(format_ticks(nice_ticks(0, 1)), ElementsAre("0.0", "0.2", "0.4", "0.6", "0.8", "1.0"));
  EXPECT_THAT(format_ticks(nice_ticks(0, 360)), ElementsAre("0", "100", "200", "300", "400"));
  EXPECT_THAT(format_ticks(nice_ticks(-1, -0.5)), ElementsAre("-1.0", "-0.9", "-0.8", "-0.7", "-0.6", "-0.5"));
  EXPECT_THAT(format_ticks({-0.5, -0.25, 0, 0.25}), ElementsAre("-0.50", "-0.25", "0.00", "0.25"));
  EXPECT_THAT(format_ticks({1, 1 + 2e-10}), ElementsAre("1.0000000000", "1.0000000002"));
  EXPECT_THAT(format_ticks({999000, 1000000, 1001000}), ElementsAre("999000", "1000000", "1001000"));
}

TEST(FormatTicks, ShortExponentsForTheVeryLargeAndSmall) {
  EXPECT_THAT(format_ticks(nice_ticks(0, 1e12)), ElementsAre("0", "2e11", "4e11", "6e11", "8e11", "1e12"));
  EXPECT_THAT(format_ticks({1e6, 1.5e6, 2e6}), ElementsAre("1e6", "1.5e6", "2e6"));
  EXPECT_THAT(format_ticks({1.001e9, 1.002e9}), ElementsAre("1.001e9", "1.002e9"));
  EXPECT_THAT(format_ticks({0, 2e-4, 4e-4}), ElementsAre("0", "2e-4", "4e-4"));
  EXPECT_THAT(format_ticks({-1e-9, -5e-10, 0, 5e-10, 1e-9}), ElementsAre("-1e-9", "-5e-10", "0", "5e-10", "1e-9"));
}

// ---- The SVG of a plot, taken apart.

std::string group(const std::string& svg, const std::string& id) {
  const std::size_t start = svg.find("<g id=\"" + id + "\"");
  if (start == std::string::npos) return "";
  const std::size_t end = svg.find("</g>", start);
  return svg.substr(start, end - start);
}

std::vector<std::string> elements(const std::string& markup, const std::string& tag) {
  std::vector<std::string> out;
  for (std::size_t at = markup.find("<" + tag + " "); at != std::string::npos;
       at = markup.find("<" + tag + " ", at + 1))
    out.push_back(markup.substr(at, markup.find('>', at) - at + 1));
  return out;
}

std::string attribute(const std::string& element, const std::string& name) {
  const std::size_t at = element.find(" " + name + "=\"");
  if (at == std::string::npos) return "";
  const std::size_t start = at + name.size() + 3;
  return element.substr(start, element.find('"', start) - start);
}

std::vector<Eigen::Vector2d> points(const std::string& element) {
  std::vector<Eigen::Vector2d> out;
  std::istringstream in(attribute(element, "points"));
  std::string pair;
  while (in >> pair) {
    const std::size_t comma = pair.find(',');
    out.emplace_back(std::stod(pair.substr(0, comma)), std::stod(pair.substr(comma + 1)));
  }
  return out;
}

std::vector<std::string> texts(const std::string& markup) {
  std::vector<std::string> out;
  for (std::size_t at = markup.find("<text "); at != std::string::npos; at = markup.find("<text ", at + 1)) {
    const std::size_t start = markup.find('>', at) + 1;
    out.push_back(markup.substr(start, markup.find("</text>", start) - start));
  }
  return out;
}

struct Rect {
  double left, top, right, bottom;
};

// The plot area: the frame, the first polygon of the axes.
Rect frame_of(const std::string& svg) {
  const auto polygons = elements(group(svg, "axes"), "polygon");
  if (polygons.empty()) return {0, 0, 0, 0};
  const auto p = points(polygons.front());
  return {p[0].x(), p[0].y(), p[2].x(), p[2].y()};
}

// sin and cos of the angle in degrees over a full turn, one sample a degree.
PlotSpec trig_spec(const std::string& sin_unit = "m", const std::string& cos_unit = "m") {
  PlotSpec spec;
  spec.title = "trig";
  spec.x_name = "crank";
  spec.x_unit = "deg";
  PlotSeries s{"sin", sin_unit, {}}, c{"cos", cos_unit, {}};
  for (int i = 0; i <= 360; ++i) {
    spec.x.push_back(i);
    s.y.push_back(std::sin(i * std::numbers::pi / 180));
    c.y.push_back(std::cos(i * std::numbers::pi / 180));
  }
  spec.series = {s, c};
  return spec;
}

std::string svg_of(const PlotSpec& spec, PlotFrame* frame = nullptr) {
  SvgCanvas canvas(spec.width, spec.height);
  const PlotFrame f = draw_plot(canvas, spec);
  if (frame) *frame = f;
  return canvas.document();
}

constexpr double kPx = 0.006;  // SVG coordinates are written to 0.01 px

TEST(DrawPlot, OneLinePerSeriesMappedOntoTheAxes) {
  PlotFrame f;
  const std::string svg = svg_of(trig_spec(), &f);
  const Rect r = frame_of(svg);
  EXPECT_NEAR(r.left, f.left, kPx);
  EXPECT_NEAR(r.right, f.right, kPx);
  EXPECT_NEAR(r.top, f.top, kPx);
  EXPECT_NEAR(r.bottom, f.bottom, kPx);
  EXPECT_GT(r.right - r.left, 400);
  EXPECT_GT(r.bottom - r.top, 250);
  // Both series span -1..1, which round ticks cover exactly.
  EXPECT_EQ(f.y_ticks.front(), -1.0);
  EXPECT_EQ(f.y_ticks.back(), 1.0);

  for (int s = 0; s < 2; ++s) {
    const auto lines = elements(group(svg, "series-" + std::to_string(s)), "polyline");
    ASSERT_EQ(lines.size(), 1u) << "series " << s;
    const auto p = points(lines[0]);
    ASSERT_EQ(p.size(), 361u);
    EXPECT_NEAR(p.front().x(), r.left, kPx);  // the x axis spans the data exactly
    EXPECT_NEAR(p.back().x(), r.right, kPx);
    EXPECT_NEAR(p[90].x(), r.left + 0.25 * (r.right - r.left), kPx);
  }
  const auto sine = points(elements(group(svg, "series-0"), "polyline")[0]);
  const double middle = 0.5 * (r.top + r.bottom);
  EXPECT_NEAR(sine[0].y(), middle, kPx);                               // sin 0 = 0
  EXPECT_NEAR(sine[90].y(), r.top, kPx);                               // sin 90 = 1, the top tick
  EXPECT_NEAR(sine[270].y(), r.bottom, kPx);                           // sin 270 = -1, the bottom tick
  EXPECT_NEAR(sine[30].y(), middle - 0.25 * (r.bottom - r.top), kPx);  // sin 30 = 0.5
  EXPECT_THAT(svg, Not(HasSubstr("series-2")));
  EXPECT_THAT(svg, Not(HasSubstr("nan")));
}

TEST(DrawPlot, AxisLabelsTicksAndTitle) {
  const std::string svg = svg_of(trig_spec());
  const auto labels = texts(group(svg, "axes"));
  EXPECT_THAT(labels, testing::Contains("crank [deg]"));
  EXPECT_THAT(labels, testing::Contains("[m]"));  // one unit for both series
  EXPECT_THAT(labels, testing::Contains("trig"));
  EXPECT_THAT(labels, testing::Contains("-1.0"));
  EXPECT_THAT(labels, testing::Contains("1.0"));
  EXPECT_THAT(labels, testing::Contains("0"));  // an x tick
  EXPECT_THAT(labels, testing::Contains("300"));
  EXPECT_FALSE(elements(group(svg, "grid"), "polyline").empty());
}

TEST(DrawPlot, LegendOneEntryPerSeriesInItsColour) {
  const std::string svg = svg_of(trig_spec());
  const std::string legend = group(svg, "legend");
  EXPECT_THAT(texts(legend), ElementsAre("sin", "cos"));
  const auto swatches = elements(legend, "polyline");
  ASSERT_EQ(swatches.size(), 2u);
  EXPECT_EQ(elements(legend, "polygon").size(), 1u);  // the box
  for (int s = 0; s < 2; ++s) {
    const auto line = elements(group(svg, "series-" + std::to_string(s)), "polyline")[0];
    EXPECT_EQ(attribute(swatches[s], "stroke"), attribute(line, "stroke"));
  }
  EXPECT_NE(attribute(swatches[0], "stroke"), attribute(swatches[1], "stroke"));
}

TEST(DrawPlot, TwoUnitsGetAYAxisEach) {
  PlotFrame f;
  PlotSpec spec = trig_spec("deg", "deg/s");
  for (double& y : spec.series[1].y) y *= 300;  // cos in deg/s, 300 times larger
  const std::string svg = svg_of(spec, &f);
  EXPECT_THAT(texts(group(svg, "legend")), ElementsAre("sin [deg]", "cos [deg/s] (right)"));
  const auto axes = texts(group(svg, "axes"));
  EXPECT_THAT(axes, testing::Contains("[deg]"));
  EXPECT_THAT(axes, testing::Contains("[deg/s]"));
  EXPECT_THAT(axes, testing::Contains("300"));  // a right tick
  ASSERT_TRUE(f.right_axis);
  EXPECT_EQ(f.y_ticks.front(), -1.0);
  EXPECT_EQ(f.y_ticks.back(), 1.0);
  EXPECT_EQ(f.y2_ticks.front(), -300.0);
  EXPECT_EQ(f.y2_ticks.back(), 300.0);
  // Each series fills the height on its own axis: cos 0 = 300 deg/s at the top, sin 90 = 1 deg too.
  const auto sine = points(elements(group(svg, "series-0"), "polyline")[0]);
  const auto cosine = points(elements(group(svg, "series-1"), "polyline")[0]);
  EXPECT_NEAR(sine[90].y(), f.top, kPx);
  EXPECT_NEAR(cosine[0].y(), f.top, kPx);
  EXPECT_NEAR(cosine[180].y(), f.bottom, kPx);
  // The right axis's labels and the legend do not overlap.
  const Rect r = frame_of(svg);
  EXPECT_NEAR(r.right, f.right, kPx);
}

TEST(DrawPlot, ThreeUnitsNamedInTheLegend) {
  PlotSpec spec = trig_spec("deg", "deg/s");
  spec.series.push_back({"tan", "1", spec.series[0].y});
  const std::string svg = svg_of(spec);
  EXPECT_THAT(texts(group(svg, "legend")), ElementsAre("sin [deg]", "cos [deg/s]", "tan [1]"));
  EXPECT_THAT(texts(group(svg, "axes")), testing::Contains("[deg], [deg/s], [1]"));
}

TEST(DrawPlot, APathGetsEqualScalesRoundEndsAMarginAndItsName) {
  // An ellipse 200 wide and 50 high about (30, 70): equal scales keep it 4 times as wide.
  PlotSpec spec;
  spec.x_name = "P.x";
  spec.x_unit = "mm";
  PlotSeries y{"P.y", "mm", {}};
  for (int i = 0; i <= 360; ++i) {
    spec.x.push_back(30 + 100 * std::cos(i * std::numbers::pi / 180));
    y.y.push_back(70 + 25 * std::sin(i * std::numbers::pi / 180));
  }
  spec.series = {y};
  ASSERT_TRUE(plots_a_path(spec));
  PlotFrame f;
  const std::string svg = svg_of(spec, &f);
  const double x_scale = (f.right - f.left) / (f.x_hi - f.x_lo), y_scale = (f.bottom - f.top) / (f.y_hi - f.y_lo);
  EXPECT_NEAR(x_scale, y_scale, 1e-9 * x_scale);
  // Both ends of both axes on round ticks, with room between the data and the frame.
  EXPECT_EQ(f.x_lo, f.x_ticks.front());
  EXPECT_EQ(f.x_hi, f.x_ticks.back());
  EXPECT_EQ(f.y_lo, f.y_ticks.front());
  const double step = f.x_ticks[1] - f.x_ticks[0];
  EXPECT_NEAR(std::remainder(f.x_lo, step), 0.0, 1e-9);
  EXPECT_LT(f.x_lo, -70.0 - 1.0);
  EXPECT_GT(f.x_hi, 130.0 + 1.0);
  EXPECT_LT(f.y_lo, 45.0 - 1.0);
  EXPECT_GT(f.y_hi, 95.0 + 1.0);
  const auto drawn = points(elements(group(svg, "series-0"), "polyline")[0]);
  double w = 0, h = 0;
  for (const auto& a : drawn)
    for (const auto& b : drawn) w = std::max(w, std::abs(a.x() - b.x())), h = std::max(h, std::abs(a.y() - b.y()));
  EXPECT_NEAR(w / h, 4.0, 0.01);
  EXPECT_THAT(texts(group(svg, "legend")), ElementsAre("path of P"));
  // Forced off, the same data spans the plot area.
  spec.equal_scales = false;
  EXPECT_FALSE(plots_a_path(spec));
  PlotFrame g;
  svg_of(spec, &g);
  EXPECT_EQ(g.x_lo, -70.0);
}

TEST(DrawPlot, OneSeriesNamedOnTheYAxis) {
  PlotSpec spec = trig_spec();
  spec.series.resize(1);
  EXPECT_THAT(texts(group(svg_of(spec), "axes")), testing::Contains("sin [m]"));
}

TEST(DrawPlot, ManySeriesAllDistinct) {
  PlotSpec spec = trig_spec();
  for (int k = 2; k < 10; ++k) {
    PlotSeries s{std::string("s").append(std::to_string(k)), "m", {}};
    for (double x : spec.x) s.y.push_back(std::sin(k * x * std::numbers::pi / 180));
    spec.series.push_back(s);
  }
  const std::string svg = svg_of(spec);
  const auto swatches = elements(group(svg, "legend"), "polyline");
  ASSERT_EQ(swatches.size(), 10u);
  std::set<std::string> looks;
  for (const auto& s : swatches) looks.insert(attribute(s, "stroke") + attribute(s, "stroke-dasharray"));
  EXPECT_EQ(looks.size(), 10u);
  for (int s = 0; s < 10; ++s) EXPECT_EQ(elements(group(svg, "series-" + std::to_string(s)), "polyline").size(), 1u);
}

TEST(DrawPlot, NonFiniteValuesLeaveGaps) {
  PlotSpec spec = trig_spec();
  spec.series.resize(1);
  auto& y = spec.series[0].y;
  y[100] = std::numeric_limits<double>::quiet_NaN();
  y[200] = std::numeric_limits<double>::infinity();
  y[202] = -std::numeric_limits<double>::infinity();  // leaves 201 alone: a dot
  spec.x[300] = std::numeric_limits<double>::quiet_NaN();
  PlotFrame f;
  const std::string svg = svg_of(spec, &f);
  const std::string series = group(svg, "series-0");
  const auto lines = elements(series, "polyline");
  ASSERT_EQ(lines.size(), 4u);
  EXPECT_EQ(points(lines[0]).size(), 100u);  // 0..99
  EXPECT_EQ(points(lines[1]).size(), 99u);   // 101..199
  EXPECT_EQ(points(lines[2]).size(), 97u);   // 203..299
  EXPECT_EQ(points(lines[3]).size(), 60u);   // 301..360
  const auto dots = elements(series, "circle");
  ASSERT_EQ(dots.size(), 1u);
  EXPECT_NEAR(std::stod(attribute(dots[0], "cx")), f.to_pixels(201, 0).x(), kPx);
  EXPECT_NEAR(std::stod(attribute(dots[0], "cy")), f.to_pixels(0, std::sin(201 * std::numbers::pi / 180)).y(), kPx);
  // The range ignores what cannot be drawn.
  EXPECT_EQ(f.y_lo, -1.0);
  EXPECT_EQ(f.y_hi, 1.0);
  EXPECT_THAT(svg, Not(HasSubstr("nan")));
  EXPECT_THAT(svg, Not(HasSubstr("inf")));
}

TEST(DrawPlot, ConstantSeriesGetsARangeAroundIt) {
  PlotSpec spec = trig_spec();
  spec.series = {PlotSeries{"O2.x", "mm", std::vector<double>(spec.x.size(), 200.0)}};
  PlotFrame f;
  const std::string svg = svg_of(spec, &f);
  EXPECT_LT(f.y_lo, 200);
  EXPECT_GT(f.y_hi, 200);
  const auto p = points(elements(group(svg, "series-0"), "polyline")[0]);
  EXPECT_NEAR(p.front().y(), f.to_pixels(0, 200).y(), kPx);
  EXPECT_GT(p.front().y(), f.top + 10);
  EXPECT_LT(p.front().y(), f.bottom - 10);
  EXPECT_NEAR(p.front().y(), p.back().y(), kPx);

  spec.series[0].y.assign(spec.x.size(), 0.0);
  f = {};
  svg_of(spec, &f);
  EXPECT_EQ(f.y_lo, -1.0);
  EXPECT_EQ(f.y_hi, 1.0);
}

TEST(DrawPlot, LinesCutAtAFixedRange) {
  PlotSpec spec = trig_spec();
  spec.series.resize(1);
  spec.y_lo = -0.5;
  spec.y_hi = 0.5;
  PlotFrame f;
  const std::string svg = svg_of(spec, &f);
  EXPECT_EQ(f.y_lo, -0.5);
  EXPECT_EQ(f.y_hi, 0.5);
  // sin leaves -0.5..0.5 over 30..150 and 210..330 degrees: three pieces remain.
  const auto lines = elements(group(svg, "series-0"), "polyline");
  ASSERT_EQ(lines.size(), 3u);
  for (const auto& line : lines)
    for (const auto& p : points(line)) {
      EXPECT_GE(p.x(), f.left - kPx);
      EXPECT_LE(p.x(), f.right + kPx);
      EXPECT_GE(p.y(), f.top - kPx);
      EXPECT_LE(p.y(), f.bottom + kPx);
    }
  const auto first = points(lines[0]), second = points(lines[1]);
  EXPECT_NEAR(first.back().y(), f.top, kPx);  // cut at the top edge
  EXPECT_NEAR(first.back().x(), f.to_pixels(30, 0).x(), 2.0);
  EXPECT_NEAR(second.front().y(), f.top, kPx);
  EXPECT_NEAR(second.back().y(), f.bottom, kPx);

  spec.y_hi.reset();
  EXPECT_THROW(svg_of(spec), nbar::Error);
  spec.y_hi = -1.0;
  EXPECT_THROW(svg_of(spec), nbar::Error);
}

TEST(DrawPlot, SeriesOfTheWrongLengthRejected) {
  PlotSpec spec = trig_spec();
  spec.series[1].y.pop_back();
  SvgCanvas canvas(spec.width, spec.height);
  EXPECT_THROW(draw_plot(canvas, spec), nbar::Error);
}

TEST(DrawPlot, OneSampleIsADot) {
  PlotSpec spec;
  spec.x_name = "t";
  spec.x = {0.5};
  spec.series = {PlotSeries{"a", "m", {3.0}}};
  PlotFrame f;
  const std::string svg = svg_of(spec, &f);
  EXPECT_LT(f.x_lo, 0.5);
  EXPECT_GT(f.x_hi, 0.5);
  EXPECT_EQ(elements(group(svg, "series-0"), "circle").size(), 1u);
  EXPECT_TRUE(elements(group(svg, "series-0"), "polyline").empty());
}

TEST(DrawPlot, NoSeriesDrawsTheAxesAlone) {
  PlotSpec spec = trig_spec();
  spec.series.clear();
  const std::string svg = svg_of(spec);
  EXPECT_EQ(elements(group(svg, "axes"), "polygon").size(), 1u);
  EXPECT_THAT(svg, Not(HasSubstr("series-0")));
  EXPECT_THAT(svg, Not(HasSubstr("legend")));
}

TEST(DrawPlot, LongLegendGoesBelowOnANarrowPicture) {
  PlotSpec spec = trig_spec("N", "N");
  spec.series[0].name = "A.crank>coupler.along-a-very-long-column-name";
  spec.width = 420;
  spec.height = 360;
  PlotFrame f;
  const std::string svg = svg_of(spec, &f);
  const auto box = points(elements(group(svg, "legend"), "polygon")[0]);
  EXPECT_GT(box[0].y(), f.bottom);  // below the plot area
  EXPECT_GT(f.right - f.left, 300);
  for (const auto& p : box) {
    EXPECT_LE(p.y(), spec.height);
    EXPECT_GE(p.x(), 0);
  }
}

TEST(DrawPlot, RastersToo) {
  PlotSpec spec = trig_spec();
  spec.series = {PlotSeries{"flat", "m", std::vector<double>(spec.x.size(), 0.0)}};
  nbar::render::ImageCanvas canvas(spec.width, spec.height);
  const PlotFrame f = draw_plot(canvas, spec);
  // The line at y = 0 across the middle, in the first colour (a blue).
  const Eigen::Vector2d at = f.to_pixels(180, 0);
  bool blue = false;
  for (int dy = -1; dy <= 1; ++dy) {
    const nbar::render::Colour c = canvas.pixel(static_cast<int>(at.x()), static_cast<int>(std::floor(at.y())) + dy);
    blue = blue || (c.b > 120 && c.r < 100);
  }
  EXPECT_TRUE(blue);
}

// ---- nbar plot.

struct PlotRun {
  int code = -1;
  std::string err;
};

PlotRun nbar_plot(const std::string& args) {
  static int count = 0;
  const fs::path err = fs::temp_directory_path() /
                       ("nbar_plot_test_" + std::to_string(::getpid()) + "_" + std::to_string(count++) + ".err");
  std::string command = NBAR_CLI_PATH;
  command += " plot ";
  command += args;
  command += " >/dev/null 2>";
  command += err.string();
  const int status = std::system(command.c_str());
  PlotRun run;
  run.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream in(err);
  std::stringstream ss;
  ss << in.rdbuf();
  run.err = ss.str();
  fs::remove(err);
  return run;
}

std::string read(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

class PlotCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("nbar_plot_cli_" + std::to_string(::getpid()) + "_" + std::to_string(n_++));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string out(const std::string& name) const { return (dir_ / name).string(); }
  static std::string example(const std::string& name) { return std::string(NBAR_EXAMPLES_DIR) + "/" + name; }

  fs::path dir_;
  static inline int n_ = 0;
};

TEST_F(PlotCli, TwoColumnsAsSvg) {
  const PlotRun run =
      nbar_plot(example("fourbar-crank-rocker.yaml") + " --y rocker.angle,rocker.omega -o " + out("x.svg"));
  ASSERT_EQ(run.code, 0) << run.err;
  const std::string svg = read(out("x.svg"));
  EXPECT_EQ(elements(group(svg, "series-0"), "polyline").size(), 1u);
  EXPECT_EQ(elements(group(svg, "series-1"), "polyline").size(), 1u);
  EXPECT_THAT(svg, Not(HasSubstr("series-2")));
  EXPECT_THAT(texts(group(svg, "legend")), ElementsAre("rocker.angle [deg]", "rocker.omega [deg/s] (right)"));
  EXPECT_THAT(texts(group(svg, "axes")), testing::Contains("crank [deg]"));         // the driver by default
  EXPECT_EQ(points(elements(group(svg, "series-0"), "polyline")[0]).size(), 361u);  // the model's steps
}

TEST_F(PlotCli, GlobsStepsAndPng) {
  const PlotRun run = nbar_plot(example("fourbar-crank-rocker.yaml") + " --y 'rocker.*' --steps 50 -o " + out("x.png"));
  ASSERT_EQ(run.code, 0) << run.err;
  EXPECT_EQ(read(out("x.png")).substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
}

TEST_F(PlotCli, OtherXAndTitle) {
  const PlotRun run =
      nbar_plot(example("fourbar-crank-rocker.yaml") + " --x P.x --y P.y --title 'Coupler curve' -o " + out("c.svg"));
  ASSERT_EQ(run.code, 0) << run.err;
  const auto labels = texts(group(read(out("c.svg")), "axes"));
  EXPECT_THAT(labels, testing::Contains("P.x [mm]"));
  EXPECT_THAT(labels, testing::Contains("P.y [mm]"));
  EXPECT_THAT(labels, testing::Contains("Coupler curve"));
}

TEST_F(PlotCli, DynamicsAndHigherOrdersWhenAsked) {
  PlotRun run = nbar_plot(example("compressor-myszka-kinetics.yaml") + " --y '*.torque' -o " + out("t.svg"));
  ASSERT_EQ(run.code, 0) << run.err;
  EXPECT_THAT(texts(group(read(out("t.svg")), "legend")), ElementsAre("crank.torque"));
  run = nbar_plot(example("fourbar-crank-rocker.yaml") + " --y rocker.jerk,rocker.d5 -o " + out("j.svg"));
  ASSERT_EQ(run.code, 0) << run.err;
  EXPECT_THAT(read(out("j.svg")), HasSubstr("series-1"));
  // An order given outright is kept.
  run = nbar_plot(example("fourbar-crank-rocker.yaml") + " --order 2 --y rocker.jerk -o " + out("k.svg"));
  EXPECT_EQ(run.code, 2);
}

TEST_F(PlotCli, UnknownColumnListsTheColumns) {
  PlotRun run = nbar_plot(example("fourbar-crank-rocker.yaml") + " --y rocker.angle,nope -o " + out("x.svg"));
  EXPECT_EQ(run.code, 2);
  EXPECT_THAT(run.err, HasSubstr("'nope'"));
  EXPECT_THAT(run.err, HasSubstr("rocker.omega"));
  EXPECT_THAT(run.err, HasSubstr("crank.torque"));  // the dynamics columns too
  EXPECT_FALSE(fs::exists(out("x.svg")));
  run = nbar_plot(example("fourbar-crank-rocker.yaml") + " --x nope --y rocker.angle -o " + out("x.svg"));
  EXPECT_EQ(run.code, 2);
  run = nbar_plot(example("fourbar-crank-rocker.yaml") + " --x 'rocker.*' --y rocker.angle -o " + out("x.svg"));
  EXPECT_EQ(run.code, 2);
  EXPECT_THAT(run.err, HasSubstr("name one"));
}

TEST_F(PlotCli, FormatFromTheExtension) {
  for (const char* name : {"x.pdf", "x", "x.svg.txt"}) {
    const PlotRun run = nbar_plot(example("fourbar-crank-rocker.yaml") + " --y rocker.angle -o " + out(name));
    EXPECT_EQ(run.code, 2) << name;
    EXPECT_THAT(run.err, HasSubstr(".svg or .png")) << name;
    EXPECT_FALSE(fs::exists(out(name))) << name;
  }
  EXPECT_EQ(nbar_plot(example("fourbar-crank-rocker.yaml") + " --y rocker.angle -o " + out("X.SVG")).code, 0);
}

TEST_F(PlotCli, ExitCodesLikeSolve) {
  std::ofstream(out("bad.yaml")) << "points: [\n";
  EXPECT_EQ(nbar_plot(out("bad.yaml") + " --y t -o " + out("x.svg")).code, 1);
  EXPECT_EQ(nbar_plot(example("fourbar-crank-rocker.yaml") + " -o " + out("x.svg")).code, 2);  // no --y
  EXPECT_EQ(nbar_plot(example("fourbar-crank-rocker.yaml") + " --y t --y-range 1,0 -o " + out("x.svg")).code, 2);
  EXPECT_EQ(nbar_plot(example("fourbar-crank-rocker.yaml") + " --y t -o " + out("no/such/dir/x.svg")).code, 2);
  EXPECT_EQ(nbar_plot("--help").code, 0);
}

}  // namespace
