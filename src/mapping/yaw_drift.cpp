#include "litamin2/mapping/yaw_drift.hpp"

#include <algorithm>
#include <cmath>

namespace litamin2::mapping {

Eigen::Isometry3d without_yaw_drift(const Eigen::Isometry3d& relative, double drift_per_m,
                                    double distance) {
  if (drift_per_m == 0.0) return relative;
  Eigen::Isometry3d out = relative;
  out.linear() =
      relative.linear() *
      Eigen::AngleAxisd(-drift_per_m * distance, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return out;
}

double yaw_of(const Eigen::Matrix3d& rotation) {
  const Eigen::AngleAxisd aa(rotation);
  return aa.angle() * aa.axis().z();
}

void YawDriftEstimator::add_anchor(const KeyframeGraph& graph, std::uint32_t node) {
  if (!enabled()) return;
  const KeyframeNode& n = graph.node(node);
  if (anchors_.size() <= n.stream) anchors_.resize(n.stream + 1);
  std::vector<std::uint32_t>& list = anchors_[n.stream];
  const auto by_id = [&graph](std::uint32_t a, std::uint32_t b) {
    return graph.node(a).key.id < graph.node(b).key.id;
  };
  // Loop ends arrive mostly in path order (a loop's newer end is the stream's newest keyframe).
  const auto at = std::lower_bound(list.begin(), list.end(), node, by_id);
  if (at != list.end() && *at == node) return;
  list.insert(at, node);
}

bool YawDriftEstimator::update(const KeyframeGraph& graph, std::uint32_t stream) {
  if (!enabled() || stream >= anchors_.size() || anchors_[stream].size() < 2) return false;
  const std::vector<std::uint32_t>& list = anchors_[stream];
  const KeyframeNode& b = graph.node(list.back());
  // The earliest loop end within the window (path lengths grow with the ids).
  const double from = b.path_length - config_.yaw_drift_window;
  const auto first = std::partition_point(
      list.begin(), list.end(), [&](std::uint32_t n) { return graph.node(n).path_length < from; });
  const KeyframeNode& a = graph.node(*first);
  const double span = b.path_length - a.path_length;
  if (span < config_.yaw_drift_min_path || span <= 0.0) return false;
  // R_odo = R_true Rz(drift d): the yaw of R_odo^T R_solved is -drift d (yaw_drift.hpp).
  const Eigen::Matrix3d odometry = (a.odom_pose.inverse() * b.odom_pose).linear();
  const Eigen::Matrix3d solved = (a.pose.inverse() * b.pose).linear();
  const double drift = -yaw_of(odometry.transpose() * solved) / span;
  if (std::abs(drift) * 180.0 / M_PI * 100.0 > config_.yaw_drift_max_deg_per_100m) {
    ++rejected_;
    return false;
  }
  if (drift_.size() <= stream) drift_.resize(stream + 1, 0.0);
  ++estimates_;
  const bool changed = drift_[stream] != drift;
  drift_[stream] = drift;
  return changed;
}

void YawDriftEstimator::update_all(const KeyframeGraph& graph) {
  for (std::uint32_t s = 0; s < anchors_.size(); ++s) update(graph, s);
}

}  // namespace litamin2::mapping
