#pragma once
/// A stream's odometry yaw drift: a turn per metre travelled that the stream's odometry adds
/// to the truth, of its own size and sign. LiDAR odometry's rotation drift (KITTI's deg/100 m)
/// can have such a systematic part (an extrinsic or range calibration error, the scene's
/// structure); the fleet bench's vehicles have one each (up to 0.5 deg per 100 m). The pose
/// graph takes each odometry edge for an unbiased measurement with white noise, so such a
/// stream bends every stretch between its loops; here its drift is estimated from what the
/// loops hold and taken out of its odometry edges and of the chaining of its new keyframes
/// (docs/benchmarks.md, "Odometry yaw drift per stream"). Not modelled: drift in time (a
/// sensor standing still that turns), drift of roll and pitch.
///
/// Model: the odometry's relative rotation over a stretch of d metres is the true one followed
/// by a turn of drift * d about the sensor's up axis, R_odo = R_true * Rz(drift * d) (yaw
/// rotations commute with the vehicle's turns to first order in its tilt).
///
/// Estimate: over the stream's latest loop ends within PoseGraphConfig::yaw_drift_window
/// metres of path, from the earliest (A) to the latest (B), the loops fix the relative pose
/// of A and B (each is tied to the map by a checked loop), so the yaw of
/// (A.odom^-1 B.odom)^T (A.pose^-1 B.pose) is -drift * (B.path - A.path). An estimate over a
/// span shorter than yaw_drift_min_path keeps the previous one (0 at first); one beyond
/// yaw_drift_max_deg_per_100m is rejected and counted.

#include "litamin2/mapping/keyframe_graph.hpp"
#include "litamin2/mapping/mapper_config.hpp"

#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace litamin2::mapping {

/// `relative` (the odometry's motion over `distance` metres of path; negative when it runs
/// backwards along the path) with a drift of `drift_per_m` radians a metre taken out:
/// relative.linear() * Rz(-drift_per_m * distance). The translation is kept.
Eigen::Isometry3d without_yaw_drift(const Eigen::Isometry3d& relative, double drift_per_m,
                                    double distance);

/// The yaw of `rotation` about its own z axis (the z component of its rotation vector), rad.
double yaw_of(const Eigen::Matrix3d& rotation);

class YawDriftEstimator {
 public:
  /// `config` must outlive the estimator.
  explicit YawDriftEstimator(const PoseGraphConfig& config) : config_(config) {}

  bool enabled() const { return config_.yaw_drift_window > 0.0; }

  /// Node `node` became a checked loop's end.
  void add_anchor(const KeyframeGraph& graph, std::uint32_t node);
  /// Estimates the stream's drift again from its loop ends' current poses. Returns whether
  /// the estimate changed.
  bool update(const KeyframeGraph& graph, std::uint32_t stream);
  /// update() for every stream.
  void update_all(const KeyframeGraph& graph);

  /// The stream's current drift estimate, radians a metre (0 when off or not estimated yet).
  double drift_per_m(std::uint32_t stream) const {
    return stream < drift_.size() ? drift_[stream] : 0.0;
  }
  /// Estimates taken and rejected (beyond yaw_drift_max_deg_per_100m) so far.
  std::size_t estimates() const { return estimates_; }
  std::size_t rejected() const { return rejected_; }

 private:
  const PoseGraphConfig& config_;
  /// Per stream, its loop ends' nodes in the order of their keyframe ids (so of their path).
  std::vector<std::vector<std::uint32_t>> anchors_;
  std::vector<double> drift_;
  std::size_t estimates_ = 0;
  std::size_t rejected_ = 0;
};

}  // namespace litamin2::mapping
