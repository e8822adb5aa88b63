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

/// The keyframe of a MapPatch. Rejects (returns std::nullopt and sets *error) a patch whose
/// stream id is not a valid stream id, whose pose, covariance, voxel size or distributions hold
/// non-finite values, or whose voxel size is not positive. Never throws for bad input.
std::optional<Keyframe> from_map_patch(const litamin2::msg::MapPatch& msg,
                                       std::string* error = nullptr);

}  // namespace litamin2::dds
