#include "nbar/io/synthesis_task.hpp"
#include "nbar/synthesis/nine_point.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <optional>
#include <sstream>
#include <string_view>
#include <system_error>

#include "yaml_support.hpp"

namespace nbar::io {

namespace {

using Eigen::Vector2d;
using yaml::AllowedKeys;
using yaml::describe;
using yaml::Entry;
using yaml::Fields;
using yaml::mark;

// Keys every task takes, then each task's own.
const std::vector<std::string_view> kCommonKeys{"task", "name", "description", "units"};
const std::vector<std::string_view> kFivePointKeys{"pivots", "points"};
const std::vector<std::string_view> kNinePointKeys{"points"};
const std::vector<std::string_view> kBurmesterKeys{"poses", "fixed_pivots", "moving_pivots", "curves", "samples"};
const std::vector<std::string_view> kFunctionKeys{"function", "x",       "input_range", "output_range",
                                                  "points",   "spacing", "frame"};
const std::vector<std::string_view> kPathKeys{"points", "curve", "constraints", "nine_point_starts"};

// The words of the task file's document-level errors.
const yaml::DocumentWording kTaskDocument{
    "the file holds no task (it is empty or only comments): start with `task: five-point`, "
    "`task: nine-point`, `task: burmester`, `task: function` or `task: path`",
    "a task file holds a single YAML document", "a task file is a mapping of keys (task:, ...), not "};

// The keys a mapping under `e` takes: "unknown key 'c' in `pivots`".
AllowedKeys keys_under(const Entry& e, std::vector<std::string_view> keys) {
  return {std::string("in `").append(e.key).append("`"), std::move(keys)};
}

// The function's text as messages quote it: whole when short, else its start.
std::string quoted_function(const std::string& text) {
  constexpr std::size_t kShown = 60;
  if (text.size() <= kShown) return "'" + text + "'";
  return "'" + text.substr(0, kShown) + "...' (" + std::to_string(text.size()) + " characters)";
}

class TaskParser : yaml::Reader {
 public:
  TaskParser(std::string text, std::string file, CurveFiles curve_files)
      : Reader(std::move(text), file), curve_files_(curve_files) {
    task_.file = std::move(file);
  }

  SynthesisTask parse() {
    const YAML::Node root = load(kTaskDocument);
    const Fields top{entries(root, "")};
    const Entry* kind = top.find("task");
    if (!kind)
      fail(root,
           "a task file needs `task: five-point`, `task: nine-point`, `task: burmester`, `task: function` or "
           "`task: path`");
    const std::string k = kind->value.IsScalar() ? kind->value.Scalar() : "";
    const std::vector<std::string_view>* own = nullptr;
    if (k == "five-point") {
      task_.kind = SynthesisKind::FivePoint;
      own = &kFivePointKeys;
    } else if (k == "burmester") {
      task_.kind = SynthesisKind::Burmester;
      own = &kBurmesterKeys;
    } else if (k == "function") {
      task_.kind = SynthesisKind::Function;
      own = &kFunctionKeys;
    } else if (k == "nine-point") {
      task_.kind = SynthesisKind::NinePoint;
      own = &kNinePointKeys;
    } else if (k == "path") {
      task_.kind = SynthesisKind::Path;
      own = &kPathKeys;
    } else {
      fail(mark(*kind), std::string("unknown task ") + describe(kind->value) +
                            " (tasks are: five-point, nine-point, burmester, function, path)");
    }
    std::vector<std::string_view> allowed = kCommonKeys;
    allowed.insert(allowed.end(), own->begin(), own->end());
    check_keys(top, AllowedKeys{std::string("in a ").append(k).append(" task"), allowed});
    task_.where = mark(*kind);
    if (const Entry* e = top.find("name")) task_.name = text_value(*e, "the name");
    if (const Entry* e = top.find("description")) text_value(*e, "the description");
    if (const Entry* e = top.find("units")) {
      task_.units = units_of(mapping(*e, keys_under(*e, {"length", "angle"}), "{length: mm, angle: deg}"), task_.units);
    }
    switch (task_.kind) {
      case SynthesisKind::FivePoint: parse_five_point(top, root); break;
      case SynthesisKind::Burmester: parse_burmester(top, root); break;
      case SynthesisKind::Function: parse_function(top, root); break;
      case SynthesisKind::NinePoint: parse_nine_point(top, root); break;
      case SynthesisKind::Path: parse_path(top, root); break;
    }
    return std::move(task_);
  }

 private:
  SynthesisTask task_;
  CurveFiles curve_files_;

  // ---- keys and values (the generic readers are yaml::Reader's) ----

  // Keys here are only keywords (task:, points:, ...), never names the user chooses.
  void check_key(const YAML::Node& key) const override {
    if (!key.IsScalar() || key.Scalar().empty()) {
      fail(key, std::string("a key must be a name, not ").append(describe(key)));
    }
  }

  int whole(const Entry& e, const std::string& what, int low, int high) const {
    const double v = number(e, what);
    if (v != std::floor(v) || v < low || v > high)
      fail(mark(e), what + " must be a whole number from " + std::to_string(low) + " to " + std::to_string(high));
    return static_cast<int>(v);
  }
  double angle(const YAML::Node& node, SourceMark at, const std::string& what) const {
    return within_turns(number(node, at, what + " (" + task_.units.angle + ")") * task_.units.angle_scale, at, what);
  }
  // An angle (SI) of at most a million turns: in radians a larger one keeps no digits of where it
  // points (1e308 deg is 296 deg round, and its radians say nothing of that).
  double within_turns(double radians, SourceMark at, const std::string& what) const {
    constexpr double kMaxTurns = 1e6;
    if (!(std::abs(radians) <= kMaxTurns * 2 * std::numbers::pi))
      fail(at, what + " is beyond a million turns: give it within a turn or a few");
    return radians;
  }
  // [a, b]
  std::array<double, 2> pair(const YAML::Node& node, SourceMark at, const std::string& what,
                             std::string_view example) const {
    if (!node.IsSequence() || node.size() != 2)
      fail(at, what + " needs two numbers, like " + std::string(example) + ", not " +
                   (node.IsSequence() ? "a list of " + std::to_string(node.size()) : describe(node)));
    return {number(node[0], mark(node[0]), what), number(node[1], mark(node[1]), what)};
  }
  Vector2d point(const YAML::Node& node, SourceMark at, const std::string& what) const {
    const auto [x, y] = pair(node, at, what, "[x, y]");
    return {x, y};
  }
  Vector2d point(const Entry& e, const std::string& what) const { return point(e.value, mark(e), what); }

  // {a: [x, y], b: [x, y]}, two distinct points.
  std::array<Vector2d, 2> pivots(const Entry& e, const std::string& what) const {
    const Fields f = mapping(e, keys_under(e, {"a", "b"}), "{a: [0, 0], b: [1, 0]}");
    const Vector2d a = point(required(f, e.value, "a", "`" + e.key + "`"), "pivot a");
    const Entry& b_entry = required(f, e.value, "b", "`" + e.key + "`");
    const Vector2d b = point(b_entry, "pivot b");
    // Beyond this their squares, summed in every distance, overflow.
    constexpr double kMaxCoordinate = 1e100;
    if (!(std::max(a.cwiseAbs().maxCoeff(), b.cwiseAbs().maxCoeff()) <= kMaxCoordinate))
      fail(mark(e), "the " + what + " have a coordinate beyond 1e100: use a larger length unit");
    if ((a - b).norm() <= 1e-9 * std::max({1.0, a.norm(), b.norm()}))
      fail(mark(b_entry), "the " + what + " a and b coincide: a four-bar needs two distinct " + what);
    return {a, b};
  }

  // ---- the tasks ----

  // The five-point solver works in the task's own scale, the distance between the fixed
  // pivots: coordinates must stay far from overflow (their squares are summed), every point
  // within kMaxSpread pivot distances of the pivots, and the points off a single line (the
  // start system degenerates there and tracking crawls for many seconds).
  void check_five_point_scale(const std::vector<YAML::Node>& items) const {
    constexpr double kMaxCoordinate = 1e100, kMaxSpread = 1000.0, kCollinear = 1e-9;
    const auto big = [](const Vector2d& p) { return !(p.cwiseAbs().maxCoeff() <= kMaxCoordinate); };
    const double frame = (task_.pivot_a - task_.pivot_b).norm();
    const Vector2d middle = 0.5 * (task_.pivot_a + task_.pivot_b);
    for (std::size_t i = 0; i < items.size(); ++i) {
      const Vector2d& p = task_.points[i];
      if (big(p))
        fail(items[i], "point " + std::to_string(i + 1) + " has a coordinate beyond 1e100: use a larger length unit");
      const double spread = (p - middle).norm() / frame;
      if (!(spread <= kMaxSpread)) {
        std::ostringstream s;
        s.precision(3);
        s << "point " << i + 1 << " is " << spread << " times as far from the fixed pivots as they are apart; the "
          << "five-point solver takes points within " << static_cast<int>(kMaxSpread) << " times the pivots' distance ("
          << frame << "): check the point, the pivots and the units";
        fail(items[i], s.str());
      }
    }
    double extent = frame, area = 0.0;
    for (const Vector2d& p : task_.points) extent = std::max(extent, (p - middle).norm());
    const Vector2d& o = task_.points[0];
    for (std::size_t i = 1; i < task_.points.size(); ++i)
      for (std::size_t j = 1; j < i; ++j) {
        const Vector2d u = task_.points[i] - o, v = task_.points[j] - o;
        area = std::max(area, std::abs(u.x() * v.y() - u.y() * v.x()));
      }
    if (area <= kCollinear * extent * extent)
      fail(items[0],
           "the five points lie on one straight line: the five-point solver needs them spread over a "
           "curve; move one off the line");
  }

  void parse_five_point(const Fields& top, const YAML::Node& root) {
    const auto [a, b] = pivots(required(top, root, "pivots", "a five-point task"), "fixed pivots");
    task_.pivot_a = a;
    task_.pivot_b = b;
    const Entry& points = required(top, root, "points", "a five-point task");
    task_.where = mark(points);
    const std::vector<YAML::Node> items = list(points, "[[x, y], ...]");
    if (items.size() != 5)
      fail(mark(points), std::string("a five-point task needs exactly 5 points for the coupler point, not ") +
                             std::to_string(items.size()));
    for (const YAML::Node& item : items)
      task_.points.push_back(point(item, mark(item), "point " + std::to_string(task_.points.size() + 1)));
    const double size = std::max({1.0, (a - b).norm()});
    for (std::size_t i = 0; i < items.size(); ++i)
      for (std::size_t j = 0; j < i; ++j)
        if ((task_.points[i] - task_.points[j]).norm() <= 1e-9 * size)
          fail(items[i], std::string("points ") + std::to_string(j + 1) + " and " + std::to_string(i + 1) +
                             " coincide: the five points must be distinct");
    check_five_point_scale(items);
  }

  // Nine distinct points, not on one line, with coordinates far from overflow.
  void parse_nine_point(const Fields& top, const YAML::Node& root) {
    const Entry& points = required(top, root, "points", "a nine-point task");
    task_.where = mark(points);
    const std::vector<YAML::Node> items = list(points, "[[x, y], ...]");
    if (items.size() != 9)
      fail(mark(points), std::string("a nine-point task needs exactly 9 points for the coupler point, not ") +
                             std::to_string(items.size()));
    constexpr double kMaxCoordinate = 1e100;
    for (const YAML::Node& item : items) {
      task_.points.push_back(point(item, mark(item), "point " + std::to_string(task_.points.size() + 1)));
      if (!(task_.points.back().cwiseAbs().maxCoeff() <= kMaxCoordinate))
        fail(item, "point " + std::to_string(task_.points.size()) +
                       " has a coordinate beyond 1e100: use a larger length unit");
    }
    Vector2d centroid = Vector2d::Zero();
    for (const Vector2d& p : task_.points) centroid += p / 9.0;
    double spread = 0.0;
    for (const Vector2d& p : task_.points) spread = std::max(spread, (p - centroid).norm());
    for (std::size_t i = 0; i < items.size(); ++i)
      for (std::size_t j = 0; j < i; ++j)
        if ((task_.points[i] - task_.points[j]).norm() <= 1e-9 * spread)
          fail(items[i], std::string("points ") + std::to_string(j + 1) + " and " + std::to_string(i + 1) +
                             " coincide: the nine points must be distinct");
    if (!(spread > 0)) fail(mark(points), "the nine points coincide");
    double ratio = 0;
    if (const std::optional<std::size_t> stray = stray_target(ratio)) fail(items[*stray], stray_message(*stray, ratio));
    // Collinear: every point within a tiny distance of the line through the two farthest apart.
    std::size_t far_a = 0, far_b = 1;
    for (std::size_t i = 0; i < 9; ++i)
      for (std::size_t j = 0; j < i; ++j)
        if ((task_.points[i] - task_.points[j]).norm() > (task_.points[far_a] - task_.points[far_b]).norm()) {
          far_a = i;
          far_b = j;
        }
    const Vector2d along = (task_.points[far_b] - task_.points[far_a]).normalized();
    double off = 0.0;
    for (const Vector2d& p : task_.points) {
      const Vector2d d = p - task_.points[far_a];
      off = std::max(off, std::abs(along.x() * d.y() - along.y() * d.x()));
    }
    if (off <= 1e-9 * spread)
      fail(mark(points),
           "the nine points lie on one straight line, which is no four-bar's coupler curve: "
           "move some off the line");
    std::array<Vector2d, 9> nine;
    std::copy(task_.points.begin(), task_.points.end(), nine.begin());
    if (const auto circle = synthesis::common_circle(nine)) {
      std::ostringstream s;
      s.precision(6);
      s << "the nine points lie on one circle (centre (" << circle->centre.x() << ", " << circle->centre.y()
        << "), radius " << circle->radius << " " << task_.units.length
        << "): a crank of that radius about its centre, whose moving pivot is the "
        << "coupler point, passes through them with any second dyad, so there are infinitely many four-bars; "
        << "move some off the circle";
      fail(mark(points), s.str());
    }
  }

  void parse_burmester(const Fields& top, const YAML::Node& root) {
    const Entry& poses = required(top, root, "poses", "a burmester task");
    task_.where = mark(poses);
    const std::vector<YAML::Node> items = list(poses, "[{point: [0, 0], angle: 0}, ...]");
    if (items.size() < 3 || items.size() > 5)
      fail(mark(poses), std::string("a burmester task needs 3, 4 or 5 poses, not ") + std::to_string(items.size()));
    for (const YAML::Node& item : items) {
      if (!item.IsMap())
        fail(item, std::string("a pose is a mapping like {point: [0, 0], angle: 0}, not ") + describe(item));
      Entry self{"pose", item, item};
      const Fields f = mapping(self, keys_under(self, {"point", "angle"}), "{point: [0, 0], angle: 0}");
      synthesis::BodyPose pose;
      pose.point = point(required(f, item, "point", "a pose"), "the pose's point");
      const Entry& a = required(f, item, "angle", "a pose");
      pose.angle = angle(a.value, mark(a), "the pose's angle");
      for (std::size_t j = 0; j < task_.poses.size(); ++j)
        if ((task_.poses[j].point - pose.point).norm() <= 1e-12 * std::max(1.0, pose.point.norm()) &&
            std::abs(task_.poses[j].angle - pose.angle) <= 1e-12)
          fail(item, std::string("poses ") + std::to_string(j + 1) + " and " + std::to_string(task_.poses.size() + 1) +
                         " are the same");
      task_.poses.push_back(pose);
    }
    const std::size_t n = items.size();
    const Entry* fixed = top.find("fixed_pivots");
    const Entry* moving = top.find("moving_pivots");
    if (n == 3) {
      if (fixed && moving) fail(moving->key_node, "give either `fixed_pivots` or `moving_pivots`, not both");
      if (!fixed && !moving)
        fail(mark(poses),
             "with 3 poses, choose two pivots: `fixed_pivots: {a: [x, y], b: [x, y]}` or "
             "`moving_pivots: {a: [x, y], b: [x, y]}` (on the coupler, in the first pose)");
      const Entry& given = fixed ? *fixed : *moving;
      task_.given = fixed ? synthesis::PivotChoice::Fixed : synthesis::PivotChoice::Moving;
      const auto [a, b] = pivots(given, fixed ? "fixed pivots" : "moving pivots");
      task_.given_a = a;
      task_.given_b = b;
    } else {
      for (const Entry* e : {fixed, moving})
        if (e)
          fail(e->key_node, "`" + e->key + "` applies to 3 poses only; with " + std::to_string(n) +
                                " poses the pivots follow from the poses");
    }
    const Entry* curves = top.find("curves");
    const Entry* samples = top.find("samples");
    if (n != 4) {
      for (const Entry* e : {curves, samples})
        if (e) fail(e->key_node, "`" + e->key + "` applies to 4 poses only (the Burmester curves)");
    }
    if (curves) {
      const Fields f = mapping(*curves, keys_under(*curves, {"radius", "step"}), "{radius: 5, step: 0.01}");
      if (const Entry* r = f.find("radius")) {
        task_.curves.radius = non_negative(*r, "the radius", true);
        const double size = synthesis::pose_scale(task_.poses);
        const double widest = synthesis::kMaxWindowRadius * size;
        if (task_.curves.radius > widest) {
          std::ostringstream s;
          s.precision(6);
          s << "the radius " << task_.curves.radius << " " << task_.units.length << " is more than 10^6 times the "
            << "size of the poses (" << size << " " << task_.units.length
            << ", the RMS distance of their points from the centroid): no curve can be traced in so wide a "
            << "window; give at most " << widest << " " << task_.units.length
            << ", or leave `radius` out for 1.5 times the farthest pose or pole";
          fail(mark(*r), s.str());
        }
      }
      if (const Entry* s = f.find("step")) task_.curves.step = non_negative(*s, "the step", true);
    }
    if (samples) task_.samples = whole(*samples, "`samples`", 2, 200);
  }

  void parse_function(const Fields& top, const YAML::Node& root) {
    const Entry& f = required(top, root, "function", "a function task");
    task_.where = mark(f);
    if (!f.value.IsScalar() || f.value.Scalar().empty())
      fail(mark(f), std::string("`function` must be an expression in x like \"log10(x)\", not ") + describe(f.value));
    task_.function_text = f.value.Scalar();
    try {
      task_.function = Law::parse(task_.function_text, 1.0, "x");
    } catch (const LawSyntaxError& e) {
      const int at = std::clamp(e.column(), 0, static_cast<int>(task_.function_text.size()));
      fail(column_in(f.value, at), "in the function " + quoted_function(task_.function_text) + ": " + e.what());
    }
    const Entry& x = required(top, root, "x", "a function task");
    const auto [x0, x1] = pair(x.value, mark(x), "x", "[1, 2]");
    if (x0 == x1) fail(mark(x), "the range of x is empty: give two different values");
    task_.x_start = x0;
    task_.x_end = x1;
    const auto angles = [&](const Entry& e) {
      const auto [from, to] = pair(e.value, mark(e), "`" + e.key + "` (" + task_.units.angle + ")", "[45, 105]");
      if (from == to) fail(mark(e), "`" + e.key + "` is empty: give the angles at the start and the end of the range");
      const std::string what = "`" + e.key + "`";
      return std::array<double, 2>{within_turns(from * task_.units.angle_scale, mark(e), what),
                                   within_turns(to * task_.units.angle_scale, mark(e), what)};
    };
    const auto in = angles(required(top, root, "input_range", "a function task"));
    const auto out = angles(required(top, root, "output_range", "a function task"));
    task_.input_from = in[0];
    task_.input_to = in[1];
    task_.output_from = out[0];
    task_.output_to = out[1];
    if (const Entry* p = top.find("points")) task_.precision_points = whole(*p, "`points`", 3, 50);
    if (const Entry* s = top.find("spacing")) {
      const std::string spacing = text_value(*s, "`spacing`");
      if (spacing != "chebyshev" && spacing != "even")
        fail(mark(*s), "unknown spacing '" + spacing + "' (use chebyshev or even)");
      task_.chebyshev = spacing == "chebyshev";
    }
    if (const Entry* fr = top.find("frame")) {
      task_.frame = non_negative(*fr, "the frame length", true);
      // As coordinates are held to 1e100: the link lengths are squared and multiplied.
      if (!(task_.frame >= 1e-100 && task_.frame <= 1e100))
        fail(mark(*fr), "the frame length must be from 1e-100 to 1e100: use another length unit");
    }
    // The function must be defined over the whole range, and not equal at its ends (the
    // output's range maps f(x_start)..f(x_end)).
    double y0 = 0.0, y1 = 0.0;
    for (int k = 0; k <= 100; ++k) {
      const double xk = x0 + (x1 - x0) * k / 100.0;
      try {
        const double y = task_.function->value(xk);
        if (k == 0) y0 = y;
        if (k == 100) y1 = y;
      } catch (const Error&) {
        std::ostringstream s;
        s << "the function " << quoted_function(task_.function_text) << " is undefined at x = " << xk
          << ", inside the range of x";
        fail(mark(f), s.str());
      }
    }
    if (y0 == y1)
      fail(mark(f),
           "the function has the same value at both ends of the range of x, so it cannot be "
           "mapped onto the output's range");
  }

  // ---- path: many target points, from the file or a CSV, and constraints ----

  static constexpr std::size_t kMinPathPoints = 10, kMaxPathPoints = 1000;

  void parse_path(const Fields& top, const YAML::Node& root) {
    const Entry* points = top.find("points");
    const Entry* curve = top.find("curve");
    if (points && curve) fail(curve->key_node, "give the targets as `points` or as a `curve` file, not both");
    if (!points && !curve)
      fail(root, "a path task needs its target points: `points: [[x, y], ...]` (10 or more) or `curve: FILE.csv`");
    std::vector<SourceMark> marks;   // of each point, where messages about it point
    std::string where_file = file_;  // the file those marks are in
    if (points) {
      task_.where = mark(*points);
      const std::vector<YAML::Node> items = list(*points, "[[x, y], ...]");
      for (const YAML::Node& item : items) {
        task_.points.push_back(point(item, mark(item), "point " + std::to_string(task_.points.size() + 1)));
        marks.push_back(mark(item));
      }
    } else {
      task_.where = mark(*curve);
      // A task given as text (the web server's, Python's parse_task) must not make its reader
      // open files: on a server that would read the server's disk for any client.
      if (curve_files_ == CurveFiles::refused)
        fail(mark(*curve),
             "`curve` reads a CSV file, which only a task read from a file may do: give the targets "
             "here as `points: [[x, y], ...]`");
      const std::string name = text_value(*curve, "`curve`");
      if (name.empty()) fail(mark(*curve), "`curve` names a CSV file of the target points (x, y on each line)");
      task_.curve_file = resolve_beside_task(name);
      read_curve_csv(task_.curve_file, mark(*curve), marks);
      where_file = task_.curve_file;
    }
    const auto at = [&](std::size_t i) { return marks[i]; };
    const auto fail_at = [&](SourceMark m, const std::string& message) -> void {
      if (where_file == file_) fail(m, message);
      throw ModelFileError(where_file, m, message);
    };
    const std::size_t n = task_.points.size();
    const std::string from = points ? "" : " (in " + task_.curve_file + ")";
    if (n < kMinPathPoints)
      fail(points ? mark(*points) : mark(*curve), "a path task needs at least " + std::to_string(kMinPathPoints) +
                                                      " target points" + from + ", not " + std::to_string(n) +
                                                      " (with 5 points and both pivots, use `task: five-point`)");
    if (n > kMaxPathPoints)
      fail(points ? mark(*points) : mark(*curve), "a path task takes at most " + std::to_string(kMaxPathPoints) +
                                                      " target points" + from + ", not " + std::to_string(n) +
                                                      ": take every k-th point of the curve");
    constexpr double kMaxCoordinate = 1e100;
    for (std::size_t i = 0; i < n; ++i)
      if (!(task_.points[i].cwiseAbs().maxCoeff() <= kMaxCoordinate))
        fail_at(at(i), "point " + std::to_string(i + 1) + " has a coordinate beyond 1e100: use a larger length unit");
    double extent = 0;
    for (const Vector2d& p : task_.points) extent = std::max(extent, (p - task_.points[0]).norm());
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < i; ++j)
        if ((task_.points[i] - task_.points[j]).norm() <= 1e-9 * std::max(extent, 1e-300)) {
          std::string message = "points " + std::to_string(j + 1) + " and " + std::to_string(i + 1) +
                                " coincide: the coupler point meets each target once";
          if (j == 0 && i == n - 1) message += " (a closed curve is given once round: leave out the last point)";
          fail_at(at(i), message);
        }
    double ratio = 0;
    if (const std::optional<std::size_t> stray = stray_target(ratio)) fail_at(at(*stray), stray_message(*stray, ratio));
    check_not_collinear(points ? mark(*points) : mark(*curve));
    if (const Entry* c = top.find("constraints")) parse_constraints(*c);
    if (const Entry* s = top.find("nine_point_starts"))
      task_.nine_point_starts = whole(*s, "`nine_point_starts`", 0, 10);
  }

  // The index of a target far outside the others' scale, a typo such as [49680, 126.456] for
  // [49.680, 126.456], or none. Measured from the coordinate-wise median, which one stray point
  // cannot move, against the median distance from it: a coupler curve's targets lie within a few
  // such distances, and the solvers' tracking crawls for minutes on such a task.
  std::optional<std::size_t> stray_target(double& ratio) const {
    constexpr double kMaxStray = 100.0;
    const std::size_t n = task_.points.size();
    const auto median = [](std::vector<double> v) {
      std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
      return v[v.size() / 2];
    };
    std::vector<double> xs(n), ys(n), distances(n);
    for (std::size_t i = 0; i < n; ++i) {
      xs[i] = task_.points[i].x();
      ys[i] = task_.points[i].y();
    }
    const Vector2d centre(median(xs), median(ys));
    for (std::size_t i = 0; i < n; ++i) distances[i] = (task_.points[i] - centre).norm();
    const double typical = median(distances);
    const auto far = std::max_element(distances.begin(), distances.end());
    if (!(typical > 0) || *far <= kMaxStray * typical) return std::nullopt;
    ratio = *far / typical;
    return static_cast<std::size_t>(far - distances.begin());
  }

  static std::string stray_message(std::size_t i, double ratio) {
    std::ostringstream s;
    s.precision(3);
    s << "point " << i + 1 << " is " << ratio
      << " times as far from the middle of the targets as a typical one is; a coupler point's targets lie within 100 "
         "times that: check its digits and the units";
    return s.str();
  }

  // The targets must span an area: a straight line is not a coupler curve to fit.
  void check_not_collinear(SourceMark at) const {
    Vector2d centre = Vector2d::Zero();
    for (const Vector2d& p : task_.points) centre += p;
    centre /= static_cast<double>(task_.points.size());
    double xx = 0, xy = 0, yy = 0;
    for (const Vector2d& p : task_.points) {
      const Vector2d d = p - centre;
      xx += d.x() * d.x();
      xy += d.x() * d.y();
      yy += d.y() * d.y();
    }
    const double mean = 0.5 * (xx + yy), half = std::hypot(0.5 * (xx - yy), xy);
    if (mean - half <= 1e-12 * (mean + half))
      fail(at,
           "the target points lie on one straight line: a path task fits a four-bar's coupler curve to points "
           "spread over a curve");
  }

  // A file named in the task, relative to the task file's folder.
  std::string resolve_beside_task(const std::string& name) const {
    const std::filesystem::path given(name);
    if (given.is_absolute() || file_.empty() || file_.front() == '<') return given.string();
    return (std::filesystem::path(file_).parent_path() / given).lexically_normal().string();
  }

  // x, y on each line (comma, semicolon, tab or spaces between them); blank lines and lines
  // starting with # are skipped, and a first line of words (a header) too.
  void read_curve_csv(const std::string& path, SourceMark from, std::vector<SourceMark>& marks) {
    const FileText file = read_file_text(path);
    if (file.error == std::errc::is_a_directory) fail(from, "`curve`: " + path + " is a folder, not a CSV file");
    if (file.error) fail(from, "`curve`: cannot read " + path + ": " + file.error.message());
    if (file.too_long) fail(from, "`curve`: cannot read " + path + ": " + too_long_message());
    std::istringstream in(file.text);
    std::string line;
    int number_of_line = 0;
    bool first_data = true;
    while (std::getline(in, line)) {
      ++number_of_line;
      if (!line.empty() && line.back() == '\r') line.pop_back();
      if (number_of_line > static_cast<int>(kMaxPathPoints) * 4 + 100)
        throw ModelFileError(path, SourceMark{number_of_line, 1},
                             "too many lines: a path task takes at most " + std::to_string(kMaxPathPoints) + " points");
      const auto fields = split_fields(line);
      if (fields.empty() || line[fields.front().first] == '#') continue;
      const bool header = first_data && marks.empty() && !starts_a_number(line[fields.front().first]);
      first_data = false;
      if (header) continue;
      if (fields.size() != 2)
        throw ModelFileError(path, SourceMark{number_of_line, static_cast<int>(fields.front().first) + 1},
                             "a line holds two numbers, x and y (found " + std::to_string(fields.size()) + " fields)");
      Vector2d p;
      for (int k = 0; k < 2; ++k) {
        const auto [begin, length] = fields[static_cast<std::size_t>(k)];
        const std::string text = line.substr(begin, length);
        char* end = nullptr;
        errno = 0;
        const double v = std::strtod(text.c_str(), &end);
        if (end != text.c_str() + text.size() || text.empty() || !std::isfinite(v))
          throw ModelFileError(path, SourceMark{number_of_line, static_cast<int>(begin) + 1},
                               "'" + text.substr(0, 40) + "' is not a finite number (" + (k == 0 ? "x" : "y") + ")");
        p(k) = v;
      }
      task_.points.push_back(p);
      marks.push_back(SourceMark{number_of_line, static_cast<int>(fields.front().first) + 1});
    }
  }

  static bool starts_a_number(char c) {
    return std::isdigit(static_cast<unsigned char>(c)) || c == '-' || c == '+' || c == '.';
  }

  // (start, length) of each field: separated by a comma, a semicolon, or blanks.
  static std::vector<std::pair<std::size_t, std::size_t>> split_fields(const std::string& line) {
    std::vector<std::pair<std::size_t, std::size_t>> out;
    const auto blank = [](char c) { return c == ' ' || c == '\t'; };
    std::size_t i = 0;
    while (i < line.size() && blank(line[i])) ++i;
    if (i == line.size()) return out;
    while (true) {
      std::size_t j = i;
      while (j < line.size() && line[j] != ',' && line[j] != ';' && !blank(line[j])) ++j;
      out.emplace_back(i, j - i);
      while (j < line.size() && blank(line[j])) ++j;
      if (j == line.size()) break;
      if (line[j] == ',' || line[j] == ';') ++j;
      while (j < line.size() && blank(line[j])) ++j;
      i = j;
      if (i == line.size()) {
        out.emplace_back(i, 0);  // a separator at the end: an empty field
        break;
      }
    }
    return out;
  }

  bool flag(const Entry& e, const std::string& what) const {
    if (e.value.IsScalar() && (e.value.Scalar() == "true" || e.value.Scalar() == "false"))
      return e.value.Scalar() == "true";
    fail(mark(e), what + " is true or false, not " + describe(e.value));
  }

  // constraints: {pivots: {min: [x, y], max: [x, y]}, crank: true, min_transmission: 30,
  //               lengths: [min, max]}
  void parse_constraints(const Entry& e) {
    const Fields f =
        mapping(e, keys_under(e, {"pivots", "crank", "min_transmission", "lengths"}),
                "{pivots: {min: [0, 0], max: [100, 50]}, crank: true, min_transmission: 30, lengths: [10, 200]}");
    synthesis::PathConstraints& c = task_.constraints;
    if (const Entry* p = f.find("pivots")) {
      const Fields box = mapping(*p, keys_under(*p, {"min", "max"}), "{min: [0, 0], max: [100, 50]}");
      const Vector2d lo = point(required(box, p->value, "min", "`pivots`"), "the region's min corner");
      const Entry& hi_entry = required(box, p->value, "max", "`pivots`");
      const Vector2d hi = point(hi_entry, "the region's max corner");
      if (!(hi.x() > lo.x() && hi.y() > lo.y()))
        fail(mark(hi_entry), "the pivots' region is empty: max must exceed min in x and in y");
      c.region_min = lo;
      c.region_max = hi;
    }
    if (const Entry* k = f.find("crank")) c.crank = flag(*k, "`crank`");
    if (const Entry* m = f.find("min_transmission")) {
      const double mu = angle(m->value, mark(*m), "`min_transmission`");
      if (!(mu >= 0 && mu < std::numbers::pi / 2))
        fail(mark(*m),
             "`min_transmission` must be at least 0 and less than a right angle (90 deg, the best a linkage can keep)");
      c.min_transmission = mu;
    }
    if (const Entry* l = f.find("lengths")) {
      const auto [lo, hi] = pair(l->value, mark(*l), "`lengths` (" + task_.units.length + ")", "[10, 200]");
      if (!(lo >= 0 && hi > lo)) fail(mark(*l), "`lengths` is [min, max] with 0 <= min < max");
      c.min_length = lo;
      c.max_length = hi;
    }
  }

  // Where the character at `offset` of a plain or quoted one-line scalar sits in the file.
  SourceMark column_in(const YAML::Node& node, int offset) const {
    const YAML::Mark m = node.Mark();
    SourceMark at = mark(node);
    if (m.pos < 0 || static_cast<std::size_t>(m.pos) >= text_.size()) return at;
    const char first = text_[static_cast<std::size_t>(m.pos)];
    if (first == '|' || first == '>') return at;
    at.column += offset + (first == '"' || first == '\'' ? 1 : 0);
    return at;
  }
};

}  // namespace

SynthesisTask parse_synthesis_task(const std::string& text, const std::string& file_name, CurveFiles curve_files) {
  return TaskParser(text, file_name, curve_files).parse();
}

SynthesisTask load_synthesis_task(const std::string& path) {
  const FileText file = read_file_text(path);
  if (file.error) throw ModelFileError(path, SourceMark{}, "cannot read: " + file.error.message());
  if (file.too_long) throw ModelFileError(path, SourceMark{1, 1}, too_long_message());
  return parse_synthesis_task(file.text, path, CurveFiles::read);
}

}  // namespace nbar::io
