#pragma once
/// How well a keyframe's distributions land on a submap at a pose (loop verification's fitness),
/// and the coarse search over a grid of yaws and planar offsets that picks the registration's
/// start (loop_verifier.hpp).

#include "litamin2/core/correspondence_search.hpp"
#include "litamin2/core/distribution.hpp"
#include "litamin2/core/voxel_map.hpp"

#include <Eigen/Geometry>
#include <cstddef>
#include <vector>

namespace litamin2::mapping {

struct Fitness {
  double fraction = 0.0;
  double rmse = 0.0;
};

/// The fitness of an alignment: among the query distributions that are not horizontal surfaces
/// (roads and ground match the road of any other place; every `stride`-th only), the share
/// whose nearest map distribution (within one voxel) is closer than `gate` along that
/// distribution's normal, and the RMS of those distances. Distances along the normal, because
/// two voxelisations of one wall put their means up to a voxel apart within the wall's plane.
class FitnessScorer {
 public:
  /// `query`, `map` and `search` (over `map`) must outlive the scorer.
  FitnessScorer(const std::vector<Distribution>& query, const VoxelMap& map,
                const CorrespondenceSearch& search);

  /// Query distributions that are not horizontal surfaces.
  std::size_t structure() const { return structure_.size(); }
  /// How many of them score() looks at with `stride`.
  std::size_t tried(std::size_t stride) const { return (structure_.size() + stride - 1) / stride; }

  Fitness score(const Eigen::Isometry3d& pose, double gate, std::size_t stride) const;
  /// The inliers score() counts at `pose`, exactly when there are at least `needed` of them;
  /// otherwise some count below `needed` (it stops once the rest cannot make up the number).
  std::size_t inliers(const Eigen::Isometry3d& pose, double gate, std::size_t stride,
                      std::size_t needed) const;

 private:
  /// Distance along the normal of the nearest map distribution to `p`, or a negative number
  /// when there is none within a voxel.
  double normal_distance(const Eigen::Vector3d& p) const;

  const std::vector<Distribution>& query_;
  const VoxelMap& map_;
  const CorrespondenceSearch& search_;
  std::vector<std::size_t> structure_;
  std::vector<Eigen::Vector3d> map_normals_;
};

struct CoarseAlignment {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  /// Its fitness fraction (score() with a gate of a quarter voxel on a subsample).
  double fraction = -1.0;
  /// Poses whose inliers were counted to the end (for tests and profiles).
  int full_scores = 0;
};

/// Scores yaws of -yaw_step, 0 and +yaw_step about `initial` and planar offsets of -4..4 half
/// voxels in x and y (243 poses) on a subsample of ~300 structure distributions with a gate of
/// a quarter voxel, and returns the first pose (in that order) of the highest fraction. With
/// `bounded`, a pose stops being scored once it can no longer reach the best so far (nor the
/// initial pose's count, which the best reaches at least): the same pose, far fewer searches.
CoarseAlignment coarse_alignment(const FitnessScorer& scorer, double voxel_size,
                                 const Eigen::Isometry3d& initial, double yaw_step,
                                 bool bounded = true);

}  // namespace litamin2::mapping
