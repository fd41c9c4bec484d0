#include "tsmframe/util/segment_grid.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace tsm::util {

SegmentGrid::SegmentGrid(const std::vector<Segment>& segments) {
  const long n = static_cast<long>(segments.size());
  low_.reserve(n);
  high_.reserve(n);
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(INFINITY), hi = Eigen::Vector2d::Constant(-INFINITY);
  double extent_sum = 0.0;
  bool finite = true;
  for (const Segment& s : segments) {
    low_.push_back(s.a.cwiseMin(s.b));
    high_.push_back(s.a.cwiseMax(s.b));
    finite = finite && s.a.allFinite() && s.b.allFinite();
    lo = lo.cwiseMin(low_.back());
    hi = hi.cwiseMax(high_.back());
    extent_sum += (high_.back() - low_.back()).maxCoeff();
  }
  if (n == 0 || !finite) return;
  const Eigen::Vector2d span = hi - lo;
  // A cell as large as an average segment's box, no smaller than the side that would give one
  // cell per segment over the whole box, and at most about four cells per segment.
  cell_ = std::max(extent_sum / static_cast<double>(n), std::sqrt(span.x() * span.y() / static_cast<double>(n)));
  if (!(cell_ > 0.0)) cell_ = std::max(span.maxCoeff(), 1.0);
  const auto count = [&](double side) { return std::floor(side / cell_) + 1.0; };  // in double: no overflow
  while (count(span.x()) * count(span.y()) > 4.0 * static_cast<double>(n) + 64.0) cell_ *= 2.0;
  if (!std::isfinite(cell_)) return;
  origin_ = lo;
  corner_ = hi;
  columns_ = static_cast<long>(count(span.x()));
  rows_ = static_cast<long>(count(span.y()));
  usable_ = true;
  cell_start_.assign(columns_ * rows_ + 1, 0);
  const auto each_cell = [&](int s, auto&& visit) {
    const long c0 = cell_index(low_[s].x(), 0), c1 = cell_index(high_[s].x(), 0);
    const long r0 = cell_index(low_[s].y(), 1), r1 = cell_index(high_[s].y(), 1);
    if ((c1 - c0 + 1) * (r1 - r0 + 1) > large_cells) return false;
    for (long r = r0; r <= r1; ++r)
      for (long c = c0; c <= c1; ++c) visit(r * columns_ + c);
    return true;
  };
  for (int s = 0; s < n; ++s)
    if (!each_cell(s, [&](long cell) { ++cell_start_[cell + 1]; })) large_.push_back(s);
  std::partial_sum(cell_start_.begin(), cell_start_.end(), cell_start_.begin());
  cell_segments_.resize(cell_start_.back());
  std::vector<int> fill(cell_start_.begin(), cell_start_.end() - 1);
  for (int s = 0; s < n; ++s) each_cell(s, [&](long cell) { cell_segments_[fill[cell]++] = s; });
}

long SegmentGrid::cell_index(double v, int axis) const {
  const long last = (axis == 0 ? columns_ : rows_) - 1;
  const double at = std::floor((v - origin_[axis]) / cell_);
  if (!(at > 0.0)) return 0;  // NaN too
  return at >= static_cast<double>(last) ? last : static_cast<long>(at);
}

void SegmentGrid::in_box(const Eigen::Vector2d& low, const Eigen::Vector2d& high, std::vector<int>& found) const {
  found.clear();
  const auto meets = [&](int s) {
    return !((high_[s].array() < low.array()).any() || (low_[s].array() > high.array()).any());
  };
  if (!usable_ || !low.allFinite() || !high.allFinite()) {
    for (int s = 0; s < size(); ++s)
      if (!usable_ || meets(s)) found.push_back(s);
    return;
  }
  for (const int s : large_)
    if (meets(s)) found.push_back(s);
  // Beside the boxes' own bounds (exact, not the cells' rounded ones) no segment is met.
  if (!(high.array() < origin_.array()).any() && !(low.array() > corner_.array()).any()) {
    const long c0 = cell_index(low.x(), 0), c1 = cell_index(high.x(), 0);
    const long r0 = cell_index(low.y(), 1), r1 = cell_index(high.y(), 1);
    for (long r = r0; r <= r1; ++r)
      for (long c = c0; c <= c1; ++c) {
        const long cell = r * columns_ + c;
        for (int i = cell_start_[cell]; i < cell_start_[cell + 1]; ++i)
          if (meets(cell_segments_[i])) found.push_back(cell_segments_[i]);
      }
  }
  std::sort(found.begin(), found.end());
  found.erase(std::unique(found.begin(), found.end()), found.end());
}

}  // namespace tsm::util
