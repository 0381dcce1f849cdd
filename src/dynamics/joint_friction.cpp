#include "joint_friction.hpp"

#include <cmath>

#include "nbar/dynamics/inverse_dynamics.hpp"

namespace nbar {

namespace {

Eigen::Vector2d perp(const Eigen::Vector2d& v) { return {-v.y(), v.x()}; }

// grad(s) . dq for one relative coordinate s, as its gradient on each point involved.
class RelativeCoordinate {
 public:
  RelativeCoordinate(const Mechanism& mech, const Eigen::VectorXd& q) : mech_(mech), q_(q) {}

  // d(theta) of a link = u x du / |u|^2, u its frame's direction (the ground does not turn).
  void add_angle(int link, double sign) {
    if (link < 0) return;
    const BodyFrame frame = body_frame(mech_.model(), link);
    if (frame.from < 0) return;
    const Eigen::Vector2d u = at(frame.to) - at(frame.from);
    const Eigen::Vector2d on_to = sign * perp(u) / u.squaredNorm();
    add(frame.to, on_to);
    add(frame.from, -on_to);
  }

  // s = (r_point - r_a) . e with e = (r_b - r_a) / |r_b - r_a|: the point's place along its guide.
  void add_slide(int point, int a, int b) {
    const Eigen::Vector2d d = at(b) - at(a), w = at(point) - at(a);
    const double length = d.norm();
    const Eigen::Vector2d e = d / length;
    const Eigen::Vector2d along_guide = (w - e.dot(w) * e) / length;  // ds/d(r_b): the guide turning
    add(point, e);
    add(b, along_guide);
    add(a, -e - along_guide);
  }

  double rate(const Eigen::VectorXd& qd) const { return gradient_.dot(qd); }
  const Eigen::VectorXd& gradient() const { return gradient_; }

 private:
  Eigen::Vector2d at(int point) const { return mech_.point_position(point, q_); }
  void add(int point, const Eigen::Vector2d& v) {
    const int col = mech_.column_of(point);
    if (col >= 0) gradient_.segment<2>(col) += v;
  }

  const Mechanism& mech_;
  const Eigen::VectorXd& q_;
  Eigen::VectorXd gradient_ = Eigen::VectorXd::Zero(q_.size());
};

}  // namespace

double friction_force(const JointFriction& friction, double speed) {
  double force = -friction.viscous * speed;
  if (friction.coulomb > 0.0) force -= friction.coulomb * std::tanh(speed / friction.creep_speed);
  return force;
}

double add_joint_friction(const Mechanism& mech, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                          Eigen::VectorXd& loads) {
  const Model& m = mech.model();
  double dissipated = 0.0;
  for (const JointFriction& friction : m.frictions) {
    RelativeCoordinate s(mech, q);
    switch (friction.joint) {
      case JointFriction::Joint::Revolute:
        s.add_angle(friction.links[0], 1.0);
        s.add_angle(friction.links[1], -1.0);
        break;
      case JointFriction::Joint::Slider: {
        const Slider& slider = m.sliders[friction.index];
        s.add_slide(slider.point, slider.along[0], slider.along[1]);
        break;
      }
      case JointFriction::Joint::Slot: {
        const Slot& slot = m.slots[friction.index];
        s.add_slide(slot.point, slot.along[0], slot.along[1]);
        break;
      }
    }
    const double speed = s.rate(qd);
    const double force = friction_force(friction, speed);
    loads += force * s.gradient();
    dissipated -= force * speed;
  }
  return dissipated;
}

}  // namespace nbar
