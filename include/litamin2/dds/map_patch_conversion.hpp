#pragma once
/// litamin2/msg/MapPatch <-> Keyframe: the one conversion each way, used by the daemon
/// (writer) and the aggregator (reader).
///
/// On the wire the pose covariance is ROS's (row-major 6x6, translation first, see
/// odometry_conversion.hpp); the keyframe holds the tracker's (phi, tau) left-update covariance.
/// Distributions travel as floats (mean, covariance upper triangle, count): a keyframe read from
/// a message converts back to the same message (distributions, position and stamp identical;
/// the quaternion and covariance to rounding, through the rotation matrix and Jacobians); shape_cov
/// / shape_cov_inv are not sent (the reader regularises `cov` for its own registration settings)
/// and are set to `cov` and its inverse (identity when `cov` is singular).

#include "litamin2/core/distribution.hpp"
#include "litamin2/core/keyframe.hpp"
#include "litamin2/msg/MapPatch.h"

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace litamin2::dds {

/// A MapPatch of a keyframe.
litamin2::msg::MapPatch to_map_patch(const Keyframe& keyframe, const std::string& frame_id);

/// Why a MapPatch was rejected.
enum class PatchError {
  kNone = 0,
  /// stream_id is not a valid stream id (service::stream_id_error).
  kBadStreamId,
  /// keyframe_id is beyond 2^63 - 1, the largest id the store can hold.
  kBadKeyframeId,
  /// The pose is not a pose (pose_msg_error: non-finite or out-of-bounds position, quaternion
  /// not of norm 1).
  kBadPose,
  /// stamp.nanosec >= 1e9.
  kBadStamp,
  /// The pose covariance is not finite, bounded, symmetric and positive semi-definite
  /// (checks::covariance_error), in the message's ROS order or in the keyframe's (phi, tau).
  kBadCovariance,
  /// The voxel size is not in [kMinVoxelSize, kMaxVoxelSize] (NaN and Inf included).
  kBadVoxelSize,
  /// More distributions than PatchConversionOptions::max_distributions.
  kTooManyDistributions,
  /// A distribution's mean is not finite or beyond checks::kMaxPosition, its covariance is not
  /// finite, bounded and positive semi-definite, or its point count is 0 or beyond INT_MAX.
  kBadDistribution,
};

/// Short name of an error ("bad_stream_id", ...), for counters and logs.
const char* to_string(PatchError error);

/// The voxel sizes a patch may have, metres: TrackerConfig's range (core/tracker_config.hpp).
constexpr float kMinVoxelSize = 0.05f;
constexpr float kMaxVoxelSize = 50.0f;

/// Options of from_map_patch.
struct PatchConversionOptions {
  /// Patches with more distributions are rejected (kTooManyDistributions) before any is
  /// converted: a keyframe costs ~250 bytes a distribution. The aggregator's
  /// limits.max_distributions_per_patch.
  std::size_t max_distributions = 200'000;
};

/// Result of from_map_patch (the shape of every conversion of a network message: CloudConversion,
/// OdometryConversion).
struct PatchConversion {
  PatchError error = PatchError::kNone;
  /// Human-readable reason when error != kNone ("patch car/3: distribution 7: mean holds a
  /// non-finite value (nan)").
  std::string message;
  /// The keyframe (empty when rejected).
  Keyframe keyframe;
  bool ok() const { return error == PatchError::kNone; }
};

/// The keyframe of a MapPatch, or why the patch is rejected (one of PatchError; every field is
/// checked, nothing is repaired: docs/security.md, "Validation"). Never throws for bad input
/// (only std::bad_alloc can escape, and not for more than options.max_distributions).
PatchConversion from_map_patch(const litamin2::msg::MapPatch& msg,
                               const PatchConversionOptions& options = {});

}  // namespace litamin2::dds
