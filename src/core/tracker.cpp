#include "litamin2/core/tracker.hpp"

#include "litamin2/core/scan_registration.hpp"
#include "litamin2/core/stopwatch.hpp"

#include <Eigen/Cholesky>
#include <chrono>
#include <cmath>

namespace litamin2 {
namespace {

double rotation_angle(const Eigen::Matrix3d& rotation) {
  return Eigen::AngleAxisd(rotation).angle();
}

/// 2 sigma^2 H^-1, sigma^2 = cost per residual degree of freedom (3 per correspondence).
Matrix6d covariance_from_hessian(const RegistrationResult& result) {
  const double dof = std::max(1.0, 3.0 * result.correspondences - 6.0);
  const double sigma_sq = result.cost / dof;
  const Eigen::LDLT<Matrix6d> ldlt(result.hessian);
  if (ldlt.info() != Eigen::Success) return Matrix6d::Zero();
  return 2.0 * sigma_sq * ldlt.solve(Matrix6d::Identity());
}

}  // namespace

Tracker::Tracker(const TrackerConfig& config)
    : config_((validate(config), config)),
      voxelizer_(config.voxelizer),
      map_(config.voxelizer, config.map) {}

Tracker::~Tracker() = default;

bool Tracker::is_keyframe(const Eigen::Isometry3d& pose) const {
  const Eigen::Isometry3d motion = last_keyframe_.inverse() * pose;
  return motion.translation().norm() >= config_.keyframe.distance ||
         rotation_angle(motion.linear()) >= config_.keyframe.angle_deg * M_PI / 180.0;
}

FrameResult Tracker::process(const PointCloud& scan) {
  FrameResult frame;
  const Eigen::Isometry3d predicted = pose_ * velocity_;
  Eigen::Isometry3d estimate = predicted;
  if (frames_ > 0 && !map_.empty() && search_) {
    const ScanRegistration registration =
        register_scan(scan, voxelizer_, map_, *search_, predicted, config_.registration);
    const RegistrationResult& result = registration.result;
    source_ = registration.source;
    frame.times.voxelize_ms = registration.voxelize_ms;
    frame.times.register_ms = registration.register_ms;
    frame.iterations = result.iterations;
    frame.voxelizations = registration.voxelizations;
    frame.correspondences = result.correspondences;
    if (result.valid) {
      estimate = result.pose;
      frame.registered = true;
      frame.covariance = covariance_from_hessian(result);
    }
  } else {
    const auto start = std::chrono::steady_clock::now();
    source_ = voxelizer_.voxelize(scan, predicted);
    frame.voxelizations = 1;
    frame.times.voxelize_ms = elapsed_ms(start);
  }
  frame.source_distributions = static_cast<int>(source_.size());

  // A frame that could not be registered also goes into the map, so that tracking can resume.
  frame.keyframe = frames_ == 0 || !frame.registered || is_keyframe(estimate);
  if (frame.keyframe) {
    const auto start = std::chrono::steady_clock::now();
    map_.add_keyframe(voxelizer_.last_voxels(), estimate);
    search_ = make_correspondence_search(config_.registration.correspondence, map_);
    last_keyframe_ = estimate;
    frame.times.map_update_ms = elapsed_ms(start);
  }

  velocity_ = frames_ == 0 ? Eigen::Isometry3d::Identity() : pose_.inverse() * estimate;
  pose_ = estimate;
  frame.pose = estimate;
  ++frames_;
  return frame;
}

Keyframe make_keyframe(const Tracker& tracker, const FrameResult& frame, KeyframeKey key,
                       Stamp stamp, const Eigen::Isometry3d& sensor_in_base) {
  const bool moved = !sensor_in_base.matrix().isIdentity(0.0);
  Keyframe keyframe;
  keyframe.key = std::move(key);
  keyframe.stamp = stamp;
  keyframe.odom_pose = moved ? Eigen::Isometry3d(sensor_in_base * frame.pose) : frame.pose;
  keyframe.covariance =
      moved ? transform_left_covariance(frame.covariance, sensor_in_base) : frame.covariance;
  keyframe.voxel_size = tracker.map().voxel_size();
  keyframe.distributions = tracker.last_distributions();
  return keyframe;
}

}  // namespace litamin2
