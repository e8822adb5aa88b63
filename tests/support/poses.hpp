#pragma once
/// Poses for tests, from a position and roll, pitch, yaw angles.

#include <Eigen/Geometry>

namespace litamin2::testing {

/// The pose at (x, y, z) turned by yaw about z, then pitch about y, then roll about x (radians).
inline Eigen::Isometry3d pose_of(double x, double y, double z, double roll, double pitch,
                                 double yaw) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                   Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
                   Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
                      .toRotationMatrix();
  pose.translation() = Eigen::Vector3d(x, y, z);
  return pose;
}

}  // namespace litamin2::testing
