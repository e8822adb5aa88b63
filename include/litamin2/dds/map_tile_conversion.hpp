#pragma once
/// litamin2/msg/MapTile <-> MapTileData: the one conversion each way, used by the aggregator
/// (writer) and the map tile clients (litamin2-map-tiles, reader).
///
/// The reader checks every field and rejects, never repairs (docs/security.md, "Validation"):
/// a tile's size and voxel size, its key (its square within checks::kMaxPosition), stamp,
/// frame and anchor, the number of distributions, each distribution (finite bounded mean,
/// finite bounded positive semi-definite covariance, count >= 1) and that each mean lies in the
/// tile's square widened by one voxel edge (a voxel belongs to the tile holding its centre and
/// a fused mean lies in its voxel; the second half voxel absorbs the floats' rounding).

#include "litamin2/core/distribution.hpp"
#include "litamin2/core/stamp.hpp"
#include "litamin2/msg/MapTile.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace litamin2::dds {

/// One map tile as a client holds it (MapTile.idl describes the fields).
struct MapTileData {
  std::int32_t ix = 0;
  std::int32_t iy = 0;
  double tile_size = 0.0;
  double voxel_size = 0.0;
  std::uint64_t revision = 0;
  Stamp stamp;
  std::string frame_id;
  std::string anchor_stream;
  std::uint64_t keyframes = 0;
  std::vector<Distribution> distributions;
};

/// A MapTile of a tile.
litamin2::msg::MapTile to_map_tile(const MapTileData& tile);

/// Why a MapTile was rejected.
enum class TileError {
  kNone = 0,
  /// tile_size is not in [kMinTileSize, kMaxTileSize] (NaN and Inf included).
  kBadTileSize,
  /// voxel_size is not in [kMinVoxelSize, kMaxVoxelSize] of map_patch_conversion.hpp.
  kBadVoxelSize,
  /// The tile's square is beyond checks::kMaxPosition.
  kBadKey,
  /// stamp.nanosec >= 1e9.
  kBadStamp,
  /// frame_id is empty or longer than kMaxFrameIdLength; anchor_stream is neither empty nor a
  /// valid stream id.
  kBadFrame,
  /// Distributions without keyframes.
  kBadKeyframes,
  /// More distributions than TileConversionOptions::max_distributions.
  kTooManyDistributions,
  /// A distribution is not one (dds::convert_distribution).
  kBadDistribution,
  /// A distribution's mean is outside the tile's square widened by one voxel edge.
  kOutsideTile,
};

/// Short name of an error ("bad_tile_size", ...), for counters and logs.
const char* to_string(TileError error);
/// Every error but kNone, in enum order (for counters).
std::vector<TileError> all_tile_errors();

/// The tile sizes a tile may have, metres: map_tiles.tile_size's range.
constexpr float kMinTileSize = 1.0f;
constexpr float kMaxTileSize = 100'000.0f;
constexpr std::size_t kMaxFrameIdLength = 256;

struct TileConversionOptions {
  /// Tiles with more distributions are rejected (kTooManyDistributions) before any is
  /// converted (~250 bytes a distribution in memory).
  std::size_t max_distributions = 1'000'000;
};

struct TileConversion {
  TileError error = TileError::kNone;
  /// Human-readable reason when error != kNone ("tile (3, -1): distribution 7: ...").
  std::string message;
  /// The tile (no distributions when rejected).
  MapTileData tile;
  bool ok() const { return error == TileError::kNone; }
};

/// The tile of a MapTile, or why it is rejected. Never throws for bad input (only
/// std::bad_alloc can escape, and not for more than options.max_distributions).
TileConversion from_map_tile(const litamin2::msg::MapTile& msg,
                             const TileConversionOptions& options = {});

}  // namespace litamin2::dds
