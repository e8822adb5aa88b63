#pragma once
/// Distributions back to voxel moments, so that the distributions of keyframes (all a map
/// patch carries) can be merged into a VoxelMap at any pose, exactly as the tracker merges
/// its scans: a distribution of n points with mean m and covariance C has, about the origin m,
/// the moments sum = 0 and sum of squares = n C.

#include "litamin2/core/distribution.hpp"
#include "litamin2/core/voxelizer.hpp"

#include <vector>

namespace litamin2::mapping {

inline GridVoxels moments_of(const std::vector<Distribution>& distributions) {
  GridVoxels voxels;
  voxels.moments.reserve(distributions.size());
  for (const Distribution& d : distributions) {
    if (d.count <= 0) continue;
    VoxelMoments& m = voxels.moments.emplace_back();
    m.origin = d.mean;
    m.count = d.count;
    const Eigen::Matrix3d s = d.count * d.cov;
    m.sum_sq << s(0, 0), s(0, 1), s(0, 2), s(1, 1), s(1, 2), s(2, 2);
  }
  return voxels;
}

}  // namespace litamin2::mapping
