#pragma once
/// Configuration of the motion within a sweep estimated with the pose (sweep_motion.hpp).

namespace litamin2 {

struct SweepMotionConfig {
  /// Estimate the twist's correction with the pose (one more voxelisation and a 12-unknown
  /// registration a scan), with deskew on, the motion before known and the sensor at least
  /// `min_speed_mps` fast.
  bool enabled = true;
  /// Standard deviation of the angular velocity's change from the twist deskew used, rad/s
  /// (KITTI 01's ground truth: the rate changes by 0.01-0.03 rad/s from one frame to the next,
  /// 95th percentile).
  double angular_sigma = 0.02;
  /// Standard deviation of the linear velocity's change, m/s (braking at 5 m/s^2 changes it by
  /// 0.5 m/s in a 10 Hz sweep).
  double linear_sigma = 0.5;
  /// Distributions whose points' times spread more (standard deviation, seconds) are left out
  /// of the correction (sweep_motion.hpp).
  double max_time_spread_s = 0.01;
  /// Newton iterations at most.
  int max_iterations = 10;
  /// Estimated only while the twist deskew used moves the sensor at least this fast, m/s
  /// (0: at any speed). The change of the twist within a sweep displaces its points by about
  /// the change times the sweep's period, so slow sweeps gain little from it for its cost.
  /// 15 m/s: above every urban KITTI sequence's speed (at most 13 m/s), below the highway's
  /// (01, ~27 m/s), where it brings the drift with deskew within 20 % of a sweep without motion
  /// (docs/accuracy.md, "Deskew").
  double min_speed_mps = 15.0;
};

/// Throws ConfigError (naming the key under "deskew.sweep_motion.") on the first invalid
/// value: sigmas finite and > 0, iterations within [1, 100], min_speed_mps finite and
/// >= 0.
void validate(const SweepMotionConfig& config);

}  // namespace litamin2
