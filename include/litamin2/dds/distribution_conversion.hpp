#pragma once
/// litamin2/msg/VoxelDistribution <-> Distribution: the one conversion each way of the
/// distributions that MapPatch and MapTile carry (floats: mean, covariance upper triangle,
/// count).

#include "litamin2/core/distribution.hpp"
#include "litamin2/msg/VoxelDistribution.h"

#include <optional>
#include <string>

namespace litamin2::dds {

/// The message of a distribution (a negative count is sent as 0, which the reader rejects).
litamin2::msg::VoxelDistribution to_voxel_distribution(const Distribution& d);

/// Why `v` cannot be a distribution (mean not finite or beyond checks::kMaxPosition, covariance
/// not finite, bounded and positive semi-definite, point count 0 or beyond INT_MAX); fills `d`
/// when it can (shape_cov = cov, shape_cov_inv its inverse, identity when cov is singular).
std::optional<std::string> convert_distribution(const litamin2::msg::VoxelDistribution& v,
                                                Distribution& d);

}  // namespace litamin2::dds
