#pragma once
// A uniform grid over line segments (beam chords): which segments' boxes meet a query box, in
// time that grows with the cells and segments near the query rather than with all segments.
// Used where every contact node would otherwise scan every element (resting contacts, the
// nearest candidate, the broad phase's near lists): the grid gives a superset, the caller applies
// its own exact test to it in ascending index order, so what it finds is what a scan finds.
//
// Each segment is kept in the cells its box covers; a segment covering more than `large_cells`
// cells (one long element beside many short ones) is kept in a list every query returns. Cell
// indices come from floor((v − origin) / h), monotone in v, so a box that meets a segment's box
// always meets one of its cells. Coordinates that are not finite leave the grid unusable: every
// query then returns every segment (the caller's scan, unchanged).

#include <Eigen/Core>
#include <vector>

namespace tsm::util {

struct Segment {
  Eigen::Vector2d a, b;
};

class SegmentGrid {
 public:
  explicit SegmentGrid(const std::vector<Segment>& segments);

  /// The segments (indices, ascending, each once) whose boxes meet the box [low, high].
  void in_box(const Eigen::Vector2d& low, const Eigen::Vector2d& high, std::vector<int>& found) const;
  /// The segments whose boxes meet the square of half-width `radius` about `x`: every segment
  /// within `radius` of `x`, and some farther.
  void near(const Eigen::Vector2d& x, double radius, std::vector<int>& found) const {
    in_box(x.array() - radius, x.array() + radius, found);
  }
  /// The side of a cell: a query of half-width `radius` looks at about (2 radius / cell + 1)² cells.
  double cell() const { return cell_; }
  int size() const { return static_cast<int>(low_.size()); }
  /// False where a coordinate is not finite: every query returns every segment.
  bool usable() const { return usable_; }

 private:
  static constexpr long large_cells = 64;
  long cell_index(double v, int axis) const;

  std::vector<Eigen::Vector2d> low_, high_;  ///< each segment's box
  Eigen::Vector2d origin_ = Eigen::Vector2d::Zero(), corner_ = Eigen::Vector2d::Zero();  ///< the boxes' bounds
  double cell_ = 1.0;
  long columns_ = 0, rows_ = 0;
  std::vector<int> cell_start_, cell_segments_;  ///< the segments in each cell (CSR, row by row)
  std::vector<int> large_;                        ///< segments in every query's answer
  bool usable_ = false;
};

}  // namespace tsm::util
