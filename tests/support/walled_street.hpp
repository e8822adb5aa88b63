#pragma once
// A street between walls with relief, as voxelised registration tests need it: planes in the
// middle of their voxels, side walls that can be cut lower ahead or behind. The normal-only
// refinement's and the Cov term's weight's tests share it.

#include "litamin2/core/point_cloud.hpp"

#include <Eigen/Core>
#include <cmath>
#include <random>

namespace litamin2::testing {

/// A street between walls, each plane in the middle of its voxels and no two in one voxel:
/// ground (z = -1.5) over |x| < 12, |y| < 6; walls along x at y = +-7.5 (|x| < 12) and across it
/// at x = +-13.5 (|y| < 6), from z = -1.5 to 4.5, with 0.1 m of relief (vertical ribs, the same
/// in every cloud), so that in-plane offsets weigh in Eq. 3's precision. The side walls' points
/// stop at `top_ahead` for x > 0 and at `top_behind` for x < 0.
inline PointCloud walled_street(double top_ahead, double top_behind, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, 0.005);
  PointCloud cloud;
  auto add = [&](double x, double y, double z) {
    cloud.points.push_back(
        Eigen::Vector3d(x + noise(rng), y + noise(rng), z + noise(rng)).cast<float>());
  };
  // The same relief in every cloud: the clouds differ only where the side walls are cut.
  auto add_wall = [&](double x, double y, double z, const Eigen::Vector3d& normal) {
    const double along = normal.x() != 0.0 ? y : x;
    const double relief = 0.1 * std::sin(2.0 * M_PI * along / 0.9);
    add(x, y, z);
    cloud.points.back() += (relief * normal).cast<float>();
  };
  const double step = 0.25;
  for (double x = -11.9; x < 12.0; x += step) {
    for (double y = -5.9; y < 6.0; y += step) add(x, y, -1.5);
    const double top = x > 0.0 ? top_ahead : top_behind;
    for (double z = -1.4; z < top; z += step) {
      add_wall(x, -7.5, z, Eigen::Vector3d::UnitY());
      add_wall(x, 7.5, z, Eigen::Vector3d::UnitY());
    }
  }
  for (double y = -5.9; y < 6.0; y += step) {
    for (double z = -1.4; z < 4.5; z += step) {
      add_wall(-13.5, y, z, Eigen::Vector3d::UnitX());
      add_wall(13.5, y, z, Eigen::Vector3d::UnitX());
    }
  }
  return cloud;
}

}  // namespace litamin2::testing
