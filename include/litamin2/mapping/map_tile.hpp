#pragma once
/// One square tile of the global map: the voxel moments of every keyframe fused into it, in the
/// map frame. A keyframe's distributions are moved by its pose and each lands in the map voxel
/// (of edge voxel_size, aligned at the origin) holding its moved mean; a voxel belongs to the
/// tile (of edge tile_size) holding its centre's x and y. Fusion is additive, so a keyframe is
/// added at a pose and later subtracted at the same pose exactly (same voxels, same moments):
/// a tile changes only by the keyframes that arrive in it or move, never by a rebuild of the
/// map. A voxel whose count returns to zero is erased.
///
/// The fused distributions are the same as the global map's (Mapper::global_map) for the same
/// keyframes at the same poses up to rounding (the sums are kept in double, relative to each
/// voxel's centre), and come out ordered by voxel key whatever the order of fusion.

#include "litamin2/core/distribution.hpp"
#include "litamin2/core/voxel_key.hpp"
#include "litamin2/core/voxel_moments.hpp"
#include "litamin2/core/voxelizer.hpp"

#include <tsl/robin_map.h>
#include <Eigen/Geometry>

#include <cstdint>
#include <map>
#include <vector>

namespace litamin2::mapping {

struct TileKey {
  std::int32_t ix = 0;
  std::int32_t iy = 0;
  bool operator<(const TileKey& o) const { return ix < o.ix || (ix == o.ix && iy < o.iy); }
  bool operator==(const TileKey& o) const { return ix == o.ix && iy == o.iy; }
  bool operator!=(const TileKey& o) const { return !(*this == o); }
};

/// What the tile index keeps of a tile (what the map summary and a client choosing tiles need).
struct TileSummary {
  TileKey key;
  /// Keyframes fused into the tile (a keyframe seen in several tiles counts in each).
  std::int64_t keyframes = 0;
  /// Voxels with enough points to be a distribution.
  std::int64_t distributions = 0;
  /// Bounding box of those distributions' means (zero when there are none).
  Eigen::Vector3f min_bound = Eigen::Vector3f::Zero();
  Eigen::Vector3f max_bound = Eigen::Vector3f::Zero();
  /// At most kSampleMeans of their means, evenly spaced in voxel-key order.
  std::vector<Eigen::Vector3f> sample;
  static constexpr std::size_t kSampleMeans = 32;
};

/// The geometry shared by every tile of a map.
struct TileGeometry {
  double tile_size = 100.0;
  /// Map voxel edge, and the voxels' minimum points and regularisation (the global map's).
  VoxelizerConfig voxels;

  /// The tile holding a voxel (by its centre).
  TileKey tile_of_voxel(const VoxelIndex& voxel) const;
  /// The tiles whose squares meet the box [x0, x1] x [y0, y1] (metres), inclusive.
  void tile_range(double x0, double y0, double x1, double y1, TileKey& lo, TileKey& hi) const;
};

class MapTile {
 public:
  struct Voxel {
    /// pack_voxel of the map voxel; moments.origin is its centre.
    std::uint64_t key = 0;
    VoxelMoments moments;
  };

  MapTile() = default;
  explicit MapTile(TileKey key) : key_(key) {}

  TileKey key() const { return key_; }
  std::int64_t keyframes() const { return keyframes_; }
  const std::vector<Voxel>& voxels() const { return voxels_; }
  bool empty() const { return voxels_.empty() && keyframes_ == 0; }
  /// Bytes it holds (for the tile cache's bound).
  std::size_t bytes() const;

  /// Adds (sign +1) or subtracts (-1) one moment, already moved to the map frame with its
  /// origin at its voxel's centre (`voxel_key`). Subtracting from a missing voxel or more
  /// points than it has is a caller's error: returns false and changes nothing.
  bool apply(std::uint64_t voxel_key, const VoxelMoments& moments, int sign);
  /// Counts a keyframe fused into (+1) or removed from (-1) the tile.
  void count_keyframe(std::int64_t sign) { keyframes_ += sign; }

  /// The voxels with at least geometry.voxels.min_points points as distributions (regularised
  /// as the global map's), ordered by voxel key.
  std::vector<Distribution> distributions(const TileGeometry& geometry) const;
  TileSummary summary(const TileGeometry& geometry) const;

  /// Restores a tile read back from the store (voxels in any order, keys unique).
  static MapTile restore(TileKey key, std::int64_t keyframes, std::vector<Voxel> voxels);

 private:
  TileKey key_;
  std::int64_t keyframes_ = 0;
  std::vector<Voxel> voxels_;
  /// Voxel key -> position in voxels_. Hashed with VoxelKeyHash: the packed key's low bits
  /// are the x index alone, and the power-of-two buckets of robin_map keep only low bits, so
  /// with the identity hash a tile's voxels of one x fall into one bucket run (a 100 m tile of
  /// 3 m voxels: ~34 runs; lookups ~1000x slower and the buckets grown to millions).
  tsl::robin_map<std::uint64_t, std::uint32_t, VoxelKeyHash> index_;
};

/// The moments of a keyframe's distributions moved to the map frame by `pose`, each with its
/// map voxel and tile: what fusing the keyframe adds to the tiles (and removing it subtracts).
struct FusedMoment {
  TileKey tile;
  std::uint64_t voxel = 0;
  VoxelMoments moments;
};
std::vector<FusedMoment> fused_moments(const std::vector<Distribution>& distributions,
                                       const Eigen::Isometry3d& pose, const TileGeometry& geometry);

}  // namespace litamin2::mapping
