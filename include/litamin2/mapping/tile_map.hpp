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
/// With segment_keyframes > 0 the unit of fusion is a rigid segment, not a keyframe
/// (segment_voxels.hpp): a stream's keyframes with ids [k n, (k + 1) n) are fused once in the
/// segment's frame, the fused pose of its reference keyframe (the lowest id fused), each at
/// its pose relative to it. A marked segment is reconciled whole: when its reference has moved
/// by more than the threshold the segment is re-placed at the reference's current pose
/// (subtracted at the old frame, added at the new: a few hundred segment voxels, no keyframe
/// read back while its moments are in the segment cache); a keyframe whose pose, through its
/// segment's frame, is more than the threshold from its own (the local optimisation bends the
/// segment), or that arrives in or leaves the map, is subtracted from / added to the segment's
/// moments at its relative pose. A keyframe of lower id than the reference (a late one)
/// rebuilds the segment. Every keyframe in the map is then fused at frame * relative pose,
/// within the thresholds of its pose after the frame's and its own threshold (the frame's
/// rotation threshold acting at the keyframe's distance from the reference, <= ~20 m for
/// segments of 10 keyframes 2 m apart). A segment's moments are kept in a cache bounded in
/// bytes; when evicted they are written to the segment spill (segment_spill.hpp), if the map
/// has one, and read back from it when the segment moves again (bit for bit what was evicted),
/// else recomputed from its keyframes' distributions at their relative poses.
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
#include "litamin2/mapping/segment_spill.hpp"
#include "litamin2/mapping/segment_voxels.hpp"

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
#include <unordered_map>
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
  /// Keyframes per rigid segment (by keyframe id), the unit of fusion; 0: every keyframe is
  /// fused on its own (the map then holds exactly the global map's voxels at the fused poses).
  int segment_keyframes = 10;
  /// The segments' moments kept in memory, MB (the others are recomputed when they move).
  double segment_cache_mb = 256.0;
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
  /// Segment mode: segments in the map, their placements added to / subtracted from the
  /// tiles, moments recomputed after an eviction, and the bytes of the moments in memory.
  std::size_t segments = 0;
  std::size_t segment_placements = 0;
  std::size_t segment_recomputes = 0;
  std::size_t segment_bytes = 0;
  /// Segment moments written to / read back from the spill, and the spill file's bytes.
  std::size_t segment_spill_writes = 0;
  std::size_t segment_spill_reads = 0;
  std::uint64_t segment_spill_bytes = 0;
};

class TileMap {
 public:
  /// A persisted tile (nullopt: none).
  using Loader = std::function<std::optional<MapTile>(TileKey)>;

  /// `voxel_size`: the map's voxel edge (MapperConfig::map_voxel_size). Throws ConfigError.
  TileMap(const TileMapConfig& config, double voxel_size, Loader loader = {},
          std::size_t max_bytes = 0);

  const TileGeometry& geometry() const { return geometry_; }

  /// Evicted segments' moments go to `spill` from now on (segment_spill.hpp), instead of being
  /// recomputed from their keyframes when needed again.
  void spill_segments_to(std::unique_ptr<SegmentSpill> spill) { spill_ = std::move(spill); }

  /// The keyframe of node `node` (KeyframeGraph numbering) may have moved or changed frame.
  void mark(std::uint32_t node);
  /// Keyframes marked and not reconciled yet.
  std::size_t pending() const { return marked_; }

  /// The state a store holds, for the graph it was committed with: each node's fused pose (by
  /// node index; nullopt: not fused) and the tile index. Marks the nodes that are not in sync.
  void restore(const KeyframeGraph& graph, std::vector<std::optional<Eigen::Isometry3d>> fused,
               std::vector<TileSummary> index);

  /// Reconciles marked keyframes, oldest mark first, until `max_keyframes` fusions have been
  /// done (0: all): a keyframe fused into or subtracted from a tile or a segment (also to
  /// recompute an evicted segment's moments), or a segment placed in or taken out of the
  /// tiles, counts one. Distributions come from `cache`.
  /// Returns the fusions done.
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
  /// Whether take_changes() has anything to give (changed tiles or fused poses).
  bool has_changes() const { return !dirty_.empty() || !changed_nodes_.empty(); }
  /// The tiles the latest update() changed (ascending), whether or not taken since.
  const std::vector<TileKey>& updated_tiles() const { return updated_; }

  /// A tile's contents (from memory or the loader); null if the map has no such tile. Valid
  /// until the next update().
  std::shared_ptr<const MapTile> tile(TileKey key);
  /// Every tile's summary, by key.
  const std::map<TileKey, TileSummary>& index() const { return index_; }
  /// The pose node `node` is fused at.
  std::optional<Eigen::Isometry3d> fused_pose(std::uint32_t node) const;
  TileMapStats stats() const;

 private:
  using Pose34 = Eigen::Matrix<double, 3, 4>;
  struct Fused {
    Pose34 pose = Pose34::Zero();
    /// Segment mode: the pose in the segment's frame (pose = frame * relative).
    Pose34 relative = Pose34::Zero();
    bool fused = false;
  };
  struct SegmentKey {
    std::uint32_t stream = 0;
    std::uint64_t index = 0;
    bool operator==(const SegmentKey& o) const { return stream == o.stream && index == o.index; }
  };
  struct SegmentHash {
    std::size_t operator()(const SegmentKey& k) const {
      return std::hash<std::uint64_t>()(k.index * 0x9E3779B97F4A7C15ull ^ k.stream);
    }
  };
  struct Segment {
    /// Every graph node of the segment, fused or not.
    std::vector<std::uint32_t> nodes;
    bool placed = false;
    std::uint32_t reference = 0;
    Pose34 frame = Pose34::Zero();
    /// The moments (null: evicted, recomputed from the fused keyframes when needed).
    std::shared_ptr<SegmentVoxels> voxels;
    std::size_t bytes = 0;
    std::list<SegmentKey>::iterator lru;
    std::uint64_t generation = 0;
    /// Where the spill holds the moments, and whether those are the current ones.
    SegmentSpill::Slot spill;
    bool spilled = false;
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
  bool moved(const Pose34& from, const Pose34& to) const;
  void evict();

  // Segment mode.
  SegmentKey segment_key(const KeyframeNode& node) const;
  /// Adds graph nodes not seen yet to their segments.
  void register_nodes(const KeyframeGraph& graph);
  /// Brings a segment in line with the graph; returns the fusions done.
  std::size_t reconcile(Segment& segment, const SegmentKey& key, const KeyframeGraph& graph,
                        DistributionCache& cache, std::int64_t anchor);
  /// The segment's moments (recomputed from its fused keyframes when evicted).
  SegmentVoxels& segment_voxels(Segment& segment, const SegmentKey& key, const KeyframeGraph& graph,
                                DistributionCache& cache);
  /// Adds (+1) or subtracts (-1) a placement of the segment's moments at `frame`.
  void place(const SegmentVoxels& voxels, const Pose34& frame, int sign, std::int64_t keyframes);
  void apply_moments(const std::vector<FusedMoment>& moments, int sign, std::int64_t keyframes);
  void changed_node(std::uint32_t n);
  void evict_segments(const SegmentKey* keep);
  /// The segment's moments changed (or were dropped): the spill's copy is stale.
  void moments_changed(Segment& segment);

  TileMapConfig config_;
  TileGeometry geometry_;
  Loader loader_;
  std::size_t max_bytes_;
  double cos_threshold_;

  std::vector<Fused> fused_;
  std::deque<std::uint32_t> queue_;
  std::vector<bool> queued_;
  std::size_t marked_ = 0;
  std::int64_t fused_anchor_ = -1;

  std::map<TileKey, TileSummary> index_;
  std::map<TileKey, Entry> tiles_;
  /// Clean tiles in memory, most recently used first.
  std::list<TileKey> clean_;
  std::set<TileKey> dirty_;
  /// Tiles touched by the update in progress (their summaries are refreshed at its end).
  std::vector<TileKey> touched_;
  std::vector<TileKey> updated_;
  std::vector<std::uint32_t> changed_nodes_;
  std::vector<bool> node_changed_;
  std::size_t bytes_ = 0;
  TileMapStats stats_;

  std::unordered_map<SegmentKey, Segment, SegmentHash> segments_;
  /// Segments whose moments are in memory, most recently used first.
  std::list<SegmentKey> segment_lru_;
  std::size_t segment_bytes_ = 0;
  std::size_t segment_max_bytes_ = 0;
  std::size_t registered_ = 0;
  /// Keyframes fused again to recompute evicted segments' moments, since construction.
  std::size_t recomputed_keyframes_ = 0;
  std::uint64_t generation_ = 0;
  std::unique_ptr<SegmentSpill> spill_;
};

}  // namespace litamin2::mapping
