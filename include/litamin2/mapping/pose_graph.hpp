#pragma once
/// Pose-graph optimisation of keyframe poses with Ceres: relative-pose edges weighted by
/// their standard deviations, a robust (Cauchy) loss on loop edges so that a wrong loop that
/// passed verification cannot bend the whole graph, and one fixed node per connected part.

#include "litamin2/core/so3.hpp"
#include "litamin2/mapping/mapper_config.hpp"

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>
#include <vector>

namespace litamin2::mapping {

struct PoseGraphEdge {
  /// Node indices: the edge measures the pose of `to` in the frame of `from`.
  int from = 0;
  int to = 0;
  Eigen::Isometry3d relative = Eigen::Isometry3d::Identity();
  /// Standard deviations of the translation (x, y, z, metres) then rotation (about x, y, z,
  /// radians) of the measurement, in `from`'s frame.
  Vector6d sigma = Vector6d::Ones();
  /// If set, the full covariance of the measurement in the residual's coordinates (translation
  /// difference in `from`'s frame, then the rotation error on the right of the measurement;
  /// mapping/odometry_covariance.hpp), used instead of `sigma`. Must be positive definite.
  std::optional<Matrix6d> covariance;
  /// Robust loss (loop edges) or plain least squares (odometry edges).
  bool robust = false;
  /// The measured poses are those of nodes[from] * from_offset and nodes[to] * to_offset: a
  /// node is then a rigid segment of keyframes and an offset a keyframe's pose in its
  /// segment's frame (segment_graph.hpp). Identity for an edge between the nodes themselves.
  Eigen::Isometry3d from_offset = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d to_offset = Eigen::Isometry3d::Identity();
};

struct PoseGraphResult {
  int iterations = 0;
  double initial_cost = 0.0;
  double final_cost = 0.0;
  bool usable = false;
  /// The solver returned poses that are not finite or moved beyond reach (within_reach):
  /// refused (usable false, `poses` left as they were).
  bool diverged = false;
  /// Solved by conjugate gradients (PoseGraphConfig::iterative_min_free_poses), not by the
  /// sparse Cholesky factorisation.
  bool iterative = false;
};

/// Whether `after` is a plausible solution from `before`: every pose finite and no
/// translation moved by more than the graph's reach, the sum of the lengths of every edge's
/// measurement and offsets (no solution that fits the edges can move a node further than a
/// path through all of them). Converged solves of a well-posed graph always pass; a solve that
/// ran off along a direction the edges do not hold (a node held only by loop edges far out in
/// their robust loss) does not.
bool within_reach(const std::vector<Eigen::Isometry3d>& before,
                  const std::vector<Eigen::Isometry3d>& after,
                  const std::vector<PoseGraphEdge>& edges);

/// Optimises `poses` in place. Nodes with fixed[i] keep their pose; every connected part of
/// the graph needs one. A solution that is not within_reach is refused (result.diverged).
PoseGraphResult optimize_pose_graph(std::vector<Eigen::Isometry3d>& poses,
                                    const std::vector<bool>& fixed,
                                    const std::vector<PoseGraphEdge>& edges,
                                    const PoseGraphConfig& config);

}  // namespace litamin2::mapping
