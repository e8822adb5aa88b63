#pragma once
/// Timing of one revolution of a spinning LiDAR: where the sweep starts, which way it turns,
/// how long it takes, and whether the vehicle moves during it (each firing then leaves from
/// its own pose on the continuous trajectory, as on a real sensor).

namespace litamin2::sim {

/// Revolution timing. With the defaults (start 0 deg, counter-clockwise, no motion) columns
/// are cast as the simulator always did: azimuth 2 pi k / steps for column k, one pose.
struct SweepOptions {
  /// Each firing is cast from the pose at its own time (motion within the sweep); each point
  /// stays in the sensor frame of its firing (raw, as drivers publish them; not deskewed).
  bool motion = false;
  /// Duration of one revolution, seconds (10 Hz: 0.1).
  double duration = 0.1;
  /// Azimuth of the first firing, degrees (0 = forward, 90 = left; Velodyne drivers cut the
  /// sweep behind the car, at 180).
  double start_azimuth_deg = 0.0;
  /// Turn clockwise seen from above (decreasing azimuth), as Velodyne and Ouster sensors do.
  bool clockwise = false;

  /// Azimuth of column k of `steps`, radians.
  double column_azimuth(int column, int steps) const;
  /// Time of column k of `steps` from the sweep start, seconds (k / steps * duration).
  double column_time(int column, int steps) const;
  /// True if the options give the simulator's original column layout (start 0, counter-
  /// clockwise, no motion).
  bool is_default_layout() const;
  /// Throws std::invalid_argument unless the duration is in (0, 1] s and the start azimuth is
  /// finite and within [-360, 360] degrees.
  void validate() const;
};

}  // namespace litamin2::sim
