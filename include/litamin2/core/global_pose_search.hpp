#pragma once
/// Global x/y/yaw search for a scan after a break in the input (many frames missing: the
/// vehicle moved metres and turned tens of degrees between two files, beyond every start the
/// recovery's scaled constant-velocity predictions give; docs/accuracy.md "Breaks in the real
/// VLP-16 drive"). A correlative search: candidate poses on a grid of x, y, yaw around the last
/// pose (z, roll, pitch from the prediction) are scored cheaply against the map's distributions,
/// coarse to fine; the tracker then registers the scan fully from the best few.

#include "litamin2/core/distribution.hpp"
#include "litamin2/core/voxel_map.hpp"

#include <Eigen/Geometry>
#include <vector>

namespace litamin2 {

struct GlobalPoseSearchConfig {
  /// The search runs when, after the recovery's retries, the best inlier share is below this
  /// fraction of the typical share. 0: off. On by default: on the simulated break sequences it
  /// removes the lost track, on the sequences without breaks it never runs (docs/accuracy.md,
  /// "Global pose search after a break").
  double trigger_ratio = 0.5;
  /// Half-widths of the searched window around the last pose: metres in x and y, degrees in yaw.
  double range_xy = 16.0;
  double range_yaw_deg = 45.0;
  /// Grid steps of the coarsest level; each further level divides them by 4 around the best
  /// candidates of the level before.
  double coarse_step_xy = 2.0;
  double coarse_step_yaw_deg = 5.0;
  /// Levels of the coarse-to-fine search (1: the coarse grid only).
  int levels = 2;
  /// Candidates carried from one level to the next, and registered fully at the end.
  int candidates = 4;
  /// Scan distributions scored per candidate (every k-th of those that constrain x, y or yaw).
  int max_sources = 256;
  /// A registration from a candidate is kept only if its inlier share is at least this fraction
  /// of the typical share (and above the share of every start tried before). After a break part
  /// of the scan sees what the map has not seen, so a correct pose reaches 0.5-0.8 of the
  /// typical share (simulated break sequences 07, 00: 0.8 kept 3 of 11 searches, 0.5 11 of 12).
  double accept_ratio = 0.5;
};

/// Throws ConfigError (naming `recovery.global_search.*`) on the first invalid value.
void validate(const GlobalPoseSearchConfig& config);

/// A scored candidate pose (sensor in the world).
struct PoseCandidate {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  /// Mean agreement of the scored scan distributions with the map, in [0, 1].
  double score = 0.0;
};

/// The scan distributions a search scores: sensor-frame means of the distributions that
/// constrain x, y or yaw (not horizontal planes, whose normal is within 25 deg of the vertical
/// of `orientation`, the predicted sensor rotation), every k-th so that at most `max_sources`
/// are left.
std::vector<Eigen::Vector3d> search_points(const std::vector<Distribution>& source,
                                           const Eigen::Matrix3d& orientation, int max_sources);

/// Agreement of points (sensor frame) placed at `pose` with the map: for each point, the map
/// distribution (mean m, covariance C) of the voxel it falls in gives
/// exp(-d^2 / 2), d^2 = (p - m)^T (C + b^2 I)^-1 (p - m), with b the blur of the grid step the
/// pose was taken from (a correlative scan-matching score: Olson, ICRA 2009, with Gaussians of
/// the map's distributions in place of a rasterised likelihood); 0 for a point in an empty
/// voxel. The blurred precisions are computed once per blur.
class PoseScorer {
 public:
  PoseScorer(const VoxelMap& map, double blur);
  /// Mean agreement over `points` (sensor frame) placed at `pose`, in [0, 1].
  double score(const std::vector<Eigen::Vector3d>& points, const Eigen::Isometry3d& pose) const;

 private:
  const VoxelMap& map_;
  double inv_voxel_;
  std::vector<Eigen::Matrix3d> precisions_;
};

/// The best `config.candidates` poses (highest score first, at least a coarse step apart) of a
/// coarse-to-fine search: x, y on a grid within range_xy of `last`'s position, yaw rotating the
/// predicted orientation about the world's z within range_yaw_deg; z, roll and pitch are the
/// prediction's. Empty if no point falls in the map at any candidate.
std::vector<PoseCandidate> search_global_pose(const std::vector<Eigen::Vector3d>& points,
                                              const VoxelMap& map, const Eigen::Isometry3d& last,
                                              const Eigen::Isometry3d& predicted,
                                              const GlobalPoseSearchConfig& config);

}  // namespace litamin2
