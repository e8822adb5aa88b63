#pragma once
/// Points the tracker drops before voxelising: returns from the vehicle's own body (self-hits).
/// They move with the sensor, so matching them to the map pulls the pose towards zero motion
/// (docs/accuracy.md, "Sparse sensors"); a box in the sensor frame removes them where a larger
/// minimum range would also remove nearby ground, kerbs and walls.

#include "litamin2/core/point_cloud.hpp"

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace litamin2 {

enum class EgoFilterMode {
  /// Keep every point (voxelizer.min_range still applies).
  kOff,
  /// Drop the points inside the configured box.
  kBox,
  /// Learn the self-hit cells from the data: sensor-frame cells near the sensor that hold
  /// returns in (almost) every one of the first scans (EgoLearner).
  kAuto,
};

struct ScanFilterConfig {
  /// How self-hits are found.
  EgoFilterMode ego = EgoFilterMode::kAuto;
  /// kBox: points strictly inside [ego_box_min, ego_box_max] (sensor frame, metres) are dropped.
  Eigen::Vector3d ego_box_min = Eigen::Vector3d::Zero();
  Eigen::Vector3d ego_box_max = Eigen::Vector3d::Zero();
  /// kAuto: only returns closer than this to the sensor can be self-hits, metres.
  double auto_radius = 3.0;
  /// kAuto: edge of the sensor-frame cells, metres.
  double auto_cell = 0.25;
  /// kAuto: the cells are decided from this many first scans. A cell that something static
  /// filled while the vehicle stood still is dropped too; within auto_radius that costs a few
  /// returns and the sensor-fixed ring of flat ground, itself a pull towards zero motion.
  int auto_scans = 10;
  /// kAuto: a cell is a self-hit cell when it held returns in at least this share of them.
  double auto_min_share = 0.9;
};

/// True if p is strictly inside the box [lo, hi].
inline bool inside_box(const Eigen::Vector3f& p, const Eigen::Vector3d& lo,
                       const Eigen::Vector3d& hi) {
  return p.x() > lo.x() && p.x() < hi.x() && p.y() > lo.y() && p.y() < hi.y() && p.z() > lo.z() &&
         p.z() < hi.z();
}

/// Writes into `out` the points of `scan` outside the box (intensities and times kept alongside).
void remove_box(const PointCloud& scan, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                PointCloud& out);

/// Learns the cells of the sensor frame that hold self-hits (EgoFilterMode::kAuto) and drops
/// their points once decided. Deterministic: depends only on the scans and the motion passed in.
class EgoLearner {
 public:
  explicit EgoLearner(const ScanFilterConfig& config);

  /// Counts the scan's near cells; decides after auto_scans scans (later calls do nothing).
  void observe(const PointCloud& scan);
  /// The cells are decided (before: filter() drops nothing).
  bool decided() const { return decided_; }
  /// Number of self-hit cells found (0 before they are decided).
  std::size_t cells() const { return ego_cells_; }
  /// Writes into `out` the points of `scan` not in a self-hit cell (intensities and times kept
  /// alongside) and returns true; returns false (out untouched) when there is nothing to drop:
  /// undecided, or no self-hit cell.
  bool filter(const PointCloud& scan, PointCloud& out) const;
  /// Whether p (sensor frame) lies in a self-hit cell.
  bool is_ego(const Eigen::Vector3f& p) const;

 private:
  int cell_of(const Eigen::Vector3f& p) const;

  ScanFilterConfig config_;
  int side_ = 0;
  std::vector<int> hits_;
  std::vector<std::uint8_t> ego_;
  std::vector<int> seen_;
  int counted_ = 0;
  bool decided_ = false;
  std::size_t ego_cells_ = 0;
};

}  // namespace litamin2
