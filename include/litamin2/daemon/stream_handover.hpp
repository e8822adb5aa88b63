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
///
/// With the old owner's last map patches at hand (HandoverSeed::map_keyframes, at most
/// ShardingConfig::seed_keyframes of them, none older than seed_max_age_s before the last
/// odometry), the new owner's tracker instead continues in the stream's own odometry frame
/// (core/tracker_seed.hpp, tracker_seed() below): its map is those keyframes, at their published
/// poses, and the first scan is registered to it from O. The extrapolation error over the gap
/// is then corrected by that registration (down to the registration's error against the old
/// owner's map) instead of staying in every later pose as the offset of a new map.

#include "litamin2/core/deskew.hpp"
#include "litamin2/core/keyframe.hpp"
#include "litamin2/core/stamp.hpp"
#include "litamin2/core/tracker_seed.hpp"

#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <vector>

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
  /// The interval between the last two odometry messages, seconds (the twist's frame
  /// interval); 0 when not known.
  double interval_s = 0.0;
  /// The stream's last keyframes as published (map patches, odometry frame), oldest first:
  /// select_map_seed()'s choice. Empty: the new owner starts a new map at O.
  std::vector<Keyframe> map_keyframes;
};

/// Which of the map patches seen of a stream seed its new owner's map.
struct MapSeedLimits {
  /// At most this many, the newest (0: none).
  std::size_t keyframes = 0;
  /// None whose stamp is more than this many seconds before the last odometry's.
  double max_age_s = 0.0;
};

/// The keyframes of `candidates` (one stream's) that seed the map: those not older than
/// limits.max_age_s before `last_stamp`, the newest limits.keyframes of them by id, one per id,
/// oldest first.
std::vector<Keyframe> select_map_seed(std::vector<Keyframe> candidates, Stamp last_stamp,
                                      const MapSeedLimits& limits);

/// The tracker seed (core/tracker_seed.hpp) for a first scan at `stamp` of a stream whose
/// sensor sits at `sensor_in_base` (StreamConfig::extrinsic, E): the tracker's frame is the
/// stream's first sensor frame (the base odometry frame moved by E^-1), so the prediction is
/// E^-1 O E (O = handover_origin), the motion per frame E^-1 Exp(interval_s xi) E (identity
/// without a twist or an interval), and each map keyframe's sensor pose E^-1 K (K its
/// published pose, sensor in the base odometry frame: make_keyframe).
TrackerSeed tracker_seed(const HandoverSeed& seed, Stamp stamp, double max_extrapolation_s,
                         const Eigen::Isometry3d& sensor_in_base);

/// O above for a first scan at `stamp`: the twist is applied for 0 < dt <= max_extrapolation_s
/// (dt = stamp - seed.stamp); otherwise (no twist, stamp not after the seed's, gap too long)
/// the last pose itself.
Eigen::Isometry3d handover_origin(const HandoverSeed& seed, Stamp stamp,
                                  double max_extrapolation_s);

}  // namespace litamin2::daemon
