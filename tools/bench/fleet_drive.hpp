#pragma once
// litamin2-fleet-bench's vehicles: each drives the world's street grid from a random
// intersection, in the right-hand lane, choosing at every intersection to go on (1/2), turn
// left or right (1/4 each), a keyframe every `spacing` metres; its odometry drifts (noise per
// keyframe on translation and rotation, and a yaw bias of its own) and starts in its own
// frame (its first pose), so vehicles must be joined by loops between them.

#include <Eigen/Geometry>
#include <random>

namespace litamin2::bench {

struct FleetDriveConfig {
  int blocks = 10;
  double block_size = 100.0;
  /// Metres between keyframes.
  double spacing = 2.0;
  /// Odometry noise per keyframe: translation (m), rotation (deg), and the range of each
  /// vehicle's yaw bias (deg per keyframe).
  double translation_noise = 0.01;
  double rotation_noise_deg = 0.02;
  double yaw_bias_deg = 0.01;
};

class FleetVehicleDrive {
 public:
  FleetVehicleDrive(const FleetDriveConfig& config, unsigned seed);

  /// Advances to the next keyframe; then truth() and odometry() are its poses.
  void next();
  /// Sensor pose in the world.
  const Eigen::Isometry3d& truth() const { return truth_; }
  /// Sensor pose in the vehicle's odometry frame (its first true pose).
  const Eigen::Isometry3d& odometry() const { return odometry_; }
  /// The odometry's yaw bias, radians a metre (drawn at construction from the seed).
  double yaw_bias_per_m() const { return yaw_bias_ / config_.spacing; }

 private:
  Eigen::Isometry3d pose_at() const;

  FleetDriveConfig config_;
  std::mt19937 rng_;
  /// Current street segment: from intersection (ix, iy) heading (dx, dy), s metres along.
  int ix_ = 0, iy_ = 0, dx_ = 1, dy_ = 0;
  double s_ = 0.0;
  double yaw_bias_ = 0.0;
  bool started_ = false;
  Eigen::Isometry3d truth_ = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d first_ = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d odometry_ = Eigen::Isometry3d::Identity();
};

}  // namespace litamin2::bench
