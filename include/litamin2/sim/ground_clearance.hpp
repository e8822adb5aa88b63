#pragma once
/// How far a trajectory's sensor heights depart from the ground the World lays under them. The
/// road follows the trajectory smoothly (a weighted fit over tens of metres), so a trajectory
/// that climbs or falls steeply where it hardly moves (e.g. KITTI 08's ground truth, 7 m up at a
/// near standstill in its first 60 frames) puts the sensor below or far above that ground, and
/// the scans there show a ground cutting through the sensor's surroundings that no vehicle sees.

#include "litamin2/sim/world.hpp"

#include <Eigen/Geometry>
#include <cstddef>
#include <vector>

namespace litamin2::sim {

struct GroundClearance {
  /// Poses whose height above the ground differs from the mount height by more than the
  /// tolerance.
  std::size_t poses_off = 0;
  /// Index of the first and last of them (0 when there is none).
  std::size_t first_off = 0;
  std::size_t last_off = 0;
  /// Largest |height above ground - mount height|, metres.
  double worst_m = 0.0;
};

/// Checks each sensor pose (world frame, z up) against world.ground_height() below it.
GroundClearance check_ground_clearance(const World& world,
                                       const std::vector<Eigen::Isometry3d>& sensor_poses,
                                       double mount_height, double tolerance_m);

}  // namespace litamin2::sim
