#pragma once
/// The global map in tiles (map_tile.hpp), kept up to date with the keyframe graph by the
/// change, never rebuilt: the keyframes whose pose or frame changed are marked, and update()
/// reconciles them with the tiles, a bounded number per call. A keyframe is in the map when its
/// stream's group is the map frame's (the group of the canonically first keyframe, as in
/// Mapper::global_map). Each keyframe is fused at one pose, remembered: it is subtracted at
/// that pose and added at its current one when it has moved by more than the move threshold
/// (smaller moves leave the map as it is: its voxels are metres wide), added when it arrives
/// in the map, subtracted when it leaves it (the map frame moved to another group).
///
/// Tiles are held in a cache bounded in bytes in front of a loader (the aggregator's store):
/// tiles changed since take_changes() stay in memory (the caller persists them), the others
/// are dropped least recently used first and read back when a keyframe touches them again.
/// Without a loader every tile stays in memory. The index (a TileSummary per tile) is always
/// in memory: it is small per tile and what the map summary is made of.
///
/// Not thread-safe: the mapping thread's.

#include "litamin2/mapping/distribution_cache.hpp"
#include "litamin2/mapping/keyframe_graph.hpp"
#include "litamin2/mapping/map_tile.hpp"

#include <Eigen/Geometry>

#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <list>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <vector>

namespace litamin2::mapping {

struct TileMapConfig {
  /// Edge of a square tile, metres.
  double tile_size = 100.0;
  /// A keyframe fused in the map is moved there once its pose is this far from the pose it
  /// was fused at, metres (below the map's voxel edge; a tenth of the default 3 m voxel:
  /// a full pass that shifts the map by centimetres then re-fuses nothing, while the map's
  /// means stay within this of a full rebuild at the current poses) ...
  double move_threshold_m = 0.3;
  /// ... or turned by this much, degrees (0.3: 0.2 m at the 40 m the patches reach).
  double move_threshold_deg = 0.3;
};

/// Throws ConfigError on the first invalid value.
void validate(const TileMapConfig& config);

struct TileMapStats {
  std::size_t tiles = 0;
  std::size_t distributions = 0;
  /// Tiles in memory and their bytes.
  std::size_t tiles_in_memory = 0;
  std::size_t bytes_in_memory = 0;
  /// Keyframes added to / subtracted from the tiles since construction.
  std::size_t added = 0;
  std::size_t subtracted = 0;
  /// Tiles read back through the loader.
  std::size_t loads = 0;
  /// Subtractions that did not match what the tile held (a corrupt store): skipped.
  std::size_t inconsistent = 0;
};

class TileMap {
 public:
  /// A persisted tile (nullopt: none).
  using Loader = std::function<std::optional<MapTile>(TileKey)>;

  /// `voxel_size`: the map's voxel edge (MapperConfig::map_voxel_size). Throws ConfigError.
  TileMap(const TileMapConfig& config, double voxel_size, Loader loader = {},
          std::size_t max_bytes = 0);

  const TileGeometry& geometry() const { return geometry_; }

  /// The keyframe of node `node` (KeyframeGraph numbering) may have moved or changed frame.
  void mark(std::uint32_t node);
  /// Keyframes marked and not reconciled yet.
  std::size_t pending() const { return queue_.size(); }

  /// The state a store holds, for the graph it was committed with: each node's fused pose (by
  /// node index; nullopt: not fused) and the tile index. Marks the nodes that are not in sync.
  void restore(const KeyframeGraph& graph, std::vector<std::optional<Eigen::Isometry3d>> fused,
               std::vector<TileSummary> index);

  /// Reconciles marked keyframes, oldest mark first, until `max_keyframes` of them have been
  /// fused or subtracted (0: all). Distributions come from `cache`. Returns how many were.
  std::size_t update(const KeyframeGraph& graph, DistributionCache& cache,
                     std::size_t max_keyframes);

  struct Changes {
    /// Tiles changed (an empty tile: deleted), by key.
    std::vector<std::shared_ptr<const MapTile>> tiles;
    /// Nodes whose fused pose changed, with it (nullopt: no longer fused), by node.
    std::vector<std::pair<std::uint32_t, std::optional<Eigen::Isometry3d>>> nodes;
  };
  /// What changed since the last call; the tiles become evictable.
  Changes take_changes();
  /// Tiles changed since the last take_changes().
  std::size_t changed_tiles() const { return dirty_.size(); }

  /// A tile's contents (from memory or the loader); null if the map has no such tile. Valid
  /// until the next update().
  std::shared_ptr<const MapTile> tile(TileKey key);
  /// Every tile's summary, by key.
  const std::map<TileKey, TileSummary>& index() const { return index_; }
  /// The pose node `node` is fused at.
  std::optional<Eigen::Isometry3d> fused_pose(std::uint32_t node) const;
  TileMapStats stats() const;

 private:
  struct Fused {
    Eigen::Matrix<double, 3, 4> pose = Eigen::Matrix<double, 3, 4>::Zero();
    bool fused = false;
  };
  struct Entry {
    std::shared_ptr<MapTile> tile;
    std::size_t bytes = 0;
    bool dirty = false;
    /// Position in clean_ (clean tiles only).
    std::list<TileKey>::iterator lru;
  };

  /// The map frame's anchor stream, or -1 without keyframes.
  static std::int64_t map_anchor(const KeyframeGraph& graph);
  void fuse(const std::vector<Distribution>& distributions, const Eigen::Isometry3d& pose,
            int sign);
  /// The tile for writing (loaded or created), marked dirty.
  MapTile& writable(TileKey key);
  /// Entry of a tile in memory or loaded; null if there is none.
  Entry* find(TileKey key);
  bool moved(const Fused& f, const Eigen::Isometry3d& pose) const;
  void evict();

  TileMapConfig config_;
  TileGeometry geometry_;
  Loader loader_;
  std::size_t max_bytes_;
  double cos_threshold_;

  std::vector<Fused> fused_;
  std::deque<std::uint32_t> queue_;
  std::vector<bool> queued_;
  std::int64_t fused_anchor_ = -1;

  std::map<TileKey, TileSummary> index_;
  std::map<TileKey, Entry> tiles_;
  /// Clean tiles in memory, most recently used first.
  std::list<TileKey> clean_;
  std::set<TileKey> dirty_;
  /// Tiles touched by the update in progress (their summaries are refreshed at its end).
  std::vector<TileKey> touched_;
  std::vector<std::uint32_t> changed_nodes_;
  std::vector<bool> node_changed_;
  std::size_t bytes_ = 0;
  TileMapStats stats_;
};

}  // namespace litamin2::mapping
