#pragma once
/// How the LiDAR is mounted on the vehicle: a fixed rotation of the sensor relative to the
/// vehicle frame (x forward, y left, z up). Real mounts are tilted by a degree or more, so the
/// scan's "up" is not the vehicle's.

#include <Eigen/Core>

namespace litamin2::sim {

/// Fixed mount rotation of the sensor on the vehicle, as roll (about x), pitch (about y) and
/// yaw (about z) in degrees, applied as R = Rz(yaw) * Ry(pitch) * Rx(roll) (sensor to vehicle).
/// Positive pitch turns the sensor's x axis downwards (nose down), as a rotation about +y.
struct SensorMount {
  /// Rotation about the vehicle's x axis, degrees.
  double roll_deg = 0.0;
  /// Rotation about the vehicle's y axis, degrees.
  double pitch_deg = 0.0;
  /// Rotation about the vehicle's z axis, degrees.
  double yaw_deg = 0.0;

  /// The rotation taking sensor-frame vectors to the vehicle frame.
  Eigen::Matrix3d rotation() const;
  /// True if all three angles are zero (the untilted sensor).
  bool is_identity() const;
  /// Throws std::invalid_argument unless roll and pitch are within +-30 degrees, yaw within
  /// +-180 degrees and all are finite.
  void validate() const;
};

}  // namespace litamin2::sim
