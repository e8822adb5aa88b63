#pragma once
/// LiTAMIN2 odometry for one sensor stream: constant-velocity prediction, registration of the
/// scan's distributions to the keyframe map, keyframe decision and map update.

#include "litamin2/core/correspondence_search.hpp"
#include "litamin2/core/keyframe.hpp"
#include "litamin2/core/registration.hpp"
#include "litamin2/core/scan_filter.hpp"
#include "litamin2/core/tracker_config.hpp"
#include "litamin2/core/voxel_map.hpp"
#include "litamin2/core/voxelizer.hpp"

#include <Eigen/Geometry>
#include <memory>

namespace litamin2 {

/// Wall-clock time of each stage of one frame, milliseconds.
struct StageTimes {
  double voxelize_ms = 0.0;
  double register_ms = 0.0;
  double map_update_ms = 0.0;
  double total_ms() const { return voxelize_ms + register_ms + map_update_ms; }
};

struct FrameResult {
  /// Sensor pose in the frame of the first scan.
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  /// Covariance of the pose in (phi, tau) coordinates of the left update, from the Hessian at
  /// convergence (2 sigma^2 H^-1 with sigma^2 the cost per residual degree of freedom); zero for
  /// the first frame.
  Matrix6d covariance = Matrix6d::Zero();
  /// This frame was added to the map.
  bool keyframe = false;
  /// Registration succeeded (false for the first frame and when it failed; the pose is then
  /// the constant-velocity prediction).
  bool registered = false;
  int iterations = 0;
  /// Times the scan was voxelised (1 + re-voxelisations after large corrections).
  int voxelizations = 0;
  /// The re-grid loop stopped because a re-voxelisation did not shrink the correction.
  bool regrid_stopped = false;
  /// Points dropped as self-hits (ScanFilterConfig).
  int self_hits = 0;
  /// Share of the source distributions matched as inliers (robust weight at least 1/2).
  double inlier_share = 0.0;
  /// The scan was registered again from other starts (RecoveryConfig); `recovered` if one of
  /// them fitted better than the prediction's.
  bool retried = false;
  bool recovered = false;
  int source_distributions = 0;
  int correspondences = 0;
  StageTimes times;
};

class Tracker {
 public:
  /// Throws ConfigError if the config is invalid. A named config.sensor applies its preset
  /// here (to the keys not in config.explicit_keys); kAuto recognises the sensor from the first
  /// scan (sensor_preset.hpp) and applies its preset then.
  explicit Tracker(const TrackerConfig& config);
  ~Tracker();

  /// Estimates the pose of the next scan of the stream.
  FrameResult process(const PointCloud& scan);

  /// The map of distributions the next scan is registered to.
  const VoxelMap& map() const { return map_; }
  /// Distributions of the last processed scan, sensor frame.
  const std::vector<Distribution>& last_distributions() const { return source_; }
  /// The config in use: after the first scan with `sensor: auto`, the recognised sensor's.
  const TrackerConfig& config() const { return config_; }
  /// Self-hit cells learnt (ScanFilterConfig, EgoFilterMode::kAuto), 0 before they are decided.
  std::size_t ego_cells() const { return ego_.cells(); }
  std::size_t frames() const { return frames_; }

 private:
  bool is_keyframe(const Eigen::Isometry3d& pose) const;
  /// The scan without its self-hits (the scan itself when there is nothing to drop).
  const PointCloud& without_self_hits(const PointCloud& scan, int& dropped);

  TrackerConfig config_;
  EgoLearner ego_;
  PointCloud filtered_;
  Voxelizer voxelizer_;
  VoxelMap map_;
  std::unique_ptr<CorrespondenceSearch> search_;
  std::vector<Distribution> source_;
  Eigen::Isometry3d pose_ = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d velocity_ = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d last_keyframe_ = Eigen::Isometry3d::Identity();
  std::size_t frames_ = 0;
  /// Running typical inlier share of registered frames (RecoveryConfig), negative before any.
  double typical_share_ = -1.0;
};

/// The keyframe of a frame the tracker has just added to its map (frame.keyframe is true): the
/// sensor's pose in the odometry frame of the vehicle base, sensor_in_base * frame.pose, with
/// the covariance moved alike (identity, the default: the tracker's own, bit for bit), the
/// scan's distributions and the map's voxel size. litamin2d and litamin2-odometry build their
/// keyframes with it.
Keyframe make_keyframe(const Tracker& tracker, const FrameResult& frame, KeyframeKey key,
                       Stamp stamp,
                       const Eigen::Isometry3d& sensor_in_base = Eigen::Isometry3d::Identity());

}  // namespace litamin2
