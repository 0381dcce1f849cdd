#include "nbar/model/model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "nbar/model/diagnostics.hpp"
#include "nbar/model/geometry.hpp"

namespace nbar {

int Model::find_point(const std::string& point_name) const {
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (points[i].name == point_name) return static_cast<int>(i);
  }
  return -1;
}

int Model::find_body(const std::string& body_name) const {
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (bodies[i].name == body_name) return static_cast<int>(i);
  }
  return -1;
}

bool Model::has_time_law() const {
  return std::any_of(drivers.begin(), drivers.end(), [](const Driver& d) { return d.law.has_value(); });
}

namespace {

// Built by appending: GCC 12 at -O3 gives a false -Wrestrict warning for "'" + name + "'".
std::string quoted_name(const std::string& name) {
  std::string out;
  out.reserve(name.size() + 2);
  out.append(1, '\'').append(name).append(1, '\'');
  return out;
}

// Below this (SI: rad/s or m/s) a driver's speed is a mistake, not a motion.
constexpr double kMinDriverSpeed = 1e-12;
// Past this the speed's powers in the higher derivatives (up to omega^5) overflow, and the sweep
// cannot follow the motion: `speed: 1e150 rad/s` was blamed on a singular position. (A huge
// acceleration is blamed at its driver when the derivatives overflow.)
constexpr double kMaxDriverSpeed = 1e30;

// A point's or a centre of mass's coordinates, in the model's length unit: past this, distances
// overflow or every other point looks coincident.
constexpr double kMaxCoordinate = 1e100;

// Checks run in the order a reader would fix them: names first, then the references
// between entities, then geometry, so that the first error reported is the root cause.
class Validator {
 public:
  explicit Validator(const Model& model) : m_(model) {}

  void run() {
    if (m_.points.empty()) fail({EntityRef::Kind::Model, -1}, "the model has no points");
    compute_tolerance();
    check_points();
    check_bodies();
    check_sliders();
    check_single_point_bodies();
    check_attachment();
    check_slots();
    check_sweep();  // before the drivers, whose travel is over the sweep's duration
    check_drivers();
    check_mass_properties();
    check_loads();
    check_springs();
    check_frictions();
  }

 private:
  const Model& m_;
  double tolerance_ = 0.0;
  double size_ = 0.0;                // the drawing's bounding-box diagonal (m)
  std::vector<int> slider_of_body_;  // slider index per body, -1 when none

  [[noreturn]] static void fail(EntityRef where, const std::string& message) { throw ModelError(where, message); }
  static EntityRef ref(EntityRef::Kind kind, std::size_t index) { return EntityRef{kind, static_cast<int>(index)}; }

  bool valid_point(int i) const { return i >= 0 && i < static_cast<int>(m_.points.size()); }
  bool valid_body(int i) const { return i >= 0 && i < static_cast<int>(m_.bodies.size()); }

  // "#3" for an index with no name. (Built by append: g++ 12 warns falsely, -Wrestrict,
  // on "#" + std::to_string(i).)
  static std::string index_name(int i) { return std::string(1, '#').append(std::to_string(i)); }

  std::string point_name(int i) const {
    if (!valid_point(i)) return index_name(i);
    return quoted_name(m_.points[i].name);
  }
  std::string body_name(int i) const {
    if (!valid_body(i)) return index_name(i);
    return quoted_name(m_.bodies[i].name);
  }
  std::string slider_name(std::size_t i) const {
    const int body = m_.sliders[i].body;
    if (valid_body(body)) return "the slider of body " + body_name(body);
    return "slider #" + std::to_string(i + 1);
  }
  std::string slot_name(std::size_t i) const {
    const int point = m_.slots[i].point;
    if (valid_point(point)) return "the slot of point " + point_name(point);
    return "slot #" + std::to_string(i + 1);
  }

  bool body_has_point(int body, int point) const {
    const auto& pts = m_.bodies[body].points;
    return std::find(pts.begin(), pts.end(), point) != pts.end();
  }

  // Coordinates are in metres but models range from watch parts to cranes, so
  // "coincident" is judged relative to the size of the drawing, not in absolute terms.
  void compute_tolerance() {
    Eigen::Vector2d lo = m_.points.front().position, hi = lo;
    for (const Point& p : m_.points) {
      if (!p.position.allFinite()) continue;
      lo = lo.cwiseMin(p.position);
      hi = hi.cwiseMax(p.position);
    }
    size_ = (hi - lo).norm();
    tolerance_ = std::isfinite(size_) ? 1e-9 * size_ : 0.0;
  }

  // A driver's value in the model's unit, for messages: a length as length_text writes it.
  std::string value_text(const Driver& d, double si) const {
    if (!d.is_angular()) return length_text(si);
    std::ostringstream s;
    s.precision(6);
    s << si / m_.units.angle_scale << " " << m_.units.angle;
    return s.str();
  }

  // A length in the model's unit, for messages.
  std::string length_text(double metres) const {
    std::ostringstream s;
    s.precision(6);
    s << metres / m_.units.length_scale << " " << m_.units.length;
    return s.str();
  }
  bool coincide(int a, int b) const { return (m_.points[a].position - m_.points[b].position).norm() <= tolerance_; }

  void check_points() {
    std::set<std::string> seen;
    for (std::size_t i = 0; i < m_.points.size(); ++i) {
      const Point& p = m_.points[i];
      const auto where = ref(EntityRef::Kind::Point, i);
      if (p.name.empty()) fail(where, "point #" + std::to_string(i + 1) + " has no name");
      if (!seen.insert(p.name).second) fail(where, "two points are named '" + p.name + "'");
      if (!p.position.allFinite()) fail(where, "point '" + p.name + "' has a coordinate that is not a finite number");
      check_coordinates(p.position, where, "point '" + p.name + "'");
    }
  }

  // `what` (a point, a centre of mass) within kMaxCoordinate of the origin in the length unit.
  void check_coordinates(const Eigen::Vector2d& position, EntityRef where, const std::string& what) const {
    if (!(position.cwiseAbs().maxCoeff() / m_.units.length_scale <= kMaxCoordinate))
      fail(where, what + " has a coordinate beyond 1e100 " + m_.units.length + ": check the number and the length unit");
  }

  void check_bodies() {
    std::set<std::string> seen;
    for (std::size_t i = 0; i < m_.bodies.size(); ++i) {
      const Body& b = m_.bodies[i];
      const auto where = ref(EntityRef::Kind::Body, i);
      if (b.name.empty()) fail(where, "body #" + std::to_string(i + 1) + " has no name");
      const std::string name = "body '" + b.name + "'";
      if (!seen.insert(b.name).second) fail(where, "two bodies are named '" + b.name + "'");
      if (b.points.empty()) fail(where, name + " has no points");
      std::set<int> listed;
      for (int p : b.points) {
        if (!valid_point(p)) fail(where, name + " refers to point #" + std::to_string(p) + ", which does not exist");
        if (!listed.insert(p).second) fail(where, name + " lists point " + point_name(p) + " twice");
      }
      if (b.points.size() >= 2 && coincide(b.points[0], b.points[1])) {
        const double apart = (m_.points[b.points[0]].position - m_.points[b.points[1]].position).norm();
        if (apart == 0.0)
          fail(where, name + " has zero length: points " + m_.points[b.points[0]].name + " and " +
                          m_.points[b.points[1]].name + " coincide");
        // Apart, but by less than the drawing's resolution: one far point makes the others so.
        fail(where, name + " is " + length_text(apart) + " long, less than a billionth of the drawing's size (" +
                        length_text(size_) + "), so its points " + m_.points[b.points[0]].name + " and " +
                        m_.points[b.points[1]].name +
                        " count as coinciding: check the coordinates far from the others");
      }
      const bool all_ground = std::all_of(b.points.begin(), b.points.end(), [&](int p) { return m_.points[p].ground; });
      if (all_ground) {
        fail(where, name + " has only ground points, so it cannot move: list its points under ground instead");
      }
      if (b.length) {
        if (b.points.size() != 2) {
          fail(where, name + " has " + std::to_string(b.points.size()) +
                          " points: an exact length applies only to a body with two points");
        }
        if (!std::isfinite(*b.length) || *b.length <= 0.0) {
          fail(where, "the length of " + name + " must be a positive number");
        }
        // The drawing is the assembly's first guess and the scale of every tolerance: a length a
        // million times the drawing is a unit mistake, not a linkage nbar can assemble.
        if (*b.length > 1e6 * size_) {
          fail(where, "the length of " + name + ", " + length_text(*b.length) +
                          ", is more than a million times the "
                          "drawing's size (" +
                          length_text(size_) + "): check the number and the length unit");
        }
      }
    }
  }

  // The body or ground that carries both guide points of a slider or a slot. Two bodies
  // sharing both points move together, so any one of them is a valid owner.
  struct GuideOwners {
    bool ground = false;
    std::vector<int> bodies;
    bool empty() const { return !ground && bodies.empty(); }
  };
  GuideOwners guide_owners(const std::array<int, 2>& along, int excluded_body) const {
    GuideOwners owners;
    owners.ground = m_.points[along[0]].ground && m_.points[along[1]].ground;
    for (std::size_t b = 0; b < m_.bodies.size(); ++b) {
      const int body = static_cast<int>(b);
      if (body == excluded_body) continue;
      if (body_has_point(body, along[0]) && body_has_point(body, along[1])) owners.bodies.push_back(body);
    }
    return owners;
  }

  void check_guide(EntityRef where, const std::string& name, const std::array<int, 2>& along) const {
    for (int p : along) {
      if (!valid_point(p)) {
        fail(where, "the guide of " + name + " refers to point #" + std::to_string(p) + ", which does not exist");
      }
    }
    if (along[0] == along[1]) fail(where, "the guide of " + name + " uses point " + point_name(along[0]) + " twice");
    if (coincide(along[0], along[1])) {
      fail(where, "the guide points " + m_.points[along[0]].name + " and " + m_.points[along[1]].name + " of " + name +
                      " coincide, so they define no direction");
    }
  }

  // The drawn pose is the start of the assembly, and the branch it picks: a sliding point drawn
  // off its guide would be moved onto it there silently, perhaps far. Off by more than rounding
  // (kOffGuide of the drawing's size), it is the model's mistake.
  void check_on_guide(EntityRef where, const std::string& name, int point, const std::array<int, 2>& along) const {
    constexpr double kOffGuide = 1e-3;
    const Eigen::Vector2d a = m_.points[along[0]].position, b = m_.points[along[1]].position;
    const Eigen::Vector2d p = m_.points[point].position;
    const Eigen::Vector2d u = (b - a).normalized();
    const double off = std::abs(u.x() * (p - a).y() - u.y() * (p - a).x());
    if (off > kOffGuide * size_) {
      fail(where, name + ": point " + point_name(point) + " is drawn " + length_text(off) + " off the line through " +
                      point_name(along[0]) + " and " + point_name(along[1]) +
                      " that it slides along; draw it on that line (the drawn pose is where the assembly starts)");
    }
  }

  void check_sliders() {
    slider_of_body_.assign(m_.bodies.size(), -1);
    for (std::size_t i = 0; i < m_.sliders.size(); ++i) {
      const Slider& s = m_.sliders[i];
      const auto where = ref(EntityRef::Kind::Slider, i);
      const std::string name = slider_name(i);
      if (!valid_body(s.body)) {
        fail(where, "slider #" + std::to_string(i + 1) + " refers to body #" + std::to_string(s.body) +
                        ", which does not exist");
      }
      if (slider_of_body_[s.body] >= 0) fail(where, "body " + body_name(s.body) + " has two sliders");
      slider_of_body_[s.body] = static_cast<int>(i);
      if (!valid_point(s.point)) {
        fail(where, name + " refers to point #" + std::to_string(s.point) + ", which does not exist");
      }
      if (!body_has_point(s.body, s.point)) {
        fail(where, name + " moves point " + point_name(s.point) + ", which is not one of the points of body " +
                        body_name(s.body));
      }
      check_guide(where, name, s.along);
      if (s.point == s.along[0] || s.point == s.along[1]) {
        fail(where, name + ": the sliding point " + point_name(s.point) + " cannot also be a guide point");
      }
      if (guide_owners(s.along, s.body).empty()) {
        fail(where, "the guide points of a slider must belong to one other body or to ground: " +
                        point_name(s.along[0]) + " and " + point_name(s.along[1]) + " of " + name + " do not");
      }
      check_on_guide(where, name, s.point, s.along);
    }
  }

  // A lone point gives a body no direction; only a slider, which keeps the body parallel
  // to its guide, supplies one.
  void check_single_point_bodies() const {
    for (std::size_t i = 0; i < m_.bodies.size(); ++i) {
      if (m_.bodies[i].points.size() == 1 && slider_of_body_[i] < 0) {
        fail(ref(EntityRef::Kind::Body, i),
             "body '" + m_.bodies[i].name +
                 "' has a single point, so its orientation is undefined: give it a second point or make it "
                 "the body of a slider");
      }
    }
  }

  void check_attachment() const {
    std::vector<bool> attached(m_.points.size(), false);
    for (const Body& b : m_.bodies) {
      for (int p : b.points) attached[p] = true;
    }
    for (std::size_t i = 0; i < m_.points.size(); ++i) {
      if (!attached[i] && !m_.points[i].ground) {
        fail(ref(EntityRef::Kind::Point, i),
             "point '" + m_.points[i].name + "' is not attached to any body or to ground");
      }
    }
  }

  void check_slots() const {
    for (std::size_t i = 0; i < m_.slots.size(); ++i) {
      const Slot& s = m_.slots[i];
      const auto where = ref(EntityRef::Kind::Slot, i);
      const std::string name = slot_name(i);
      if (!valid_point(s.point)) {
        fail(where, "slot #" + std::to_string(i + 1) + " refers to point #" + std::to_string(s.point) +
                        ", which does not exist");
      }
      check_guide(where, name, s.along);
      if (s.point == s.along[0] || s.point == s.along[1]) {
        fail(where, name + ": point " + point_name(s.point) + " cannot be one of its own guide points");
      }
      const GuideOwners owners = guide_owners(s.along, -1);
      if (owners.empty()) {
        fail(where, "the guide points of a slot must belong to one body or to ground: " + point_name(s.along[0]) +
                        " and " + point_name(s.along[1]) + " of " + name + " do not");
      }
      if (owners.ground && m_.points[s.point].ground) {
        fail(where, name + ": point " + point_name(s.point) + " is on ground, like its guide, so it cannot slide");
      }
      for (int b : owners.bodies) {
        if (body_has_point(b, s.point)) {
          fail(where, name + ": point " + point_name(s.point) + " belongs to body " + body_name(b) +
                          ", which also carries the guide, so it cannot slide");
        }
      }
      check_on_guide(where, name, s.point, s.along);
    }
  }

  void check_drivers() const {
    std::set<std::string> seen;
    const bool time_sweep = m_.has_time_law();
    const double size = mechanism_size();
    for (std::size_t i = 0; i < m_.drivers.size(); ++i) {
      const Driver& d = m_.drivers[i];
      const auto where = ref(EntityRef::Kind::Driver, i);
      if (d.name.empty()) fail(where, "driver #" + std::to_string(i + 1) + " has no name");
      if (!seen.insert(d.name).second) fail(where, "two drivers are named '" + d.name + "': give one a `name:`");
      const std::string name = "driver '" + d.name + "'";
      // A driver's name is its column in the results: 'rocker.angle' made two columns of that name.
      if (d.name == "step" || d.name == "t" || d.name.find('.') != std::string::npos)
        fail(where, name +
                        ": a driver's name is its column in the results, so it cannot be 'step' or 't' or hold "
                        "a '.' (which joins a name to its quantity, as in rocker.angle): give it another `name:`");
      check_driven(d, where, name);
      check_motion(d, time_sweep, size, where, name);
      check_rocking(d, where, name);
    }
  }

  // A rocking driver turns back where the mechanism's path does, at its own speed: it must be the
  // only input (another one's motion would not turn with it) and keep its speed (no law, no
  // acceleration), and a number of cycles means nothing without it.
  void check_rocking(const Driver& d, EntityRef where, const std::string& name) const {
    if (d.at_limits != AtLimits::Reverse) {
      if (d.cycles)
        fail(where, name + ": `cycles` counts the cycles of a rocking motion: it needs `at_limits: reverse`");
      return;
    }
    const std::string rocks = name + " turns back at the mechanism's limits (`at_limits: reverse`), ";
    if (m_.drivers.size() != 1)
      fail(where, rocks + "which needs it to be the model's only driver (this model has " +
                      std::to_string(m_.drivers.size()) + ")");
    if (d.law) fail(where, rocks + "at its speed: it cannot also follow a law");
    if (d.accel != 0.0) fail(where, rocks + "at a steady speed: it takes no `accel`");
    if (d.free) fail(where, rocks + "so it cannot be free");
    if (d.cycles && (*d.cycles < 1 || *d.cycles > kMaxRockingCycles))
      fail(where, name + ": `cycles` is a whole number from 1 to " + std::to_string(kMaxRockingCycles) + ", not " +
                      std::to_string(*d.cycles));
  }

  // The mechanism's size: the diagonal of its points' bounding box.
  double mechanism_size() const {
    Eigen::Vector2d low = Eigen::Vector2d::Constant(0.0), high = low;
    if (!m_.points.empty()) low = high = m_.points.front().position;
    for (const Point& p : m_.points) {
      low = low.cwiseMin(p.position);
      high = high.cwiseMax(p.position);
    }
    return (high - low).norm();
  }

  // What a driver drives (a body's angle, a distance, a slider) exists and can move.
  void check_driven(const Driver& d, EntityRef where, const std::string& name) const {
    switch (d.kind) {
      case DriverKind::Angle:
        if (!valid_body(d.body)) {
          fail(where, name + " refers to body #" + std::to_string(d.body) + ", which does not exist");
        }
        if (m_.bodies[d.body].points.size() < 2) {
          fail(where, name + ": body " + body_name(d.body) + " needs two points to have an angle");
        }
        if (d.relative_to >= 0) {
          if (!valid_body(d.relative_to)) {
            fail(where, name + " is relative to body #" + std::to_string(d.relative_to) + ", which does not exist");
          }
          if (d.relative_to == d.body) fail(where, name + " cannot be relative to its own body");
          if (m_.bodies[d.relative_to].points.size() < 2) {
            fail(where, name + ": body " + body_name(d.relative_to) + " needs two points to have an angle");
          }
        }
        break;
      case DriverKind::Distance:
        for (int p : d.points) {
          if (!valid_point(p)) {
            fail(where, name + " refers to point #" + std::to_string(p) + ", which does not exist");
          }
        }
        if (d.points[0] == d.points[1]) {
          fail(where, name + " measures the distance from point " + point_name(d.points[0]) + " to itself");
        }
        if (m_.points[d.points[0]].ground && m_.points[d.points[1]].ground) {
          fail(where, name + " drives the distance between two ground points, which cannot change");
        }
        for (std::size_t b = 0; b < m_.bodies.size(); ++b) {
          const int body = static_cast<int>(b);
          if (body_has_point(body, d.points[0]) && body_has_point(body, d.points[1])) {
            fail(where,
                 name + " drives the distance between two points of body " + body_name(body) + ", which cannot change");
          }
        }
        break;
      case DriverKind::Slide:
        if (d.slider < 0 || d.slider >= static_cast<int>(m_.sliders.size())) {
          fail(where, name + " refers to slider #" + std::to_string(d.slider) + ", which does not exist");
        }
        break;
    }
  }

  // A driver's motion: finite numbers, a speed that means one, time running forwards, a travel
  // the sweep can follow, and no `from`, `to` or law that would be ignored.
  void check_motion(const Driver& d, bool time_sweep, double size, EntityRef where, const std::string& name) const {
    const auto finite = [](const std::optional<double>& v) { return !v || std::isfinite(*v); };
    if (!finite(d.from)) fail(where, name + ": `from` is not a finite number");
    if (!finite(d.to)) fail(where, name + ": `to` is not a finite number");
    if (!std::isfinite(d.speed)) fail(where, name + ": the speed is not a finite number");
    if (!std::isfinite(d.accel)) fail(where, name + ": the acceleration is not a finite number");
    if (d.speed == 0.0) fail(where, name + ": the speed must not be zero");
    // Time is travel over speed: a speed that is zero in all but name (1e-308) would make
    // it infinite, and every rate computed from it meaningless.
    if (std::abs(d.speed) < kMinDriverSpeed)
      fail(where, name +
                      ": the speed is too small to mean a motion (its size must be at least 1e-12 rad/s or "
                      "m/s); give a real speed, or leave `speed` out");
    if (std::abs(d.speed) > kMaxDriverSpeed)
      fail(where, name +
                      ": the speed is too large to compute with (its size must be at most 1e30 rad/s or m/s, "
                      "beyond which its powers in the accelerations and higher derivatives overflow)");
    // A free driver's initial speed sets the kinetic energy and the velocity products of every
    // acceleration: as large, it overflows them (1e300 gave rows of NaN and a step of -nan s).
    if (!std::isfinite(d.initial_speed)) fail(where, name + ": the initial speed is not a finite number");
    if (std::abs(d.initial_speed) > kMaxDriverSpeed)
      fail(where, name +
                      ": the initial speed is too large to compute with (its size must be at most 1e30 rad/s "
                      "or m/s, beyond which the kinetic energy and the accelerations overflow)");
    if (d.from && d.to && !std::isfinite((*d.to - *d.from) / d.speed))
      fail(where, name + ": its travel over its speed is not a finite time");
    // The time a sample is at is its travel over the speed: against each other they gave t < 0,
    // a crank going from 360 to 0 at +120 rpm with omega +720 deg/s.
    if (d.from && d.to && (*d.to - *d.from) * d.speed < 0.0)
      fail(where, name + " goes from " + value_text(d, *d.from) + " to " + value_text(d, *d.to) +
                      " against the sign of its speed, so time would run backwards: make the speed " +
                      (d.speed > 0.0 ? "negative" : "positive") + " (or swap `from` and `to`)");
    check_travel(d, time_sweep, size, where, name);
    if (d.law && (d.from || d.to)) {
      fail(where, name + " follows a law, so it takes no `from` or `to`");
    }
    // In a time sweep a driver without a law just runs at its speed from `from`;
    // silently ignoring a `to` would hide a misunderstanding.
    if (time_sweep && !d.law && d.to) {
      fail(where, name +
                      ": `to` has no meaning when another driver follows a time law (drivers without a "
                      "law then move at their speed from `from`)");
    }
  }

  // The sweep tracks the motion in steps no longer than a fraction of a turn or of the
  // mechanism's size, so its work grows with the travel whatever the number of samples: an
  // angle driver may turn at most kMaxTurns times, a distance or slide at most kMaxSizes
  // times the mechanism's size.
  void check_travel(const Driver& d, bool time_sweep, double size, EntityRef where, const std::string& name) const {
    constexpr double kMaxTurns = kMaxDriverTurns, kMaxSizes = 1000.0;
    double travel = 0.0;
    std::string_view inputs = "`from`, `to`, the speed";
    if (d.law) {
      travel = law_travel(*d.law);
      inputs = "the law";
      where.law = 0;
    } else if (time_sweep) {
      const double t = m_.sweep.duration;
      travel = std::abs(d.speed * t) + 0.5 * std::abs(d.accel) * t * t;
    } else if (d.from && d.to) {
      travel = std::abs(*d.to - *d.from);
    }
    std::ostringstream s;
    s.precision(3);
    if (d.is_angular()) {
      const double turns = travel / (2 * std::numbers::pi);
      if (turns <= kMaxTurns) return;
      s << name << " turns " << turns << " times over the sweep; a sweep is limited to " << static_cast<int>(kMaxTurns)
        << " turns (the work grows with the travel): check " << inputs << " and the units";
    } else {
      if (!(size > 0.0) || travel <= kMaxSizes * size) return;
      s << name << " travels " << travel / size << " times the mechanism's size over the sweep; a sweep is limited to "
        << static_cast<int>(kMaxSizes) << " times (the work grows with the travel): check " << inputs
        << " and the units";
    }
    fail(where, s.str());
  }

  // How far a law moves over the sweep's duration, summed over evenly spaced times (at most
  // kTravelSamples of them, so an oscillation faster than that is undercounted, never
  // overcounted). Times where the law is undefined are skipped: the laws' check reports them.
  double law_travel(const Law& law) const {
    constexpr int kTravelSamples = 1000;
    const double duration = m_.sweep.duration;
    const double samples = duration / m_.sweep.time_step.value_or(duration / 100.0);
    const int n = std::isfinite(samples) ? static_cast<int>(std::clamp(std::ceil(samples), 1.0, double(kTravelSamples)))
                                         : kTravelSamples;
    double travel = 0.0;
    std::optional<double> previous;
    for (int k = 0; k <= n; ++k) {
      try {
        const double x = law.value(duration * k / n);
        if (previous) travel += std::abs(x - *previous);
        previous = x;
      } catch (const Error&) {
        previous.reset();
      }
    }
    return travel;
  }

  void check_sweep() const {
    const SweepSpec& s = m_.sweep;
    const EntityRef where{EntityRef::Kind::Sweep, -1};
    if (s.steps < 1) fail(where, "the sweep needs at least 1 step (got " + std::to_string(s.steps) + ")");
    if (!std::isfinite(s.duration) || s.duration <= 0.0) fail(where, "the sweep duration must be positive");
    if (s.time_step) {
      if (!std::isfinite(*s.time_step) || *s.time_step <= 0.0) fail(where, "the sweep time step must be positive");
      if (*s.time_step > s.duration) fail(where, "the sweep time step is longer than its duration");
    }
    // A time sweep's samples are its duration over its step: a count that is not even a number
    // is the model's mistake; a finite one is bounded by sweep_path against the caller's limit
    // (as a double, before anything converts it to an integer).
    if (m_.has_time_law()) {
      const double samples = s.duration / s.time_step.value_or(s.duration / 100.0);
      if (!std::isfinite(samples))
        fail(where,
             "the sweep's duration over its time step makes more samples than nbar can count: "
             "give a longer `step` or a shorter `duration`");
    }
  }

  // Shapes, materials and given mass properties: what the dynamics and stress stages need.
  void check_mass_properties() const {
    for (std::size_t i = 0; i < m_.bodies.size(); ++i) {
      const Body& b = m_.bodies[i];
      const auto where = ref(EntityRef::Kind::Body, i);
      const std::string name = "body " + quoted_name(b.name);
      if (b.shape) {
        try {
          check_region(*b.shape);
        } catch (const Error& error) {
          fail(where, "the shape of " + name + " is not valid: " + error.what());
        }
        if (!std::isfinite(b.thickness) || b.thickness <= 0.0) {
          fail(where, name + " has a shape, so its thickness must be a positive number");
        }
        // (A density or a gravity that is not a number is reported below, as such.)
        if (b.material && !b.inertia && b.material->density > 0.0 && std::isfinite(b.material->density) &&
            m_.gravity.allFinite())
          check_weighable(b, where, name);
      }
      if (b.material) {
        const Material& mat = *b.material;
        const std::string what = mat.name.empty() ? "the material of " + name : "material " + quoted_name(mat.name);
        if (!std::isfinite(mat.density) || mat.density <= 0.0) {
          fail(where, what + " needs a positive density");
        }
        if (mat.yield_strength && (!std::isfinite(*mat.yield_strength) || *mat.yield_strength <= 0.0)) {
          fail(where, "the yield strength of " + what + " must be a positive number");
        }
        if (mat.youngs_modulus && (!std::isfinite(*mat.youngs_modulus) || *mat.youngs_modulus <= 0.0)) {
          fail(where, "Young's modulus of " + what + " must be a positive number");
        }
        if (mat.poisson_ratio && !(*mat.poisson_ratio >= 0.0 && *mat.poisson_ratio < 0.5)) {
          fail(where, "Poisson's ratio of " + what + " must be at least 0 and less than 0.5");
        }
      }
      if (b.inertia) {
        const GivenInertia& g = *b.inertia;
        if (!std::isfinite(g.mass) || g.mass < 0.0) fail(where, "the mass of " + name + " must not be negative");
        if (m_.gravity.allFinite() && !std::isfinite(g.mass * m_.gravity.norm()))
          fail(where, "the weight of " + name + " (its mass times gravity) is too large to compute with");
        if (!g.cg.allFinite()) fail(where, "the centre of mass of " + name + " is not a finite point");
        // 1e300 m away it was taken for a body without inertia: its moment about the frame overflowed.
        check_coordinates(g.cg, where, "the centre of mass of " + name);
        if (!b.points.empty() &&
            !std::isfinite(g.mass * (g.cg - m_.points[b.points.front()].position).squaredNorm()))
          fail(where, "the centre of mass of " + name + " is too far from its points for its mass (" +
                          "the moment of its mass about them is too large to compute with)");
        if (!std::isfinite(g.inertia) || g.inertia < 0.0) {
          fail(where, "the moment of inertia of " + name + " must not be negative");
        }
      } else {
        if (b.shape && !b.material) fail(where, name + " has a shape but no material and no given mass");
        if (b.material && !b.shape) fail(where, name + " has a material but no shape to weigh and no given mass");
      }
    }
    if (!m_.gravity.allFinite()) fail({EntityRef::Kind::Model, -1}, "gravity is not a finite vector");
  }

  // A body weighed from its shape: density x thickness x area (and the polar moment) must be
  // numbers, and so must its weight; 1e306 m thick overflows.
  void check_weighable(const Body& b, EntityRef where, const std::string& name) const {
    const AreaProperties a = area_properties(*b.shape);
    const double per_area = b.material->density * b.thickness;
    const double mass = per_area * a.area;
    if (!std::isfinite(mass) || !std::isfinite(per_area * a.polar()))
      fail(where, "the mass of " + name +
                      " (density x thickness x area) is too large to compute with: check its `thickness` and its "
                      "material's density");
    // A mass that is a number, with a gravity so large that the weight is not: gravity's fault.
    if (!std::isfinite(mass * m_.gravity.norm()))
      fail(where, "the weight of " + name + " (its mass times gravity) is too large to compute with: check `gravity`");
  }

  // A law that was never parsed has no text.
  static bool has_law(const Law& law) { return !law.text().empty(); }

  void check_loads() const {
    for (std::size_t i = 0; i < m_.point_loads.size(); ++i) {
      const PointLoad& load = m_.point_loads[i];
      const auto where = ref(EntityRef::Kind::PointLoad, i);
      const std::string name = "force #" + std::to_string(i + 1);
      if (!valid_point(load.point)) {
        fail(where, name + " acts on point #" + std::to_string(load.point) + ", which does not exist");
      }
      if (load.body != -1) {
        if (!valid_body(load.body)) {
          fail(where, name + " acts on body #" + std::to_string(load.body) + ", which does not exist");
        }
        if (!body_has_point(load.body, load.point)) {
          fail(where, name + " acts on point " + point_name(load.point) + " of body " + body_name(load.body) +
                          ", which does not have that point");
        }
      }
      if (!has_law(load.fx) || !has_law(load.fy)) fail(where, name + " has no value for fx or fy");
    }
    for (std::size_t i = 0; i < m_.torques.size(); ++i) {
      const BodyTorque& torque = m_.torques[i];
      const auto where = ref(EntityRef::Kind::Torque, i);
      const std::string name = "torque #" + std::to_string(i + 1);
      if (!valid_body(torque.body)) {
        fail(where, name + " acts on body #" + std::to_string(torque.body) + ", which does not exist");
      }
      if (!has_law(torque.torque)) fail(where, name + " on body " + body_name(torque.body) + " has no value");
    }
  }

  void check_springs() const {
    std::set<std::string> seen;
    for (std::size_t i = 0; i < m_.springs.size(); ++i) {
      const Spring& s = m_.springs[i];
      const auto where = ref(EntityRef::Kind::Spring, i);
      if (s.name.empty()) fail(where, "spring #" + std::to_string(i + 1) + " has no name");
      if (!seen.insert(s.name).second) fail(where, "two springs are named " + quoted_name(s.name));
      const std::string name = "spring " + quoted_name(s.name);
      for (int p : s.points) {
        if (!valid_point(p)) fail(where, name + " refers to point #" + std::to_string(p) + ", which does not exist");
      }
      if (s.points[0] == s.points[1]) fail(where, name + " joins point " + point_name(s.points[0]) + " to itself");
      const auto non_negative = [](double v) { return std::isfinite(v) && v >= 0.0; };
      if (!non_negative(s.stiffness)) fail(where, "the stiffness of " + name + " must not be negative");
      if (!non_negative(s.damping)) fail(where, "the damping of " + name + " must not be negative");
      if (!non_negative(s.free_length)) fail(where, "the free length of " + name + " must not be negative");
      if (s.stiffness > kMaxLoadCoefficient) fail(where, "the stiffness of " + name + " is out of range");
      if (s.damping > kMaxLoadCoefficient) fail(where, "the damping of " + name + " is out of range");
    }
  }

  // Friction in joints (`nbar simulate`): a pin between two links that meet there, an existing
  // slider or slot, coefficients in [0, kMaxLoadCoefficient] and a positive creep speed.
  void check_frictions() const {
    for (std::size_t i = 0; i < m_.frictions.size(); ++i) {
      const JointFriction& f = m_.frictions[i];
      const auto where = ref(EntityRef::Kind::Friction, i);
      const std::string name = "friction #" + std::to_string(i + 1);
      using Joint = JointFriction::Joint;
      if (f.joint == Joint::Revolute) {
        if (!valid_point(f.index))
          fail(where, name + " is at point #" + std::to_string(f.index) + ", which does not exist");
        for (int link : f.links) {
          const bool meets = link == -1 ? m_.points[f.index].ground : valid_body(link) && body_has_point(link, f.index);
          if (!meets) fail(where, name + " names a link that does not meet at point " + point_name(f.index));
        }
        if (f.links[0] == f.links[1]) fail(where, name + " acts between a link and itself");
      } else {
        const int count = static_cast<int>(f.joint == Joint::Slider ? m_.sliders.size() : m_.slots.size());
        if (f.index < 0 || f.index >= count) fail(where, name + " names a slider or slot that does not exist");
      }
      const auto in_range = [](double v) { return std::isfinite(v) && v >= 0.0 && v <= kMaxLoadCoefficient; };
      if (!in_range(f.viscous)) fail(where, "the viscous coefficient of " + name + " is negative or out of range");
      if (!in_range(f.coulomb)) fail(where, "the Coulomb friction of " + name + " is negative or out of range");
      if (!(std::isfinite(f.creep_speed) && f.creep_speed > 0.0))
        fail(where, "the creep speed of " + name + " must be positive");
    }
  }
};

}  // namespace

void validate(const Model& model) { Validator(model).run(); }

}  // namespace nbar
