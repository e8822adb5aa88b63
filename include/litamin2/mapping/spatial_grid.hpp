#pragma once
/// Keyframe positions in a hash grid of square cells on the ground plane, for the proximity
/// search: the keyframes within a radius of a position are found by visiting the cells that
/// the disc overlaps, not every keyframe. Positions move (optimisation): move() re-files a
/// node whose cell changed.

#include <Eigen/Core>

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

  /// Calls visit(node) for every node in a cell that the disc of `radius` around `position`
  /// (on the ground plane) overlaps: a superset of the nodes within `radius`, each once.
  template <class Visit>
  void visit_near(const Eigen::Vector3d& position, double radius, Visit&& visit) const {
    const std::int64_t x0 = coord(position.x() - radius), x1 = coord(position.x() + radius);
    const std::int64_t y0 = coord(position.y() - radius), y1 = coord(position.y() + radius);
    for (std::int64_t x = x0; x <= x1; ++x) {
      for (std::int64_t y = y0; y <= y1; ++y) {
        const auto it = cells_.find(key(x, y));
        if (it == cells_.end()) continue;
        for (std::uint32_t node : it->second) visit(node);
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
