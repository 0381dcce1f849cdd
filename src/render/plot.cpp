#include "nbar/render/plot.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <utility>

#include "nbar/model/diagnostics.hpp"

namespace nbar::render {

namespace {

using Vec2 = Eigen::Vector2d;

constexpr double kLargest = 1e300;  // larger magnitudes are treated like infinities

// Okabe & Ito's palette, which readers with any common colour-vision deficiency can tell
// apart (its yellow, too pale on white, left out). After seven series the colours repeat with
// dashes.
constexpr std::array<std::uint32_t, 7> kPalette = {0x0072B2, 0xD55E00, 0x009E73, 0xCC79A7,
                                                   0xE69F00, 0x56B4E9, 0x000000};

const Colour kPlotInk = Colour::rgb(0x222222);
const Colour kFrame = Colour::rgb(0x444444);
const Colour kGrid = Colour::rgb(0xe4e4e4);
const Colour kZeroLine = Colour::rgb(0xb0b0b0);

constexpr double kTickFont = 12, kLabelFont = 13, kTitleFont = 16, kLegendFont = 12;
constexpr double kTickLength = 5;

// An estimate of the width of sans-serif text (digits are 0.56 em, letters average less).
double text_width(const std::string& text, double size) { return 0.6 * size * static_cast<double>(text.size()); }

double pow10(int exponent) { return std::pow(10.0, exponent); }

bool usable(double v) { return std::isfinite(v) && std::abs(v) <= kLargest; }

Stroke series_stroke(std::size_t i) {
  Stroke s;
  s.colour = Colour::rgb(kPalette[i % kPalette.size()]);
  s.width = 1.8;
  switch ((i / kPalette.size()) % 4) {
    case 1: s.dash = {7, 4}; break;
    case 2: s.dash = {2, 3}; break;
    case 3: s.dash = {9, 3, 2, 3}; break;
    default: break;
  }
  return s;
}

// The exponent of the last significant digit of a tick step: 0.25 -> -2, 200 -> 2.
int last_digit(double step) {
  const int first = static_cast<int>(std::floor(std::log10(step) + 1e-9));
  for (int d = first; d > first - 17; --d) {
    const double scaled = d < 0 ? step * pow10(-d) : step / pow10(d);
    if (std::abs(scaled - std::round(scaled)) <= 1e-6 * scaled) return d;
  }
  return first - 3;
}

std::string strip_exponent(const std::string& s) {
  // "1.50e+06" -> "1.5e6", "2e-04" -> "2e-4"
  const std::size_t e = s.find('e');
  if (e == std::string::npos) return s;
  std::string mantissa = s.substr(0, e);
  if (mantissa.find('.') != std::string::npos) {
    while (mantissa.back() == '0') mantissa.pop_back();
    if (mantissa.back() == '.') mantissa.pop_back();
  }
  std::string exponent = s.substr(e + 1);
  std::string sign;
  if (!exponent.empty() && (exponent[0] == '+' || exponent[0] == '-')) {
    if (exponent[0] == '-') sign = "-";
    exponent.erase(0, 1);
  }
  while (exponent.size() > 1 && exponent[0] == '0') exponent.erase(0, 1);
  std::string out = mantissa;
  out += 'e';
  out += sign;
  out += exponent;
  return out;
}

// Liang-Barsky: the part of a-b inside the rectangle, as fractions t0 <= t1 along it.
bool clip_segment(const Vec2& a, const Vec2& b, const PlotFrame& f, double& t0, double& t1) {
  t0 = 0.0;
  t1 = 1.0;
  const Vec2 d = b - a;
  const std::array<double, 4> p = {-d.x(), d.x(), -d.y(), d.y()};
  const std::array<double, 4> q = {a.x() - f.left, f.right - a.x(), a.y() - f.top, f.bottom - a.y()};
  for (int i = 0; i < 4; ++i) {
    if (p[i] == 0.0) {
      if (q[i] < 0.0) return false;
      continue;
    }
    const double r = q[i] / p[i];
    if (p[i] < 0.0)
      t0 = std::max(t0, r);
    else
      t1 = std::min(t1, r);
    if (t0 > t1) return false;
  }
  return true;
}

bool inside(const Vec2& p, const PlotFrame& f) {
  return p.x() >= f.left && p.x() <= f.right && p.y() >= f.top && p.y() <= f.bottom;
}

// The pieces of a series' line inside the plot area, and the samples with no finite neighbour
// (drawn as dots, since a line through one point is invisible).
struct Pieces {
  std::vector<std::vector<Vec2>> lines;
  std::vector<Vec2> dots;
};

Pieces clip_series(const std::vector<double>& x, const std::vector<double>& y, const PlotFrame& f) {
  Pieces out;
  const std::size_t n = x.size();
  auto valid = [&](std::size_t i) { return usable(x[i]) && usable(y[i]); };
  std::vector<Vec2> line;
  auto flush = [&] {
    if (line.size() >= 2) out.lines.push_back(std::move(line));
    line.clear();
  };
  for (std::size_t i = 0; i < n; ++i) {
    if (!valid(i)) {
      flush();
      continue;
    }
    const Vec2 a = f.to_pixels(x[i], y[i]);
    const bool next = i + 1 < n && valid(i + 1);
    if (!next) {
      const bool previous = i > 0 && valid(i - 1);
      if (!previous && inside(a, f)) out.dots.push_back(a);
      flush();
      continue;
    }
    const Vec2 b = f.to_pixels(x[i + 1], y[i + 1]);
    double t0 = 0, t1 = 1;
    if (!clip_segment(a, b, f, t0, t1)) {
      flush();
      continue;
    }
    const Vec2 from = a + t0 * (b - a), to = a + t1 * (b - a);
    if (line.empty() || t0 > 0.0) {
      flush();
      line.push_back(from);
    }
    line.push_back(to);
    if (t1 < 1.0) flush();
  }
  flush();
  return out;
}

std::string with_unit(const std::string& name, const std::string& unit) {
  if (unit.empty()) return name;
  std::string s = name;
  if (!s.empty()) s += ' ';
  s += '[';
  s += unit;
  s += ']';
  return s;
}

// Ticks of `lo`..`hi` lying inside it (the x axis spans its data exactly).
std::vector<double> inner_ticks(double lo, double hi, int target) {
  const double tol = 1e-9 * (hi - lo);
  std::vector<double> ticks;
  for (double t : nice_ticks(lo, hi, target))
    if (t >= lo - tol && t <= hi + tol) ticks.push_back(t);
  return ticks;
}

double widest(const std::vector<std::string>& texts, double size) {
  double w = 0;
  for (const std::string& t : texts) w = std::max(w, text_width(t, size));
  return w;
}

}  // namespace

Vec2 PlotFrame::to_pixels(double x, double y) const {
  const double u = x_hi > x_lo ? (x - x_lo) / (x_hi - x_lo) : 0.5;
  const double v = y_hi > y_lo ? (y - y_lo) / (y_hi - y_lo) : 0.5;
  return {left + u * (right - left), bottom - v * (bottom - top)};
}

Vec2 PlotFrame::to_pixels_right(double x, double y) const {
  PlotFrame right = *this;
  right.y_lo = y2_lo;
  right.y_hi = y2_hi;
  return right.to_pixels(x, y);
}

bool plots_a_path(const PlotSpec& spec) {
  if (spec.equal_scales) return *spec.equal_scales;
  auto coordinate = [](const std::string& name) {
    return name.size() > 2 && (name.ends_with(".x") || name.ends_with(".y"));
  };
  if (spec.series.empty() || spec.x_unit.empty() || !coordinate(spec.x_name)) return false;
  return std::all_of(spec.series.begin(), spec.series.end(),
                     [&](const PlotSeries& s) { return s.unit == spec.x_unit && coordinate(s.name); });
}

std::vector<double> nice_ticks(double lo, double hi, int target) {
  if (!std::isfinite(lo) || !std::isfinite(hi)) throw Error(ErrorKind::BadInput, "nice_ticks: the range is not finite");
  if (std::abs(lo) > kLargest || std::abs(hi) > kLargest)
    throw Error(ErrorKind::BadInput, "nice_ticks: the range is too large (beyond 1e300)");
  if (target < 1 || target > 1000)
    throw Error(ErrorKind::BadInput, "nice_ticks: the target must be 1 to 1000 intervals");
  if (lo > hi) std::swap(lo, hi);
  const double size = std::max(std::abs(lo), std::abs(hi));
  if (hi - lo <= 1e-10 * size || hi - lo < 1e-290) {
    const double centre = 0.5 * (lo + hi);
    const double half = std::abs(centre) < 1e-290 ? 1.0 : 0.1 * std::abs(centre);
    lo = centre - half;
    hi = centre + half;
  }
  const int first_exponent = static_cast<int>(std::floor(std::log10((hi - lo) / target))) - 1;
  // Within a few ulps of a tick counts as on it, so 1 / 0.2e-9 still starts at 1.
  auto tolerance = [](double q) { return 1e-9 + 1e-14 * std::abs(q); };
  // A step larger than the range gives at most two intervals, so the search ends; only a
  // target of one interval can be impossible (a range about zero), and then two are used.
  for (int allowed = target;; ++allowed) {
    for (int exponent = first_exponent; exponent <= first_exponent + 8; ++exponent) {
      for (int mantissa : {1, 2, 5}) {
        const double step = mantissa * pow10(exponent);
        const double q_lo = lo / step, q_hi = hi / step;
        const double k_lo = std::floor(q_lo + tolerance(q_lo));
        double k_hi = std::ceil(q_hi - tolerance(q_hi));
        if (k_hi <= k_lo) k_hi = k_lo + 1;
        if (k_hi - k_lo > allowed) continue;
        std::vector<double> ticks;
        for (double k = k_lo; k <= k_hi; k += 1.0) {
          const double units = k * mantissa;  // an integer, exact
          ticks.push_back(exponent < 0 ? units / pow10(-exponent) : units * pow10(exponent));
        }
        return ticks;
      }
    }
  }
}

std::vector<std::string> format_ticks(const std::vector<double>& ticks) {
  std::vector<std::string> labels;
  if (ticks.empty()) return labels;
  double largest = 0;
  for (double t : ticks) largest = std::max(largest, std::abs(t));
  double step = 0;
  for (std::size_t i = 1; i < ticks.size(); ++i) {
    const double d = std::abs(ticks[i] - ticks[i - 1]);
    if (d > 0) step = step > 0 ? std::min(step, d) : d;
  }
  if (step == 0) step = largest > 0 ? largest : 1.0;
  const int digit = last_digit(step);
  // Exponents for millions with few digits that change (2e6, 1.5e6, but 1001000), for
  // billions and up, and for thousandths and below.
  const int largest_magnitude = largest > 0 ? static_cast<int>(std::floor(std::log10(largest * (1 + 1e-12)))) : 0;
  const bool exponents =
      (largest >= 1e6 && (largest_magnitude - digit <= 2 || largest_magnitude >= 9)) || (largest > 0 && largest < 1e-3);
  char buf[64];
  for (double t : ticks) {
    if (!std::isfinite(t)) {
      labels.push_back(std::isnan(t) ? "nan" : t > 0 ? "inf" : "-inf");
      continue;
    }
    const bool zero = std::abs(t) < 1e-6 * step;
    if (exponents) {
      if (zero) {
        labels.push_back("0");
        continue;
      }
      const int magnitude = static_cast<int>(std::floor(std::log10(std::abs(t) * (1 + 1e-12))));
      std::snprintf(buf, sizeof buf, "%.*e", std::max(0, magnitude - digit), t);
      labels.push_back(strip_exponent(buf));
    } else {
      std::snprintf(buf, sizeof buf, "%.*f", std::max(0, -digit), zero ? 0.0 : t);
      labels.push_back(buf);
    }
  }
  return labels;
}

namespace {

constexpr double kPad = 12, kSwatch = 24, kEntryHeight = 18;

void check_spec(const PlotSpec& spec) {
  for (const PlotSeries& s : spec.series)
    if (s.y.size() != spec.x.size())
      throw Error(ErrorKind::BadInput, "plot: series '" + s.name + "' has " + std::to_string(s.y.size()) +
                                           " values for " + std::to_string(spec.x.size()) + " values of " +
                                           spec.x_name);
  if (spec.y_lo.has_value() != spec.y_hi.has_value())
    throw Error(ErrorKind::BadInput, "plot: a fixed y range needs both ends");
  if (spec.y_lo && !(usable(*spec.y_lo) && usable(*spec.y_hi) && *spec.y_lo < *spec.y_hi))
    throw Error(ErrorKind::BadInput, "plot: the fixed y range must be finite and increasing");
}

// Data ranges over the samples that can be drawn.
struct DataRange {
  double x_lo = INFINITY, x_hi = -INFINITY, y_lo = INFINITY, y_hi = -INFINITY;
};
// Over the series `on_right` says (all when it is empty).
DataRange data_range(const PlotSpec& spec, const std::vector<bool>& on_right = {}, bool right = false) {
  DataRange r;
  for (std::size_t i = 0; i < spec.x.size(); ++i) {
    if (!usable(spec.x[i])) continue;
    bool any = spec.series.empty();
    for (std::size_t k = 0; k < spec.series.size(); ++k) {
      const PlotSeries& s = spec.series[k];
      if (!on_right.empty() && on_right[k] != right) continue;
      if (!usable(s.y[i])) continue;
      any = true;
      r.y_lo = std::min(r.y_lo, s.y[i]);
      r.y_hi = std::max(r.y_hi, s.y[i]);
    }
    if (!any) continue;
    r.x_lo = std::min(r.x_lo, spec.x[i]);
    r.x_hi = std::max(r.x_hi, spec.x[i]);
  }
  if (r.x_lo > r.x_hi) r.x_lo = 0, r.x_hi = 1;
  if (r.y_lo > r.y_hi) r.y_lo = 0, r.y_hi = 1;
  return r;
}

// The axis labels and legend entries: one unit for all, or each series' own in the legend.
struct Labels {
  std::string x, y, y2;
  std::vector<std::string> entries;
};

// The series of a second unit, when there are exactly two units and no fixed range.
std::vector<bool> right_series(const PlotSpec& spec) {
  std::vector<std::string> units;
  for (const PlotSeries& s : spec.series)
    if (std::find(units.begin(), units.end(), s.unit) == units.end()) units.push_back(s.unit);
  std::vector<bool> right(spec.series.size(), false);
  if (units.size() != 2 || spec.y_lo || plots_a_path(spec)) return {};
  for (std::size_t k = 0; k < spec.series.size(); ++k) right[k] = spec.series[k].unit == units[1];
  return right;
}

// "path of P" for P.y against P.x, "Q.y against P.x" otherwise.
std::string path_name(const std::string& x, const std::string& y) {
  const std::string px = x.substr(0, x.size() - 2), py = y.substr(0, y.size() - 2);
  if (px == py && x.back() != y.back()) return "path of " + px;
  return y + " against " + x;
}

Labels labels_of(const PlotSpec& spec) {
  Labels l;
  const std::vector<bool> right = right_series(spec);
  if (!right.empty()) {
    for (std::size_t k = 0; k < spec.series.size(); ++k) {
      std::string& label = right[k] ? l.y2 : l.y;
      if (label.empty()) label = with_unit("", spec.series[k].unit);
      l.entries.push_back(with_unit(spec.series[k].name, spec.series[k].unit) + (right[k] ? " (right)" : ""));
    }
    l.x = with_unit(spec.x_name, spec.x_unit);
    return l;
  }
  if (plots_a_path(spec)) {
    l.y = spec.series.size() == 1 ? with_unit(spec.series[0].name, spec.series[0].unit)
                                  : with_unit("", spec.series[0].unit);
    for (const PlotSeries& s : spec.series) l.entries.push_back(path_name(spec.x_name, s.name));
    l.x = with_unit(spec.x_name, spec.x_unit);
    return l;
  }
  bool same_unit = true;
  for (const PlotSeries& s : spec.series) same_unit = same_unit && s.unit == spec.series.front().unit;
  if (spec.series.size() == 1) {
    l.y = with_unit(spec.series[0].name, spec.series[0].unit);
  } else if (same_unit && !spec.series.empty()) {
    l.y = with_unit("", spec.series[0].unit);
  } else {
    std::vector<std::string> units;
    for (const PlotSeries& s : spec.series)
      if (!s.unit.empty() && std::find(units.begin(), units.end(), s.unit) == units.end()) units.push_back(s.unit);
    for (std::size_t i = 0; i < units.size(); ++i) {
      if (i) l.y += ", ";
      l.y += with_unit("", units[i]);
    }
  }
  for (const PlotSeries& s : spec.series) l.entries.push_back(same_unit ? s.name : with_unit(s.name, s.unit));
  l.x = with_unit(spec.x_name, spec.x_unit);
  return l;
}

// Where the plot area and the legend go: title, y label above the plot area, legend to its
// right (or below it when the entries are long), x tick labels and x label below.
struct Layout {
  PlotFrame frame;
  bool legend_right = false;
  double legend_width = 0, legend_rows_height = 0;
  std::vector<std::pair<std::size_t, Vec2>> legend_places;  // entry, offset from the legend's top left
  std::vector<std::string> x_tick_labels, y_tick_labels, y2_tick_labels;
  double right_axis_room = 0;  // px right of the plot area taken by the right axis's labels
};

void place_legend(const Labels& labels, bool titled, double width, double height, Layout& layout) {
  PlotFrame& f = layout.frame;
  const auto& entries = labels.entries;
  layout.legend_width = 10 + kSwatch + 6 + widest(entries, kLegendFont) + 10;
  f.top = kPad + (titled ? kTitleFont + 10 : 0) + (labels.y.empty() ? 4 : kLabelFont + 16);
  layout.legend_right = !entries.empty() && layout.legend_width <= 0.32 * width &&
                        static_cast<double>(entries.size()) * kEntryHeight + 12 <= height - f.top - kPad;
  f.right = width - (layout.legend_right ? kPad + layout.legend_width + 14 : 2 * kPad);  // room for half an x label
  // Below the plot: a flow of entries in rows.
  if (!entries.empty() && !layout.legend_right) {
    double x = 10, row = 0;
    const double room = width - 2 * kPad - 20;
    for (std::size_t i = 0; i < entries.size(); ++i) {
      const double w = kSwatch + 6 + text_width(entries[i], kLegendFont) + 16;
      if (x > 10 && x + w > room) x = 10, row += 1;
      layout.legend_places.push_back({i, Vec2(x, 6 + row * kEntryHeight)});
      x += w;
    }
    layout.legend_rows_height = (row + 1) * kEntryHeight + 12;
  }
  f.bottom = height - kPad - (labels.x.empty() ? 0 : kLabelFont + 8) - (kTickFont + kTickLength + 8) -
             (layout.legend_rows_height > 0 ? layout.legend_rows_height + 8 : 0);
  f.bottom = std::max(f.bottom, f.top + 10);
}

// y ticks cover the data (or the fixed range); their labels decide the left margin.
void place_y_axis(const PlotSpec& spec, const DataRange& data, Layout& layout) {
  PlotFrame& f = layout.frame;
  const int y_target = std::clamp(static_cast<int>((f.bottom - f.top) / 40), 2, 12);
  if (spec.y_lo) {
    f.y_lo = *spec.y_lo;
    f.y_hi = *spec.y_hi;
    f.y_ticks = inner_ticks(f.y_lo, f.y_hi, y_target);
  } else {
    f.y_ticks = nice_ticks(data.y_lo, data.y_hi, y_target);
    f.y_lo = f.y_ticks.front();
    f.y_hi = f.y_ticks.back();
  }
  layout.y_tick_labels = format_ticks(f.y_ticks);
  f.left = kPad + widest(layout.y_tick_labels, kTickFont) + kTickLength + 6;
  if (f.right_axis) {
    const DataRange right = data_range(spec, f.series_on_right, true);
    f.y2_ticks = nice_ticks(right.y_lo, right.y_hi, y_target);
    f.y2_lo = f.y2_ticks.front();
    f.y2_hi = f.y2_ticks.back();
    layout.y2_tick_labels = format_ticks(f.y2_ticks);
    layout.right_axis_room = widest(layout.y2_tick_labels, kTickFont) + kTickLength + 6;
    f.right -= layout.right_axis_room;
  }
  f.right = std::max(f.right, f.left + 10);
}

// A path in the plane: both axes from a round tick to a round tick around the data with a
// margin of 4%, and one scale for both, so that a circle stays round. The plot area shrinks
// along the axis that has room to spare, and stays centred in the room it had.
void place_path_axes(const DataRange& data, Layout& layout) {
  PlotFrame& f = layout.frame;
  const double span = std::max({data.x_hi - data.x_lo, data.y_hi - data.y_lo, 1e-300});
  const double margin = 0.04 * span;
  const double room_w = f.right - f.left, room_h = f.bottom - f.top;
  const int target = std::clamp(static_cast<int>(std::min(room_w, room_h) / 50), 2, 12);
  f.x_ticks = nice_ticks(data.x_lo - margin, data.x_hi + margin, target);
  f.y_ticks = nice_ticks(data.y_lo - margin, data.y_hi + margin, target);
  // One step for both axes: the larger.
  const double step = std::max(f.x_ticks[1] - f.x_ticks[0], f.y_ticks[1] - f.y_ticks[0]);
  auto on_step = [&](double lo, double hi) {
    std::vector<double> ticks;
    for (double k = std::floor(lo / step + 1e-9); k <= std::ceil(hi / step - 1e-9); k += 1.0) ticks.push_back(k * step);
    return ticks;
  };
  f.x_ticks = on_step(data.x_lo - margin, data.x_hi + margin);
  f.y_ticks = on_step(data.y_lo - margin, data.y_hi + margin);
  f.x_lo = f.x_ticks.front(), f.x_hi = f.x_ticks.back();
  f.y_lo = f.y_ticks.front(), f.y_hi = f.y_ticks.back();
  layout.x_tick_labels = format_ticks(f.x_ticks);
  layout.y_tick_labels = format_ticks(f.y_ticks);
  const double scale = std::min(room_w / (f.x_hi - f.x_lo), room_h / (f.y_hi - f.y_lo));
  const double w = scale * (f.x_hi - f.x_lo), h = scale * (f.y_hi - f.y_lo);
  f.left += 0.5 * (room_w - w);
  f.right = f.left + w;
  f.bottom = f.top + h;
}

// x spans the data exactly (a single value gets a range around it); as many ticks as fit.
void place_x_axis(DataRange data, Layout& layout) {
  PlotFrame& f = layout.frame;
  if (data.x_hi - data.x_lo <= 1e-10 * std::max(std::abs(data.x_lo), std::abs(data.x_hi)) ||
      data.x_hi - data.x_lo < 1e-290) {
    const std::vector<double> around = nice_ticks(data.x_lo, data.x_hi, 4);
    data.x_lo = around.front();
    data.x_hi = around.back();
  }
  f.x_lo = data.x_lo;
  f.x_hi = data.x_hi;
  for (int target = std::clamp(static_cast<int>((f.right - f.left) / 60), 2, 14); target >= 1; --target) {
    f.x_ticks = inner_ticks(f.x_lo, f.x_hi, target);
    layout.x_tick_labels = format_ticks(f.x_ticks);
    const double spacing = f.x_ticks.size() >= 2
                               ? (f.x_ticks[1] - f.x_ticks[0]) / (f.x_hi - f.x_lo) * (f.right - f.left)
                               : f.right - f.left;
    if (widest(layout.x_tick_labels, kTickFont) + 12 <= spacing) break;
  }
}

// Grid, with the zero line a little darker.
void draw_grid(Canvas& canvas, const PlotFrame& f) {
  canvas.begin_group("grid", "plot-grid");
  for (double t : f.x_ticks) {
    const double px = f.to_pixels(t, 0).x();
    if (px <= f.left + 0.5 || px >= f.right - 0.5) continue;
    canvas.polyline({{px, f.top}, {px, f.bottom}}, Stroke{kGrid, 1.0, {}});
  }
  for (double t : f.y_ticks) {
    const double py = f.to_pixels(0, t).y();
    if (py <= f.top + 0.5 || py >= f.bottom - 0.5) continue;
    const bool zero = std::abs(t) < 1e-9 * (f.y_hi - f.y_lo);
    canvas.polyline({{f.left, py}, {f.right, py}}, Stroke{zero ? kZeroLine : kGrid, 1.0, {}});
  }
  canvas.end_group();
}

void draw_series(Canvas& canvas, const PlotSpec& spec, const PlotFrame& f) {
  for (std::size_t i = 0; i < spec.series.size(); ++i) {
    const Stroke stroke = series_stroke(i);
    canvas.begin_group("series-" + std::to_string(i), "plot-series");
    PlotFrame axis = f;
    if (f.right_axis && f.series_on_right[i]) axis.y_lo = f.y2_lo, axis.y_hi = f.y2_hi;
    const Pieces pieces = clip_series(spec.x, spec.series[i].y, axis);
    for (const auto& line : pieces.lines) canvas.polyline(line, stroke);
    for (const Vec2& dot : pieces.dots) canvas.circle(dot, 2.0, Paint{stroke.colour, std::nullopt});
    canvas.end_group();
  }
}

// Frame, ticks, labels and title.
void draw_axes(Canvas& canvas, const PlotSpec& spec, const Labels& labels, const Layout& layout) {
  const PlotFrame& f = layout.frame;
  canvas.begin_group("axes", "plot-axes");
  canvas.polygon({{f.left, f.top}, {f.right, f.top}, {f.right, f.bottom}, {f.left, f.bottom}},
                 Paint{std::nullopt, Stroke{kFrame, 1.0, {}}});
  for (std::size_t i = 0; i < f.x_ticks.size(); ++i) {
    const double px = f.to_pixels(f.x_ticks[i], 0).x();
    canvas.polyline({{px, f.bottom}, {px, f.bottom + kTickLength}}, Stroke{kFrame, 1.0, {}});
    canvas.text({px, f.bottom + kTickLength + 3 + kTickFont * 0.8}, layout.x_tick_labels[i], kTickFont, Anchor::Middle,
                kPlotInk);
  }
  for (std::size_t i = 0; i < f.y_ticks.size(); ++i) {
    const double py = f.to_pixels(0, f.y_ticks[i]).y();
    canvas.polyline({{f.left - kTickLength, py}, {f.left, py}}, Stroke{kFrame, 1.0, {}});
    canvas.text({f.left - kTickLength - 4, py + 0.35 * kTickFont}, layout.y_tick_labels[i], kTickFont, Anchor::End,
                kPlotInk);
  }
  for (std::size_t i = 0; f.right_axis && i < f.y2_ticks.size(); ++i) {
    const double py = f.to_pixels_right(0, f.y2_ticks[i]).y();
    canvas.polyline({{f.right, py}, {f.right + kTickLength, py}}, Stroke{kFrame, 1.0, {}});
    canvas.text({f.right + kTickLength + 4, py + 0.35 * kTickFont}, layout.y2_tick_labels[i], kTickFont, Anchor::Start,
                kPlotInk);
  }
  if (!labels.y2.empty()) canvas.text({f.right, f.top - 14}, labels.y2, kLabelFont, Anchor::End, kPlotInk);
  if (!labels.x.empty())
    canvas.text({0.5 * (f.left + f.right), f.bottom + kTickLength + kTickFont + 10 + kLabelFont}, labels.x, kLabelFont,
                Anchor::Middle, kPlotInk);
  if (!labels.y.empty())
    canvas.text({std::max(kPad, f.left - widest(layout.y_tick_labels, kTickFont) - kTickLength - 4), f.top - 14},
                labels.y, kLabelFont, Anchor::Start, kPlotInk);
  if (!spec.title.empty())
    canvas.text({0.5 * canvas.width(), kPad + kTitleFont}, spec.title, kTitleFont, Anchor::Middle, kPlotInk);
  canvas.end_group();
}

// Legend: a box of entries, each a short stretch of its line and its name.
void draw_legend(Canvas& canvas, const Labels& labels, Layout layout) {
  const auto& entries = labels.entries;
  if (entries.empty()) return;
  const PlotFrame& f = layout.frame;
  canvas.begin_group("legend", "plot-legend");
  Vec2 corner;
  double box_w = 0, box_h = 0;
  if (layout.legend_right) {
    corner = {f.right + 14 + layout.right_axis_room, f.top};
    box_w = layout.legend_width;
    box_h = static_cast<double>(entries.size()) * kEntryHeight + 12;
    layout.legend_places.clear();
    for (std::size_t i = 0; i < entries.size(); ++i)
      layout.legend_places.push_back({i, Vec2(10, 6 + static_cast<double>(i) * kEntryHeight)});
  } else {
    corner = {kPad, f.bottom + kTickLength + kTickFont + 10 + (labels.x.empty() ? 0 : kLabelFont + 8)};
    for (const auto& [i, at] : layout.legend_places)
      box_w = std::max(box_w, at.x() + kSwatch + 6 + text_width(entries[i], kLegendFont) + 10);
    box_h = layout.legend_rows_height;
  }
  canvas.polygon({corner, corner + Vec2(box_w, 0), corner + Vec2(box_w, box_h), corner + Vec2(0, box_h)},
                 Paint{Colour::rgb(0xffffff), Stroke{Colour::rgb(0xaaaaaa), 1.0, {}}});
  for (const auto& [i, at] : layout.legend_places) {
    const Vec2 row = corner + at + Vec2(0, 0.5 * kEntryHeight);
    Stroke stroke = series_stroke(i);
    stroke.width = 2.5;
    canvas.polyline({row, row + Vec2(kSwatch, 0)}, stroke);
    canvas.text(row + Vec2(kSwatch + 6, 0.35 * kLegendFont), entries[i], kLegendFont, Anchor::Start, kPlotInk);
  }
  canvas.end_group();
}

}  // namespace

PlotFrame draw_plot(Canvas& canvas, const PlotSpec& spec) {
  check_spec(spec);
  const Labels labels = labels_of(spec);
  Layout layout;
  layout.frame.series_on_right = right_series(spec);
  layout.frame.right_axis = !layout.frame.series_on_right.empty();
  const DataRange data = data_range(spec, layout.frame.series_on_right, false);
  place_legend(labels, !spec.title.empty(), canvas.width(), canvas.height(), layout);
  if (plots_a_path(spec) && !spec.y_lo) {
    layout.frame.left = kPad + widest(format_ticks(nice_ticks(data.y_lo, data.y_hi, 8)), kTickFont) + kTickLength + 6;
    place_path_axes(data, layout);
  } else {
    place_y_axis(spec, data, layout);
    place_x_axis(data, layout);
  }
  draw_grid(canvas, layout.frame);
  draw_series(canvas, spec, layout.frame);
  draw_axes(canvas, spec, labels, layout);
  draw_legend(canvas, labels, layout);
  return layout.frame;
}

void set_plot_data(PlotSpec& spec, const ResultTable& x_column, const ResultTable& y_columns) {
  if (x_column.columns.empty() || x_column.units.empty())
    throw Error(ErrorKind::BadInput, "plot: there is no x column");
  spec.x_name = x_column.columns.front();
  spec.x_unit = x_column.units.front();
  spec.x.clear();
  for (const auto& row : x_column.rows) spec.x.push_back(row[0]);
  spec.series.clear();
  for (std::size_t c = 0; c < y_columns.columns.size(); ++c) {
    PlotSeries s{y_columns.columns[c], y_columns.units[c], {}};
    for (const auto& row : y_columns.rows) s.y.push_back(row[c]);
    spec.series.push_back(std::move(s));
  }
}

}  // namespace nbar::render
