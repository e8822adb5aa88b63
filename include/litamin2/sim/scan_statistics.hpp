#pragma once
/// Summary statistics of a scan, used to compare simulated scans with real ones.

#include <cstddef>
#include <string>

#include "litamin2/core/point_cloud.hpp"

namespace litamin2::sim {

/// Voxel occupancy and range distribution of a scan (voxels: floor(p / size) in the sensor
/// frame; ranges: Euclidean distance from the sensor origin).
struct ScanStatistics {
  std::size_t points = 0;
  std::size_t voxels_1m = 0;
  std::size_t voxels_2m = 0;
  std::size_t voxels_3m = 0;
  /// 3 m voxels holding at least 5 points.
  std::size_t voxels_3m_min5 = 0;
  std::size_t voxels_5m = 0;
  double range_median = 0.0;
  /// 90th percentile of the range.
  double range_p90 = 0.0;
  double range_max = 0.0;
};

/// Computes the statistics (percentiles by nearest rank on the sorted ranges).
ScanStatistics compute_scan_statistics(const PointCloud& cloud);

/// One-line summary "points=... v1=... v2=... v3=... v3>=5=... v5=... r50=... r90=... rmax=...".
std::string to_string(const ScanStatistics& s);

}  // namespace litamin2::sim
