#pragma once
// Registration of one point cloud against a map built from another, as the tests use it.

#include "litamin2/core/correspondence_search.hpp"
#include "litamin2/core/scan_registration.hpp"
#include "litamin2/core/voxel_map.hpp"

namespace litamin2::testing {

/// Builds a map from `target` (at the identity), and registers `source` to it from `initial`
/// with `config`, default voxelisation.
inline RegistrationResult register_clouds(const PointCloud& target, const PointCloud& source,
                                          const Eigen::Isometry3d& initial,
                                          const RegistrationConfig& config) {
  const VoxelizerConfig voxels;
  VoxelMap map(voxels, VoxelMapConfig{});
  map.insert(target, Eigen::Isometry3d::Identity());
  Voxelizer voxelizer(voxels);
  const auto search = make_correspondence_search(config.correspondence, map);
  return register_scan(source, voxelizer, map, *search, initial, config).result;
}

}  // namespace litamin2::testing
