#pragma once
// Views of the synthetic scene for the mapping tests: a sensor's distributions, a map of them,
// and the scene mirrored across the road (another street).

#include "litamin2/core/voxel_map.hpp"
#include "litamin2/core/voxelizer.hpp"
#include "litamin2/mapping/distribution_moments.hpp"
#include "support/synthetic_scene.hpp"

#include <vector>

namespace litamin2::testing {

/// Distributions of the scene seen from a sensor at `sensor` (scene frame).
inline std::vector<Distribution> view(const PointCloud& scene, const Eigen::Isometry3d& sensor) {
  Voxelizer voxelizer(VoxelizerConfig{});
  return voxelizer.voxelize(transformed(scene, sensor.inverse()));
}

/// A map holding `distributions` as they are (every voxel kept).
inline VoxelMap map_of(const std::vector<Distribution>& distributions) {
  VoxelizerConfig voxels;
  voxels.min_points = 1;
  VoxelMap map(voxels, VoxelMapConfig{});
  map.insert(mapping::moments_of(distributions), Eigen::Isometry3d::Identity());
  return map;
}

/// The scene's buildings and poles mirrored across the road: another street.
inline PointCloud mirrored(const PointCloud& scene) {
  PointCloud out = scene;
  for (auto& p : out.points) p.y() = -p.y();
  return out;
}

}  // namespace litamin2::testing
