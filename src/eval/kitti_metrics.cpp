#include "litamin2/eval/kitti_metrics.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "litamin2/eval/relative_error.hpp"

namespace litamin2::eval {
namespace {

constexpr double kRadToDeg = 180.0 / 3.14159265358979323846;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace

std::vector<double> trajectory_distances(const std::vector<Eigen::Isometry3d>& poses) {
  std::vector<double> dist;
  dist.reserve(poses.size());
  if (poses.empty()) return dist;
  dist.push_back(0.0);
  for (std::size_t i = 1; i < poses.size(); ++i) {
    dist.push_back(dist.back() + (poses[i].translation() - poses[i - 1].translation()).norm());
  }
  return dist;
}

std::optional<std::size_t> last_frame_from_segment_length(const std::vector<double>& dist,
                                                          std::size_t first_frame, double length,
                                                          bool strict) {
  if (first_frame >= dist.size()) return std::nullopt;
  const double target = dist[first_frame] + length;
  for (std::size_t i = first_frame; i < dist.size(); ++i) {
    if (strict ? dist[i] > target : dist[i] >= target) return i;
  }
  return std::nullopt;
}

KittiMetrics compute_kitti_metrics(const std::vector<Eigen::Isometry3d>& ground_truth,
                                   const std::vector<Eigen::Isometry3d>& estimate,
                                   const KittiMetricsOptions& options) {
  if (ground_truth.size() != estimate.size()) {
    throw std::invalid_argument("compute_kitti_metrics: ground truth has " +
                                std::to_string(ground_truth.size()) + " poses, estimate has " +
                                std::to_string(estimate.size()));
  }
  if (options.step_size == 0) {
    throw std::invalid_argument("compute_kitti_metrics: step_size must be positive");
  }

  KittiMetrics result;
  const std::vector<double> dist = trajectory_distances(ground_truth);
  for (std::size_t first = 0; first < ground_truth.size(); first += options.step_size) {
    for (const double length : options.lengths) {
      const auto last =
          last_frame_from_segment_length(dist, first, length, options.strict_segment_end);
      if (!last) continue;
      const RelativeError error = relative_error(ground_truth[first], ground_truth[*last],
                                                 estimate[first], estimate[*last]);
      SegmentError segment;
      segment.first_frame = first;
      segment.last_frame = *last;
      segment.length = length;
      segment.rotation_error = error.rotation / length;
      segment.translation_error = error.translation / length;
      segment.speed = length / (options.frame_period * static_cast<double>(*last - first + 1));
      result.segment_errors.push_back(segment);
    }
  }
  result.segments = result.segment_errors.size();

  double t_sum = 0.0;
  double r_sum = 0.0;
  for (const SegmentError& segment : result.segment_errors) {
    t_sum += segment.translation_error;
    r_sum += segment.rotation_error;
  }
  const auto n = static_cast<double>(result.segments);
  result.translation_percent = result.segments > 0 ? 100.0 * t_sum / n : kNaN;
  result.rotation_deg_per_100m = result.segments > 0 ? 100.0 * kRadToDeg * r_sum / n : kNaN;

  for (const double length : options.lengths) {
    LengthStats stats;
    stats.length = length;
    double t = 0.0;
    double r = 0.0;
    for (const SegmentError& segment : result.segment_errors) {
      if (segment.length != length) continue;
      t += segment.translation_error;
      r += segment.rotation_error;
      ++stats.segments;
    }
    const auto count = static_cast<double>(stats.segments);
    stats.translation_percent = stats.segments > 0 ? 100.0 * t / count : kNaN;
    stats.rotation_deg_per_100m = stats.segments > 0 ? 100.0 * kRadToDeg * r / count : kNaN;
    result.per_length.push_back(stats);
  }
  return result;
}

}  // namespace litamin2::eval
