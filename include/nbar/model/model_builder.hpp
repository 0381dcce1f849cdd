// Building a model in code, the way a model file writes it: points by name as drawn, the
// ground, bodies as lists of point names, joints, drivers, loads. Numbers are in the builder's
// units (set with units(); metres and degrees by default) and stored in SI. Names are resolved
// when used, and build() validates the whole model, so every mistake is an nbar::Error of kind
// InvalidModel that names what is wrong.
//
//   Model m = ModelBuilder("four-bar").units("mm", "deg")
//                 .ground("O2", 0, 0).ground("O4", 200, 0)
//                 .point("A", 80, 0).point("B", 181.25, 148.82)
//                 .body("crank", {"O2", "A"}).body("coupler", {"A", "B"}).body("rocker", {"O4", "B"})
//                 .angle_driver("crank", "crank", {.from = 0, .to = 360})
//                 .build();
#pragma once

#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

#include "nbar/model/model.hpp"

namespace nbar {

// How a driver moves, in the builder's units: from `from` to `to` (unset: the drawn value) at
// `speed` per second with `accel`, or by `law`, an expression in t (docs/model-format.md).
struct DriverMotion {
  std::optional<double> from;
  std::optional<double> to;
  double speed = 1.0;
  double accel = 0.0;
  std::string law;
};

class ModelBuilder {
 public:
  explicit ModelBuilder(std::string name = {});

  // "m", "mm", "cm", "in", "ft" and "deg", "rad"; applies to the numbers given after it.
  ModelBuilder& units(const std::string& length, const std::string& angle = "deg");

  ModelBuilder& point(const std::string& name, double x, double y);   // a moving point
  ModelBuilder& ground(const std::string& name, double x, double y);  // a point fixed to the frame
  // A rigid body through these points (the first two define its angle); `length` overrides the
  // drawn distance of a two-point body.
  ModelBuilder& body(const std::string& name, const std::vector<std::string>& points,
                     std::optional<double> length = std::nullopt);
  // `point` of `body` slides on the line through `from` and `to`; the body keeps its angle to the guide.
  ModelBuilder& slider(const std::string& body, const std::string& point, const std::string& from,
                       const std::string& to);
  // `point` moves on the line through `from` and `to` and may turn.
  ModelBuilder& slot(const std::string& point, const std::string& from, const std::string& to);

  // The angle of `body` from +x, or relative to `relative_to`.
  ModelBuilder& angle_driver(const std::string& name, const std::string& body, const DriverMotion& motion = {},
                             const std::string& relative_to = {});
  ModelBuilder& distance_driver(const std::string& name, const std::string& from_point, const std::string& to_point,
                                const DriverMotion& motion = {});
  // The position along its guide of the slider on `body`.
  ModelBuilder& slide_driver(const std::string& name, const std::string& body, const DriverMotion& motion = {});

  ModelBuilder& steps(int samples);                                         // from/to sweeps
  ModelBuilder& duration(double seconds, std::optional<double> step = {});  // time-law sweeps

  ModelBuilder& gravity(double gx, double gy);  // m/s^2
  // Mass properties given directly: kg, centre of mass (builder's length unit), kg m^2.
  ModelBuilder& mass(const std::string& body, double kilograms, double cg_x, double cg_y, double inertia);
  // A constant force (N) at a point, on `body` there or (empty) on the joint's pin.
  ModelBuilder& force(const std::string& point, double fx, double fy, const std::string& body = {});
  ModelBuilder& torque(const std::string& body, double newton_metres);
  // Stiffness N/m, free length in the builder's length unit, damping N s/m.
  ModelBuilder& spring(const std::string& name, const std::string& from_point, const std::string& to_point,
                       double stiffness, double free_length, double damping = 0.0);

  // The model, validated (nbar::validate). Throws Error(ErrorKind::InvalidModel).
  Model build() const;

 private:
  int point_index(const std::string& name) const;
  int body_index(const std::string& name) const;
  void add_point(const std::string& name, double x, double y, bool ground);
  void add_driver(Driver driver, const DriverMotion& motion);

  Model model_;
};

}  // namespace nbar
