#pragma once
/// Where a stream's results go: the DDS writers in the daemon, a recorder in tests.

#include "litamin2/core/distribution.hpp"
#include "litamin2/core/registration_config.hpp"
#include "litamin2/daemon/frame.hpp"

#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <vector>

namespace litamin2::daemon {

using Matrix6d = Eigen::Matrix<double, 6, 6>;

/// The odometry of one frame.
struct OdometryOutput {
  const std::string& stream;
  /// The input scan's header stamp.
  Stamp stamp;
  /// Pose of the stream's base (the sensor pose moved by the extrinsic) in the odometry frame
  /// (the base at the stream's first scan).
  Eigen::Isometry3d pose;
  /// Covariance of `pose` in (phi, tau) left-update coordinates (the tracker's convention).
  Matrix6d covariance;
  bool keyframe = false;
  bool registered = false;
  /// The frame's per-stream sequence number.
  std::uint64_t sequence = 0;
};

/// A keyframe of a stream: what the aggregator builds its map from.
struct KeyframeOutput {
  const std::string& stream;
  /// 0, 1, 2, ... per stream.
  std::uint64_t keyframe_id = 0;
  Stamp stamp;
  /// Sensor pose in the odometry frame.
  Eigen::Isometry3d pose;
  /// Covariance of the base pose, as in OdometryOutput.
  Matrix6d covariance;
  double voxel_size = 0.0;
  /// The keyframe's distributions, sensor frame.
  const std::vector<Distribution>& distributions;
};

class ResultSink {
 public:
  virtual ~ResultSink() = default;
  /// Called once per processed frame, in the stream's order, from the stream's task (never
  /// concurrently for one stream; concurrently for different streams).
  virtual void publish_odometry(const OdometryOutput& odometry) = 0;
  /// Called after publish_odometry for keyframes.
  virtual void publish_keyframe(const KeyframeOutput& keyframe) = 0;
};

}  // namespace litamin2::daemon
