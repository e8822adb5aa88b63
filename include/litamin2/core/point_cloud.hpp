#pragma once
/// A LiDAR scan as the library sees it: points in the sensor frame, optional intensities.

#include <Eigen/Core>
#include <vector>

namespace litamin2 {

struct PointCloud {
  /// Points in metres, in the sensor frame (x forward, y left, z up for KITTI's Velodyne).
  std::vector<Eigen::Vector3f> points;
  /// Either empty or one value per point.
  std::vector<float> intensities;

  std::size_t size() const { return points.size(); }
  bool empty() const { return points.empty(); }
  bool has_intensities() const { return !intensities.empty(); }
};

}  // namespace litamin2
