#include "nbar/kinematics/loops.hpp"
#include "nbar/kinematics/loop_closure.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <set>
#include <sstream>

#include "model/plane_vectors.hpp"
#include "model/triangle.hpp"
#include "nbar/model/units.hpp"

namespace nbar {

namespace {

// Links are numbered 0 for the ground and body + 1 for bodies.
struct Edge {
  int link;
  int point;
};

int body_of(int link) { return link - 1; }

std::string link_name(const Model& m, int body) { return body < 0 ? std::string("ground") : m.bodies[body].name; }

bool has_angle_driver(const Model& m, int body, int frame_body) {
  for (const Driver& d : m.drivers)
    if (d.kind == DriverKind::Angle && d.body == body && d.relative_to == frame_body) return true;
  return false;
}

}  // namespace

std::vector<FourBarLoop> find_four_bar_loops(const Model& model) {
  const int links = static_cast<int>(model.bodies.size()) + 1;
  // Links meet at points. The walk goes link -> point -> link and leaves a link by another
  // point than it came in by, so a point shared by many links (a hub pinning thousands of
  // bodies) costs its links once per visit, not their square.
  std::vector<std::vector<int>> points_of(links);
  std::vector<std::vector<int>> links_at(model.points.size());
  for (std::size_t p = 0; p < model.points.size(); ++p)
    if (model.points[p].ground) {
      links_at[p].push_back(0);
      points_of[0].push_back(static_cast<int>(p));
    }
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    std::vector<int>& own = points_of[b + 1];
    own = model.bodies[b].points;
    std::sort(own.begin(), own.end());
    own.erase(std::unique(own.begin(), own.end()), own.end());
    for (int p : own) links_at[p].push_back(static_cast<int>(b) + 1);
  }
  // The links joined to `link`, each with the point they share, in the order of the points
  // and then of the links at a point, skipping the points in `except`.
  const auto for_each_neighbour = [&](int link, std::initializer_list<int> except, const auto& visit) {
    for (int p : points_of[link]) {
      if (std::find(except.begin(), except.end(), p) != except.end()) continue;
      for (int other : links_at[p])
        if (other != link) visit(Edge{other, p});
    }
  };

  std::set<std::array<int, 8>> seen;
  std::vector<FourBarLoop> loops;
  // The frame of a loop is its lowest-numbered link: the ground whenever the loop has it.
  for (int l0 = 0; l0 < links; ++l0) {
    for_each_neighbour(l0, {}, [&](const Edge& e1) {
      if (e1.link <= l0) return;
      for_each_neighbour(e1.link, {e1.point}, [&](const Edge& e2) {
        if (e2.link <= l0 || e2.link == e1.link) return;
        for_each_neighbour(e2.link, {e1.point, e2.point}, [&](const Edge& e3) {
          if (e3.link <= l0 || e3.link == e1.link || e3.link == e2.link) return;
          for_each_neighbour(e3.link, {e1.point, e2.point, e3.point}, [&](const Edge& e4) {
            if (e4.link != l0) return;
            std::array<int, 4> ls{l0, e1.link, e2.link, e3.link};
            std::array<int, 4> ps{e1.point, e2.point, e3.point, e4.point};
            std::sort(ls.begin(), ls.end());
            std::sort(ps.begin(), ps.end());
            std::array<int, 8> key{ls[0], ls[1], ls[2], ls[3], ps[0], ps[1], ps[2], ps[3]};
            if (!seen.insert(key).second) return;

            // Walk l0 -> e1.link -> e2.link -> e3.link -> l0; the input is the frame's
            // neighbour that carries a driver, else the lower-numbered one.
            FourBarLoop loop;
            loop.frame = body_of(l0);
            int first = e1.link, last = e3.link;
            int o2 = e1.point, a = e2.point, b = e3.point, o4 = e4.point;
            const bool first_driven = has_angle_driver(model, body_of(first), loop.frame);
            const bool last_driven = has_angle_driver(model, body_of(last), loop.frame);
            if ((last_driven && !first_driven) || (first_driven == last_driven && last < first)) {
              std::swap(first, last);
              std::swap(o2, o4);
              std::swap(a, b);
            }
            loop.input = body_of(first);
            loop.coupler = body_of(e2.link);
            loop.output = body_of(last);
            loop.o2 = o2;
            loop.a = a;
            loop.b = b;
            loop.o4 = o4;
            loop.name = link_name(model, loop.input) + "-" + link_name(model, loop.coupler) + "-" +
                        link_name(model, loop.output);
            loops.push_back(loop);
          });
        });
      });
    });
  }
  return loops;
}

GrashofReport classify_grashof(double frame, double input, double coupler, double output, double tolerance) {
  GrashofReport r;
  r.frame = frame;
  r.input = input;
  r.coupler = coupler;
  r.output = output;
  const std::array<double, 4> len{frame, input, coupler, output};
  const int shortest = static_cast<int>(std::min_element(len.begin(), len.end()) - len.begin());
  const double s = len[shortest];
  const double l = *std::max_element(len.begin(), len.end());
  const double sum = frame + input + coupler + output;
  r.margin = (sum - s - l) - (s + l);
  if (r.margin < -tolerance) {
    r.kind = GrashofClass::TripleRocker;
    return r;
  }
  if (r.margin <= tolerance) {
    r.kind = GrashofClass::ChangePoint;
    r.margin = 0.0;  // equal within the tolerance: don't print rounding noise
    // A shortest link turns fully relative to its neighbours. At a change point the shortest may
    // be several equal links (a parallelogram's two cranks, a rhombus's four), and which of them
    // compares smallest is rounding noise: every link within the tolerance of the shortest counts.
    for (int i = 0; i < 4; ++i) {
      if (len[i] > s + tolerance) continue;
      if (i == 0 || i == 1) r.input_turns_fully = true;
      if (i == 0 || i == 3) r.output_turns_fully = true;
    }
    return r;
  }
  // Otherwise (s + l < p + q) the shortest link is one link: two equal shortest links would make
  // l < q, and l is the longest.
  switch (shortest) {
    case 0:
      r.kind = GrashofClass::DoubleCrank;
      r.input_turns_fully = r.output_turns_fully = true;
      break;
    case 1:
      r.kind = GrashofClass::CrankRocker;
      r.input_turns_fully = true;
      break;
    case 3:
      r.kind = GrashofClass::CrankRocker;
      r.output_turns_fully = true;
      break;
    default: r.kind = GrashofClass::DoubleRocker; break;
  }
  return r;
}

GrashofReport classify_grashof(const FourBarLoop& loop, const std::vector<Eigen::Vector2d>& p, double tolerance) {
  return classify_grashof((p[loop.o4] - p[loop.o2]).norm(), (p[loop.a] - p[loop.o2]).norm(),
                          (p[loop.b] - p[loop.a]).norm(), (p[loop.o4] - p[loop.b]).norm(), tolerance);
}

std::string grashof_name(GrashofClass kind, bool input_turns_fully) {
  switch (kind) {
    case GrashofClass::CrankRocker: return input_turns_fully ? "crank-rocker" : "rocker-crank";
    case GrashofClass::DoubleCrank: return "double-crank";
    case GrashofClass::DoubleRocker: return "double-rocker";
    case GrashofClass::TripleRocker: return "triple-rocker";
    case GrashofClass::ChangePoint: return "change point";
  }
  return "";
}

std::string to_string(GrashofClass kind) { return grashof_name(kind); }

std::string describe(const GrashofReport& r, const FourBarLoop& loop, const Model& m) {
  std::ostringstream s;
  const double unit = m.units.length_scale;
  // Which side of Grashof's condition the name's class lies on, where the name alone may not say.
  const char* qualifier = r.kind == GrashofClass::DoubleRocker   ? " (Grashof)"
                          : r.kind == GrashofClass::TripleRocker ? " (non-Grashof)"
                                                                 : "";
  s << to_string(r.kind) << qualifier << ": frame " << link_name(m, loop.frame) << " " << r.frame / unit << ", input "
    << link_name(m, loop.input) << " " << r.input / unit << ", coupler " << link_name(m, loop.coupler) << " "
    << r.coupler / unit << ", output " << link_name(m, loop.output) << " " << r.output / unit << " " << m.units.length
    << "; (p + q) - (s + l) = " << r.margin / unit;
  std::vector<std::string> cranks;
  if (r.input_turns_fully) cranks.push_back(link_name(m, loop.input));
  if (r.output_turns_fully) cranks.push_back(link_name(m, loop.output));
  if (r.kind == GrashofClass::DoubleRocker) {
    s << "; the coupler turns fully, neither " << link_name(m, loop.input) << " nor " << link_name(m, loop.output)
      << " does";
  } else if (!cranks.empty()) {
    s << "; turns fully relative to " << link_name(m, loop.frame) << ": ";
    for (std::size_t i = 0; i < cranks.size(); ++i) s << (i ? " and " : "") << cranks[i];
    if (r.kind == GrashofClass::ChangePoint) s << " (through change points)";
  } else {
    s << "; no link turns fully";
  }
  return s.str();
}

InputLimits input_limits(double frame, double input, double coupler, double output, double frame_angle, double at) {
  constexpr double kPi = 3.14159265358979323846;
  InputLimits r;
  r.from = r.to = at;
  const double a = input, d = frame;
  // |alpha| (the input from the frame line) where the diagonal has length f: 0 when f is below
  // the shortest diagonal and pi above the longest.
  const auto alpha_at = [&](double f) { return angle_opposite(f, a, d); };
  const double lo = alpha_at(std::abs(coupler - output));  // below: the diagonal is too short
  const double hi = alpha_at(coupler + output);            // above: too long
  if (lo <= 0.0 && hi >= kPi) {
    r.full = true;
    return r;
  }
  const double alpha = std::remainder(at - frame_angle, 2.0 * kPi);  // [-pi, pi]
  const double size = std::abs(alpha);
  if (size < lo || size > hi) {
    r.closes = false;
    return r;
  }
  if (lo <= 0.0) {  // one range about the frame line's direction: [-hi, hi]
    r.from = at - alpha - hi;
    r.to = at - alpha + hi;
  } else if (hi >= kPi) {  // one range through the opposite direction: [lo, 2 pi - lo]
    const double beta = alpha < 0 ? alpha + 2.0 * kPi : alpha;
    r.from = at - beta + lo;
    r.to = at - beta + 2.0 * kPi - lo;
  } else if (alpha >= 0) {  // two ranges, [lo, hi] and [-hi, -lo]
    r.from = at - alpha + lo;
    r.to = at - alpha + hi;
  } else {
    r.from = at - alpha - hi;
    r.to = at - alpha - lo;
  }
  return r;
}

double link_length(const Model& m, int link, int from_point, int to_point) {
  const double drawn = (m.points[to_point].position - m.points[from_point].position).norm();
  if (link < 0) return drawn;
  const Body& body = m.bodies[link];
  if (!body.length || body.points.size() < 2) return drawn;
  const double first_two = (m.points[body.points[1]].position - m.points[body.points[0]].position).norm();
  return first_two > 0.0 ? drawn * (*body.length / first_two) : drawn;
}

std::string loop_closure_failure(const Model& m, const std::vector<FourBarLoop>& loops) {
  for (const FourBarLoop& loop : loops) {
    const std::array<int, 4> links{loop.input, loop.coupler, loop.output, loop.frame};
    const std::array<double, 4> lengths{
        link_length(m, loop.input, loop.o2, loop.a), link_length(m, loop.coupler, loop.a, loop.b),
        link_length(m, loop.output, loop.b, loop.o4), link_length(m, loop.frame, loop.o4, loop.o2)};
    const int longest = static_cast<int>(std::max_element(lengths.begin(), lengths.end()) - lengths.begin());
    const double others = lengths[0] + lengths[1] + lengths[2] + lengths[3] - lengths[longest];
    if (lengths[longest] - others <= 1e-9 * lengths[longest]) continue;
    const double unit = m.units.length_scale;
    const auto name = [&](int i) { return links[i] < 0 ? std::string("frame") : link_name(m, links[i]); };
    std::ostringstream s;
    bool first = true;
    for (int i = 0; i < 4; ++i) {
      if (i == longest) continue;
      s << (first ? "" : " + ") << name(i) << " " << lengths[i] / unit;
      first = false;
    }
    s << " < " << name(longest) << " " << lengths[longest] / unit << " " << m.units.length << ": loop " << loop.name
      << " cannot close (its longest link is longer than the other three together)";
    return s.str();
  }
  return {};
}

TransmissionOverTurn transmission_over_full_turn(double frame, double input, double coupler, double output) {
  const auto mu_at = [&](double f) { return angle_opposite(f, coupler, output); };
  TransmissionOverTurn t;
  t.min = mu_at(std::abs(frame - input));
  t.max = mu_at(frame + input);
  t.design = std::min(std::min(t.min, std::numbers::pi - t.min), std::min(t.max, std::numbers::pi - t.max));
  return t;
}

double transmission_angle(const FourBarLoop& loop, const std::vector<Eigen::Vector2d>& p) {
  const Eigen::Vector2d coupler = p[loop.a] - p[loop.b];
  const Eigen::Vector2d output = p[loop.o4] - p[loop.b];
  // atan2 rather than the acos of the cosine, which loses half the digits where the angle nears 0
  // or pi (a toggle, a change point): there the cross product still holds them all.
  return std::atan2(std::abs(cross(coupler, output)), coupler.dot(output));
}

int branch_sign(const FourBarLoop& loop, const std::vector<Eigen::Vector2d>& p) {
  return cross(p[loop.o4] - p[loop.a], p[loop.b] - p[loop.a]) >= 0 ? 1 : -1;
}

std::string branch_name(int branch_sign) { return branch_sign > 0 ? "open" : "crossed"; }

}  // namespace nbar
