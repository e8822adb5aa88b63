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
/// - place descriptor: uint16 rings, uint16 sectors, float32 ring_key[rings], uint8
///   cells[rings * sectors] (row-major by ring).
/// - map tile voxels: 84 bytes per voxel, uint64 pack_voxel key, uint32 count, float64 sum[3],
///   float64 sum of squares upper triangle (xx, xy, xz, yy, yz, zz), relative to the voxel's
///   centre (the moments the tile adds and subtracts exactly; map_tile.hpp).
/// - tile summary: float32 min_bound[3], float32 max_bound[3], then float32 x y z per sampled
///   mean.
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
#include "litamin2/mapping/map_tile.hpp"
#include "litamin2/mapping/place_descriptor.hpp"

#include <Eigen/Geometry>
#include <cstddef>
#include <string>
#include <vector>

namespace litamin2::store {

constexpr std::size_t kPoseBytes = 12 * sizeof(double);
constexpr std::size_t kMatrix6Bytes = 36 * sizeof(double);
constexpr std::size_t kDistributionBytes = 10 * 4;
constexpr std::size_t kTileVoxelBytes = 8 + 4 + 9 * 8;

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

std::string encode_descriptor(const mapping::PlaceDescriptor& descriptor);
/// `with_cells` false: the ring key only (the blob is checked whole either way).
mapping::PlaceDescriptor decode_descriptor(const void* data, std::size_t size,
                                           bool with_cells = true);

/// Voxels with a non-positive count or non-finite sums are refused (std::invalid_argument).
std::string encode_tile_voxels(const std::vector<mapping::MapTile::Voxel>& voxels);
/// The voxels' origins are their centres for map voxels of edge `voxel_size`.
std::vector<mapping::MapTile::Voxel> decode_tile_voxels(const void* data, std::size_t size,
                                                        double voxel_size);

/// The summary's bounds and sample (its key and counts are columns of their own).
std::string encode_tile_summary(const mapping::TileSummary& summary);
void decode_tile_summary(const void* data, std::size_t size, mapping::TileSummary& summary);

}  // namespace litamin2::store
