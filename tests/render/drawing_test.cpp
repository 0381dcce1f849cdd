// Drawings of every example as SVG: well-formed, with the expected elements where the model
// says they are.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <regex>
#include <string>

#include "nbar/io/model_file.hpp"
#include "nbar/render/drawing.hpp"
#include "nbar/render/image_canvas.hpp"
#include "nbar/render/pictures.hpp"
#include "nbar/render/stress_map.hpp"

namespace nbar::render {
namespace {

namespace fs = std::filesystem;

// Tags balanced and properly nested, attributes quoted: enough to call the SVG well-formed
// for what the canvas writes (no comments, CDATA or entities other than the five it escapes).
::testing::AssertionResult well_formed(const std::string& xml) {
  std::vector<std::string> open;
  std::size_t i = xml.find("<svg");
  if (i == std::string::npos) return ::testing::AssertionFailure() << "no <svg>";
  const std::regex tag(R"(^<(/?)([a-zA-Z][\w:-]*)((\s+[\w:-]+="[^"<]*")*)\s*(/?)>)");
  while ((i = xml.find('<', i)) != std::string::npos) {
    std::smatch m;
    const std::string rest = xml.substr(i, xml.find('>', i) + 1 - i);  // one tag, however long
    if (!std::regex_search(rest, m, tag)) return ::testing::AssertionFailure() << "bad tag at " << rest.substr(0, 60);
    if (m[1] == "/") {
      if (open.empty() || open.back() != m[2]) return ::testing::AssertionFailure() << "unbalanced </" << m[2] << ">";
      open.pop_back();
    } else if (m[5] != "/") {
      open.push_back(m[2]);
    }
    i += m.length(0);
  }
  if (!open.empty()) return ::testing::AssertionFailure() << "unclosed <" << open.back() << ">";
  return ::testing::AssertionSuccess();
}

int count(const std::string& text, const std::string& what) {
  int n = 0;
  for (std::size_t i = text.find(what); i != std::string::npos; i = text.find(what, i + 1)) ++n;
  return n;
}

struct DrawnExample {
  io::LoadedModel file;
  Mechanism mech;
  SweepResult sweep;
  explicit DrawnExample(const std::string& name)
      : file(io::load_model_file(std::string(NBAR_EXAMPLES_DIR) + "/" + name)),
        mech(file.model),
        sweep(run_sweep(mech, [] {
          SweepOptions o;
          o.order = 0;
          o.steps = 37;
          return o;
        }())) {}
};

TEST(Drawing, FourBarHasAGroupPerBodyACirclePerJointAndAPathPerTrace) {
  const DrawnExample d("fourbar-crank-rocker.yaml");
  DrawOptions options;
  options.labels = true;
  options.traces = {d.mech.model().find_point("P"), d.mech.model().find_point("B")};
  SvgCanvas canvas(options.width, options.height);
  draw_sample(canvas, d.mech, d.sweep, 0, options);
  const std::string svg = canvas.document();
  EXPECT_TRUE(well_formed(svg));
  for (const char* body : {"crank", "coupler", "rocker"})
    EXPECT_EQ(count(svg, std::string("id=\"body-") + body + "\""), 1);
  // Joints O2, O4, A, B as open circles (white fill, r 4.5); the coupler point as a dot.
  EXPECT_EQ(count(svg, "r=\"4.5\" fill=\"#ffffff\""), 4);
  EXPECT_EQ(count(svg, "r=\"2.5\""), 1);
  // Two traces, one polyline each, with one vertex per sample of the finer sweep the traces
  // are solved on (the sweep has 37).
  const auto traces =
      svg.substr(svg.find("id=\"traces\""), svg.find("</g>", svg.find("id=\"traces\"")) - svg.find("id=\"traces\""));
  EXPECT_EQ(count(traces, "<polyline"), 2);
  const std::size_t points = traces.find("points=\"") + 8;
  EXPECT_EQ(count(traces.substr(points, traces.find('"', points) - points), ","), kTraceSamples);
  EXPECT_EQ(count(svg, ">O2</text>"), 1);
  EXPECT_THAT(svg, ::testing::HasSubstr(" mm</text>"));  // scale bar in the model's unit
}

TEST(Drawing, GroundPivotsAndJointsLandWhereTheViewMapsThem) {
  const DrawnExample d("fourbar-crank-rocker.yaml");
  DrawOptions options;
  const View view = fit_view(d.mech, d.sweep, options);
  SvgCanvas canvas(options.width, options.height);
  const auto points = sample_points(d.mech, d.sweep.samples[5]);
  draw_mechanism(canvas, view, d.mech, d.sweep, points, options);
  const std::string svg = canvas.document();
  for (const char* name : {"O2", "O4", "A", "B"}) {
    const Eigen::Vector2d p = view.to_pixels(points[d.mech.model().find_point(name)]);
    char cx[64];
    std::snprintf(cx, sizeof cx, "cx=\"%.2f", p.x());
    std::string want(cx);
    while (want.back() == '0') want.pop_back();
    if (want.back() == '.') want.pop_back();
    EXPECT_THAT(svg, ::testing::HasSubstr(want)) << name;
    EXPECT_GT(p.x(), options.margin);
    EXPECT_LT(p.x(), options.width - options.margin);
    EXPECT_GT(p.y(), options.margin);
    EXPECT_LT(p.y(), options.height - options.margin);
  }
}

TEST(Drawing, EveryPoseOfTheSweepFitsTheView) {
  const DrawnExample d("slider-crank-offset.yaml");
  DrawOptions options;
  const View view = fit_view(d.mech, d.sweep, options);
  // Every point of a body; the guide's far end (a ground point of no body) may lie outside.
  const Model& m = d.mech.model();
  for (const Sample& s : d.sweep.samples)
    for (const Body& body : m.bodies)
      for (int point : body.points) {
        const Eigen::Vector2d q = view.to_pixels(sample_points(d.mech, s)[point]);
        EXPECT_GE(q.x(), options.margin);
        EXPECT_LE(q.x(), options.width - options.margin);
        EXPECT_GE(q.y(), options.margin);
        EXPECT_LE(q.y(), options.height - options.margin);
      }
}

TEST(Drawing, BodyTransformsCarryTheStartingPoseOntoAnyOther) {
  const DrawnExample d("fourbar-steel-bars.yaml");
  DrawOptions options;
  const View view = fit_view(d.mech, d.sweep, options);
  const auto start = sample_points(d.mech, d.sweep.samples[0]);
  const auto later = sample_points(d.mech, d.sweep.samples[11]);
  const auto transforms = body_transforms(d.mech, view, start, later);
  const Model& m = d.mech.model();
  for (std::size_t b = 0; b < m.bodies.size(); ++b) {
    const PixelTransform& t = transforms[b];
    const double a = t.angle_deg * std::acos(-1.0) / 180.0;
    for (int p : m.bodies[b].points) {
      // SVG: translate(shift) rotate(angle, pivot): screen rotation is clockwise for a > 0.
      const Eigen::Vector2d q = view.to_pixels(start[p]) - t.pivot;
      const Eigen::Vector2d moved(std::cos(a) * q.x() - std::sin(a) * q.y(), std::sin(a) * q.x() + std::cos(a) * q.y());
      EXPECT_LT((moved + t.pivot + t.shift - view.to_pixels(later[p])).norm(), 1e-9) << m.bodies[b].name;
    }
  }
}

TEST(Drawing, EveryExampleDrawsAsWellFormedSvg) {
  for (const auto& e : fs::directory_iterator(NBAR_EXAMPLES_DIR)) {
    if (e.path().extension() != ".yaml") continue;
    SCOPED_TRACE(e.path().filename().string());
    const DrawnExample d(e.path().filename().string());
    DrawOptions options;
    options.labels = true;
    SvgCanvas canvas(options.width, options.height);
    draw_sample(canvas, d.mech, d.sweep, static_cast<int>(d.sweep.samples.size()) / 2, options);
    const std::string svg = canvas.document();
    EXPECT_TRUE(well_formed(svg));
    EXPECT_EQ(count(svg, "id=\"body-"), static_cast<int>(d.mech.model().bodies.size()));
    EXPECT_EQ(svg.find("nan"), std::string::npos);
    // And as PNG: something drawn, the border left blank.
    ImageCanvas image(options.width, options.height);
    draw_sample(image, d.mech, d.sweep, static_cast<int>(d.sweep.samples.size()) / 2, options);
    int inked = 0;
    for (int y = 0; y < image.height(); y += 2)
      for (int x = 0; x < image.width(); x += 2) {
        const std::uint8_t* p = image.data() + y * image.stride() + 4 * x;
        inked += (p[0] < 250 || p[1] < 250 || p[2] < 250) ? 1 : 0;
      }
    EXPECT_GT(inked, 200);
  }
}

// The plate four-bar coloured by its finite-element von Mises stress: every link's map, the
// legend from 0 to the crank's peak (the driver's torque as shear around its 20 mm hole,
// sqrt(3) T / (2 pi r^2 t) = 11.17 MPa for T = 405.6 N m), each peak marked.
TEST(StressMap, PlateFourBarIsColouredWithLegendAndPeaks) {
  const io::LoadedModel file = io::load_model_file(std::string(NBAR_EXAMPLES_DIR) + "/fourbar-ansys-plates.yaml");
  const auto mech = std::make_shared<const Mechanism>(file.model);
  AnalysisOptions options;
  options.stress = true;
  options.stress_method = StressMethod::fe;
  const Analysis analysis = analyse(mech, options);
  DrawOptions draw;
  add_stress_maps(draw, analysis, 0);
  ASSERT_EQ(draw.stress_maps.size(), 3u);
  ASSERT_EQ(draw.markers.size(), 3u);
  EXPECT_NEAR(stress_scale(draw), 11.17e6, 0.01 * 11.17e6);
  EXPECT_EQ(draw.markers[0].label, "11.2 MPa");
  // The crank's peak is on the edge of its O2 hole (radius 10 mm around the origin of its frame).
  EXPECT_NEAR(draw.markers[0].local.norm(), 0.01, 1e-3);
  const std::string svg = drawing_svg(*mech, analysis.sweep, sample_points(*mech, analysis.sweep.samples[0]), draw);
  EXPECT_NE(svg.find("stress-legend"), std::string::npos);
  EXPECT_NE(svg.find("11.2 MPa"), std::string::npos);
  EXPECT_EQ(stress_colour(0.0).hex(), "#2b52d9");
  EXPECT_EQ(stress_colour(1.0).hex(), "#de1f1a");
  EXPECT_EQ(stress_text(246e3), "246 kPa");
}

}  // namespace
}  // namespace nbar::render
