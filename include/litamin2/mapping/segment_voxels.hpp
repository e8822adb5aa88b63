#pragma once
/// A rigid segment's keyframes fused once in the segment's own frame, so that a segment the
/// full pass moves rigidly (graph_optimizer.hpp: every keyframe of a segment moves by its
/// segment's correction) is re-placed in the map tiles by its new frame, voxel by voxel of the
/// segment, instead of re-fused keyframe by keyframe (each ~400 distributions read back from
/// the store, subtracted and added again).
///
/// The segment's frame is a pose of the map frame (tile_map.hpp: the fused pose of the
/// segment's reference keyframe); each keyframe is held at its pose relative to it. A
/// keyframe's distributions, moved by that relative pose, land in the segment voxel (edge
/// voxel_size, aligned at the segment frame's origin) holding each moved mean, with the sums
/// relative to that voxel's centre, as map_tile.hpp fuses a keyframe into the map's voxels. A
/// placement moves each segment voxel's moments by the frame (VoxelMoments::transformed:
/// sum' = R sum + n d, S' = R S R^T + R sum d^T + d (R sum)^T + n d d^T) into the map voxel
/// holding its moved mean. A rigid move of the frame moves every point of the segment by the
/// same transform, so the count, the first and the second moments of the placed segment are
/// exactly those of its keyframes fused one by one at the same poses; only the voxel a point
/// ends in may differ (a segment voxel lands whole: up to a voxel's reach of smear, as a
/// keyframe's distribution lands whole today).
///
/// Additive like MapTile: a keyframe added at a relative pose is subtracted at the same pose
/// exactly (same voxels). Held compactly (a sorted array of count and double sums, the origin
/// implied by the key: 88 B a voxel) because a fleet's map holds a segment per 10 keyframes.
/// Not thread-safe.

#include "litamin2/core/distribution.hpp"
#include "litamin2/core/voxel_moments.hpp"
#include "litamin2/mapping/map_tile.hpp"

#include <Eigen/Geometry>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace litamin2::mapping {

class SegmentVoxels {
 public:
  /// Adds (sign +1) or subtracts (-1) a keyframe's distributions at `relative` (its pose in
  /// the segment frame). Returns how many of its moments did not match what the segment holds
  /// on a subtraction (skipped: a caller's or a store's error); 0 otherwise.
  std::size_t apply(const std::vector<Distribution>& distributions,
                    const Eigen::Isometry3d& relative, double voxel_size, int sign);

  struct Voxel {
    /// pack_voxel of the segment voxel; the sums are relative to its centre.
    std::uint64_t key = 0;
    std::int32_t count = 0;
    double sum[3] = {0.0, 0.0, 0.0};
    /// xx, xy, xz, yy, yz, zz (VoxelMoments::sum_sq).
    double sum_sq[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  };
  /// Ordered by key.
  const std::vector<Voxel>& voxels() const { return voxels_; }
  /// A voxel's moments with their origin (the voxel's centre for `voxel_size`).
  static VoxelMoments moments(const Voxel& v, double voxel_size);
  bool empty() const { return voxels_.empty(); }
  /// A segment of the given voxels (ordered by key, as voxels() gives them: segment_spill.hpp
  /// reads a segment back from them).
  static SegmentVoxels of(std::vector<Voxel> voxels);
  std::size_t bytes() const;

 private:
  std::vector<Voxel> voxels_;
};

/// The segment's moments placed in the map by `frame`: one FusedMoment per segment voxel, in
/// the map voxel holding its moved mean and the tile holding that voxel.
std::vector<FusedMoment> placed_moments(const SegmentVoxels& segment,
                                        const Eigen::Isometry3d& frame,
                                        const TileGeometry& geometry);

}  // namespace litamin2::mapping
