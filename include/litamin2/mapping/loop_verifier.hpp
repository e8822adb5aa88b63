#pragma once
/// Verification of a place-recognition candidate by LiTAMIN2 registration: the query
/// keyframe's distributions are registered to a submap of the candidate keyframe and its
/// neighbours, starting from the descriptor's yaw, after a coarse search over translations
/// (the two keyframes can be several metres apart). The loop is accepted when enough of the
/// query's distributions land close to map distributions (the fitness gate).

#include "litamin2/core/distribution.hpp"
#include "litamin2/core/voxel_map.hpp"
#include "litamin2/mapping/mapper_config.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <string>
#include <vector>

namespace litamin2::mapping {

struct LoopVerification {
  bool accepted = false;
  /// Pose of the query's sensor in the submap's frame.
  Eigen::Isometry3d relative = Eigen::Isometry3d::Identity();
  /// Fraction of the query's non-horizontal distributions within fitness_distance of the map.
  double fitness = 0.0;
  /// Root mean square distance of those, metres.
  double rmse = 0.0;
  /// Why it was rejected (empty when accepted).
  std::string reason;
};

/// Registers `query` (its sensor frame) to `submap` (the candidate's sensor frame) from
/// `initial` (the query's pose in the submap's frame), searching first over planar offsets of
/// up to two voxels and yaws of +-`yaw_step` radians around it (half a descriptor sector: the
/// descriptor's yaw resolution; the default is half of 60 sectors').
LoopVerification verify_loop(const std::vector<Distribution>& query, const VoxelMap& submap,
                             const Eigen::Isometry3d& initial, const LoopVerificationConfig& config,
                             double yaw_step = M_PI / 60.0);

/// The pose of a rotation by `yaw` radians about z.
Eigen::Isometry3d yaw_pose(double yaw);

}  // namespace litamin2::mapping
