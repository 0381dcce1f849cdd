// Internal to the model file reader: its parser, one class whose sections are read in
// model_file.cpp (the top level and the generic values), model_file_points_bodies.cpp (points,
// bodies, sliders, slots, drivers and the sweep), model_file_shapes.cpp (shapes, curves and
// imports) and model_file_kinetics.cpp (materials, gravity and loads).
#pragma once

#include <yaml-cpp/yaml.h>

#include <Eigen/Core>

#include <array>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "nbar/io/model_file.hpp"
#include "nbar/model/curves.hpp"
#include "nbar/model/geometry.hpp"
#include "nbar/model/materials.hpp"
#include "yaml_support.hpp"

namespace nbar::io::model_file_detail {

using yaml::AllowedKeys;
using yaml::describe;
using yaml::Entry;
using yaml::Fields;
using yaml::join;
using yaml::mark;
using yaml::NumberStatus;
using yaml::parse_number;
using yaml::suggestion;

// The largest driver angle a model may give (rad): past it the spacing of doubles eats the motion.
inline constexpr double kMaxDriverAngle = 1e6;

// The keys each kind of mapping accepts, all in one place: new sections (shapes, loads,
// gravity, materials...) are declared here and then read in Parser::parse.
inline const AllowedKeys kTopLevelKeys{
    "at the top level",
    {"name", "description", "units", "points", "ground", "bodies", "lengths", "sliders", "slots", "drivers", "sweep",
     "gravity", "materials", "forces", "torques", "springs", "friction", "simulation"}};
inline const AllowedKeys kUnitsKeys{"in `units`", {"length", "angle"}};
inline const AllowedKeys kSliderKeys{"in a slider", {"body", "point", "along"}};
inline const AllowedKeys kSlotKeys{"in a slot", {"point", "along"}};
inline const AllowedKeys kGuideKeys{"in a guide by a point and an angle", {"point", "angle", "body"}};
inline const AllowedKeys kDriverKeys{"in a driver",
                                     {"name", "angle", "relative_to", "distance", "slide", "from", "to", "speed",
                                      "accel", "law", "free", "initial_speed", "at_limits", "cycles"}};
inline const AllowedKeys kSweepKeys{"in `sweep`", {"steps", "duration", "step"}};
inline const AllowedKeys kBodyKeys{"in a body",
                                   {"points", "shape", "bar", "thickness", "material", "mass", "cg", "inertia"}};
inline const AllowedKeys kShapeKeys{"in a `shape`", {"outline", "upper", "lower", "import", "layer", "units", "holes"}};
inline const AllowedKeys kCurveKeys{"in a curve", {"x", "y", "s", "steps", "spline"}};
inline const AllowedKeys kArcKeys{"in an arc", {"centre", "radius", "angles"}};
inline const AllowedKeys kHoleKeys{"in a hole", {"at", "circle", "radius", "polygon"}};
inline const AllowedKeys kBarKeys{"in a `bar`", {"width", "margin", "hole", "holes", "between"}};
inline const AllowedKeys kMaterialKeys{"in a material", {"density", "yield", "youngs_modulus", "poisson_ratio"}};
inline const AllowedKeys kForceKeys{"in a force", {"point", "body", "force", "fx", "fy"}};
inline const AllowedKeys kTorqueKeys{"in a torque", {"body", "torque", "no_load_speed"}};
inline const AllowedKeys kSpringKeys{"in a spring",
                                     {"between", "stiffness", "free_length", "damping", "preload", "name"}};
inline const AllowedKeys kFrictionKeys{"in a joint's friction",
                                       {"joint", "links", "slider", "slot", "viscous", "coulomb", "creep_speed"}};
inline const AllowedKeys kSimulationKeys{"in `simulation`", {"to", "dt", "rtol", "stop_when", "at_toggle"}};

// A unit a quantity may be written in, and its value in SI.
struct UnitScale {
  std::string_view unit;
  double scale;
};

class Parser : yaml::Reader {
 public:
  Parser(std::string text, std::string file) : Reader(std::move(text), file) { source_.file = std::move(file); }

  // Lets `shape: {import: FILE}` read files, relative to `dir` (the model file's folder). A
  // model parsed from text (the web server's) may not open files.
  void allow_imports(std::filesystem::path dir) { import_dir_ = std::move(dir); }

  // A model being built (parse_draft_model): no points yet is no error, and validate()'s
  // complaint is kept in `draft_problem` rather than thrown.
  void allow_drafts() { draft_ = true; }
  std::optional<ModelFileError> draft_problem;

  LoadedModel parse();

 private:
  Model model_;
  bool draft_ = false;
  std::optional<std::filesystem::path> import_dir_;
  SourceMap source_;
  std::vector<Material> user_materials_;  // from `materials:`

  // ---- keys, mappings and lists (the generic readers are yaml::Reader's; model_file.cpp) ----

  void check_key(const YAML::Node& key) const override;
  Fields section_fields(const Entry& e, const AllowedKeys& allowed, std::string_view example) const;
  std::vector<YAML::Node> section_list(const Entry& e, std::string_view example) const;

  // ---- values (model_file.cpp) ----

  int whole_number(const Entry& e, std::string_view what) const;
  std::string name_of(const YAML::Node& node, std::string_view what) const;

  template <typename Items, typename NameOf>
  [[noreturn]] void fail_unknown(const YAML::Node& at, std::string_view kind, std::string_view plural,
                                 const std::string& name, const Items& items, NameOf name_of_item) const {
    std::vector<std::string> names;
    for (const auto& item : items) names.push_back(name_of_item(item));
    std::string message = "unknown " + std::string(kind) + " '" + name + "'";
    if (names.empty()) {
      message += " (there are no " + std::string(plural) + ")";
    } else if (auto close = suggestion(name, names)) {
      message += "; did you mean '" + *close + "'?";
    } else {
      message += " (" + std::string(plural) + " are: " + join(names) + ")";
    }
    fail(at, message);
  }

  int point_ref(const YAML::Node& node) const;
  int body_ref(const YAML::Node& node) const;
  std::array<int, 2> point_pair(const Entry& e, std::string_view example) const;
  std::optional<SourceMark> column_in_scalar(const YAML::Node& node, int offset) const;
  Law law_of(const YAML::Node& node, SourceMark at, const std::string& text, double scale,
             const std::string& hint = {}) const;

  // ---- sections ----

  // model_file.cpp
  void parse_units(const Entry& e);

  // model_file_points_bodies.cpp
  void parse_points(const Entry* e);
  void parse_ground(const Entry& e);
  void parse_bodies(const Entry& e);
  void parse_body_details(const Entry& b, Body& body);
  void parse_lengths(const Entry& e);
  void parse_sliders(const Entry& e);
  void parse_slots(const Entry& e);
  std::array<int, 2> guide(const Entry& e, std::string_view example, int slider_body);
  int guide_carrier(const Entry& e, int through, int slider_body) const;
  int guide_carrier(const YAML::Node& at, int through, int slider_body) const;
  int guide_direction_point(const YAML::Node& at, int through, double angle, const std::string& name, int carrier);
  void parse_drivers(const Entry& e);
  void parse_driver(const YAML::Node& item);
  Driver driver_of_kind(const YAML::Node& item, const Fields& f);
  void parse_driver_motion(const Fields& f, Driver& d, std::array<SourceMark, 2>& law_marks);
  void parse_driver_run(const Fields& f, Driver& d);
  // SI per model unit of the driver's value: the angle's or the length's.
  double driver_scale(const Driver& d) const {
    return d.is_angular() ? model_.units.angle_scale : model_.units.length_scale;
  }
  double rate(const Entry& e, int order, const Driver& d, double scale, bool initial = false) const;
  double driver_value(const Entry& e, const Driver& d, double scale, const std::string& unit) const;
  Law parse_law(const Entry& e, double scale) const;
  void parse_sweep(const Entry& e);

  // ---- shapes, curves and imports (model_file_shapes.cpp) ----

  // An outline or polygon hole: vertices [x, y], each optionally [x, y, {bulge: b}] or
  // [x, y, {through: [x, y]}] to make the edge to the next vertex a circular arc, and curves
  // (parametric, function profiles, splines) that add their polygonised vertices.
  struct Ring {
    std::vector<Eigen::Vector2d> vertices;
    std::vector<double> bulges;      // empty when every edge is straight
    std::vector<YAML::Node> origin;  // the item each vertex came from
    bool curves = false;
  };

  // A curve item of a ring, sampled once the ring's size (and so the tolerance) is known.
  struct CurveItem {
    YAML::Node node;
    CurveFunction point;
    double from = 0, to = 0;
    int steps = 0;  // 0: adaptive
    std::shared_ptr<const CubicSpline> spline;
  };

  // One item of a ring as written: a vertex (possibly starting an arc) or a curve.
  struct RingItem {
    YAML::Node node;
    std::optional<Eigen::Vector2d> vertex;
    double bulge = 0;
    std::optional<std::pair<YAML::Node, Eigen::Vector2d>> through;
    std::optional<CurveItem> curve;
    std::optional<Eigen::Vector2d> arc_end;  // an arc by centre, radius and angles: vertex to arc_end, with `bulge`
  };

  // One hole of a shape, in model units, before it is checked.
  struct Hole {
    YAML::Node node;
    std::optional<Circle> circle;
    Ring polygon;
  };

  void check_listed_holes(const Region& region, const std::vector<Hole>& holes, const std::string& invalid) const;
  Eigen::Vector2d coordinates(const YAML::Node& node, std::string_view what) const;
  Law curve_law(const YAML::Node& node, const std::string& text, std::string_view variable) const;
  static std::string_view trimmed(std::string_view s);
  double constant_text(const YAML::Node& node, std::string_view written, std::string_view what) const;
  double curve_constant(const YAML::Node& node, std::string_view what) const;
  std::pair<double, double> curve_interval(const YAML::Node& node, std::string_view what) const;
  int curve_steps(const YAML::Node& node) const;
  CurveItem profile(const YAML::Node& node, const YAML::Node& function, std::string_view variable,
                    const YAML::Node* interval, const YAML::Node* steps) const;
  CurveItem curve_item(const YAML::Node& node) const;
  RingItem arc_item(const YAML::Node& node) const;
  RingItem ring_item(const YAML::Node& v) const;
  std::vector<Eigen::Vector2d> curve_vertices(const CurveItem& c, double tolerance) const;
  double ring_tolerance(const std::vector<RingItem>& items) const;
  Ring ring_of(const std::vector<RingItem>& items, SourceMark where, std::string_view what) const;
  Ring polygon(const Entry& e, std::string_view what) const;
  Ring profiles_ring(const Entry* lower, const Entry* upper, const YAML::Node& shape) const;
  static std::string with_origins(std::string message, const Ring& ring);
  Eigen::Vector2d drawn(int point) const;
  Region to_si(Region r) const;
  static void add_hole(Region& r, const Hole& h);
  Hole parse_hole(const YAML::Node& item) const;
  Region parse_shape(const Entry& e, const std::string& body) const;
  Region import_plate(const Entry& e, const std::string& layer, const Entry* units) const;
  Region parse_bar(const Entry& e, const Body& body, const std::string& name) const;

  // ---- kinetics: materials, gravity, loads (model_file_kinetics.cpp) ----

  double quantity(const Entry& e, const std::string& what, const std::vector<UnitScale>& units,
                  std::string_view example) const;
  void parse_materials(const Entry& e);
  Material material_fields(const YAML::Node& map, const std::string& name) const;
  Material material_of(const Entry& e) const;
  void parse_gravity(const Entry& e);
  Law load_law(const YAML::Node& node, SourceMark at, const std::string& what, std::string_view unit) const;
  void parse_forces(const Entry& e);
  void parse_torques(const Entry& e);
  void parse_springs(const Entry& e);

  // ---- joint friction and the simulation's settings (model_file_simulation.cpp) ----

  double load_coefficient(const Entry& e, const std::string& what, const std::string& unit) const;
  std::vector<int> links_at(int point) const;
  std::array<int, 2> friction_links(const Fields& f, const Entry& joint, int point) const;
  double drawing_diagonal() const;
  void parse_friction(const Entry& e);
  void parse_simulation(const Entry& e);
};

}  // namespace nbar::io::model_file_detail
