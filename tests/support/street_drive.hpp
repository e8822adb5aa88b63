#pragma once
// Keyframes of vehicles driving the synthetic street (synthetic_scene.hpp): the mapper's,
// the place index's and the aggregator core's tests share them.

#include "litamin2/core/keyframe.hpp"
#include "litamin2/core/voxelizer.hpp"
#include "support/synthetic_scene.hpp"

#include <string>
#include <vector>

namespace litamin2::testing {

/// A drive along the street's centre line, from x = -30 to 30 m and back, a keyframe every
/// 3 m: the way back passes every place of the way out, facing the other way.
inline std::vector<Eigen::Isometry3d> out_and_back() {
  std::vector<Eigen::Isometry3d> poses;
  for (double x = -30.0; x <= 30.0; x += 3.0) poses.push_back(planar_pose(x, 0.0, 0.0));
  for (double x = 28.5; x >= -30.0; x -= 3.0) poses.push_back(planar_pose(x, 1.0, 180.0));
  return poses;
}

/// Keyframes of one stream: distributions of the scene seen from each true pose, and an
/// odometry that turns `drift_deg` too far per keyframe, in the frame of the first pose.
inline std::vector<Keyframe> drive(const std::string& stream,
                                   const std::vector<Eigen::Isometry3d>& truth, double drift_deg,
                                   unsigned seed) {
  const PointCloud scene = synthetic_scene(seed, 40000);
  Voxelizer voxelizer(VoxelizerConfig{});
  std::vector<Keyframe> out;
  Eigen::Isometry3d odom = Eigen::Isometry3d::Identity();
  for (std::size_t i = 0; i < truth.size(); ++i) {
    if (i > 0) odom = odom * (truth[i - 1].inverse() * truth[i]) * planar_pose(0, 0, drift_deg);
    Keyframe kf;
    kf.key = {stream, i};
    kf.stamp.nanoseconds = static_cast<std::int64_t>(i) * 100000000;
    kf.odom_pose = odom;
    kf.voxel_size = 3.0;
    kf.distributions = voxelizer.voxelize(transformed(scene, truth[i].inverse()));
    out.push_back(std::move(kf));
  }
  return out;
}

}  // namespace litamin2::testing
