#pragma once
/// Generated trajectories for running the simulator without any data files, and the default
/// KITTI calibration used when none is given.

#include <Eigen/Geometry>
#include <string>
#include <vector>

namespace litamin2::sim {

/// A generated drive at 10 Hz as sensor (velodyne) poses in the world frame (z up); the first
/// pose is the identity. Names:
///  - "loop": a closed ~310 m city drive (rounded rectangle 110 m x 55 m with S-bends on the long
///    sides and a gentle 1.5 m hill), 8 m/s, returns to its start (loop closure);
///  - "highway": 600 m of gently curving road at 25 m/s (open stretch, like KITTI 01).
/// Throws std::invalid_argument for an unknown name.
std::vector<Eigen::Isometry3d> builtin_trajectory(const std::string& name);

/// Names accepted by builtin_trajectory.
std::vector<std::string> builtin_trajectory_names();

/// Tr (velodyne -> camera 0) of KITTI odometry sequences 00-02, the default calibration
/// (rotation re-orthonormalised, see orthonormalized).
Eigen::Isometry3d kitti_default_velo_to_cam();

/// The transform with its rotation replaced by the nearest rotation matrix. KITTI's Tr is
/// orthonormal only to ~1e-7, so Tr * Tr.inverse() (transpose-based) is not exactly the identity;
/// the simulator uses orthonormalised calibrations so poses round-trip exactly.
Eigen::Isometry3d orthonormalized(const Eigen::Isometry3d& T);

}  // namespace litamin2::sim
