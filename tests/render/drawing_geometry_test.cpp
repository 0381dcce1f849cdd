// What a reader sees in a drawing, asserted on the primitives drawn: pins in slots, bars,
// the side a guide is hatched on, labels clear of lines, colours, the fitted view and the
// drawn pose.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>

#include "nbar/io/model_file.hpp"
#include "nbar/render/drawing.hpp"
#include "recording_canvas.hpp"

namespace nbar::render {
namespace {

using test_support::Drawn;
using test_support::RecordingCanvas;

struct Example {
  io::LoadedModel file;
  Mechanism mech;
  SweepResult sweep;
  explicit Example(const std::string& name, int steps = 37)
      : file(io::load_model_file(std::string(NBAR_EXAMPLES_DIR) + "/" + name)),
        mech(file.model),
        sweep(run_sweep(mech, [steps] {
          SweepOptions o;
          o.order = 0;
          o.steps = steps;
          return o;
        }())) {}
  int point(const std::string& name) const { return mech.model().find_point(name); }
};

struct Picture {
  DrawOptions options;
  View view;
  RecordingCanvas canvas;
  std::vector<Eigen::Vector2d> points;
  Picture(const Example& e, int step, DrawOptions o)
      : options(std::move(o)),
        view(fit_view(e.mech, e.sweep, options)),
        canvas(options.width, options.height),
        points(sample_points(e.mech, e.sweep.samples.at(step))) {
    draw_mechanism(canvas, view, e.mech, e.sweep, points, options);
  }
  Eigen::Vector2d px(int point) const { return view.to_pixels(points[point]); }
};

bool inside(const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& p) {
  bool in = false;
  for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++)
    if ((polygon[i].y() > p.y()) != (polygon[j].y() > p.y()) &&
        p.x() < (polygon[j].x() - polygon[i].x()) * (p.y() - polygon[i].y()) / (polygon[j].y() - polygon[i].y()) +
                    polygon[i].x())
      in = !in;
  return in;
}

// Whether the box (left, top, right, bottom) comes within `reach` of the segment a-b: sampled
// along the segment and the box's edges, finely enough for pixels.
bool box_near_segment(const std::array<double, 4>& box, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                      double reach) {
  const int n = 200;
  for (int i = 0; i <= n; ++i) {
    const Eigen::Vector2d p = a + (b - a) * (static_cast<double>(i) / n);
    const double dx = std::max({box[0] - p.x(), 0.0, p.x() - box[2]});
    const double dy = std::max({box[1] - p.y(), 0.0, p.y() - box[3]});
    if (std::hypot(dx, dy) < reach) return true;
  }
  return false;
}

// A label's box as drawn: 12 px sans-serif is about 0.6 em a character wide, 0.8 em above
// the baseline and 0.2 em below.
std::array<double, 4> text_box(const Drawn& t) {
  return {t.points[0].x(), t.points[0].y() - 0.8 * t.size,
          t.points[0].x() + 0.6 * t.size * static_cast<double>(t.text.size()), t.points[0].y() + 0.2 * t.size};
}

const Drawn* circle_at(const RecordingCanvas& c, const std::string& group, const Eigen::Vector2d& at, double radius) {
  for (const Drawn* d : c.in(group, Drawn::Circle))
    if ((d->points[0] - at).norm() < 1e-9 && std::abs(d->size - radius) < 1e-9) return d;
  return nullptr;
}

TEST(DrawingGeometry, APinInASlotHasAJointCircleAndTheSlotIsARoundedOutlineOverItsTravel) {
  const Example e("scissor-lift.yaml");
  for (int step : {0, 18, 36}) {
    const Picture pic(e, step, {});
    const Eigen::Vector2d t1 = pic.px(e.point("T1"));
    // T1 belongs to arm3 alone: its joint circle moves with arm3.
    const Drawn* pin = circle_at(pic.canvas, "body-arm3", t1, 4.5);
    ASSERT_NE(pin, nullptr) << "step " << step;
    EXPECT_EQ(pin->paint.fill->hex(), "#ffffff");
    // The slot: a white outline in the platform's group, round at both ends, holding the pin
    // in this pose, and drawn before the pin (the pin is on top).
    const auto slots = pic.canvas.in("body-platform", Drawn::Polygon);
    ASSERT_EQ(slots.size(), 1u);
    const auto& outline = slots[0]->points;
    EXPECT_GE(outline.size(), 16u);
    EXPECT_TRUE(inside(outline, t1));
    EXPECT_LT(slots[0], pin);
    // As wide as the pin plus a clearance, and as long as the pin's travel along the platform
    // over the sweep (plus the rounded ends).
    double lo = INFINITY, hi = -INFINITY;
    for (const Sample& s : e.sweep.samples) {
      const auto p = sample_points(e.mech, s);
      const Eigen::Vector2d along = (p[e.point("Q")] - p[e.point("T2")]).normalized();
      const double t = along.dot(p[e.point("T1")] - p[e.point("T2")]);
      lo = std::min(lo, t), hi = std::max(hi, t);
    }
    double longest = 0;
    for (const auto& a : outline)
      for (const auto& b : outline) longest = std::max(longest, (a - b).norm());
    const double travel_px = (hi - lo) * pic.view.pixels_per_metre();
    EXPECT_GT(travel_px, 50.0);
    EXPECT_NEAR(longest, std::hypot(travel_px + 2 * 6.5, 0.0), 0.5);
  }
}

// The slotted-lever quick return: the crank pin A runs in a slot of the lever O4-T (no block).
TEST(DrawingGeometry, TheCrankPinOfASlottedLeverIsAJointInTheLeversSlot) {
  const io::LoadedModel file = io::parse_model(
      "units: {length: mm, angle: deg}\n"
      "points: {O4: [0, 0], O2: [0, 250], A: [100, 250], T: [185.695338, 464.238345]}\n"
      "ground: [O4, O2]\n"
      "bodies: {crank: [O2, A], lever: [O4, T]}\n"
      "slots:\n  - {point: A, along: [O4, T]}\n"
      "drivers:\n  - {angle: crank, from: 0, to: 360, speed: 30 rpm}\n"
      "sweep: {steps: 37}\n");
  const Mechanism mech(file.model);
  SweepOptions o;
  o.order = 0;
  const SweepResult sweep = run_sweep(mech, o);
  ASSERT_TRUE(sweep.complete);
  DrawOptions options;
  const View view = fit_view(mech, sweep, options);
  for (int step : {0, 12, 25}) {
    RecordingCanvas canvas(options.width, options.height);
    const auto points = sample_points(mech, sweep.samples[step]);
    draw_mechanism(canvas, view, mech, sweep, points, options);
    const Eigen::Vector2d a = view.to_pixels(points[file.model.find_point("A")]);
    const Drawn* pin = circle_at(canvas, "body-crank", a, 4.5);
    ASSERT_NE(pin, nullptr) << "step " << step;
    const auto slots = canvas.in("body-lever", Drawn::Polygon);
    ASSERT_EQ(slots.size(), 1u);
    EXPECT_TRUE(inside(slots[0]->points, a)) << "step " << step;
    EXPECT_LT(slots[0], pin);  // the lever first, the pin over it
    // The lever is wider than the slot it carries.
    const auto lever = canvas.in("body-lever", Drawn::Polyline);
    ASSERT_EQ(lever.size(), 1u);
    EXPECT_GT(lever[0]->size, 2 * 6.5);
  }
}

TEST(DrawingGeometry, ACollinearThreePointBodyIsABarAsWideAsATwoPointOne) {
  const Example scissor("scissor-lift.yaml");
  const Picture pic(scissor, 0, {});
  const Example fourbar("fourbar-crank-rocker.yaml");
  const Picture bars(fourbar, 0, {});
  const auto crank = bars.canvas.in("body-crank", Drawn::Polyline);
  ASSERT_EQ(crank.size(), 1u);
  for (const char* arm : {"arm1", "arm2", "arm3", "arm4"}) {
    const auto lines = pic.canvas.in(std::string("body-") + arm, Drawn::Polyline);
    ASSERT_EQ(lines.size(), 1u) << arm;
    EXPECT_EQ(lines[0]->size, crank[0]->size) << arm;
    EXPECT_TRUE(pic.canvas.in(std::string("body-") + arm, Drawn::Polygon).empty()) << arm << " drawn as an area";
    // From end to end: G1 to U1 for arm1 (the cross pin M1 in the middle).
    const Body& body = scissor.mech.model().bodies[scissor.mech.model().find_body(arm)];
    const Eigen::Vector2d a = pic.px(body.points[0]), b = pic.px(body.points[2]);
    const auto& drawn = lines[0]->points;
    EXPECT_LT(std::min((drawn[0] - a).norm() + (drawn[1] - b).norm(), (drawn[0] - b).norm() + (drawn[1] - a).norm()),
              1e-9)
        << arm;
  }
}

// +1 when every hatch stroke of the guide group `guide` lies below its line on screen, -1 when
// every one lies above it, 0 otherwise.
int hatch_side(const Picture& pic, const std::string& guide) {
  const auto lines = pic.canvas.in(guide, Drawn::Polyline);
  if (lines.size() < 5) return 0;
  const double line_y = lines[0]->points[0].y();
  bool below = true, above = true;
  for (std::size_t i = 1; i < lines.size(); ++i)
    for (const auto& p : lines[i]->points) below = below && p.y() > line_y + 1, above = above && p.y() < line_y - 1;
  return below ? 1 : above ? -1 : 0;
}

// The side comes from the whole sweep, not from the pose drawn: an offset slider-crank's
// hatching stays on one side through the turn (the web app moves the drawing of one pose
// through the others), and an in-line one, which the crank straddles evenly, stands on it.
TEST(DrawingGeometry, AGuideKeepsItsHatchedSideInEveryPose) {
  for (const auto& [file, side] : {std::pair{"slider-crank-offset.yaml", -1}, std::pair{"compressor-myszka.yaml", 1},
                                   std::pair{"slider-crank-centred.yaml", 1}}) {
    const Example e(file);
    const Model& m = e.mech.model();
    ASSERT_FALSE(m.sliders.empty()) << file;
    const std::string guide = "guide-" + m.points[m.sliders[0].point].name;
    for (std::size_t k = 0; k < e.sweep.samples.size(); k += 4)
      EXPECT_EQ(hatch_side(Picture(e, static_cast<int>(k), {}), guide), side) << file << " sample " << k;
  }
}

TEST(DrawingGeometry, AGuideIsHatchedOnTheSideAwayFromTheMechanism) {
  // The scissor lift stands on its slide: hatching below the line (larger y on screen).
  {
    const Example e("scissor-lift.yaml");
    const Picture pic(e, 0, {});
    const auto lines = pic.canvas.in("guide-S", Drawn::Polyline);
    ASSERT_GT(lines.size(), 5u);
    const double line_y = lines[0]->points[0].y();
    EXPECT_NEAR(lines[0]->points[1].y(), line_y, 1e-9);
    for (std::size_t i = 1; i < lines.size(); ++i) {
      for (const auto& p : lines[i]->points) {
        EXPECT_GT(p.y(), line_y + 1) << "hatch " << i;
      }
    }
  }
  // The shaper's ram hangs under its guide: hatching above it.
  {
    const Example e("inverted-slider-crank-shaper.yaml");
    const Picture pic(e, 0, {});
    const auto lines = pic.canvas.in("guide-R", Drawn::Polyline);
    ASSERT_GT(lines.size(), 5u);
    const double line_y = lines[0]->points[0].y();
    for (std::size_t i = 1; i < lines.size(); ++i) {
      for (const auto& p : lines[i]->points) {
        EXPECT_LT(p.y(), line_y - 1) << "hatch " << i;
      }
    }
  }
}

// Every point's label, in every example drawn at its start: its box clear of every bar and
// guide line, and of every slider block.
TEST(DrawingGeometry, LabelsStayOffBarsGuidesAndBlocks) {
  for (const char* name : {"inverted-slider-crank-shaper.yaml", "scissor-lift.yaml", "slider-crank-offset.yaml",
                           "fourbar-crank-rocker.yaml", "v-twin.yaml"}) {
    const Example e(name);
    DrawOptions options;
    options.labels = true;
    const Picture pic(e, 0, options);
    const auto labels = pic.canvas.in("labels", Drawn::Text);
    ASSERT_EQ(labels.size(), e.mech.model().points.size()) << name;
    for (const Drawn& d : pic.canvas.drawn) {
      const bool body = d.group.rfind("body-", 0) == 0, guide = d.group.rfind("guide-", 0) == 0;
      if (!body && !guide) continue;
      for (const Drawn* label : labels) {
        const auto box = text_box(*label);
        if (d.kind == Drawn::Polyline) {
          for (std::size_t i = 0; i + 1 < d.points.size(); ++i) {
            EXPECT_FALSE(box_near_segment(box, d.points[i], d.points[i + 1], 0.5 * d.size))
                << name << ": label " << label->text << " on a line of " << d.group;
          }
        }
        if (d.kind == Drawn::Polygon && d.points.size() == 4 && d.paint.fill && d.paint.fill->a < 255) {
          // A slider block: no corner or centre of the label inside it.
          const Eigen::Vector2d centre(0.5 * (box[0] + box[2]), 0.5 * (box[1] + box[3]));
          for (const Eigen::Vector2d& c : {centre, Eigen::Vector2d(box[0], box[1]), Eigen::Vector2d(box[2], box[3])}) {
            EXPECT_FALSE(inside(d.points, c)) << name << ": label " << label->text << " on block " << d.group;
          }
        }
      }
    }
  }
}

// A stress marker's label (which the report draws on the steel four-bar's plates) is read
// beside the plates, not over them.
TEST(DrawingGeometry, AMarkerLabelStaysOffThePlates) {
  const Example e("fourbar-steel-bars.yaml");
  const Model& m = e.mech.model();
  for (int step : {0, 1, 35}) {
    for (std::size_t b = 0; b < m.bodies.size(); ++b) {
      DrawOptions options;
      // Near the body's first point, on its axis: the label's first choice (up right) would
      // cross the plate.
      options.markers.push_back({static_cast<int>(b), {0.02, 0.0}, "44.9 MPa"});
      const Picture pic(e, step, options);
      const auto labels = pic.canvas.in("markers", Drawn::Text);
      ASSERT_EQ(labels.size(), 1u);
      const auto box = text_box(*labels[0]);
      for (const Drawn& plate : pic.canvas.drawn) {
        if (plate.kind != Drawn::Outline) continue;
        for (const Eigen::Vector2d& c :
             {Eigen::Vector2d(box[0], box[1]), Eigen::Vector2d(box[2], box[1]), Eigen::Vector2d(box[2], box[3]),
              Eigen::Vector2d(box[0], box[3]), Eigen::Vector2d(0.5 * (box[0] + box[2]), 0.5 * (box[1] + box[3]))}) {
          EXPECT_FALSE(inside(plate.points, c))
              << "step " << step << ", marker on " << m.bodies[b].name << ": its label is on " << plate.group;
        }
      }
    }
  }
}

TEST(DrawingGeometry, TracesAreSmoothWhateverTheSweepsSampleCount) {
  const Example e("fourbar-crank-rocker.yaml", 13);
  DrawOptions options;
  options.traces = {e.point("P")};
  const Picture pic(e, 0, options);
  const auto traces = pic.canvas.in("traces", Drawn::Polyline);
  ASSERT_EQ(traces.size(), 1u);
  const auto& path = traces[0]->points;
  ASSERT_EQ(path.size(), static_cast<std::size_t>(kTraceSamples));
  // The coarse sweep's own samples lie on the fine path (same path, every 30th sample), and
  // no chord of it is longer than a few pixels.
  for (std::size_t k = 0; k < e.sweep.samples.size(); ++k) {
    const Eigen::Vector2d coarse = pic.view.to_pixels(sample_points(e.mech, e.sweep.samples[k])[e.point("P")]);
    EXPECT_LT((path[k * 30] - coarse).norm(), 1e-6) << k;
  }
  for (std::size_t i = 1; i < path.size(); ++i) EXPECT_LT((path[i] - path[i - 1]).norm(), 6.0);
}

TEST(DrawingGeometry, EveryBodyOfALargeMachineHasItsOwnColourAndJointsAreAbovePlates) {
  const Example e("machine-18.yaml");
  const Model& m = e.mech.model();
  std::set<std::string> colours;
  for (std::size_t b = 0; b < m.bodies.size(); ++b) colours.insert(body_colour(static_cast<int>(b)).hex());
  EXPECT_EQ(colours.size(), m.bodies.size());
  ASSERT_GT(m.bodies.size(), 10u);
  const Picture pic(e, 0, {});
  // Every joint circle is drawn after every plate that covers it.
  for (std::size_t i = 0; i < pic.canvas.drawn.size(); ++i) {
    const Drawn& c = pic.canvas.drawn[i];
    if (c.kind != Drawn::Circle || c.group.rfind("body-", 0) != 0) continue;
    for (std::size_t j = i + 1; j < pic.canvas.drawn.size(); ++j) {
      const Drawn& plate = pic.canvas.drawn[j];
      if ((plate.kind == Drawn::Outline || plate.kind == Drawn::Polygon) && plate.group.rfind("body-", 0) == 0) {
        EXPECT_FALSE(inside(plate.points, c.points[0])) << "a joint of " << c.group << " under " << plate.group;
      }
    }
  }
}

TEST(DrawingGeometry, TheViewFitsTheMovingPartsNotFarGuideEnds) {
  const Example e("inverted-slider-crank-shaper.yaml");
  const DrawOptions options;
  const View view = fit_view(e.mech, e.sweep, options);
  // Every moving point over the sweep is on the canvas, and they fill most of its height
  // (the guide ends G1, G2 at +-600 mm would leave them a third of it).
  double top = INFINITY, bottom = -INFINITY;
  for (const Sample& s : e.sweep.samples) {
    const auto p = sample_points(e.mech, s);
    for (const char* name : {"O4", "O2", "A", "T", "R"}) {
      const Eigen::Vector2d q = view.to_pixels(p[e.point(name)]);
      EXPECT_GE(q.x(), options.margin);
      EXPECT_LE(q.x(), options.width - options.margin);
      top = std::min(top, q.y()), bottom = std::max(bottom, q.y());
    }
  }
  EXPECT_GT(bottom - top, 0.7 * options.height);
  EXPECT_GT(view.to_pixels(e.mech.model().points[e.point("G2")].position).x(), options.width);
  // Nor are the far guide ends drawn at the canvas's edge, with or without their names.
  DrawOptions labelled;
  labelled.labels = true;
  const Picture pic(e, 0, labelled);
  for (const Drawn* d : pic.canvas.in("ground", Drawn::Polygon))
    for (const auto& p : d->points) EXPECT_TRUE(p.x() > 0 && p.x() < options.width) << p.transpose();
  for (const Drawn* t : pic.canvas.in("labels", Drawn::Text)) EXPECT_NE(t->text, "G1");
}

// A phone turned sideways (the web app's drawing at 808 x 176): fixed margins of 66 px at the
// top and bottom left the sweep 44 px of height, a quarter of the picture.
TEST(DrawingGeometry, AShortWidePictureGivesTheMechanismMostOfItsHeight) {
  const Example e("fourbar-crank-rocker.yaml");
  DrawOptions options;
  options.width = 808;
  options.height = 176;
  const View view = fit_view(e.mech, e.sweep, options);
  double top = INFINITY, bottom = -INFINITY;
  for (const Sample& s : e.sweep.samples)
    for (const Eigen::Vector2d& p : sample_points(e.mech, s)) {
      const Eigen::Vector2d q = view.to_pixels(p);
      EXPECT_GE(q.y(), 0.15 * options.height);
      EXPECT_LE(q.y(), 0.85 * options.height);
      top = std::min(top, q.y()), bottom = std::max(bottom, q.y());
    }
  EXPECT_GT(bottom - top, 0.5 * options.height);
}

TEST(DrawingGeometry, AFlatStartIsNotTheDefaultDrawnPose) {
  // The compressor starts at top dead centre, every point on the line of stroke: the pose
  // drawn is the widest one, with the crank near square to the line of stroke.
  const Example flat("compressor-myszka-kinetics.yaml", 361);
  const int step = default_drawn_step(flat.mech, flat.sweep);
  const auto p = sample_points(flat.mech, flat.sweep.samples.at(step));
  const Eigen::Vector2d crank = p[flat.point("A")] - p[flat.point("O2")];
  EXPECT_GT(std::abs(crank.y()), 0.9 * crank.norm()) << "step " << step;
  // A four-bar's start tells its story already.
  const Example open("fourbar-crank-rocker.yaml");
  EXPECT_EQ(default_drawn_step(open.mech, open.sweep), 0);
}

}  // namespace
}  // namespace nbar::render
