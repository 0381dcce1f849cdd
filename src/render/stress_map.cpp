#include "nbar/render/stress_map.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace nbar::render {

Colour stress_colour(double fraction) {
  // Blue, cyan, green, yellow, red: the scale FE packages use, so a designer reads it at once.
  static constexpr std::array<std::array<double, 3>, 5> kStops{
      {{0.17, 0.32, 0.85}, {0.10, 0.75, 0.90}, {0.25, 0.80, 0.30}, {0.98, 0.85, 0.15}, {0.87, 0.12, 0.10}}};
  const double f = std::isfinite(fraction) ? std::clamp(fraction, 0.0, 1.0) : 1.0;
  const double x = f * (kStops.size() - 1);
  const std::size_t i = std::min<std::size_t>(static_cast<std::size_t>(x), kStops.size() - 2);
  const double t = x - static_cast<double>(i);
  const auto channel = [&](int c) {
    return static_cast<std::uint8_t>(std::lround(255.0 * ((1 - t) * kStops[i][c] + t * kStops[i + 1][c])));
  };
  return {channel(0), channel(1), channel(2), 255};
}

std::string stress_text(double pascals) {
  const double a = std::abs(pascals);
  if (a >= 1e9) return fmt::format("{:.3g} GPa", pascals / 1e9);
  if (a >= 1e6) return fmt::format("{:.3g} MPa", pascals / 1e6);
  if (a >= 1e3) return fmt::format("{:.3g} kPa", pascals / 1e3);
  return fmt::format("{:.3g} Pa", pascals);
}

void draw_stress_plate(Canvas& canvas, const StressMap& map, double scale,
                       const std::function<Eigen::Vector2d(const Eigen::Vector2d&)>& to_pixels) {
  if (!map.mesh) return;
  const fe::TriMesh& mesh = *map.mesh;
  std::vector<Eigen::Vector2d> px(mesh.nodes.size());
  for (std::size_t n = 0; n < mesh.nodes.size(); ++n) px[n] = to_pixels(mesh.nodes[n]);
  // The quarters of a 6-node triangle (corners 0 1 2, mid-sides 3 (0-1), 4 (1-2), 5 (2-0)).
  static constexpr int kQuarters[4][3] = {{0, 3, 5}, {3, 1, 4}, {5, 4, 2}, {3, 4, 5}};
  const double top = scale > 0.0 ? scale : 1.0;
  for (const auto& t : mesh.triangles) {
    for (const auto& q : kQuarters) {
      double value = 0.0;
      for (int k : q) value += map.values[t[k]];
      const Colour c = stress_colour(value / 3.0 / top);
      // Stroked in its own colour, so that neighbours leave no hairline of background between
      // them when antialiased.
      canvas.polygon({px[t[q[0]]], px[t[q[1]]], px[t[q[2]]]}, Paint{c, Stroke{c, 0.6, {}}});
    }
  }
}

void draw_stress_legend(Canvas& canvas, double scale) {
  const Colour ink = Colour::rgb(0x222222);
  const double bar_height = std::clamp(0.35 * canvas.height(), 80.0, 200.0);
  const double bar_width = 14.0;
  const double x = canvas.width() - kStressLegendWidth + 6.0, top = 44.0;
  constexpr int kBands = 40;
  canvas.begin_group("stress-legend", "stress-legend");
  canvas.text({canvas.width() - 10.0, top - 12.0}, "von Mises", 12, Anchor::End, ink);
  for (int i = 0; i < kBands; ++i) {
    const double y0 = top + bar_height * i / kBands, y1 = top + bar_height * (i + 1) / kBands;
    const Colour c = stress_colour(1.0 - (i + 0.5) / kBands);
    canvas.polygon({{x, y0}, {x + bar_width, y0}, {x + bar_width, y1}, {x, y1}}, Paint{c, Stroke{c, 0.5, {}}});
  }
  canvas.polygon({{x, top}, {x + bar_width, top}, {x + bar_width, top + bar_height}, {x, top + bar_height}},
                 Paint{std::nullopt, Stroke{ink, 1.0, {}}});
  for (int k = 0; k <= 4; ++k) {
    const double y = top + bar_height * (1.0 - k / 4.0);
    canvas.polyline({{x + bar_width, y}, {x + bar_width + 4, y}}, Stroke{ink, 1.0, {}});
    canvas.text({x + bar_width + 6, y + 4}, k == 0 ? "0" : stress_text(scale * k / 4.0), 10, Anchor::Start, ink);
  }
  canvas.end_group();
}

double stress_scale(const DrawOptions& options) {
  if (options.stress_scale > 0.0) return options.stress_scale;
  double top = 0.0;
  for (const StressMap& map : options.stress_maps)
    for (double v : map.values)
      if (std::isfinite(v)) top = std::max(top, v);
  return top;
}

namespace {

const LinkFe& fe_of(const Analysis& analysis) {
  if (!analysis.stress || !analysis.stress->fe)
    throw Error(ErrorKind::BadInput, "stress maps need the finite-element stresses (StressMethod::fe)");
  return *analysis.stress->fe;
}

}  // namespace

std::vector<StressMap> stress_maps(const Analysis& analysis, int sample) {
  const LinkFe& fe = fe_of(analysis);
  if (sample < 0 || sample >= static_cast<int>(analysis.dynamics->samples.size()))
    throw Error(ErrorKind::BadInput, "step " + std::to_string(sample) + " was not solved");
  std::vector<StressMap> maps;
  for (std::size_t b = 0; b < analysis.model().bodies.size(); ++b) {
    const int body = static_cast<int>(b);
    if (!fe.analysed(body)) continue;
    StressMap map;
    map.body = body;
    // Shares the plate models, so that a map may outlive the analysis that made it.
    map.mesh = std::shared_ptr<const fe::TriMesh>(analysis.stress->fe, &fe.plate(body).mesh());
    map.values = fe.solve(analysis.dynamics->samples[sample], body).von_mises;
    maps.push_back(std::move(map));
  }
  return maps;
}

void add_stress_maps(DrawOptions& options, const Analysis& analysis, int sample, double scale) {
  options.stress_maps = stress_maps(analysis, sample);
  options.stress_scale = scale;
  const Model& m = analysis.model();
  for (const StressMap& map : options.stress_maps) {
    const auto peak = std::max_element(map.values.begin(), map.values.end());
    if (peak == map.values.end()) continue;
    const Eigen::Vector2d at = map.mesh->nodes[static_cast<std::size_t>(peak - map.values.begin())];
    options.markers.push_back({map.body, body_frame_point(m, map.body, at), stress_text(*peak)});
  }
}

double sweep_stress_scale(const Analysis& analysis) {
  if (!analysis.stress) return 0.0;
  double top = 0.0;
  for (const FePeak& p : analysis.stress->fe_peaks)
    if (std::isfinite(p.von_mises)) top = std::max(top, p.von_mises);
  return top;
}

}  // namespace nbar::render
