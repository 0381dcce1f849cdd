// Drawing a mechanism the way a textbook does: each body in its own colour (its plate when it
// has a shape, otherwise a bar or a filled polygon), revolute joints as small circles, ground
// pivots on hatched bases, slider blocks on their guides, slots, point labels, the paths of
// chosen points, equal axis scales and a scale bar.
//
// Every body is drawn in its own group; for animations the groups are drawn once at the
// starting pose and moved by rigid transforms (body_transforms), or the whole picture is drawn
// again for each frame (raster formats).
#pragma once

#include <Eigen/Core>

#include <memory>
#include <string>
#include <vector>

#include "nbar/kinematics/sweep.hpp"
#include "nbar/render/canvas.hpp"
#include "nbar/stress/mesh.hpp"

namespace nbar::render {

// A spot to mark on a body, e.g. where its largest stress is.
struct Marker {
  int body = -1;
  Eigen::Vector2d local{0, 0};  // in the body frame: x along its axis from its first point, y to the left, m
  std::string label;
};

// A point to mark where it is (not on a body), e.g. an instant centre: a cross in a circle and
// a label.
struct MarkedPoint {
  Eigen::Vector2d position{0, 0};  // m
  std::string label;
};

// A link's plate coloured by a value at every node of its mesh (the von Mises stress): the
// mesh in the plate's own frame (the starting pose), one value per node (Pa).
struct StressMap {
  int body = -1;
  std::shared_ptr<const fe::TriMesh> mesh;
  std::vector<double> values;
};

struct DrawOptions {
  int width = 900, height = 640;  // px
  double margin = 36;             // px around the mechanism
  bool labels = false;            // point names
  std::vector<int> traces;        // points whose paths over the sweep are drawn
  // The paths of `traces` (m), when already computed (trace_paths); empty: computed when drawn.
  std::vector<std::vector<Eigen::Vector2d>> trace_paths;
  std::vector<Marker> markers;
  std::vector<MarkedPoint> marked_points;  // drawn last, in the group "marked-points"
  bool scale_bar = true;
  std::string title;  // drawn at the top left when not empty
  // Plates coloured by stress (render/stress_map.hpp), with a colour legend at the top right
  // from 0 to `stress_scale` (Pa; 0: the largest value of the maps).
  std::vector<StressMap> stress_maps;
  double stress_scale = 0.0;
};

// A view in which every pose of the sweep fits, so that animation frames share it.
View fit_view(const Mechanism& mech, const SweepResult& sweep, const DrawOptions& options);

// The paths of `points` over the sweep's path, sampled finely enough for a smooth curve
// whatever the sweep's own number of samples: when it has fewer than kTraceSamples, the same
// sweep is solved again (positions only) with kTraceSamples samples. Falls back to the sweep's
// own samples when that finer sweep does not get as far.
constexpr int kTraceSamples = 361;
std::vector<std::vector<Eigen::Vector2d>> trace_paths(const Mechanism& mech, const SweepResult& sweep,
                                                      const std::vector<int>& points);

// The sample to draw when none is asked for: the first, unless every point there lies on (or
// next to) one line, as a slider-crank at dead centre, which tells little; then the sample
// where the points spread widest (the largest area of their convex hull).
int default_drawn_step(const Mechanism& mech, const SweepResult& sweep);

// The positions of every point at a sample (m).
std::vector<Eigen::Vector2d> sample_points(const Mechanism& mech, const Sample& sample);

// One pose. Groups: "ground", "traces", "body-<name>" (one per body, with its joints),
// "labels", "markers", "marked-points", "scale-bar".
void draw_mechanism(Canvas& canvas, const View& view, const Mechanism& mech, const SweepResult& sweep,
                    const std::vector<Eigen::Vector2d>& points, const DrawOptions& options);

// Convenience: the whole picture of sample `step` on a fitted view.
void draw_sample(Canvas& canvas, const Mechanism& mech, const SweepResult& sweep, int step, const DrawOptions& options);

// The rigid motion, in pixels, that takes each body from where it is drawn at `reference` to
// where it is at `points`: p -> rotation(angle) * (p - pivot) + pivot + shift. Angles in
// degrees, clockwise positive on screen (SVG's rotate()).
struct PixelTransform {
  double angle_deg = 0.0;
  Eigen::Vector2d pivot{0, 0};
  Eigen::Vector2d shift{0, 0};
};
std::vector<PixelTransform> body_transforms(const Mechanism& mech, const View& view,
                                            const std::vector<Eigen::Vector2d>& reference,
                                            const std::vector<Eigen::Vector2d>& points);

// The indices of the points named, for DrawOptions::traces. Throws Error(ErrorKind::BadInput)
// "'X' is not a point of the model; the points are: A, B, ..." for an unknown name.
std::vector<int> trace_points(const Model& model, const std::vector<std::string>& names);

// The colour of body `index` (a palette that stays distinct for neighbouring bodies).
Colour body_colour(int index);

}  // namespace nbar::render
