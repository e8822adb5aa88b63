#include "litamin2/daemon/stream_processor.hpp"

#include <ctime>

#include "litamin2/core/so3.hpp"

namespace litamin2::daemon {

namespace {

/// The calling thread's CPU time, seconds.
double thread_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_nsec) * 1e-9;
}

}  // namespace

Eigen::Isometry3d base_pose(const Eigen::Isometry3d& sensor_pose,
                            const Eigen::Isometry3d& extrinsic) {
  return extrinsic * sensor_pose * extrinsic.inverse();
}

StreamProcessor::StreamProcessor(StreamConfig config, ResultSink& sink, StreamStats& stats)
    : config_(std::move(config)),
      has_extrinsic_(!config_.extrinsic.matrix().isIdentity(0.0)),
      extrinsic_inverse_(config_.extrinsic.inverse()),
      tracker_(std::make_unique<Tracker>(config_.tracker)),
      sink_(sink),
      stats_(stats) {}

StreamProcessor::StreamProcessor(StreamConfig config, ResultSink& sink, StreamStats& stats,
                                 HandoverSeed seed, double max_extrapolation_s)
    : StreamProcessor(std::move(config), sink, stats) {
  keyframes_ = seed.next_keyframe_id;
  seed_ = std::move(seed);
  max_extrapolation_s_ = max_extrapolation_s;
}

void StreamProcessor::process(Frame& frame) {
  // With the stream's tracker.deskew enabled, a scan with per-point times (read from the
  // PointCloud2's time field, DaemonNode) is corrected for the motion within its sweep; one
  // without is registered as it is. Invalid times throw and the frame counts as failed.
  // Stamps of a stream increase (PointsListener drops the others) except after a publisher
  // restarts: the tracker's clock restarts with it.
  const std::optional<Stamp> previous_stamp = last_stamp_;
  if (last_stamp_ && !(*last_stamp_ < frame.stamp)) tracker_->restart_clock();
  last_stamp_ = frame.stamp;
  if (seed_ && !origin_ && !continued_ && !seed_->map_keyframes.empty()) {
    // Taken over with the old owner's last map patches: the tracker continues in the stream's
    // own frame from them (stream_handover.hpp), no origin is applied.
    tracker_->continue_from(
        tracker_seed(*seed_, frame.stamp, max_extrapolation_s_, config_.extrinsic));
    continued_ = true;
    seed_->map_keyframes.clear();
  }
  const double cpu_before = thread_cpu_seconds();
  const FrameResult result = tracker_->process(frame.cloud, SweepTiming{frame.stamp});
  stats_.record_tracking_cpu(thread_cpu_seconds() - cpu_before);
  // Without an extrinsic the published pose is the tracker's, bit for bit.
  const Eigen::Isometry3d sensor_pose = result.pose;
  Eigen::Isometry3d pose =
      has_extrinsic_ ? Eigen::Isometry3d(config_.extrinsic * sensor_pose * extrinsic_inverse_)
                     : sensor_pose;
  Matrix6d covariance = has_extrinsic_
                            ? transform_left_covariance(result.covariance, config_.extrinsic)
                            : result.covariance;
  if (seed_ && !origin_ && !continued_)
    origin_ = handover_origin(*seed_, frame.stamp, max_extrapolation_s_);
  if (origin_) {
    pose = *origin_ * pose;
    covariance = transform_left_covariance(covariance, *origin_);
  }
  std::optional<TwistEstimate> twist;
  if (result.registered && last_pose_ && previous_stamp && *previous_stamp < frame.stamp) {
    const double seconds =
        static_cast<double>(frame.stamp.nanoseconds - previous_stamp->nanoseconds) * 1e-9;
    twist = twist_between(*last_pose_, pose, covariance, seconds);
  }
  last_pose_ = pose;
  sink_.publish_odometry(OdometryOutput{config_.id, frame.stamp, pose, covariance, result.keyframe,
                                        result.registered, frame.sequence, twist});
  if (result.keyframe) {
    Keyframe keyframe = make_keyframe(*tracker_, result, KeyframeKey{config_.id, keyframes_},
                                      frame.stamp, config_.extrinsic);
    if (origin_) {
      keyframe.odom_pose = *origin_ * keyframe.odom_pose;
      keyframe.covariance = transform_left_covariance(keyframe.covariance, *origin_);
    }
    sink_.publish_keyframe(keyframe);
    ++keyframes_;
  }
  stats_.record_result(frame.arrival, std::chrono::steady_clock::now(), result.keyframe,
                       result.registered, tracker_->map().distributions().size());
}

}  // namespace litamin2::daemon
