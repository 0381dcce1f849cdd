#include "model/box_index.hpp"

#include <algorithm>
#include <cmath>

namespace nbar {

namespace {

constexpr double kMostColumns = 2e6;

bool finite(const Eigen::AlignedBox2d& b) {
  return b.min().allFinite() && b.max().allFinite() && (b.min().array() <= b.max().array()).all();
}

}  // namespace

Eigen::AlignedBox2d inflated(const Eigen::AlignedBox2d& box) {
  const double size = std::max(box.min().cwiseAbs().maxCoeff(), box.max().cwiseAbs().maxCoeff());
  const Eigen::Vector2d pad = Eigen::Vector2d::Constant(1e-9 * size + 1e-300);
  return {box.min() - pad, box.max() + pad};
}

BoxIndex::BoxIndex(std::vector<Eigen::AlignedBox2d> boxes) : boxes_(std::move(boxes)), seen_(boxes_.size(), 0) {
  Eigen::AlignedBox2d all;
  double area = 0, perimeter = 0;
  std::size_t placed = 0;
  for (std::size_t i = 0; i < boxes_.size(); ++i) {
    if (!finite(boxes_[i])) {
      everywhere_.push_back(i);
      continue;
    }
    boxes_[i] = inflated(boxes_[i]);
    all.extend(boxes_[i]);
    area += boxes_[i].volume();
    perimeter += boxes_[i].sizes().sum();
    ++placed;
  }
  if (placed == 0) return;
  const Eigen::Vector2d extent = all.sizes();
  // A box of sides w, h meets about (w/side + 1)(h/side + 1) cells: summed over the boxes, their
  // area / side² + their half-perimeters / side + their count, each at most the count here.
  const double count = static_cast<double>(placed);
  side_ = std::max(std::sqrt(area / count), perimeter / count);
  // Boxes that are points (as far as the padding goes): about a box per cell over the extent.
  if (!(side_ > 1e-6 * extent.maxCoeff()))
    side_ = std::max(std::sqrt(extent.x() * extent.y() / count), extent.maxCoeff() / count);
  side_ = std::max({side_, extent.x() / kMostColumns, extent.y() / kMostColumns});
  if (!(side_ > 0)) side_ = 1.0;
  origin_ = all.min();
  columns_ = static_cast<std::int64_t>(std::min(kMostColumns, std::floor(extent.x() / side_))) + 1;
  rows_ = static_cast<std::int64_t>(std::min(kMostColumns, std::floor(extent.y() / side_))) + 1;
  for (std::size_t i = 0; i < boxes_.size(); ++i) {
    if (!finite(boxes_[i])) continue;
    const CellRange r = cells_of(boxes_[i]);
    for (std::int64_t x = r.x0; x <= r.x1; ++x)
      for (std::int64_t y = r.y0; y <= r.y1; ++y) cells_[key(x, y)].push_back(i);
  }
}

BoxIndex::CellRange BoxIndex::cells_of(const Eigen::AlignedBox2d& box) const {
  const auto cell = [&](double at, double from, std::int64_t count) {
    // NaN (a drawing whose extent overflows, so one cell) goes to cell 0 with the rest.
    const double c = std::floor((at - from) / side_);
    if (!(c > 0)) return std::int64_t{0};
    return c >= static_cast<double>(count - 1) ? count - 1 : static_cast<std::int64_t>(c);
  };
  return {cell(box.min().x(), origin_.x(), columns_), cell(box.min().y(), origin_.y(), rows_),
          cell(box.max().x(), origin_.x(), columns_), cell(box.max().y(), origin_.y(), rows_)};
}

std::vector<std::size_t> BoxIndex::meeting(const Eigen::AlignedBox2d& query) const {
  std::vector<std::size_t> out = everywhere_;
  if (!finite(query)) {
    out.resize(boxes_.size());
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = i;
    visits_ += out.size();
    return out;
  }
  const Eigen::AlignedBox2d q = inflated(query);
  ++queries_;
  const auto visit = [&](const std::vector<std::size_t>& cell) {
    for (std::size_t i : cell) {
      ++visits_;
      if (seen_[i] == queries_) continue;
      seen_[i] = queries_;
      if (boxes_[i].intersects(q)) out.push_back(i);
    }
  };
  const CellRange r = cells_of(q);
  const double span = static_cast<double>(r.x1 - r.x0 + 1) * static_cast<double>(r.y1 - r.y0 + 1);
  if (span > static_cast<double>(cells_.size())) {
    // A query wider than the occupied cells (a ray across the plate): those cells, not the range.
    for (const auto& [k, cell] : cells_) {
      const auto x = static_cast<std::int64_t>(k >> 32), y = static_cast<std::int64_t>(k & 0xffffffffu);
      if (x >= r.x0 && x <= r.x1 && y >= r.y0 && y <= r.y1) visit(cell);
    }
  } else {
    for (std::int64_t x = r.x0; x <= r.x1; ++x)
      for (std::int64_t y = r.y0; y <= r.y1; ++y)
        if (const auto it = cells_.find(key(x, y)); it != cells_.end()) visit(it->second);
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace nbar
