#pragma once
// A sensor path no road can lie under: 60 m flat, then 8 m up while moving 8 m forward (a
// ground truth's height drift at a near standstill, as at KITTI 08's start), then flat again
// for 60 m. Shared by the simulator's ground-check and drivable-height tests.

#include <Eigen/Geometry>
#include <vector>

namespace litamin2::testing {

/// The path's 160 poses (world frame, z up), each turned by `yaw_per_pose` times its index.
inline std::vector<Eigen::Isometry3d> climb_in_place(double yaw_per_pose = 0.0) {
  std::vector<Eigen::Isometry3d> climb;
  for (int i = 0; i < 160; ++i) {
    Eigen::Isometry3d p = Eigen::Isometry3d::Identity();
    const bool in_place = i >= 60 && i < 100;
    const double x = i < 60 ? 1.0 * i : i < 100 ? 60.0 + 0.2 * (i - 60) : 68.0 + 1.0 * (i - 100);
    p.translation() = Eigen::Vector3d(x, 0.0, in_place ? 0.2 * (i - 60) : (i < 60 ? 0.0 : 8.0));
    p.rotate(Eigen::AngleAxisd(yaw_per_pose * i, Eigen::Vector3d::UnitZ()));
    climb.push_back(p);
  }
  return climb;
}

}  // namespace litamin2::testing
