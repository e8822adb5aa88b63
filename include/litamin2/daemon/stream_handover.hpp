#pragma once
/// Where a stream's tracking continues when it moves from one daemon to another (sharding,
/// docs/deploy.md "Several daemon hosts"). The new owner's tracker starts empty, at identity in
/// its own first base frame; its outputs are moved into the stream's existing odometry frame by
/// the origin O, the base pose at the new owner's first scan: the old owner's last published
/// pose P (at stamp t0, with body twist xi) carried on at constant velocity,
///   O = P Exp((t - t0) xi)      (the constant-twist motion of deskew.hpp, motion_after),
/// so that subscribers see one odometry frame with a jump of only the extrapolation error over
/// the handover gap. Published poses are O T (T the new tracker's base pose), their left-update
/// covariances Ad_O C Ad_O^T (transform_left_covariance), and keyframe ids continue after the
/// last one the old owner published.

#include "litamin2/core/deskew.hpp"
#include "litamin2/core/stamp.hpp"

#include <Eigen/Geometry>
#include <cstdint>
#include <optional>

namespace litamin2::daemon {

/// What the new owner knows of a stream from the old owner's outputs.
struct HandoverSeed {
  /// The last published base pose in the stream's odometry frame (rt/<stream>/odom).
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  /// Its header stamp.
  Stamp stamp;
  /// Its body twist, when the message had one (a registered frame after another).
  std::optional<Twist> twist;
  /// The id of the next keyframe: the last one seen on the map patches topic plus one (0 when
  /// none was seen).
  std::uint64_t next_keyframe_id = 0;
};

/// O above for a first scan at `stamp`: the twist is applied for 0 < dt <= max_extrapolation_s
/// (dt = stamp - seed.stamp); otherwise (no twist, stamp not after the seed's, gap too long)
/// the last pose itself.
Eigen::Isometry3d handover_origin(const HandoverSeed& seed, Stamp stamp,
                                  double max_extrapolation_s);

}  // namespace litamin2::daemon
