#pragma once
/// A sensor driving a gentle S-curve through the synthetic scene (synthetic_scene.hpp): the
/// tracker tests' known path and the scans seen along it.

#include "litamin2/core/so3.hpp"
#include "support/synthetic_scene.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <vector>

namespace litamin2::testing {

/// Sensor poses along a gentle S-curve, 0.8 m per frame.
inline std::vector<Eigen::Isometry3d> s_curve_path(int frames) {
  std::vector<Eigen::Isometry3d> poses;
  double yaw = 0.0;
  Eigen::Vector3d position(-20.0, 0.0, 0.0);
  for (int i = 0; i < frames; ++i) {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = so3_exp(Eigen::Vector3d(0, 0, yaw));
    pose.translation() = position;
    poses.push_back(pose);
    yaw += 0.01 * std::sin(i * 0.2);
    position += pose.linear() * Eigen::Vector3d(0.8, 0.0, 0.0);
  }
  return poses;
}

/// The scene seen from `pose` (an independent sampling of 40,000 points for each seed).
inline PointCloud scan_seen_from(const Eigen::Isometry3d& pose, unsigned seed) {
  return transformed(synthetic_scene(seed, 40000), pose.inverse());
}

}  // namespace litamin2::testing
