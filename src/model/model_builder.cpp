#include "nbar/model/model_builder.hpp"

#include <iomanip>
#include <sstream>

namespace nbar {

namespace {

// "unknown point 'X'; the points are: A, B" (names in the order they were added).
template <class Items>
[[noreturn]] void unknown(const char* what, const std::string& name, const Items& items, EntityRef::Kind kind) {
  std::string known;
  for (const auto& item : items) known += (known.empty() ? "" : ", ") + item.name;
  throw ModelError({kind, -1},
                   std::string("unknown ") + what + " '" + name + "'" +
                       (known.empty() ? std::string(" (none yet)") : "; the " + std::string(what) + "s are: " + known));
}

// A constant as a law, written to the last bit so that its text reads back to the same value.
Law constant(double value) {
  std::ostringstream text;
  text << std::setprecision(17) << value;
  return Law::parse(text.str());
}

}  // namespace

ModelBuilder::ModelBuilder(std::string name) { model_.name = std::move(name); }

ModelBuilder& ModelBuilder::units(const std::string& length, const std::string& angle) {
  const std::optional<Units> u = Units::make(length, angle);
  if (!u) throw ModelError({}, "unknown units '" + length + "', '" + angle + "' (use m, mm, cm, in, ft and deg, rad)");
  model_.units = *u;
  return *this;
}

int ModelBuilder::point_index(const std::string& name) const {
  const int p = model_.find_point(name);
  if (p < 0) unknown("point", name, model_.points, EntityRef::Kind::Point);
  return p;
}

int ModelBuilder::body_index(const std::string& name) const {
  const int b = model_.find_body(name);
  if (b < 0) unknown("body", name, model_.bodies, EntityRef::Kind::Body);
  return b;
}

void ModelBuilder::add_point(const std::string& name, double x, double y, bool ground) {
  const Units& u = model_.units;
  model_.points.push_back(Point{name, Eigen::Vector2d(u.to_si_length(x), u.to_si_length(y)), ground});
}

ModelBuilder& ModelBuilder::point(const std::string& name, double x, double y) {
  add_point(name, x, y, false);
  return *this;
}

ModelBuilder& ModelBuilder::ground(const std::string& name, double x, double y) {
  add_point(name, x, y, true);
  return *this;
}

ModelBuilder& ModelBuilder::body(const std::string& name, const std::vector<std::string>& points,
                                 std::optional<double> length) {
  Body b;
  b.name = name;
  for (const std::string& p : points) b.points.push_back(point_index(p));
  if (length) b.length = model_.units.to_si_length(*length);
  model_.bodies.push_back(std::move(b));
  return *this;
}

ModelBuilder& ModelBuilder::slider(const std::string& body, const std::string& point, const std::string& from,
                                   const std::string& to) {
  model_.sliders.push_back(Slider{body_index(body), point_index(point), {point_index(from), point_index(to)}});
  return *this;
}

ModelBuilder& ModelBuilder::slot(const std::string& point, const std::string& from, const std::string& to) {
  model_.slots.push_back(Slot{point_index(point), {point_index(from), point_index(to)}});
  return *this;
}

void ModelBuilder::add_driver(Driver driver, const DriverMotion& motion) {
  const double scale = driver.is_angular() ? model_.units.angle_scale : model_.units.length_scale;
  if (motion.from) driver.from = *motion.from * scale;
  if (motion.to) driver.to = *motion.to * scale;
  driver.speed = motion.speed * scale;
  driver.accel = motion.accel * scale;
  if (!motion.law.empty()) {
    try {
      driver.law = Law::parse(motion.law, scale);
    } catch (const LawSyntaxError& e) {
      throw ModelError({EntityRef::Kind::Driver, static_cast<int>(model_.drivers.size())},
                       "in the law '" + motion.law + "' of driver '" + driver.name + "': " + e.what());
    }
  }
  model_.drivers.push_back(std::move(driver));
}

ModelBuilder& ModelBuilder::angle_driver(const std::string& name, const std::string& body, const DriverMotion& motion,
                                         const std::string& relative_to) {
  Driver d;
  d.name = name;
  d.kind = DriverKind::Angle;
  d.body = body_index(body);
  if (!relative_to.empty()) d.relative_to = body_index(relative_to);
  add_driver(std::move(d), motion);
  return *this;
}

ModelBuilder& ModelBuilder::distance_driver(const std::string& name, const std::string& from_point,
                                            const std::string& to_point, const DriverMotion& motion) {
  Driver d;
  d.name = name;
  d.kind = DriverKind::Distance;
  d.points = {point_index(from_point), point_index(to_point)};
  add_driver(std::move(d), motion);
  return *this;
}

ModelBuilder& ModelBuilder::slide_driver(const std::string& name, const std::string& body, const DriverMotion& motion) {
  const int b = body_index(body);
  Driver d;
  d.name = name;
  d.kind = DriverKind::Slide;
  for (std::size_t s = 0; s < model_.sliders.size(); ++s)
    if (model_.sliders[s].body == b) d.slider = static_cast<int>(s);
  if (d.slider < 0) throw ModelError({EntityRef::Kind::Body, b}, "body '" + body + "' has no slider to drive");
  add_driver(std::move(d), motion);
  return *this;
}

ModelBuilder& ModelBuilder::steps(int samples) {
  model_.sweep.steps = samples;
  return *this;
}

ModelBuilder& ModelBuilder::duration(double seconds, std::optional<double> step) {
  model_.sweep.duration = seconds;
  model_.sweep.time_step = step;
  return *this;
}

ModelBuilder& ModelBuilder::gravity(double gx, double gy) {
  model_.gravity = {gx, gy};
  return *this;
}

ModelBuilder& ModelBuilder::mass(const std::string& body, double kilograms, double cg_x, double cg_y, double inertia) {
  const Units& u = model_.units;
  model_.bodies[body_index(body)].inertia =
      GivenInertia{kilograms, Eigen::Vector2d(u.to_si_length(cg_x), u.to_si_length(cg_y)), inertia};
  return *this;
}

ModelBuilder& ModelBuilder::force(const std::string& point, double fx, double fy, const std::string& body) {
  PointLoad load;
  load.point = point_index(point);
  load.body = body.empty() ? -1 : body_index(body);
  load.fx = constant(fx);
  load.fy = constant(fy);
  model_.point_loads.push_back(std::move(load));
  return *this;
}

ModelBuilder& ModelBuilder::torque(const std::string& body, double newton_metres) {
  model_.torques.push_back(BodyTorque{body_index(body), constant(newton_metres), std::nullopt});
  return *this;
}

ModelBuilder& ModelBuilder::spring(const std::string& name, const std::string& from_point, const std::string& to_point,
                                   double stiffness, double free_length, double damping) {
  model_.springs.push_back(Spring{name,
                                  {point_index(from_point), point_index(to_point)},
                                  stiffness,
                                  model_.units.to_si_length(free_length),
                                  damping,
                                  0.0});
  return *this;
}

Model ModelBuilder::build() const {
  validate(model_);
  return model_;
}

}  // namespace nbar
