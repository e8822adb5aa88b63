#pragma once
/// A LiDAR scan as the library sees it: points in the sensor frame, optional intensities and
/// optional per-point times.

#include <Eigen/Core>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

namespace litamin2 {

/// Largest |time| of a point relative to its scan's stamp, seconds. A sweep of a spinning or
/// solid-state LiDAR lasts 0.05-0.2 s (and a merged multi-sensor frame adds the sensors' stamp
/// offsets, a fraction of a period); a time beyond a second is a wrong unit or an absolute time
/// taken for a relative one.
inline constexpr double kMaxPointTime = 1.0;

struct PointCloud {
  /// Points in metres, in the sensor frame (x forward, y left, z up for KITTI's Velodyne).
  std::vector<Eigen::Vector3f> points;
  /// Either empty or one value per point.
  std::vector<float> intensities;
  /// Either empty or one value per point: when the point was measured, seconds relative to the
  /// scan's stamp (its reference time; negative before it), as the drivers' time fields give it
  /// (dds/pointcloud2_conversion.hpp, io/pcd.hpp). Deskew (core/deskew.hpp) uses it; everything
  /// else ignores it.
  std::vector<float> times;

  std::size_t size() const { return points.size(); }
  bool empty() const { return points.empty(); }
  bool has_intensities() const { return !intensities.empty(); }
  bool has_times() const { return !times.empty(); }
};

/// Why the cloud's times cannot be used, or nothing: there must be one per point, each finite
/// and within +-kMaxPointTime seconds. An empty `times` is valid (the cloud has none).
inline std::optional<std::string> point_times_error(const PointCloud& cloud) {
  if (cloud.times.empty()) return std::nullopt;
  if (cloud.times.size() != cloud.points.size())
    return std::to_string(cloud.times.size()) + " times for " +
           std::to_string(cloud.points.size()) + " points";
  for (std::size_t i = 0; i < cloud.times.size(); ++i) {
    const float t = cloud.times[i];
    if (!std::isfinite(t) || std::abs(static_cast<double>(t)) > kMaxPointTime)
      return "time of point " + std::to_string(i) + " is " + std::to_string(t) +
             " s (must be finite and within +-1 s of the scan's stamp)";
  }
  return std::nullopt;
}

}  // namespace litamin2
