// The finite-element stress field of one link at one step as tables in the model's units (lengths
// in its unit, angles in its angle unit, stresses in MPa), for every front-end: at points, along
// a line, around a hole's edge, and cross-section by cross-section (the beam's section profile's
// columns, from the field). They need the stress stage by finite elements (analyse with
// StressMethod::fe); each solves the link's load case at that step once (a back-substitution).
//
// Places are given, and stress components reported, in the body's frame (x along the link from
// its first point towards its second, y to its left, as the stress reports place the peak) or in
// the model's coordinates (the drawing's, where the shapes are given).
#pragma once

#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

#include "nbar/analysis/analysis.hpp"
#include "nbar/kinematics/table.hpp"

namespace nbar {

enum class QueryFrame { body, model };

// A drawing point of `body` (model coordinates, m) in `frame`, in the model's length unit; and back.
Eigen::Vector2d query_point(const Model& model, int body, QueryFrame frame, const Eigen::Vector2d& drawn);
Eigen::Vector2d drawn_point(const Model& model, int body, QueryFrame frame, const Eigen::Vector2d& query);

// The circle hole (index in the body's shape) whose inside holds the drawing position of point
// `point`, or -1.
int hole_at_point(const Model& model, int body, int point);

// Each throws Error(BadInput) about the body for an analysis without the finite-element stage, a
// body without a plate, a step that was not solved, or a hole the shape does not have.

// x, y, then sigma_xx, sigma_yy, tau_xy, von_mises, sigma_1, sigma_2 (MPa) and the angle of
// sigma_1 from x, one row per point (in `frame`, model units). A point off the plate (in a hole,
// outside the outline) is an Error(BadInput) naming the body and the point.
ResultTable fe_points_table(const Analysis& analysis, int body, int step, const std::vector<Eigen::Vector2d>& points,
                            QueryFrame frame);
// `samples` points evenly from `from` to `to` (ends included): arc (from `from`), x, y and the
// columns above; points off the plate (a hole the line crosses) are left out, and a line with
// none on the plate is an Error(BadInput).
ResultTable fe_line_table(const Analysis& analysis, int body, int step, const Eigen::Vector2d& from,
                          const Eigen::Vector2d& to, int samples, QueryFrame frame);
// Every node on the edge of circle hole `hole` of the body's shape (0-based), by angle around its
// centre from the frame's x axis, counterclockwise: angle, x, y, sigma_hoop, sigma_radial, then
// the columns above. With `radius` (model units), `samples` points evenly around a circle of that
// radius about the hole's centre instead, those off the plate left out.
ResultTable fe_hole_table(const Analysis& analysis, int body, int step, int hole, QueryFrame frame,
                          std::optional<double> radius = std::nullopt, int samples = 360);
// `sections` cuts across the link, evenly over its plate's length along the body's x axis, each
// integrated over the parts of the cut on the plate: x, area, N, V, M (about the cut's centroid),
// sigma_right and sigma_left (sigma_xx at the cut's ends, right and left of the axis), tau (the
// largest |tau_xy| on the cut) and von_mises (the largest on the cut): the beam method's columns,
// from the field.
ResultTable fe_section_table(const Analysis& analysis, int body, int step, int sections);

// The link seen at a point of the drawing: the plate drawn at `posed` (model coordinates, m) with
// the mechanism at sample `step`, and where that point is on the link as the model draws it (model
// coordinates in the model's length unit, as `fe_points_table` with QueryFrame::model takes it).
// Each plate moves rigidly with its body's frame (its origin point and direction, as the drawing
// places it). Links later in the model are drawn over earlier ones, so the last whose plate holds
// the point is the one seen; nullopt when none does. Needs the finite-element stage (Error
// BadInput otherwise, or for a step that was not solved).
struct PlateUnder {
  int body = -1;
  Eigen::Vector2d at{0, 0};
};
std::optional<PlateUnder> plate_under(const Analysis& analysis, int step, const Eigen::Vector2d& posed);

// "at step 3 (crank = 30 deg, t = 0.5 s)": a step of the sweep and its driver values, for titles.
std::string step_description(const Analysis& analysis, int step);

}  // namespace nbar
