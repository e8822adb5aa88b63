#pragma once
/// Byte encodings of the keyframe store's BLOB columns. All are little-endian whatever the
/// host, so a store file can be copied between machines.
///
/// - pose: 12 float64, the 3x4 matrix [R | t] in column-major order (R's columns, then t);
///   the bottom row of the isometry is implied.
/// - 6x6 matrix (covariance, information): 36 float64, column-major.
/// - distributions: 40 bytes per distribution, the layout of litamin2/msg/VoxelDistribution.idl:
///   float32 mean[3], float32 covariance upper triangle (xx, xy, xz, yy, yz, zz), uint32 count.
///   Only the ICP-term covariance is stored; the Cov term's shape_cov and shape_cov_inv are
///   recomputed on decoding with the caller's regulariser, as the tracker computes them.
///
/// Encoders and decoders check the values as the network conversions do (core/value_checks.hpp,
/// docs/security.md "Validation"): a pose's rotation is orthonormal with determinant +1 and its
/// translation finite and within checks::kMaxPosition; a 6x6 matrix (covariance, information)
/// and a distribution's covariance are finite, bounded, symmetric and positive semi-definite; a
/// distribution's mean is a bounded position and its count is 1 .. 2^31 - 1. A value that fails
/// is rejected with std::invalid_argument naming the reason, never repaired: what is written can
/// always be read back, and a corrupt or tampered row never comes back into the mapper. Decoders
/// also reject a wrong size; the store adds which row it was.

#include "litamin2/core/covariance_regularizer.hpp"
#include "litamin2/core/distribution.hpp"
#include "litamin2/core/keyframe.hpp"

#include <Eigen/Geometry>
#include <cstddef>
#include <string>
#include <vector>

namespace litamin2::store {

constexpr std::size_t kPoseBytes = 12 * sizeof(double);
constexpr std::size_t kMatrix6Bytes = 36 * sizeof(double);
constexpr std::size_t kDistributionBytes = 10 * 4;

/// Throws std::invalid_argument if the pose is not a valid rigid transform (see above).
std::string encode_pose(const Eigen::Isometry3d& pose);
Eigen::Isometry3d decode_pose(const void* data, std::size_t size);

/// Throws std::invalid_argument if the matrix is not a valid covariance (see above).
std::string encode_matrix6(const Matrix6d& m);
Matrix6d decode_matrix6(const void* data, std::size_t size);

/// Throws std::invalid_argument if a distribution is not valid (see above), naming its index.
std::string encode_distributions(const std::vector<Distribution>& distributions);
std::vector<Distribution> decode_distributions(const void* data, std::size_t size,
                                               const RegularizerConfig& regularizer);

}  // namespace litamin2::store
