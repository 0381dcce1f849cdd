// Line plots of result columns against one another: axes with round-numbered ticks, a light
// grid, one line per series in colours told apart by colour-blind readers, and a legend.
#pragma once

#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

#include "nbar/kinematics/table.hpp"
#include "nbar/render/canvas.hpp"

namespace nbar::render {

struct PlotSeries {
  std::string name, unit;
  std::vector<double> y;  // one value per x; NaN or infinity leaves a gap in the line
};

struct PlotSpec {
  std::string title;  // drawn at the top when not empty
  std::string x_name, x_unit;
  std::vector<double> x;
  std::vector<PlotSeries> series;
  // A fixed y range instead of one covering the data (both or neither); lines leaving it are
  // cut at its edges.
  std::optional<double> y_lo, y_hi;
  int width = 900, height = 520;  // px: the size of the canvas to make (draw_plot uses the canvas's own)
  // Equal scales on both axes, for a path in the plane. By default (nullopt) when x and every
  // series are coordinates (names ending in ".x" or ".y") in one unit.
  std::optional<bool> equal_scales;
};

// Whether draw_plot gives `spec` equal scales (its own choice, or the default above).
bool plots_a_path(const PlotSpec& spec);

// The x data and the series of `spec` from result columns: the first column of `x_column`
// along x, one series per column of `y_columns` (both tables with the same rows).
void set_plot_data(PlotSpec& spec, const ResultTable& x_column, const ResultTable& y_columns);

// Where the data went: the plot area in pixels and the data ranges its edges stand for.
struct PlotFrame {
  double left = 0, top = 0, right = 0, bottom = 0;  // px
  double x_lo = 0, x_hi = 1, y_lo = 0, y_hi = 1;    // data at the left, right, bottom and top edges
  std::vector<double> x_ticks, y_ticks;
  // A second y axis on the right, for the series of a second unit (series_on_right).
  bool right_axis = false;
  double y2_lo = 0, y2_hi = 1;
  std::vector<double> y2_ticks;
  std::vector<bool> series_on_right;  // one per series
  Eigen::Vector2d to_pixels(double x, double y) const;
  Eigen::Vector2d to_pixels_right(double x, double y) const;  // y on the right axis
};

// Draws the plot over the whole canvas. The x axis spans the data exactly; the y axis runs from
// a tick below the data to a tick above it. Series whose units all agree share a y label with
// that unit; otherwise each legend entry says "name [unit]", and with exactly two units (and no
// fixed y range) the series of the second unit get their own y axis on the right. A path
// (plots_a_path) gets equal scales, both axes from a round tick to a round tick around the
// data with a margin, and the legend names the path ("path of P" for P.y against P.x). A series that never changes is
// shown in a range around its value. Groups: "grid", "series-<i>" (one per series, in order),
// "axes" (frame, ticks, labels, title), "legend".
// Throws Error(ErrorKind::BadInput) when a series has a different number of values than x, or for a
// fixed y range that is not finite, increasing and given at both ends.
PlotFrame draw_plot(Canvas& canvas, const PlotSpec& spec);

// Ticks at multiples of a step of 1, 2 or 5 times a power of ten, the first at or below `lo`
// and the last at or above `hi`: the smallest such step giving at most `target` intervals.
// An empty or nearly empty range (narrower than 1e-10 of its size) is widened to 10% of its
// value either side (to -1..1 about zero). Throws Error(ErrorKind::BadInput) for non-finite or
// overly large bounds (beyond 1e300) and for a target outside 1..1000.
std::vector<double> nice_ticks(double lo, double hi, int target = 6);

// Labels for evenly spaced ticks, all in one style: fixed with as many decimals as the step
// needs ("0.0", "0.5", "-40", "1001000", "1.0000000002"), or short exponents ("2e6", "1.5e6",
// "4e11", "5e-10") for millions with at most three significant digits, billions and up, and
// ticks all below 1e-3.
std::vector<std::string> format_ticks(const std::vector<double>& ticks);

}  // namespace nbar::render
