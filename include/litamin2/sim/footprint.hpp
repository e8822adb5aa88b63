#pragma once
/// Ground footprints of the objects the World layout places, and the occupancy grid that keeps
/// them from overlapping. Part of the World builder.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_set>

namespace litamin2::sim {

/// Oriented rectangle on the ground plane.
struct Footprint {
  /// Centre (world frame).
  Eigen::Vector2d c;
  /// Rotation about z of the rectangle's x axis, radians.
  double yaw;
  /// Half sizes along the rectangle's x and y axes, metres.
  double hx, hy;

  /// Calls visit(q) for the points of a lattice about 1 m apart that spans the footprint
  /// (corners included; only the points on its edge if `edge_only`), in a fixed order, until
  /// visit returns false. Returns false if it did, true if every point passed.
  template <class Visit>
  bool all_points(bool edge_only, Visit&& visit) const {
    const Eigen::Vector2d ex(std::cos(yaw), std::sin(yaw)), ey(-ex.y(), ex.x());
    const int nx = std::max(1, static_cast<int>(std::ceil(2 * hx))),
              ny = std::max(1, static_cast<int>(std::ceil(2 * hy)));
    for (int i = 0; i <= nx; ++i) {
      for (int j = 0; j <= ny; ++j) {
        if (edge_only && i != 0 && i != nx && j != 0 && j != ny) continue;
        const Eigen::Vector2d q = c + ex * (-hx + 2 * hx * i / nx) + ey * (-hy + 2 * hy * j / ny);
        if (!visit(q)) return false;
      }
    }
    return true;
  }
};

/// The 1 m ground cells covered by the footprints placed so far.
class Occupancy {
 public:
  /// True if none of the footprint's lattice points lies in a covered cell.
  bool free(const Footprint& f) const;
  /// Covers the cells of the footprint's lattice points.
  void occupy(const Footprint& f);

 private:
  std::unordered_set<std::int64_t> cells_;
};

}  // namespace litamin2::sim
