// The readers and checks are near-linear (issue 41): each is given an input and one twice its
// size, and the elementary geometric tests it ran (geometry_work(), counted where they run, so a
// loop over all pairs anywhere would show) must about double, not quadruple. Counting, not
// timing, so that a loaded machine cannot fail them. And the spatial index must find the same
// first fault the scan of every pair found.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <random>
#include <string>
#include <vector>

#include "model/box_index.hpp"
#include "nbar/io/model_file.hpp"
#include "nbar/io/sketch.hpp"
#include "nbar/io/sketch_model.hpp"
#include "nbar/model/diagnostics.hpp"
#include "nbar/model/geometry.hpp"
#include "nbar/model/model.hpp"

namespace nbar {
namespace {

using Eigen::Vector2d;

// The work `run` does, as geometry_work() counts it.
template <class Run>
double work_of(const Run& run) {
  const std::size_t before = geometry_work();
  run();
  return static_cast<double>(geometry_work() - before);
}

// Work for n and for 2n: the ratio of a linear check is 2 (a little more for the logarithms
// of sorting and for cells at the grid's edges), of one over all pairs 4.
template <class Run>
double doubling_ratio(int n, const Run& run) {
  const double once = work_of([&] { run(n); });
  const double twice = work_of([&] { run(2 * n); });
  EXPECT_GT(once, n) << "the work counter counted nothing";
  return twice / once;
}

constexpr double kLinear = 2.5;

// A square plate of side about 10 sqrt(n) holding n holes on a grid of pitch 10.
Region plate_with_holes(int n, bool polygons) {
  const int side = static_cast<int>(std::ceil(std::sqrt(n)));
  Region r;
  r.outline = {{-10, -10}, {10.0 * side, -10}, {10.0 * side, 10.0 * side}, {-10, 10.0 * side}};
  for (int k = 0; k < n; ++k) {
    const Vector2d c(10.0 * (k / side), 10.0 * (k % side));
    if (polygons) {
      r.polygon_holes.push_back({c + Vector2d(-3, -3), c + Vector2d(3, -3), c + Vector2d(3, 3), c + Vector2d(-3, 3)});
    } else {
      r.circle_holes.push_back({c, 3});
    }
  }
  return r;
}

TEST(ReaderScaling, CheckRegionWithRoundHolesIsNearLinear) {
  EXPECT_LT(doubling_ratio(2000, [](int n) { check_region(plate_with_holes(n, false)); }), kLinear);
}

TEST(ReaderScaling, CheckRegionWithPolygonHolesIsNearLinear) {
  EXPECT_LT(doubling_ratio(2000, [](int n) { check_region(plate_with_holes(n, true)); }), kLinear);
}

// The model reader checks each listed hole, and each pair near each other.
std::string model_with_holes(int n) {
  const int side = static_cast<int>(std::ceil(std::sqrt(n)));
  std::string text = fmt::format(R"(units: {{length: mm, angle: deg}}
points: {{O2: [0, 0], O4: [200, 0], A: [80, 0], B: [181.25, 148.823511]}}
ground: [O2, O4]
bodies:
  crank: {{points: [O2, A], mass: 1}}
  rocker: {{points: [O4, B], mass: 1}}
  coupler:
    points: [A, B]
    thickness: 10
    material: steel
    shape:
      outline: [[-100, {0}], [{1}, {0}], [{1}, 300], [-100, 300]]
      holes:
)",
                                 -110.0 - 10.0 * side, std::max(300.0, 10.0 * side));
  for (int k = 0; k < n; ++k)
    text += fmt::format("        - {{circle: [{}, {}], radius: 3}}\n", -90 + 10 * (k / side),
                        -100 - 10 * side + 10 * (k % side));
  return text + "drivers:\n  - {angle: crank, from: 0, to: 360}\n";
}

TEST(ReaderScaling, ModelFileHolesAreNearLinear) {
  EXPECT_LT(doubling_ratio(1000, [](int n) { io::parse_model(model_with_holes(n), "m.yaml"); }), kLinear);
}

// DXF: a plate holding n pin holes (CIRCLEs), or n separate squares (LWPOLYLINEs).
std::string dxf(int n, bool squares) {
  const int side = static_cast<int>(std::ceil(std::sqrt(n)));
  std::string text = "0\nSECTION\n2\nENTITIES\n";
  const auto square = [&](double x0, double y0, double x1, double y1) {
    text += fmt::format(
        "0\nLWPOLYLINE\n8\n0\n90\n4\n70\n1\n10\n{0}\n20\n{1}\n10\n{2}\n20\n{1}\n10\n{2}\n20\n{3}\n10\n{0}\n20\n{3}\n",
        x0, y0, x1, y1);
  };
  if (!squares) square(-10, -10, 10.0 * side, 10.0 * side);
  for (int k = 0; k < n; ++k) {
    const double x = 10.0 * (k / side), y = 10.0 * (k % side);
    if (squares) {
      square(x, y, x + 5, y + 5);
      text += fmt::format("0\nCIRCLE\n8\n0\n10\n{}\n20\n{}\n40\n1\n", x + 2.5, y + 2.5);
    } else {
      text += fmt::format("0\nCIRCLE\n8\n0\n10\n{}\n20\n{}\n40\n2\n", x, y);
    }
  }
  return text + "0\nENDSEC\n0\nEOF\n";
}

void import(const std::string& text, io::SketchFormat format) {
  io::SketchModelOptions options;
  options.source_name = "drawing";
  io::model_from_sketch(io::read_sketch(text, "drawing", format), options);
}

TEST(ReaderScaling, DxfImportOfManyCirclesIsNearLinear) {
  EXPECT_LT(doubling_ratio(2000, [](int n) { import(dxf(n, false), io::SketchFormat::kDxf); }), kLinear);
}

TEST(ReaderScaling, DxfImportOfManySeparatePlatesIsNearLinear) {
  EXPECT_LT(doubling_ratio(1000, [](int n) { import(dxf(n, true), io::SketchFormat::kDxf); }), kLinear);
}

// SVG: n small square paths, each with a round hole, so that each is a link.
std::string svg(int n) {
  const int side = static_cast<int>(std::ceil(std::sqrt(n)));
  std::string text = fmt::format(R"(<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 {0} {0}">)", 10 * side) + "\n";
  for (int k = 0; k < n; ++k) {
    const int x = 10 * (k / side), y = 10 * (k % side);
    text += fmt::format(R"(<path d="M {} {} h 5 v 5 h -5 z"/><circle cx="{}" cy="{}" r="1"/>)", x, y, x + 2.5, y + 2.5);
    text += "\n";
  }
  return text + "</svg>\n";
}

TEST(ReaderScaling, SvgImportOfManyPathsIsNearLinear) {
  EXPECT_LT(doubling_ratio(1000, [](int n) { import(svg(n), io::SketchFormat::kSvg); }), kLinear);
}

// The first overlapping pair by a scan of every pair, in check_region's order: each polygon
// with each later polygon, then with each circle; then each circle with each later circle.
std::string first_overlap_by_scan(const Region& r) {
  const auto inside = [](const std::vector<Vector2d>& p, const Vector2d& x) {
    bool in = false;
    for (std::size_t i = 0, j = p.size() - 1; i < p.size(); j = i++)
      if ((p[i].y() > x.y()) != (p[j].y() > x.y()) &&
          x.x() < (p[j].x() - p[i].x()) * (x.y() - p[i].y()) / (p[j].y() - p[i].y()) + p[i].x())
        in = !in;
    return in;
  };
  const std::size_t polygons = r.polygon_holes.size(), circles = r.circle_holes.size();
  for (std::size_t i = 0; i < polygons; ++i) {
    const auto& a = r.polygon_holes[i];
    for (std::size_t j = i + 1; j < polygons; ++j) {
      const auto& b = r.polygon_holes[j];
      if (polygons_meet(a, b) || inside(a, b[0]) || inside(b, a[0]))
        return fmt::format("polygon hole {} and polygon hole {}", i, j);
    }
    for (std::size_t j = 0; j < circles; ++j)
      if (inside(a, r.circle_holes[j].centre) || !circle_clear_of_edges(r.circle_holes[j], a))
        return fmt::format("polygon hole {} and circle hole {}", i, j);
  }
  for (std::size_t i = 0; i < circles; ++i)
    for (std::size_t j = i + 1; j < circles; ++j)
      if ((r.circle_holes[i].centre - r.circle_holes[j].centre).norm() <=
          r.circle_holes[i].radius + r.circle_holes[j].radius)
        return fmt::format("circle hole {} and circle hole {}", i, j);
  return "";
}

// Random holes of random sizes on a plate, some overlapping: the index's first fault is the
// scan's, over 300 plates (most of which have several overlapping pairs).
TEST(ReaderScaling, IndexedHoleCheckReportsTheScansFirstOverlap) {
  std::mt19937 random(41);
  std::uniform_real_distribution<double> at(0, 100), size(0.2, 4);
  int faults = 0;
  for (int plate = 0; plate < 300; ++plate) {
    Region r;
    r.outline = {{-20, -20}, {120, -20}, {120, 120}, {-20, 120}};
    const int holes = 20 + plate % 40;
    for (int k = 0; k < holes; ++k) {
      const Vector2d c(at(random), at(random));
      if (k % 3 == 0) {
        const double h = size(random);
        r.polygon_holes.push_back({c + Vector2d(-h, -h), c + Vector2d(h, -h), c + Vector2d(0, h)});
      } else {
        r.circle_holes.push_back({c, size(random)});
      }
    }
    const std::string expected = first_overlap_by_scan(r);
    try {
      check_region(r);
      EXPECT_EQ(expected, "") << "plate " << plate;
    } catch (const Error& e) {
      ++faults;
      ASSERT_NE(expected, "") << "plate " << plate << ": " << e.what();
      // "circle hole 3 (centre ..., radius ...) and circle hole 7 (...) overlap": the two names.
      std::string names = e.what();
      for (std::size_t open = names.find(" ("); open != std::string::npos; open = names.find(" (")) {
        std::size_t close = open + 2, depth = 1;
        while (close < names.size() && depth > 0)
          depth += names[close] == '(' ? 1 : names[close] == ')' ? -1 : 0, ++close;
        names.erase(open, close - open);
      }
      EXPECT_EQ(names, expected + " overlap") << "plate " << plate;
    }
  }
  EXPECT_GT(faults, 200);  // the comparison was mostly of faults, not of clean plates
}

TEST(ReaderScaling, TooManyHolesAreRefusedByCount) {
  Region r = plate_with_holes(static_cast<int>(kMaxHolesPerPlate) + 1, false);
  try {
    check_region(r);
    FAIL() << "a plate of 100 001 holes was accepted";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "the plate has 100001 holes; at most 100000 are allowed");
  }
}

// One entity more than a drawing may hold: refused at the line where that entity starts.
TEST(ReaderScaling, TooManyEntitiesInADrawingAreRefusedAtTheFirstOneOver) {
  std::string text = "0\nSECTION\n2\nENTITIES\n";  // lines 1-4; entity k starts at line 5 + 8k
  for (int k = 0; k <= 200000; ++k) text += fmt::format("0\nPOINT\n8\n0\n10\n{}\n20\n0\n", k);
  text += "0\nENDSEC\n0\nEOF\n";
  try {
    io::read_sketch(text, "many.dxf", io::SketchFormat::kDxf);
    FAIL() << "200 001 entities were read";
  } catch (const io::ModelFileError& e) {
    EXPECT_EQ(std::string(e.what()),
              "many.dxf:1600005:1: the drawing has 200001 entities (lines, arcs, curves, circles and points); at "
              "most 200000 are read, and this is the first one over");
  }
}

// One hole more than a plate may have: refused at that hole's line and column.
TEST(ReaderScaling, TooManyHolesInAModelAreRefusedAtTheFirstOneOver) {
  const std::string text = model_with_holes(static_cast<int>(kMaxHolesPerPlate) + 1);
  // The holes are listed from line 14, one a line, at column 11 ("        - {circle...").
  try {
    io::parse_model(text, "m.yaml");
    FAIL() << "a plate of 100 001 holes was read";
  } catch (const io::ModelFileError& e) {
    EXPECT_EQ(
        std::string(e.what()),
        "m.yaml:100014:11: the shape of body 'coupler' is not valid: a plate has at most 100000 holes; this is one "
        "more");
  }
}

TEST(ReaderScaling, BoxIndexFindsExactlyTheBoxesThatMeet) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> at(-50, 50), size(0, 8);
  std::vector<Eigen::AlignedBox2d> boxes;
  for (int k = 0; k < 500; ++k) {
    const Vector2d lo(at(random), at(random));
    boxes.emplace_back(lo, lo + Vector2d(size(random), k % 7 == 0 ? 0.0 : size(random)));
  }
  const BoxIndex index(boxes);
  for (int q = 0; q < 200; ++q) {
    const Vector2d lo(at(random), at(random));
    const Eigen::AlignedBox2d query(lo, lo + Vector2d(size(random) * 3, size(random)));
    std::vector<std::size_t> expected;
    for (std::size_t k = 0; k < boxes.size(); ++k)
      if (inflated(boxes[k]).intersects(inflated(query))) expected.push_back(k);
    EXPECT_EQ(index.meeting(query), expected) << "query " << q;
  }
}

}  // namespace
}  // namespace nbar
