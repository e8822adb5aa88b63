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
  /// The pose has a NaN or +-Inf.
  kNonFinitePose,
  /// stamp.nanosec >= 1e9.
  kBadStamp,
  /// The pose covariance has a NaN or +-Inf.
  kNonFiniteCovariance,
  /// The voxel size is not a positive finite number.
  kBadVoxelSize,
  /// A distribution's mean or covariance has a NaN or +-Inf.
  kNonFiniteDistribution,
};

/// Short name of an error ("bad_stream_id", ...), for counters and logs.
const char* to_string(PatchError error);

/// Result of from_map_patch (the shape of every conversion of a network message: CloudConversion,
/// OdometryConversion).
struct PatchConversion {
  PatchError error = PatchError::kNone;
  /// Human-readable reason when error != kNone ("patch car/3: distribution 7 has a non-finite
  /// mean").
  std::string message;
  /// The keyframe (empty when rejected).
  Keyframe keyframe;
  bool ok() const { return error == PatchError::kNone; }
};

/// The keyframe of a MapPatch, or why the patch is rejected: a stream id that is not a valid
/// stream id, a pose, covariance, voxel size or distribution holding non-finite values, a voxel
/// size that is not positive, a stamp whose nanosec is not below 1e9. Never throws for bad
/// input.
PatchConversion from_map_patch(const litamin2::msg::MapPatch& msg);

}  // namespace litamin2::dds
