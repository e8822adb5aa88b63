#pragma once
/// KITTI odometry benchmark metric (relative errors over 100..800 m segments), reproducing
/// evaluate_odometry.cpp of the official KITTI odometry devkit.

#include <Eigen/Geometry>
#include <cstddef>
#include <optional>
#include <vector>

namespace litamin2::eval {

/// Parameters of the KITTI metric. The defaults are those of the official devkit.
struct KittiMetricsOptions {
  /// Segment lengths in metres (devkit: 100, 200, ..., 800).
  std::vector<double> lengths{100.0, 200.0, 300.0, 400.0, 500.0, 600.0, 700.0, 800.0};
  /// A segment starts every step_size frames (devkit: 10).
  std::size_t step_size = 10;
  /// Frame period in seconds; used only for SegmentError::speed (devkit: 0.1 s).
  double frame_period = 0.1;
  /// true (devkit): the last frame of a segment is the first frame i with
  /// dist[i] > dist[first] + len. false: the first frame with dist[i] >= dist[first] + len.
  bool strict_segment_end = true;
};

/// Error of one segment, in the devkit's raw units.
struct SegmentError {
  std::size_t first_frame = 0;
  std::size_t last_frame = 0;
  /// Nominal segment length in metres (one of KittiMetricsOptions::lengths).
  double length = 0.0;
  /// Rotation angle of the segment error divided by length, in rad/m.
  double rotation_error = 0.0;
  /// Translation norm of the segment error divided by length, in m/m.
  double translation_error = 0.0;
  /// length / (frame_period * (last_frame - first_frame + 1)), in m/s.
  double speed = 0.0;
};

/// Averages over all segments of one nominal length. NaN values when segments == 0.
struct LengthStats {
  double length = 0.0;
  std::size_t segments = 0;
  /// Mean translation error in percent (devkit t_err * 100).
  double translation_percent = 0.0;
  /// Mean rotation error in deg per 100 m (devkit r_err * 180/pi * 100).
  double rotation_deg_per_100m = 0.0;
};

/// Result of compute_kitti_metrics().
struct KittiMetrics {
  /// Mean over all segments (devkit "average" / stats.txt) of t_err, in percent. NaN if
  /// segments == 0.
  double translation_percent = 0.0;
  /// Mean over all segments of r_err, in deg per 100 m. NaN if segments == 0.
  double rotation_deg_per_100m = 0.0;
  /// One entry per KittiMetricsOptions::lengths, in that order (also lengths without segments).
  std::vector<LengthStats> per_length;
  /// Every evaluated segment, ordered by first frame, then length (devkit order).
  std::vector<SegmentError> segment_errors;
  /// Number of evaluated segments. 0 means the metric is undefined (ground truth path shorter
  /// than the shortest segment length).
  std::size_t segments = 0;

  /// true if at least one segment was evaluated.
  bool valid() const { return segments > 0; }
};

/// Cumulative path length along the translations of `poses`; result[0] = 0.
std::vector<double> trajectory_distances(const std::vector<Eigen::Isometry3d>& poses);

/// Index of the first frame >= first_frame whose distance exceeds dist[first_frame] + length
/// (strictly, or >= when strict is false); std::nullopt if there is none.
std::optional<std::size_t> last_frame_from_segment_length(const std::vector<double>& dist,
                                                          std::size_t first_frame, double length,
                                                          bool strict = true);

/// KITTI odometry metric of `estimate` against `ground_truth` (pose i of one is compared with
/// pose i of the other; both are poses in a common world frame, e.g. camera 0 w.r.t. frame 0).
/// Segment start frames, lengths and averaging follow the devkit; distances are measured along
/// the ground truth. Throws std::invalid_argument if the sizes differ.
KittiMetrics compute_kitti_metrics(const std::vector<Eigen::Isometry3d>& ground_truth,
                                   const std::vector<Eigen::Isometry3d>& estimate,
                                   const KittiMetricsOptions& options = {});

}  // namespace litamin2::eval
