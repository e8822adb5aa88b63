#pragma once
/// Motion compensation within a sweep (deskew). Added to LiTAMIN2: the paper registers scans as
/// they are (KITTI's are deskewed by the dataset). A spinning LiDAR measures each point from the
/// sensor's pose at that point's own time, so at 30 m/s the last firings of a 100 ms sweep are
/// taken 3 m from the first. With the sensor moving at a constant body velocity (twist) xi, its
/// pose at time t after the scan's stamp is T(t) = T(0) Exp(t xi), and a point p measured at t
/// is, in the sensor frame at the stamp, p' = Exp(t xi) p. deskew() applies that to every point;
/// the tracker (core/tracker.hpp, Tracker::process with a SweepTiming) estimates xi from the
/// constant-velocity prediction and again from the registered motion.

#include "litamin2/core/point_cloud.hpp"
#include "litamin2/core/sweep_motion_config.hpp"

#include <Eigen/Geometry>
#include <vector>

namespace litamin2 {

/// Where a scan's per-point times come from.
enum class TimeSource {
  /// The scan's own times (PointCloud::times, the driver's time field); a scan without them is
  /// registered as it is, and counted (FrameResult::deskewed is false).
  kField,
  /// From each point's azimuth (AzimuthTiming), for drivers that publish no time field; a
  /// time field, if any, is ignored.
  kAzimuth,
  /// The scan's times when it has them, else from the azimuth.
  kFieldOrAzimuth,
};

/// How a spinning LiDAR's firing time follows from a point's azimuth atan2(y, x).
struct AzimuthTiming {
  /// One revolution, seconds (10 Hz: 0.1).
  double period_s = 0.1;
  /// Azimuth of the first firing after the scan's stamp, degrees (0 forward, 90 left); Velodyne
  /// drivers cut the sweep behind the vehicle, at 180.
  double start_deg = 180.0;
  /// Turning clockwise seen from above (decreasing azimuth), as Velodyne, Ouster and Hesai
  /// units do.
  bool clockwise = true;
};

struct DeskewConfig {
  /// Correct each scan's points for the motion within its sweep before voxelisation.
  bool enabled = false;
  /// Where the per-point times come from.
  TimeSource time_source = TimeSource::kField;
  /// For TimeSource::kAzimuth and kFieldOrAzimuth.
  AzimuthTiming azimuth;
  /// 1: correct with the constant-velocity prediction of the motion only. 2: register that
  /// scan, correct the raw scan again with the motion registration found, and register the
  /// result (twice the registration work). Either way the second scan's registered motion also
  /// deskews the first scan in hindsight (it was taken with no motion known) and the map is
  /// rebuilt from it.
  int passes = 2;
  /// After the passes, the twist's correction estimated with the pose and the scan deskewed
  /// again with it (sweep_motion.hpp).
  SweepMotionConfig sweep_motion;
};

/// Throws ConfigError (naming the key under "deskew.") on the first invalid value: period
/// within (0, 1] s, start azimuth finite within [-360, 360] degrees, passes 1 or 2.
void validate(const DeskewConfig& config);

/// A constant body velocity: angular (rad/s) and linear (m/s), in the sensor frame.
struct Twist {
  Eigen::Vector3d angular = Eigen::Vector3d::Zero();
  Eigen::Vector3d linear = Eigen::Vector3d::Zero();
};

/// The twist that moves the sensor by `motion` (T(seconds) = T(0) motion) in `seconds` (> 0):
/// Log(motion) / seconds, with SE(3)'s logarithm (screw motion, not rotation and translation
/// apart).
Twist twist_from_motion(const Eigen::Isometry3d& motion, double seconds);

/// Exp(seconds * twist): the sensor's motion after `seconds` at the constant twist.
Eigen::Isometry3d motion_after(const Twist& twist, double seconds);

/// The scan with every point moved into the sensor frame at the scan's stamp: point i, measured
/// at times[i], becomes Exp(times[i] xi) p_i. The scan's times must be valid
/// (point_times_error); intensities are kept, `out.times` is left empty (every point is now at
/// the stamp). Exp is evaluated on a 0.1 ms grid and carried to each point's own time to first
/// order (the error is about 1e-7 m at 100 m and 1 rad/s, below float precision). Deterministic:
/// the same input gives the same bits whatever the number of threads. `out` may not alias
/// `scan`.
void deskew(const PointCloud& scan, const Twist& twist, PointCloud& out);

/// The same with the times given apart (e.g. from times_from_azimuth), one per point; the
/// scan's own times are ignored.
void deskew(const PointCloud& scan, const std::vector<float>& times, const Twist& twist,
            PointCloud& out);

/// Per-point times from the azimuth of each point (for scans without a time field): the share
/// of a revolution turned from `timing.start_deg` in the turning direction, times the period,
/// so times lie in [0, period). Raw points are in the sensor frame at their firing, where the
/// azimuth is the firing's. Writes one time per point into `times`.
void times_from_azimuth(const PointCloud& scan, const AzimuthTiming& timing,
                        std::vector<float>& times);

}  // namespace litamin2
