#pragma once
/// Where a stream's results go: the DDS writers in the daemon, a recorder in tests.

#include "litamin2/core/frame_twist.hpp"
#include "litamin2/core/keyframe.hpp"
#include "litamin2/core/so3.hpp"
#include "litamin2/core/stamp.hpp"

#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <string>

namespace litamin2::daemon {

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
  /// The base's twist from the previous frame's pose to `pose`, in the base frame, with its
  /// covariance (core/frame_twist.hpp); absent for the first frame, a frame not registered
  /// (its pose is the prediction, not a measurement), and a stamp not after the previous one.
  std::optional<TwistEstimate> twist;
};

class ResultSink {
 public:
  virtual ~ResultSink() = default;
  /// Called once per processed frame, in the stream's order, from the stream's task (never
  /// concurrently for one stream; concurrently for different streams).
  virtual void publish_odometry(const OdometryOutput& odometry) = 0;
  /// Called after publish_odometry for keyframes (make_keyframe: ids 0, 1, 2, ... per stream).
  virtual void publish_keyframe(const Keyframe& keyframe) = 0;
};

}  // namespace litamin2::daemon
