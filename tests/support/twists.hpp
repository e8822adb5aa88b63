#pragma once
// Twists and rotation angles as the deskew and sweep-motion tests write them.

#include "litamin2/core/deskew.hpp"

#include <Eigen/Geometry>
#include <cmath>

namespace litamin2::testing {

/// A body twist: angular (wx, wy, wz) rad/s, linear (vx, vy, vz) m/s.
inline Twist twist(double wx, double wy, double wz, double vx, double vy, double vz) {
  Twist t;
  t.angular = Eigen::Vector3d(wx, wy, wz);
  t.linear = Eigen::Vector3d(vx, vy, vz);
  return t;
}

/// The angle of a rotation, degrees.
inline double angle_deg(const Eigen::Matrix3d& r) {
  return Eigen::AngleAxisd(r).angle() * 180.0 / M_PI;
}

}  // namespace litamin2::testing
