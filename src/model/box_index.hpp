#pragma once

#include <Eigen/Geometry>

#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "nbar/model/geometry.hpp"

namespace nbar {

// The most holes (polygon and circle together) a plate may have: check_region is near-linear
// in them (docs/robustness.md), and a plate of 100 000 holes is already a 5 MB model file.
inline constexpr std::size_t kMaxHolesPerPlate = 100000;

// The smallest box holding the ring (its arcs included) or the circle: for indexing shapes.
Eigen::AlignedBox2d ring_bounds(const std::vector<Eigen::Vector2d>& ring, const std::vector<double>& bulges);
Eigen::AlignedBox2d circle_bounds(const Circle& c);

// The elementary geometric tests (a pair of edges, an edge and a point, a pair of circles, an
// entry looked at in a spatial index) the checks and readers ran on this thread since it
// started: what the tests compare between an input and one twice its size, to show that the
// work about doubles, instead of timing them.
std::size_t geometry_work();
void add_geometry_work(std::size_t tests);

// A uniform grid over bounding boxes, so that the readers' and checks' tests between shapes
// (holes that overlap, outlines that nest, edges that cross) only touch the shapes near each
// other instead of every pair (8 000 holes were 32 million pair tests and 40 s).
//
// The cell's side is chosen so that a box meets a few cells on average whatever the sizes and
// shapes (a long edge is a thin box): side = max(sqrt(sum of areas / n), sum of (w + h) / n), so
// the boxes' cells sum to at most about 3 per box (2 000 000 columns at most per axis). Boxes are inflated by a
// relative 1e-9 of their coordinates, so that an exact test in floating point that a box test ruled out cannot have
// passed by a rounding error: an index only narrows the candidates, it never decides.
class BoxIndex {
 public:
  explicit BoxIndex(std::vector<Eigen::AlignedBox2d> boxes);

  // The boxes (their indices, ascending, each once) that meet `query` (closed boxes). A box or a
  // query that is not finite meets everything: the caller's exact test decides.
  std::vector<std::size_t> meeting(const Eigen::AlignedBox2d& query) const;

  std::size_t size() const { return boxes_.size(); }
  // Every box a query looked at, summed over the queries so far: the work of the index, which
  // the tests compare between inputs of different sizes (so that doubling the input about
  // doubles it) instead of timing them.
  std::size_t visits() const { return visits_; }

 private:
  using Key = std::uint64_t;
  struct CellRange {
    std::int64_t x0, y0, x1, y1;
  };
  CellRange cells_of(const Eigen::AlignedBox2d& box) const;
  static Key key(std::int64_t x, std::int64_t y) { return (static_cast<Key>(x) << 32) | static_cast<Key>(y); }

  std::vector<Eigen::AlignedBox2d> boxes_;  // inflated
  std::vector<std::size_t> everywhere_;     // boxes that are not finite
  Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();
  double side_ = 1.0;
  std::int64_t columns_ = 1, rows_ = 1;
  std::unordered_map<Key, std::vector<std::size_t>> cells_;
  mutable std::vector<std::size_t> seen_;  // the query that last found each box
  mutable std::size_t queries_ = 0;
  mutable std::size_t visits_ = 0;
};

// `box` grown by a relative 1e-9 of its coordinates (and 1e-300), as the index grows its own.
Eigen::AlignedBox2d inflated(const Eigen::AlignedBox2d& box);

}  // namespace nbar
