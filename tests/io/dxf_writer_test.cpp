// The cutting DXF read back with a small reader written here: a well-formed file (group-code
// pairs, sections opened and closed, EOF last), one layer per plate, and every outline vertex,
// bulge and hole where the model puts it, as drawn and in a solved pose.
#include "nbar/io/dxf_writer.hpp"
#include "nbar/analysis/pose.hpp"
#include "nbar/io/model_file.hpp"
#include "nbar/kinematics/sweep.hpp"
#include "nbar/model/diagnostics.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <map>
#include <numbers>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace nbar::io {
namespace {

struct Pair {
  int code;
  std::string value;
};

// Group codes and values on alternate lines; a code must be an integer.
std::vector<Pair> read_pairs(const std::string& text) {
  std::istringstream in(text);
  std::vector<Pair> pairs;
  std::string code, value;
  while (std::getline(in, code)) {
    EXPECT_TRUE(std::getline(in, value)) << "a group code without its value: " << code;
    std::size_t used = 0;
    const int c = std::stoi(code, &used);
    EXPECT_EQ(code.find_first_not_of(' ', used), std::string::npos) << "not a group code: '" << code << "'";
    pairs.push_back({c, value});
  }
  return pairs;
}

struct Entity {
  std::string type, layer;
  std::map<int, std::vector<double>> numbers;  // every value of a numeric group code, in order
  std::vector<Entity> vertices;                // a POLYLINE's VERTEXes
};

// The ENTITIES section, with POLYLINEs gathering their VERTEXes up to SEQEND; checks the
// sections' nesting and the EOF at the end on the way.
std::vector<Entity> read_entities(const std::vector<Pair>& pairs, std::vector<std::string>* layers) {
  std::vector<Entity> entities;
  std::string section;
  bool in_polyline = false;
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const Pair& p = pairs[i];
    if (p.code == 0 && p.value == "SECTION") {
      EXPECT_EQ(section, "") << "a SECTION inside " << section;
      EXPECT_EQ(pairs.at(i + 1).code, 2);
      section = pairs.at(i + 1).value;
      ++i;
      continue;
    }
    if (p.code == 0 && p.value == "ENDSEC") {
      EXPECT_NE(section, "") << "ENDSEC outside a section";
      EXPECT_FALSE(in_polyline) << "a POLYLINE without SEQEND";
      section.clear();
      continue;
    }
    if (p.code == 0 && p.value == "EOF") {
      EXPECT_EQ(i + 1, pairs.size()) << "EOF before the end";
      EXPECT_EQ(section, "") << "EOF inside a section";
      continue;
    }
    if (section == "TABLES" && p.code == 0 && p.value == "LAYER") layers->push_back(pairs.at(i + 1).value);
    if (section != "ENTITIES") continue;
    if (p.code == 0) {
      if (p.value == "SEQEND") {
        in_polyline = false;
        continue;
      }
      Entity e;
      e.type = p.value;
      if (p.value == "VERTEX") {
        EXPECT_TRUE(in_polyline) << "a VERTEX outside a POLYLINE";
        entities.back().vertices.push_back(e);
      } else {
        EXPECT_FALSE(in_polyline) << p.value << " inside a POLYLINE";
        in_polyline = p.value == "POLYLINE";
        entities.push_back(e);
      }
      continue;
    }
    Entity& e = in_polyline && !entities.back().vertices.empty() ? entities.back().vertices.back() : entities.back();
    if (p.code == 8) {
      e.layer = p.value;
    } else {
      e.numbers[p.code].push_back(std::stod(p.value));
    }
  }
  EXPECT_FALSE(pairs.empty());
  if (!pairs.empty()) {
    EXPECT_EQ(pairs.back().value, "EOF");
  }
  return entities;
}

// A crank O-A as a slot with a pin hole at each end and a polygon hole with an arc, and a
// rocker bar; lengths in mm.
const std::string kModel =
    "units: {length: mm}\n"
    "points: {O: [0, 0], A: [80, 0], B: [180, 150], C: [200, 0]}\n"
    "ground: [O, C]\n"
    "bodies:\n"
    "  crank:\n"
    "    points: [O, A]\n"
    "    shape:\n"
    "      outline: [[0, -10], [80, -10, {bulge: 1}], [80, 10], [0, 10, {bulge: 1}]]\n"
    "      holes: [{at: O, radius: 5}, {at: A, radius: 5}, {polygon: [[30, -4], [50, -4, {bulge: 0.5}], [50, 4], [30, "
    "4]]}]\n"
    "    thickness: 8\n"
    "    material: steel\n"
    "  coupler: [A, B]\n"
    "  rocker point:\n"
    "    points: [C, B]\n"
    "    bar: {width: 20, margin: 12, hole: 5}\n"
    "    thickness: 8\n"
    "    material: steel\n"
    "drivers: [{angle: crank, from: 0, to: 360}]\n";

TEST(DxfWriter, WellFormedWithOneLayerPerPlate) {
  const Mechanism mech(parse_model(kModel, "m.yaml").model);
  std::vector<Eigen::Vector2d> drawn;
  for (const Point& p : mech.model().points) drawn.push_back(p.position);
  const std::string dxf = cutting_dxf(mech, drawn);
  std::vector<std::string> layers;
  const std::vector<Entity> entities = read_entities(read_pairs(dxf), &layers);
  EXPECT_THAT(layers, ::testing::ElementsAre("crank", "rocker_point"));  // the coupler has no plate
  EXPECT_THAT(dxf, ::testing::HasSubstr("$ACADVER\n  1\nAC1009\n"));
  EXPECT_THAT(dxf, ::testing::HasSubstr("$INSUNITS\n 70\n4\n"));  // millimetres

  // The crank: its outline and polygon hole as closed POLYLINEs with their bulges, two CIRCLEs.
  std::vector<const Entity*> crank;
  for (const Entity& e : entities)
    if (e.layer == "crank") crank.push_back(&e);
  ASSERT_EQ(crank.size(), 4u);
  const Entity& outline = *crank[0];
  EXPECT_EQ(outline.type, "POLYLINE");
  EXPECT_EQ(outline.numbers.at(70).front(), 1);  // closed
  ASSERT_EQ(outline.vertices.size(), 4u);
  const double xs[] = {0, 80, 80, 0}, ys[] = {-10, -10, 10, 10}, bulges[] = {0, 1, 0, 1};
  for (int i = 0; i < 4; ++i) {
    const Entity& v = outline.vertices[i];
    EXPECT_EQ(v.layer, "crank");
    EXPECT_DOUBLE_EQ(v.numbers.at(10).front(), xs[i]);
    EXPECT_DOUBLE_EQ(v.numbers.at(20).front(), ys[i]);
    EXPECT_DOUBLE_EQ(v.numbers.count(42) ? v.numbers.at(42).front() : 0.0, bulges[i]);
  }
  EXPECT_EQ(crank[1]->type, "POLYLINE");
  ASSERT_EQ(crank[1]->vertices.size(), 4u);
  EXPECT_DOUBLE_EQ(crank[1]->vertices[1].numbers.at(42).front(), 0.5);
  EXPECT_EQ(crank[2]->type, "CIRCLE");
  EXPECT_DOUBLE_EQ(crank[2]->numbers.at(10).front(), 0);
  EXPECT_DOUBLE_EQ(crank[2]->numbers.at(40).front(), 5);
  EXPECT_EQ(crank[3]->type, "CIRCLE");
  EXPECT_DOUBLE_EQ(crank[3]->numbers.at(10).front(), 80);

  // The rocker's bar: a rectangle 20 wide around C-B, 12 beyond each end, and its two holes.
  std::vector<const Entity*> rocker;
  for (const Entity& e : entities)
    if (e.layer == "rocker_point") rocker.push_back(&e);
  ASSERT_EQ(rocker.size(), 3u);
  const Eigen::Vector2d c(200, 0), b(180, 150), u = (b - c).normalized(), n(-u.y(), u.x());
  const Eigen::Vector2d corner = c - 12 * u - 10 * n;
  EXPECT_NEAR(rocker[0]->vertices[0].numbers.at(10).front(), corner.x(), 1e-9);
  EXPECT_NEAR(rocker[0]->vertices[0].numbers.at(20).front(), corner.y(), 1e-9);
  EXPECT_NEAR(rocker[2]->numbers.at(10).front(), 180, 1e-9);
  EXPECT_NEAR(rocker[2]->numbers.at(20).front(), 150, 1e-9);
}

TEST(DxfWriter, PlatesMoveWithTheSolvedPose) {
  const Mechanism mech(parse_model(kModel, "m.yaml").model);
  // The crank turned to 90 degrees: its plate turns a quarter turn about O.
  const Sample pose = pose_at(mech, 90);
  const std::string dxf = cutting_dxf(mech, point_positions(mech, pose.taylor.col(0)));
  std::vector<std::string> layers;
  const std::vector<Entity> entities = read_entities(read_pairs(dxf), &layers);
  const Entity& outline = entities.at(0);
  ASSERT_EQ(outline.layer, "crank");
  const double xs[] = {0, 80, 80, 0}, ys[] = {-10, -10, 10, 10};
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(outline.vertices[i].numbers.at(10).front(), -ys[i], 1e-9);
    EXPECT_NEAR(outline.vertices[i].numbers.at(20).front(), xs[i], 1e-9);
  }
  EXPECT_DOUBLE_EQ(outline.vertices[1].numbers.at(42).front(), 1);
  EXPECT_NEAR(entities.at(3).numbers.at(20).front(), 80, 1e-9);  // the hole at A, now at (0, 80)
}

// kModel in metres with every length times `scale` (the bulges are ratios and stay).
std::string scaled_model(double scale) {
  std::string text = kModel;
  text.replace(text.find("{length: mm}"), 12, "{length: m}");
  std::string out;
  const std::regex number(R"((bulge: )?-?\d+(\.\d+)?)");
  std::size_t at = 0;
  for (std::sregex_iterator it(text.begin(), text.end(), number), end; it != end; ++it) {
    const std::smatch& m = *it;
    out.append(text, at, static_cast<std::size_t>(m.position()) - at);
    at = static_cast<std::size_t>(m.position() + m.length());
    const bool length = !m[1].matched && text.compare(static_cast<std::size_t>(m.position()) - 6, 5, "from:") != 0 &&
                        text.compare(static_cast<std::size_t>(m.position()) - 4, 3, "to:") != 0;
    out += length ? fmt::format("{:.17g}", std::stod(m.str()) * scale) : m.str();
  }
  return out + text.substr(at);
}

// The numbers an SVG of plates writes, each marked a length or not (an A command's rotation
// and flags, the stroke width in mm), and the text around them.
struct Written {
  std::string skeleton;
  std::vector<double> values;
  std::vector<bool> lengths;
};

Written svg_numbers(const std::string& svg) {
  Written w;
  const std::regex attribute(R"(([\w-]+)=\"([^\"]*)\")");
  std::size_t at = 0;
  for (std::sregex_iterator it(svg.begin(), svg.end(), attribute), end; it != end; ++it) {
    const std::string name = (*it)[1].str(), value = (*it)[2].str();
    const bool lengths =
        name == "width" || name == "height" || name == "viewBox" || name == "cx" || name == "cy" || name == "r";
    if (!lengths && name != "d" && name != "stroke-width") continue;
    const auto pos = static_cast<std::size_t>(it->position(2));
    w.skeleton += svg.substr(at, pos - at);
    at = pos + value.size();
    std::istringstream tokens(value);
    std::string token;
    int in_arc = -1;  // the place of a number among an A command's seven, -1 outside one
    while (tokens >> token) {
      if (std::isalpha(static_cast<unsigned char>(token[0])) &&
          token.find_first_of("0123456789") == std::string::npos) {
        w.skeleton += token + " ";
        in_arc = token == "A" ? 0 : -1;
        continue;
      }
      std::size_t used = 0;
      w.values.push_back(std::stod(token, &used));
      w.skeleton += '#';
      w.skeleton.append(token, used);  // "mm" after a width
      w.skeleton += ' ';
      const bool ratio = name == "stroke-width" || (in_arc >= 2 && in_arc <= 4);
      w.lengths.push_back(!ratio);
      if (in_arc >= 0) ++in_arc;
    }
  }
  w.skeleton += svg.substr(at);
  return w;
}

Written dxf_numbers(const std::string& dxf) {
  Written w;
  for (const Pair& p : read_pairs(dxf)) {
    const bool length = p.code == 10 || p.code == 20 || p.code == 30 || p.code == 40;
    if (!length && p.code != 42) {
      w.skeleton += std::to_string(p.code) + " " + p.value + "\n";
      continue;
    }
    w.skeleton += std::to_string(p.code) + " #\n";
    w.values.push_back(std::stod(p.value));
    w.lengths.push_back(length);
  }
  return w;
}

// The same plates in a model in metres at 1e-12 to 1e6 the size: every length written the one
// at scale 1 times the scale, to 1e-9 of itself, none of them 0 but those that are at scale 1,
// in DXF and in SVG, as drawn and in a solved pose. Rounded to a fixed 1e-9 of the unit, a
// plate 2.5e-4 m across kept 5 significant digits and one 2.5e-10 m across was all zeros.
TEST(DxfWriter, TheModelsScaleChangesNothingButTheLengths) {
  const auto written = [](double scale, bool posed, bool svg) {
    const Mechanism mech(parse_model(scaled_model(scale), "m.yaml").model);
    std::vector<Eigen::Vector2d> points;
    for (const Point& p : mech.model().points) points.push_back(p.position);
    if (posed) points = point_positions(mech, pose_at(mech, 30).taylor.col(0));
    return svg ? svg_numbers(cutting_svg(mech, points)) : dxf_numbers(cutting_dxf(mech, points));
  };
  for (const bool svg : {false, true}) {
    for (const bool posed : {false, true}) {
      const Written one = written(1, posed, svg);
      ASSERT_GT(one.values.size(), 40u);
      for (const double scale : {1e-12, 1e-9, 1e-6, 1e-3, 1e3, 1e6}) {
        SCOPED_TRACE(fmt::format("{} at {}{}", svg ? "SVG" : "DXF", scale, posed ? ", posed" : ""));
        const Written w = written(scale, posed, svg);
        ASSERT_EQ(w.skeleton, one.skeleton);
        ASSERT_EQ(w.values.size(), one.values.size());
        int wrong = 0;
        for (std::size_t i = 0; i < w.values.size(); ++i) {
          const double expected = one.lengths[i] ? one.values[i] * scale : one.values[i];
          const bool ok = std::abs(w.values[i] - expected) <= 1e-9 * std::abs(expected) &&
                          (w.values[i] == 0) == (one.values[i] == 0);
          if (!ok && ++wrong <= 5) ADD_FAILURE() << "number " << i << ": " << w.values[i] << ", not " << expected;
        }
        EXPECT_EQ(wrong, 0);
      }
    }
  }
}

TEST(DxfWriter, NothingToCut) {
  const Mechanism mech(parse_model("points: {O: [0, 0], A: [1, 0]}\nground: [O]\nbodies: {crank: [O, A]}\n"
                                   "drivers: [{angle: crank, from: 0, to: 90}]\n",
                                   "m.yaml")
                           .model);
  std::vector<Eigen::Vector2d> drawn{{0, 0}, {1, 0}};
  EXPECT_THROW(cutting_dxf(mech, drawn), Error);
}

TEST(DxfWriter, LayerNames) {
  EXPECT_EQ(dxf_layer_name("rocker point"), "rocker_point");
  EXPECT_EQ(dxf_layer_name("arm-2$"), "arm-2$");
  EXPECT_EQ(dxf_layer_name("é"), "__");
}

}  // namespace
}  // namespace nbar::io
