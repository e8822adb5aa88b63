#pragma once
/// Keyframe positions in a hash grid of square cells on the ground plane, for the proximity
/// search: the keyframes within a radius of a position are found by visiting the cells that
/// the disc overlaps, nearest first, not every keyframe. Positions move (optimisation): move()
/// re-files a node whose cell changed. Each cell keeps its nodes in ascending order (the
/// order keyframes arrive), so that a search can look at a revisited place's latest ones only.

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace litamin2::mapping {

class SpatialGrid {
 public:
  /// Cell edge, metres (> 0).
  explicit SpatialGrid(double cell_size);

  /// Files node `node` at `position`; nodes are numbered 0, 1, 2, ... in the order added.
  void add(std::uint32_t node, const Eigen::Vector3d& position);
  /// The node is now at `position`.
  void move(std::uint32_t node, const Eigen::Vector3d& position);

  /// Calls visit(node) for nodes in the cells that the disc of `radius` around `position` (on
  /// the ground plane) overlaps, ring of cells by ring outwards from the position's cell: in
  /// each cell its `per_cell` latest nodes (highest numbers; 0 = all), each node once. Before
  /// each ring it calls reach_sq(), the squared distance within which the caller still looks
  /// (its best so far), and stops when no cell of the ring is that near. With per_cell 0 and an
  /// infinite reach it visits a superset of the nodes within `radius`.
  template <class Visit, class Reach>
  void visit_nearest_first(const Eigen::Vector3d& position, double radius, std::size_t per_cell,
                           Visit&& visit, Reach&& reach_sq) const {
    const std::int64_t x0 = coord(position.x() - radius), x1 = coord(position.x() + radius);
    const std::int64_t y0 = coord(position.y() - radius), y1 = coord(position.y() + radius);
    const std::int64_t cx = coord(position.x()), cy = coord(position.y());
    const std::int64_t rings = std::max({cx - x0, x1 - cx, cy - y0, y1 - cy});
    auto visit_cell = [&](std::int64_t x, std::int64_t y) {
      if (x < x0 || x > x1 || y < y0 || y > y1) return;
      const auto it = cells_.find(key(x, y));
      if (it == cells_.end()) return;
      const std::vector<std::uint32_t>& nodes = it->second;
      const std::size_t first =
          per_cell > 0 && nodes.size() > per_cell ? nodes.size() - per_cell : 0;
      for (std::size_t i = first; i < nodes.size(); ++i) visit(nodes[i]);
    };
    visit_cell(cx, cy);
    for (std::int64_t r = 1; r <= rings; ++r) {
      // Ring r lies outside the block of the rings inside it: no point of it is nearer than
      // the block's border.
      const double gap = std::min({position.x() - double(cx - r + 1) * cell_size_,
                                   double(cx + r) * cell_size_ - position.x(),
                                   position.y() - double(cy - r + 1) * cell_size_,
                                   double(cy + r) * cell_size_ - position.y()});
      if (gap > radius || gap * gap > reach_sq()) return;
      for (std::int64_t x = cx - r; x <= cx + r; ++x) {
        visit_cell(x, cy - r);
        visit_cell(x, cy + r);
      }
      for (std::int64_t y = cy - r + 1; y <= cy + r - 1; ++y) {
        visit_cell(cx - r, y);
        visit_cell(cx + r, y);
      }
    }
  }

  double cell_size() const { return cell_size_; }

 private:
  std::int64_t coord(double v) const {
    return static_cast<std::int64_t>(std::floor(v / cell_size_));
  }
  static std::uint64_t key(std::int64_t x, std::int64_t y) {
    return (static_cast<std::uint64_t>(x) << 32) ^ (static_cast<std::uint64_t>(y) & 0xffffffffu);
  }
  std::uint64_t key_of(const Eigen::Vector3d& p) const { return key(coord(p.x()), coord(p.y())); }

  double cell_size_;
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> cells_;
  /// Each node's cell key.
  std::vector<std::uint64_t> cell_of_;
};

}  // namespace litamin2::mapping
