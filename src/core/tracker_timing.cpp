// The tracker's timed entry points: deskew (added to LiTAMIN2, core/deskew.hpp) before the
// unchanged per-scan pipeline of Tracker::process(scan), and frames skipped over a gap.

#include "litamin2/core/deskew.hpp"
#include "litamin2/core/motion_model.hpp"
#include "litamin2/core/scan_registration.hpp"
#include "litamin2/core/stopwatch.hpp"
#include "litamin2/core/sweep_motion.hpp"
#include "litamin2/core/tracker.hpp"

#include <chrono>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

namespace litamin2 {

double Tracker::interval_to(const SweepTiming& timing) const {
  if (!has_stamp_) return 0.0;
  if (!(last_stamp_ < timing.stamp))
    throw std::invalid_argument("Tracker: stamp " + std::to_string(timing.stamp.nanoseconds) +
                                " ns is not after the previous scan's " +
                                std::to_string(last_stamp_.nanoseconds) + " ns");
  return static_cast<double>(timing.stamp.nanoseconds - last_stamp_.nanoseconds) * 1e-9;
}

const std::vector<float>* Tracker::point_times(const PointCloud& scan) {
  const DeskewConfig& d = config_.deskew;
  if (d.time_source != TimeSource::kAzimuth && scan.has_times()) return &scan.times;
  if (d.time_source == TimeSource::kField) return nullptr;
  times_from_azimuth(scan, d.azimuth, azimuth_times_);
  return &azimuth_times_;
}

double Tracker::prediction_scale(double interval) const {
  const double max_ratio = config_.prediction.max_interval_ratio;
  // Before two frames there is no motion to scale (velocity_ is the identity or a seed's).
  if (max_ratio <= 0.0 || frames_ < 2) return 1.0;
  const double ratio = interval_ratio(interval, last_interval_, max_ratio);
  // Intervals equal up to the stamps' rounding (e.g. times.txt's 0.1 s steps in nanoseconds):
  // the last motion as it is, bit for bit.
  return std::abs(ratio - 1.0) <= 1e-6 ? 1.0 : ratio;
}

FrameResult Tracker::process(const PointCloud& scan, const SweepTiming& timing) {
  const DeskewConfig& d = config_.deskew;
  prepare_first_scan(scan);
  const double interval = interval_to(timing);
  const std::vector<float>* times = nullptr;
  // With deskew, self-hits are dropped first, in the sensor frame of their firing: they move
  // with the sensor, and deskew would move them by the motion within the sweep (at highway
  // speed up to a sweep's 2.5 m of travel), out of the cells or box that catch them.
  const PointCloud* measured = &scan;
  std::optional<int> self_hits;
  if (d.enabled) {
    if (const auto why = point_times_error(scan)) throw std::invalid_argument("Tracker: " + *why);
    self_hits = 0;
    measured = &without_self_hits(scan, *self_hits);
    times = point_times(*measured);
  }
  const PointCloud* input = measured;
  // Constant velocity in time (PredictionConfig): the last motion spans last_interval_, this
  // scan comes `interval` after the last one (longer when files were dropped).
  const double motion_scale = prediction_scale(interval);
  choose_frame_registration();
  StageTimes first_pass;
  if (times) {
    // Pass 1: the motion within this sweep predicted by constant velocity, the previous frame's
    // motion over its interval (none before two frames).
    Twist twist;
    if (frames_ >= 2 && last_interval_ > 0.0) twist = twist_from_motion(velocity_, last_interval_);
    auto start = std::chrono::steady_clock::now();
    deskew(*measured, *times, twist, deskewed_);
    first_pass.deskew_ms += elapsed_ms(start);
    // Pass 2: register the corrected scan, and correct the raw scan again with the motion
    // registration found from the last pose to this one (a frame fresher than the
    // prediction's); process() below registers that and puts it into the map. At the second
    // scan (with either number of passes) the map is the first scan, taken with no motion
    // known: it is deskewed in hindsight with this motion (constant velocity over both sweeps)
    // and the map rebuilt from it, then the motion is registered again against that map.
    const bool redo_first = frames_ == 1 && !first_scan_.empty();
    std::optional<Eigen::Isometry3d> registered_pose;
    double registered_share = 0.0;
    if ((d.passes == 2 || redo_first) && interval > 0.0 && frames_ > 0 && !map_.empty() &&
        search_) {
      for (int round = 0; round < (redo_first ? 2 : 1); ++round) {
        RegistrationStart from = registration_start(deskewed_, motion_scale, interval, first_pass);
        const ScanRegistration registered = register_from(deskewed_, from);
        first_pass.voxelize_ms += registered.voxelize_ms;
        first_pass.register_ms += registered.register_ms;
        if (!registered.result.valid) break;
        registered_pose = registered.result.pose;
        registered_share = registered.inlier_share();
        twist = twist_from_motion(pose_.inverse() * registered.result.pose, interval);
        start = std::chrono::steady_clock::now();
        deskew(*measured, *times, twist, deskewed_);
        first_pass.deskew_ms += elapsed_ms(start);
        if (redo_first) rebuild_first_keyframe(twist);
      }
    }
    // Only where the scan fits the map as frames usually do: after a break, or on a scan that
    // fits badly, the correction would fit the twist to the misfit. And only at speed
    // (SweepMotionConfig::min_speed_mps).
    if (d.sweep_motion.enabled && registered_pose && frames_ >= 2 && fitting_share_ > 0.0 &&
        registered_share >= config_.recovery.trigger_ratio * fitting_share_ &&
        twist.linear.norm() >= d.sweep_motion.min_speed_mps)
      correct_sweep_motion(*measured, *times, *registered_pose, twist, first_pass);
    input = &deskewed_;
  }
  if (frames_ == 0 && times) {
    first_scan_ = *measured;
    first_times_ = *times;
  } else if (frames_ >= 1) {
    first_scan_ = PointCloud();
    first_times_.clear();
  }
  FrameResult frame = process_scaled(*input, motion_scale, self_hits, interval);
  frame.deskewed = times != nullptr;
  frame.times.voxelize_ms += first_pass.voxelize_ms;
  frame.times.register_ms += first_pass.register_ms;
  frame.times.deskew_ms += first_pass.deskew_ms;
  has_stamp_ = true;
  last_stamp_ = timing.stamp;
  // After restart_clock() there is no interval: the previous one still belongs to velocity_,
  // as it does when the global search kept the last velocity over a break.
  if (interval > 0.0 && !frame.velocity_kept) last_interval_ = interval;
  return frame;
}

void Tracker::correct_sweep_motion(const PointCloud& measured, const std::vector<float>& times,
                                   const Eigen::Isometry3d& pose, Twist& twist, StageTimes& spent) {
  // The scan as deskewed with `twist`, cut in the map's grid at the registered pose, each
  // distribution with its points' mean firing time; registered with the twist's correction.
  auto start = std::chrono::steady_clock::now();
  const std::vector<Distribution> source = voxelizer_.voxelize(deskewed_, pose);
  const DistributionTimes source_times = distribution_times(deskewed_, times, voxelizer_);
  spent.voxelize_ms += elapsed_ms(start);
  start = std::chrono::steady_clock::now();
  const SweepMotionResult sweep = register_with_sweep_motion(
      source, source_times, map_, *search_, pose, frame_registration_, config_.deskew.sweep_motion);
  spent.register_ms += elapsed_ms(start);
  if (!sweep.valid) return;
  twist.angular += sweep.correction.angular;
  twist.linear += sweep.correction.linear;
  start = std::chrono::steady_clock::now();
  deskew(measured, times, twist, deskewed_);
  spent.deskew_ms += elapsed_ms(start);
}

void Tracker::rebuild_first_keyframe(const Twist& twist) {
  PointCloud corrected;
  deskew(first_scan_, first_times_, twist, corrected);
  // The map holds the first scan alone (frames_ == 1), at the first pose, pose_.
  map_ = VoxelMap(config_.voxelizer, config_.map);
  voxelizer_.voxelize(corrected, pose_);
  map_.add_keyframe(voxelizer_.last_voxels(), pose_);
  search_ = make_correspondence_search(config_.registration.correspondence, map_);
}

FrameResult Tracker::skip_frame() {
  FrameResult frame;
  pose_ = pose_ * velocity_;
  frame.pose = pose_;
  ++frames_;
  return frame;
}

FrameResult Tracker::skip_frame(const SweepTiming& timing) {
  const double interval = interval_to(timing);
  // Extrapolated over the skipped scan's interval; the velocity, and the interval it spans,
  // stay the last registered ones.
  FrameResult frame;
  pose_ = pose_ * predicted_motion(prediction_scale(interval));
  frame.pose = pose_;
  ++frames_;
  has_stamp_ = true;
  last_stamp_ = timing.stamp;
  return frame;
}

}  // namespace litamin2
