#pragma once
/// Votes the points of a scan into voxel moments: the inner loop shared by the scan voxeliser
/// and the map. Points arrive in ring order, so consecutive points mostly fall into the same
/// voxel: a run of them is summed in a local accumulator and merged into the voxel once, which
/// saves the hash lookup and the memory round trip per point.

#include "litamin2/core/point_cloud.hpp"
#include "litamin2/core/voxel_key.hpp"
#include "litamin2/core/voxel_moments.hpp"
#include "litamin2/core/voxel_voting_sse2.hpp"
#include "litamin2/core/voxelizer.hpp"

#include <Eigen/Geometry>

#include <utility>

namespace litamin2 {

/// vote_points' portable loop, in double throughout.
template <class MomentsOf>
void vote_points_scalar(const Eigen::Vector3f* begin, const Eigen::Vector3f* end,
                        const Eigen::Isometry3d& pose, const VoxelizerConfig& config,
                        MomentsOf&& moments_of) {
  const double size = config.voxel_size;
  const double inv_size = 1.0 / size;
  const double min_range_sq = config.min_range * config.min_range;
  const double max_range_sq = config.max_range * config.max_range;
  const Eigen::Matrix3d rotation = pose.linear();
  const Eigen::Vector3d translation = pose.translation();
  // floor(x / size) + 2^20 as one truncation: x / size + 2^20 is positive wherever pack_voxel
  // is defined (|index| < 2^20), and truncating a positive number floors it. This is
  // pack_voxel's offset index, so the three truncations give the packed key directly.
  constexpr double kOffset = static_cast<double>(kVoxelKeyOffset);

  VoxelMoments run;
  std::uint64_t run_key = 0;
  auto flush = [&] {
    if (run.count > 0) moments_of(unpack_voxel(run_key)).merge(run);
  };
  for (const Eigen::Vector3f* it = begin; it != end; ++it) {
    const Eigen::Vector3d p = it->cast<double>();
    const double range_sq = p.squaredNorm();
    if (!(range_sq >= min_range_sq && range_sq <= max_range_sq)) continue;  // also drops NaN
    const Eigen::Vector3d world = rotation * p + translation;
    const std::uint64_t ix = static_cast<std::uint64_t>(world.x() * inv_size + kOffset);
    const std::uint64_t iy = static_cast<std::uint64_t>(world.y() * inv_size + kOffset);
    const std::uint64_t iz = static_cast<std::uint64_t>(world.z() * inv_size + kOffset);
    const std::uint64_t key = (ix & kVoxelKeyMask) | ((iy & kVoxelKeyMask) << kVoxelKeyBits) |
                              ((iz & kVoxelKeyMask) << (2 * kVoxelKeyBits));
    if (run.count == 0 || key != run_key) {
      flush();
      run = VoxelMoments();
      run.origin = (unpack_voxel(key).cast<double>() + Eigen::Vector3d::Constant(0.5)) * size;
      run_key = key;
    }
    run.add(world);
  }
  flush();
}

/// Adds each point of [begin, end) whose range is within the config's limits, moved by `pose`,
/// to the moments of its voxel. `moments_of(index)` returns the VoxelMoments of a voxel
/// (creating it with its centre as origin); the reference is used before the next call only.
/// Uses the SSE2 kernel where the config allows it (voxel_voting_sse2.hpp), else the scalar loop.
template <class MomentsOf>
void vote_points(const Eigen::Vector3f* begin, const Eigen::Vector3f* end,
                 const Eigen::Isometry3d& pose, const VoxelizerConfig& config,
                 MomentsOf&& moments_of) {
#if defined(LITAMIN2_HAVE_SSE2_VOTING)
  if (sse2_voting::fits(config)) {
    vote_points_sse2(begin, end, pose, config, std::forward<MomentsOf>(moments_of));
    return;
  }
#endif
  vote_points_scalar(begin, end, pose, config, std::forward<MomentsOf>(moments_of));
}

/// vote_points over a whole scan.
template <class MomentsOf>
void vote_points(const PointCloud& scan, const Eigen::Isometry3d& pose,
                 const VoxelizerConfig& config, MomentsOf&& moments_of) {
  const Eigen::Vector3f* data = scan.points.data();
  vote_points(data, data + scan.points.size(), pose, config, std::forward<MomentsOf>(moments_of));
}

}  // namespace litamin2
