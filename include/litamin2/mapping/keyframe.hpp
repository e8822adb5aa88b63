#pragma once
/// A keyframe of one sensor stream as the mapper sees it: what a daemon publishes on
/// rt/litamin2/map_patches (litamin2/msg/MapPatch.idl), in the core library's types.

#include "litamin2/core/distribution.hpp"

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <tuple>
#include <vector>

namespace litamin2::mapping {

using Matrix6d = Eigen::Matrix<double, 6, 6>;

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
  /// Header stamp of the keyframe's scan, nanoseconds since the epoch.
  std::int64_t stamp_ns = 0;
  /// Sensor pose in the stream's odometry frame (the frame of the stream's first scan).
  Eigen::Isometry3d odom_pose = Eigen::Isometry3d::Identity();
  /// Covariance of odom_pose from the tracker, in (phi, tau) left-update coordinates
  /// (Tracker's FrameResult::covariance).
  Matrix6d covariance = Matrix6d::Zero();
  /// Voxel edge the distributions were computed on, metres.
  double voxel_size = 0.0;
  /// The keyframe scan's distributions, sensor frame.
  std::vector<Distribution> distributions;
};

/// Canonical processing order of keyframes: by stamp, then stream, then id. The mapper's
/// result depends only on the set of keyframes when they are given in this order.
inline bool canonical_before(const Keyframe& a, const Keyframe& b) {
  return std::tie(a.stamp_ns, a.key.stream, a.key.id) <
         std::tie(b.stamp_ns, b.key.stream, b.key.id);
}

}  // namespace litamin2::mapping
