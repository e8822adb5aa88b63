#pragma once
/// Summary statistics of a scan, used to compare simulated scans with real ones: voxel
/// occupancy, points per voxel, line-like voxels (one ring crossing a voxel), the range
/// distribution, hits near the sensor, points per ring, the azimuth step, the roughness of the
/// lowest ring and a robust fit of the ground plane.

#include <cstddef>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "litamin2/core/point_cloud.hpp"

namespace litamin2::sim {

/// Upper edges of the range histogram's bins, metres (the last bin is open).
inline constexpr double kRangeBinEdges[] = {2.0, 5.0, 10.0, 20.0, 40.0, 80.0};
/// Number of range histogram bins (one more than the edges).
inline constexpr std::size_t kRangeBins = sizeof(kRangeBinEdges) / sizeof(double) + 1;

/// Voxel occupancy and range distribution of a scan (voxels: floor(p / size) in the sensor
/// frame; ranges: Euclidean distance from the sensor origin). The ring fields are filled only
/// when the beam elevations are given (each point is assigned the ring of the nearest
/// elevation; real scans without a ring field get it that way).
struct ScanStatistics {
  /// Points in the scan.
  std::size_t points = 0;
  /// Occupied 1 m voxels.
  std::size_t voxels_1m = 0;
  /// Occupied 2 m voxels.
  std::size_t voxels_2m = 0;
  /// Occupied 3 m voxels.
  std::size_t voxels_3m = 0;
  /// 3 m voxels holding at least 5 points.
  std::size_t voxels_3m_min5 = 0;
  /// Occupied 5 m voxels.
  std::size_t voxels_5m = 0;
  /// Median number of points in an occupied 1 m voxel.
  double median_points_1m = 0.0;
  /// Median number of points in an occupied 2 m voxel.
  double median_points_2m = 0.0;
  /// Median number of points in an occupied 3 m voxel.
  double median_points_3m = 0.0;
  /// Share of the 3 m voxels with >= 5 points whose points all come from one ring.
  double single_ring_3m = 0.0;
  /// Share of the 3 m voxels with >= 5 points whose distribution is a line (second largest
  /// covariance eigenvalue below 1 % of the largest).
  double linear_3m = 0.0;
  /// Share of the 3 m voxels with >= 5 points whose distribution is a plane (smallest
  /// eigenvalue below 1 % of the middle one, middle above 1 % of the largest).
  double planar_3m = 0.0;
  /// Share of the 3 m voxels with >= 5 points whose distribution is round (smallest over
  /// largest eigenvalue above 0.05: what litamin2's max_isotropy gate leaves out).
  double round_3m = 0.0;
  /// Share of the 3 m voxels with >= 5 points whose distribution is horizontal ground-like
  /// (planar with a normal within 15 degrees of the sensor's z axis).
  double horizontal_3m = 0.0;
  /// Points closer than 2 m to the sensor (self-hits on the vehicle).
  std::size_t near_2m = 0;
  /// Median range, metres.
  double range_median = 0.0;
  /// 90th percentile of the range, metres.
  double range_p90 = 0.0;
  /// Largest range, metres.
  double range_max = 0.0;
  /// Share of the points in each range bin (kRangeBinEdges).
  std::vector<double> range_histogram = std::vector<double>(kRangeBins, 0.0);
  /// Points per ring, top ring (highest elevation) first; empty without elevations.
  std::vector<std::size_t> ring_points;
  /// Median azimuth difference between neighbouring points of a ring, degrees.
  double azimuth_step_deg = 0.0;
  /// Robust standard deviation (1.4826 MAD / sqrt(6)) of the second difference of the range
  /// along the lowest ring: range noise plus the roughness of what the ring sweeps (ground).
  double lowest_ring_roughness = 0.0;
  /// Ground plane fitted (trimmed least squares) to points 4-16 m away horizontally and more
  /// than 1 m below the sensor: height of the sensor above it, metres.
  double ground_height = 0.0;
  /// Ground plane's slope along x as an angle, degrees (the sensor's pitch relative to it).
  double ground_pitch_deg = 0.0;
  /// Ground plane's slope along y as an angle, degrees (the sensor's roll relative to it).
  double ground_roll_deg = 0.0;
  /// Standard deviation of the ground inliers from the plane, metres (non-planar ground).
  double ground_residual = 0.0;
};

/// Computes the statistics (percentiles by nearest rank on the sorted values). With
/// `elevations_deg` (the sensor's beam elevations, any order) the ring fields are filled too.
ScanStatistics compute_scan_statistics(const PointCloud& cloud,
                                       const std::vector<double>& elevations_deg = {});

/// The statistics as (label, value) rows in a fixed order, for tables and for averaging
/// several scans (ring rows only when ring_points is filled; one row per histogram bin).
std::vector<std::pair<std::string, double>> statistic_rows(const ScanStatistics& s);

/// Mean of the statistic rows of several scans (rows that only some scans have, e.g. ring rows
/// of a sensor with more rings, are averaged over the scans that have them).
class ScanStatisticsMean {
 public:
  /// Adds one scan's statistics.
  void add(const ScanStatistics& s);
  /// Scans added.
  std::size_t count() const { return count_; }
  /// (label, mean) in the order the labels first appeared.
  std::vector<std::pair<std::string, double>> rows() const;
  /// Mean of one row; 0 if no scan had it.
  double mean(const std::string& label) const;

 private:
  std::size_t count_ = 0;
  /// (label, sum, scans with the row), in first-appearance order.
  std::vector<std::tuple<std::string, double, std::size_t>> sums_;
};

/// One-line summary "points=... v1=... v2=... v3=... v3>=5=... v5=... r50=... r90=... rmax=...".
std::string to_string(const ScanStatistics& s);

}  // namespace litamin2::sim
