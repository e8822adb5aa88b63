#pragma once
/// A verified loop closure: the pose of one keyframe in the sensor frame of another, found by
/// LiTAMIN2 registration of their distributions.

#include "litamin2/core/keyframe.hpp"

namespace litamin2::mapping {

struct LoopEdge {
  /// The keyframe whose frame the relative pose is expressed in (the older of the two).
  KeyframeKey from;
  /// The keyframe whose pose is measured (the newer one).
  KeyframeKey to;
  /// Pose of `to`'s sensor in `from`'s sensor frame.
  Eigen::Isometry3d relative = Eigen::Isometry3d::Identity();
  /// Information (inverse covariance) of the relative pose in (phi, tau) left-update
  /// coordinates of `to`'s pose.
  Matrix6d information = Matrix6d::Identity();
  /// Fraction of `to`'s non-horizontal distributions within the verification gate of the
  /// target's surfaces at convergence (loop_verifier.hpp).
  double fitness = 0.0;
  /// Root mean square of those distances along the normals, metres.
  double rmse = 0.0;
};

}  // namespace litamin2::mapping
