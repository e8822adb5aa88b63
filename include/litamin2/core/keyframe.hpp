#pragma once
/// A keyframe of one sensor stream: the scan's distributions at a tracked pose. The daemon
/// builds it from its tracker (make_keyframe, core/tracker.hpp) and sends it as a map patch
/// (litamin2/msg/MapPatch.idl, dds/map_patch_conversion.hpp); the aggregator stores it and
/// builds its map from it; the offline tool feeds it to the same mapper in process.

#include "litamin2/core/distribution.hpp"
#include "litamin2/core/so3.hpp"
#include "litamin2/core/stamp.hpp"

#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <tuple>
#include <vector>

namespace litamin2 {

/// Identity of a keyframe: its stream and its per-stream number (0, 1, 2, ...).
struct KeyframeKey {
  std::string stream;
  std::uint64_t id = 0;

  friend bool operator==(const KeyframeKey& a, const KeyframeKey& b) {
    return a.id == b.id && a.stream == b.stream;
  }
  friend bool operator!=(const KeyframeKey& a, const KeyframeKey& b) { return !(a == b); }
  friend bool operator<(const KeyframeKey& a, const KeyframeKey& b) {
    return std::tie(a.stream, a.id) < std::tie(b.stream, b.id);
  }
};

struct Keyframe {
  KeyframeKey key;
  /// Header stamp of the keyframe's scan.
  Stamp stamp;
  /// Sensor pose in the stream's odometry frame (the frame of the stream's vehicle base at its
  /// first scan; the sensor's own first frame when it has no extrinsic).
  Eigen::Isometry3d odom_pose = Eigen::Isometry3d::Identity();
  /// Covariance of odom_pose from the tracker, in (phi, tau) left-update coordinates
  /// (FrameResult::covariance, moved to the base by the extrinsic).
  Matrix6d covariance = Matrix6d::Zero();
  /// Voxel edge the distributions were computed on, metres.
  double voxel_size = 0.0;
  /// The keyframe scan's distributions, sensor frame.
  std::vector<Distribution> distributions;
};

/// Canonical processing order of keyframes: by stamp, then stream, then id. The mapper's
/// result depends only on the set of keyframes when they are given in this order.
inline bool canonical_before(const Keyframe& a, const Keyframe& b) {
  return std::tie(a.stamp.nanoseconds, a.key.stream, a.key.id) <
         std::tie(b.stamp.nanoseconds, b.key.stream, b.key.id);
}

}  // namespace litamin2
