#pragma once
/// The target of registration: a world-frame voxel map of normal distributions built from the
/// points of keyframes. Insertion merges moments into existing voxels; voxels beyond a radius
/// of the vehicle are removed, so memory is bounded by the radius, not by the drive's length.

#include "litamin2/core/distribution.hpp"
#include "litamin2/core/point_cloud.hpp"
#include "litamin2/core/voxel_key.hpp"
#include "litamin2/core/voxelizer.hpp"

#include <Eigen/Geometry>
#include <memory>
#include <vector>

namespace litamin2 {

struct VoxelMapConfig {
  /// Voxels whose centre is farther than this from the current position are dropped, metres.
  double radius = 100.0;
};

class VoxelMap {
 public:
  /// Voxel size, minimum points, point range limits and regularisation come from `voxels`.
  VoxelMap(const VoxelizerConfig& voxels, const VoxelMapConfig& config);
  ~VoxelMap();
  VoxelMap(VoxelMap&&) noexcept;
  VoxelMap& operator=(VoxelMap&&) noexcept;

  /// Votes the scan's points, moved to the world by `pose`, into the map.
  void insert(const PointCloud& scan, const Eigen::Isometry3d& pose);
  /// Merges a scan's grid voxels (Voxelizer::last_voxels()) into the map for a scan whose final
  /// pose is `pose`: each voxel's moments are moved exactly by the correction
  /// pose * grid_pose^-1 and merged into the map voxel holding the moved mean. Costs one merge
  /// per voxel instead of one vote per point; only points of a voxel straddling a boundary by
  /// less than the correction (the regrid tolerance, 2 cm by default) land one voxel off.
  void insert(const GridVoxels& voxels, const Eigen::Isometry3d& pose);
  /// Drops every voxel whose centre is farther than the configured radius from `position`.
  void remove_far(const Eigen::Vector3d& position);
  /// A keyframe's update: insert(voxels, pose) then remove_far(pose.translation()), with the
  /// distributions rebuilt once instead of twice (same result).
  void add_keyframe(const GridVoxels& voxels, const Eigen::Isometry3d& pose);
  /// Merges a keyframe known only by its distributions (a map patch: core/keyframe.hpp), taken
  /// in the frame that `pose` moves to the map's: each distribution (mean m, covariance C, n
  /// points) becomes the moments of n points with mean R m + t and covariance R C R^T
  /// (VoxelMoments::of_distribution) merged into the voxel holding the moved mean, then the far
  /// voxels are dropped as in add_keyframe. C is the distribution's lightly regularised
  /// covariance (Distribution::cov), so a flat voxel comes back a little thicker than its
  /// points were. Distributions with count < 1 are skipped.
  void add_distributions(const std::vector<Distribution>& distributions,
                         const Eigen::Isometry3d& pose);

  /// Distributions of the voxels with enough points, world frame. Their order is deterministic
  /// but not the voxels' (a dropped voxel's place is taken by the last distribution).
  const std::vector<Distribution>& distributions() const { return distributions_; }
  /// Index into distributions() of the voxel at `index`, or -1 if there is none.
  int find(const VoxelIndex& index) const;
  /// Number of voxels holding points (with or without a valid distribution).
  std::size_t num_voxels() const;
  /// Edge of a voxel, metres.
  double voxel_size() const { return voxels_.voxel_size; }
  bool empty() const { return distributions_.empty(); }

 private:
  void merge_grid_voxels(const GridVoxels& voxels, const Eigen::Isometry3d& pose);
  /// Drops the far voxels; true if there were any.
  bool drop_far_cells(const Eigen::Vector3d& position);
  /// Removes distributions_[index], moving the last one into its place.
  void remove_distribution(int index);
  /// Recomputes the distributions of the voxels that changed since the last call (only those:
  /// a keyframe's update costs what it changes, not the map's size).
  void rebuild_distributions();

  struct Cells;
  VoxelizerConfig voxels_;
  VoxelMapConfig config_;
  std::unique_ptr<Cells> cells_;
  std::vector<Distribution> distributions_;
};

}  // namespace litamin2
