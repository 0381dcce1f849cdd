#include "nbar/analysis/fe_tables.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>

#include "nbar/dynamics/inverse_dynamics.hpp"
#include "nbar/kinematics/continuation.hpp"
#include "nbar/kinematics/sweep.hpp"
#include "nbar/model/units.hpp"
#include "nbar/stress/field_query.hpp"
#include "stress/t6_element.hpp"

namespace nbar {

namespace {

// The query frame's axes in the drawing: its origin (m) and the angle of its x axis (rad).
struct FrameAxes {
  Eigen::Vector2d origin{0, 0};
  double angle = 0.0;
};

FrameAxes frame_axes(const Model& model, int body, QueryFrame frame) {
  if (frame == QueryFrame::model) return {};
  // body_frame_point is the rigid map p -> R (p - o): read R and o back from it.
  const Eigen::Vector2d at_zero = body_frame_point(model, body, {0, 0});
  const Eigen::Vector2d ex = body_frame_point(model, body, {1, 0}) - at_zero;  // (cos a, -sin a)
  FrameAxes axes;
  axes.angle = std::atan2(-ex.y(), ex.x());
  const Eigen::Rotation2Dd rotation(axes.angle);
  axes.origin = -(rotation * at_zero);
  return axes;
}

const char* kStressColumns[] = {"sigma_xx", "sigma_yy", "tau_xy", "von_mises", "sigma_1", "sigma_2"};

// One body at one step: its plate, the field at that step, and the frame the table is in.
struct FieldAtStep {
  const Analysis& analysis;
  const Model& model;
  int body;
  int step;
  const fe::PlateModel& plate;
  fe::StressField field;
  FrameAxes axes;
  double length_unit, angle_unit;

  Eigen::Vector2d to_drawn(const Eigen::Vector2d& query) const {
    return axes.origin + Eigen::Rotation2Dd(axes.angle) * (query * length_unit);
  }
  Eigen::Vector2d to_query(const Eigen::Vector2d& drawn) const {
    return (Eigen::Rotation2Dd(-axes.angle) * (drawn - axes.origin)) / length_unit;
  }
  // The stress columns of a point, components in the frame's axes.
  void append(std::vector<double>& row, const fe::PointStress& s) const {
    const fe::PointStress turned = fe::stress_state(s.at, fe::rotate_stress(s.stress, axes.angle));
    for (double v : {turned.stress[0], turned.stress[1], turned.stress[2], turned.von_mises, turned.principal_1,
                     turned.principal_2})
      row.push_back(to_megapascal(v));
    row.push_back(turned.principal_angle / angle_unit);
  }
  void name_columns(ResultTable& t) const {
    for (const char* c : kStressColumns) t.columns.push_back(c), t.units.push_back("MPa");
    t.columns.push_back("angle_1");
    t.units.push_back(model.units.angle);
  }
};

std::string body_label(const Model& m, int body) {
  return body >= 0 && body < static_cast<int>(m.bodies.size()) ? m.bodies[body].name : std::to_string(body);
}

[[noreturn]] void fail(int body, const std::string& message) {
  throw Error(ErrorKind::BadInput, message, EntityRef{EntityRef::Kind::Body, body});
}

FieldAtStep field_at_step(const Analysis& analysis, int body, int step, QueryFrame frame) {
  const Model& m = analysis.model();
  if (!analysis.stress || !analysis.stress->fe)
    throw Error(ErrorKind::BadInput, "the stresses anywhere in a link need the finite-element stress stage");
  if (body < 0 || body >= static_cast<int>(m.bodies.size()) || !analysis.stress->fe->analysed(body))
    fail(std::max(body, 0), "'" + body_label(m, body) + "' has no plate to analyse (no shape, or no thickness)");
  const int steps = static_cast<int>(analysis.sweep.samples.size());
  if (step < 0 || step >= steps)
    throw Error(ErrorKind::BadInput,
                "step " + std::to_string(step) + " is not a solved step (0 to " + std::to_string(steps - 1) + ")");
  const LinkFe& fe = *analysis.stress->fe;
  return FieldAtStep{analysis,
                     m,
                     body,
                     step,
                     fe.plate(body),
                     fe.solve(analysis.dynamics->samples[step], body),
                     frame_axes(m, body, frame),
                     m.units.length_scale,
                     m.units.angle_scale};
}

std::string frame_words(const Model& m, int body, QueryFrame frame) {
  if (frame == QueryFrame::model) return "model coordinates";
  const Body& b = m.bodies[body];
  return "the body's frame (x from " + m.points[b.points[0]].name +
         (b.points.size() > 1 ? " towards " + m.points[b.points[1]].name : std::string()) + ", y to its left)";
}

std::string number_text(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

std::string point_text(const Eigen::Vector2d& p, const std::string& unit) {
  std::ostringstream out;
  out << "(" << p.x() << ", " << p.y() << ") " << unit;
  return out.str();
}

std::string title(const FieldAtStep& f, const std::string& what, QueryFrame frame) {
  return "Stresses of " + f.model.bodies[f.body].name + " " + what + " " + step_description(f.analysis, f.step) +
         ", in " + frame_words(f.model, f.body, frame);
}

// The inverse of the drawing's placement of a plate (render/drawing.cpp): a point of the body seen
// at `posed` when its frame's points are at `points`, back where the model draws it (m).
Eigen::Vector2d drawn_from_posed(const Model& m, int body, const std::vector<Eigen::Vector2d>& points,
                                 const Eigen::Vector2d& posed) {
  const BodyFrame f = body_frame(m, body);
  const Eigen::Vector2d from_origin = posed - points[f.origin];
  const Eigen::Vector2d& origin_drawn = m.points[f.origin].position;
  if (f.from < 0) return origin_drawn + from_origin;
  const Eigen::Vector2d direction = points[f.to] - points[f.from];
  const Eigen::Vector2d direction_drawn = m.points[f.to].position - m.points[f.from].position;
  const double ll = direction.squaredNorm();
  if (ll == 0.0) return origin_drawn + from_origin;
  // Components along the posed direction and its left normal, laid on the drawn ones.
  const double along = from_origin.dot(direction) / ll;
  const double across = (direction.x() * from_origin.y() - direction.y() * from_origin.x()) / ll;
  return origin_drawn + along * direction_drawn + across * Eigen::Vector2d(-direction_drawn.y(), direction_drawn.x());
}

}  // namespace

std::string step_description(const Analysis& analysis, int step) {
  const Model& m = analysis.model();
  const Sample& at = analysis.sweep.samples.at(step);
  std::string inputs;
  for (std::size_t d = 0; d < m.drivers.size(); ++d)
    inputs += m.drivers[d].name + " = " + format_driver_value(m, static_cast<int>(d), at.driver_values[d]) + ", ";
  std::ostringstream time;
  time << at.time;
  return "at step " + std::to_string(step) + " (" + inputs + "t = " + time.str() + " s)";
}

Eigen::Vector2d query_point(const Model& model, int body, QueryFrame frame, const Eigen::Vector2d& drawn) {
  const FrameAxes axes = frame_axes(model, body, frame);
  Eigen::Vector2d out = (Eigen::Rotation2Dd(-axes.angle) * (drawn - axes.origin)) / model.units.length_scale;
  // A point on the body's axis (its own points) is on it, not 1e-16 beside it: rounding of the turn.
  const double scale = std::max(out.cwiseAbs().maxCoeff(), drawn.norm() / model.units.length_scale);
  for (int k = 0; k < 2; ++k)
    if (std::abs(out[k]) < 1e-12 * scale) out[k] = 0;
  return out;
}

Eigen::Vector2d drawn_point(const Model& model, int body, QueryFrame frame, const Eigen::Vector2d& query) {
  const FrameAxes axes = frame_axes(model, body, frame);
  return axes.origin + Eigen::Rotation2Dd(axes.angle) * (query * model.units.length_scale);
}

int hole_at_point(const Model& model, int body, int point) {
  const Body& b = model.bodies.at(body);
  if (!b.shape || point < 0 || point >= static_cast<int>(model.points.size())) return -1;
  const Eigen::Vector2d& p = model.points[point].position;
  for (std::size_t h = 0; h < b.shape->circle_holes.size(); ++h)
    if ((p - b.shape->circle_holes[h].centre).norm() < b.shape->circle_holes[h].radius) return static_cast<int>(h);
  return -1;
}

ResultTable fe_points_table(const Analysis& analysis, int body, int step, const std::vector<Eigen::Vector2d>& points,
                            QueryFrame frame) {
  const FieldAtStep f = field_at_step(analysis, body, step, frame);
  const fe::MeshLocator locator(f.plate.mesh());
  ResultTable t;
  const std::string& len = f.model.units.length;
  t.columns = {"x", "y"};
  t.units = {len, len};
  f.name_columns(t);
  for (const Eigen::Vector2d& p : points) {
    const std::optional<fe::PointStress> s = fe::stress_at(locator, f.field, f.to_drawn(p));
    if (!s)
      fail(body, "the point " + point_text(p, len) + " in " + frame_words(f.model, body, frame) +
                     " is not on the plate of '" + f.model.bodies[body].name +
                     "' (it is in a hole or outside the outline)");
    std::vector<double> row{p.x(), p.y()};
    f.append(row, *s);
    t.rows.push_back(std::move(row));
  }
  zero_numerical_noise(t);
  t.title = title(f, "at " + std::to_string(points.size()) + (points.size() == 1 ? " point" : " points"), frame);
  return t;
}

std::optional<PlateUnder> plate_under(const Analysis& analysis, int step, const Eigen::Vector2d& posed) {
  const Model& m = analysis.model();
  if (!analysis.stress || !analysis.stress->fe)
    throw Error(ErrorKind::BadInput, "the stresses anywhere in a link need the finite-element stress stage");
  const int steps = static_cast<int>(analysis.sweep.samples.size());
  if (step < 0 || step >= steps)
    throw Error(ErrorKind::BadInput,
                "step " + std::to_string(step) + " is not a solved step (0 to " + std::to_string(steps - 1) + ")");
  const std::vector<Eigen::Vector2d> points =
      point_positions(*analysis.mechanism, analysis.sweep.samples[step].positions());
  const LinkFe& fe = *analysis.stress->fe;
  for (int body = static_cast<int>(m.bodies.size()) - 1; body >= 0; --body) {
    if (!fe.analysed(body)) continue;
    const Eigen::Vector2d drawn = drawn_from_posed(m, body, points, posed);
    if (fe::MeshLocator(fe.plate(body).mesh()).locate(drawn))
      return PlateUnder{body, query_point(m, body, QueryFrame::model, drawn)};
  }
  return std::nullopt;
}

ResultTable fe_line_table(const Analysis& analysis, int body, int step, const Eigen::Vector2d& from,
                          const Eigen::Vector2d& to, int samples, QueryFrame frame) {
  const FieldAtStep f = field_at_step(analysis, body, step, frame);
  const fe::MeshLocator locator(f.plate.mesh());
  ResultTable t;
  const std::string& len = f.model.units.length;
  t.columns = {"arc", "x", "y"};
  t.units = {len, len, len};
  f.name_columns(t);
  const double length = (to - from).norm();
  for (const fe::LineSample& s : fe::stress_along(locator, f.field, f.to_drawn(from), f.to_drawn(to), samples)) {
    if (!s.stress) continue;
    const double share = length > 0 ? s.arc / (length * f.length_unit) : 0.0;
    const Eigen::Vector2d q = from + share * (to - from);
    std::vector<double> row{share * length, q.x(), q.y()};
    f.append(row, *s.stress);
    t.rows.push_back(std::move(row));
  }
  if (t.rows.empty())
    fail(body, "the line from " + point_text(from, len) + " to " + point_text(to, len) + " in " +
                   frame_words(f.model, body, frame) + " does not cross the plate of '" + f.model.bodies[body].name +
                   "'");
  t.title = title(f, "along the line from " + point_text(from, len) + " to " + point_text(to, len), frame);
  return t;
}

ResultTable fe_hole_table(const Analysis& analysis, int body, int step, int hole, QueryFrame frame,
                          std::optional<double> radius, int samples) {
  const FieldAtStep f = field_at_step(analysis, body, step, frame);
  const int holes = static_cast<int>(f.model.bodies[body].shape->circle_holes.size());
  if (hole < 0 || hole >= holes)
    fail(body, "'" + f.model.bodies[body].name + "' has " +
                   (holes == 0 ? std::string("no round hole") : "round holes 1 to " + std::to_string(holes)) +
                   ", not hole " + std::to_string(hole + 1));
  ResultTable t;
  const std::string& len = f.model.units.length;
  t.columns = {"angle", "x", "y", "sigma_hoop", "sigma_radial"};
  t.units = {f.model.units.angle, len, len, "MPa", "MPa"};
  f.name_columns(t);
  constexpr double kTurn = 2 * 3.141592653589793238462643383279502884;
  std::vector<std::vector<double>> rows;
  const auto add_row = [&](double plate_angle, const fe::PointStress& s) {
    const Eigen::Vector3d polar = fe::rotate_stress(s.stress, plate_angle);  // radial, hoop, shear
    const double angle = std::fmod(plate_angle - f.axes.angle + 2 * kTurn, kTurn);
    const Eigen::Vector2d q = f.to_query(s.at);
    std::vector<double> row{angle / f.angle_unit, q.x(), q.y(), to_megapascal(polar[1]), to_megapascal(polar[0])};
    f.append(row, s);
    rows.push_back(std::move(row));
  };
  const Circle& circle = f.model.bodies[body].shape->circle_holes[hole];
  if (radius) {
    // A circle around the hole: sampled, points off the plate left out.
    const fe::MeshLocator locator(f.plate.mesh());
    const auto [centre, fitted] = f.plate.hole_circle(hole);
    for (int k = 0; k < samples; ++k) {
      const double angle = kTurn * k / samples;
      const Eigen::Vector2d at = centre + *radius * f.length_unit * Eigen::Vector2d(std::cos(angle), std::sin(angle));
      if (const std::optional<fe::PointStress> s = fe::stress_at(locator, f.field, at)) add_row(angle, *s);
    }
    if (rows.empty())
      fail(body, "the circle of radius " + number_text(*radius) + " " + f.model.units.length + " around hole " +
                     std::to_string(hole + 1) + " of '" + f.model.bodies[body].name + "' does not cross its plate");
  } else {
    for (const fe::HoleSample& s : fe::stress_around_hole(f.plate, f.field, hole)) add_row(s.angle, s.stress);
  }
  std::sort(rows.begin(), rows.end());
  t.rows = std::move(rows);
  zero_numerical_noise(t);
  std::ostringstream hole_radius;
  hole_radius << circle.radius / f.length_unit;
  Eigen::Vector2d centre = f.to_query(circle.centre);
  for (int k = 0; k < 2; ++k)  // rounding of the frame's rotation, not a place
    if (std::abs(centre[k]) < 1e-9 * circle.radius / f.length_unit) centre[k] = 0;
  t.title = title(f,
                  (radius ? "on a circle of radius " + number_text(*radius) + " " + len + " " : std::string()) +
                      "around hole " + std::to_string(hole + 1) + " (centre " + point_text(centre, len) + ", radius " +
                      hole_radius.str() + " " + len + "), angle counterclockwise from x,",
                  frame);
  return t;
}

namespace {

// What one cut across the plate carries, integrated over its parts on the plate (SI).
struct CutResult {
  double length = 0, axial = 0, shear = 0, moment = 0;  // per unit thickness: m, N/m, N/m, N
  double sigma_right = 0, sigma_left = 0, tau = 0, von_mises = 0;
};

// The cut at body-frame x from y = low to y = high (m). Each part on the plate is split into
// pieces integrated by 5-point Gauss, so the sums are those of the interpolated field.
std::optional<CutResult> integrate_cut(const FieldAtStep& f, const fe::MeshLocator& locator, double x, double low,
                                       double high) {
  const auto drawn = [&](double y) { return Eigen::Vector2d(f.to_drawn(Eigen::Vector2d(x, y) / f.length_unit)); };
  const auto parts = fe::segment_on_plate(locator, drawn(low), drawn(high), 64);
  if (parts.empty()) return std::nullopt;
  CutResult cut;
  double first_moment = 0, stress_moment = 0;  // ∫y dy, ∫y σxx dy
  const auto body_stress = [&](double y) -> std::optional<Eigen::Vector3d> {
    const std::optional<fe::PointStress> s = fe::stress_at(locator, f.field, drawn(y));
    if (!s) return std::nullopt;
    const Eigen::Vector3d turned = fe::rotate_stress(s->stress, f.axes.angle);
    cut.von_mises = std::max(cut.von_mises, s->von_mises);
    cut.tau = std::max(cut.tau, std::abs(turned[2]));
    return turned;
  };
  for (const auto& [t0, t1] : parts) {
    const double y0 = low + t0 * (high - low), y1 = low + t1 * (high - low);
    const int pieces = std::max(1, static_cast<int>(std::ceil(32 * (t1 - t0))));
    const double step = (y1 - y0) / pieces;
    for (int p = 0; p < pieces; ++p)
      for (const auto& [s, weight] : fe::t6::kGaussLine5) {
        const double y = y0 + (p + 0.5 * (s + 1)) * step, w = 0.5 * weight * step;
        const std::optional<Eigen::Vector3d> sigma = body_stress(y);
        if (!sigma) continue;
        cut.length += w;
        first_moment += w * y;
        cut.axial += w * (*sigma)[0];
        cut.shear += w * (*sigma)[2];
        stress_moment += w * y * (*sigma)[0];
      }
  }
  // A hair inside the plate: the bisection leaves each end within 1e-9 of the cut, either side.
  const double inward = 1e-7 * (high - low);
  const double y_right = low + parts.front().first * (high - low) + inward;
  const double y_left = low + parts.back().second * (high - low) - inward;
  if (const auto s = body_stress(y_right)) cut.sigma_right = (*s)[0];
  if (const auto s = body_stress(y_left)) cut.sigma_left = (*s)[0];
  if (cut.length <= 0) return std::nullopt;
  // M about the cut's centroid, as the beam method's: sigma(y) = N/A - M (y - yc) / I.
  cut.moment = -(stress_moment - first_moment / cut.length * cut.axial);
  return cut;
}

}  // namespace

ResultTable fe_section_table(const Analysis& analysis, int body, int step, int sections) {
  const FieldAtStep f = field_at_step(analysis, body, step, QueryFrame::body);
  const fe::MeshLocator locator(f.plate.mesh());
  Eigen::Vector2d low = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity()), high = -low;
  for (const Eigen::Vector2d& node : f.plate.mesh().nodes) {
    const Eigen::Vector2d q = f.to_query(node) * f.length_unit;
    low = low.cwiseMin(q), high = high.cwiseMax(q);
  }
  const double pad = 1e-3 * (high.y() - low.y()), thickness = f.plate.material().thickness;
  ResultTable t;
  const std::string len = f.model.units.length;
  t.columns = {"x", "area", "N", "V", "M", "sigma_right", "sigma_left", "tau", "von_mises"};
  t.units = {len, len + "^2", "N", "N", "N m", "MPa", "MPa", "MPa", "MPa"};
  sections = std::max(sections, 1);
  for (int k = 0; k < sections; ++k) {
    const double x = low.x() + (k + 0.5) / sections * (high.x() - low.x());
    const std::optional<CutResult> cut = integrate_cut(f, locator, x, low.y() - pad, high.y() + pad);
    if (!cut) continue;
    t.rows.push_back({x / f.length_unit, cut->length * thickness / (f.length_unit * f.length_unit),
                      cut->axial * thickness, cut->shear * thickness, cut->moment * thickness,
                      to_megapascal(cut->sigma_right), to_megapascal(cut->sigma_left), to_megapascal(cut->tau),
                      to_megapascal(cut->von_mises)});
  }
  zero_numerical_noise(t);
  t.title = "Sections of " + f.model.bodies[body].name + " " + step_description(analysis, step) +
            " by finite elements: x from " + f.model.points[f.model.bodies[body].points[0]].name +
            (f.model.bodies[body].points.size() > 1 ? " towards " + f.model.points[f.model.bodies[body].points[1]].name
                                                    : std::string()) +
            ", each cut integrated over the plate";
  return t;
}

}  // namespace nbar
