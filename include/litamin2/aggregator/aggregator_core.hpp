#pragma once
/// The aggregator's state without threads or transport: the durable store and the mapper.
///
/// Opening recovers the mapper's graph from the store's indexed tables (nodes with their
/// descriptors, corrected poses, loop edges: Recovery::kTables), without a registration, in
/// time linear in the keyframes with a small constant; the distributions stay in the store and
/// come back through the mapper's bounded DistributionCache. A store written before those
/// tables (schema version 1) is replayed once: every keyframe loaded in canonical order into a
/// new mapper (Recovery::kReplay, also what `export --replay` does: a state that depends only
/// on the set of stored keyframes).
///
/// ingest() runs one store transaction per batch: the new keyframes, then the graph changes
/// they caused (new loop edges, moved corrected poses). A kill -9 at any point leaves either
/// the batch's keyframes with all they caused or none of it (then the daemons' transient-local
/// history delivers them again). Nothing is published before the commit. Duplicates (a key
/// already known, or twice in one batch) are counted and ignored: the first patch of a key wins.
///
/// The global map is kept in tiles (mapping/tile_map.hpp): ingest and full passes mark the
/// keyframes that arrived or moved, update_map() fuses a bounded number of them into the tiles
/// and commits the changed tiles with the poses their keyframes are fused at (one
/// transaction; the mapping thread does so at most every map_tiles.persist_period_s), so that
/// a restart recovers the tiles and what is still to be fused into them from the tables too.
///
/// Not thread-safe: one owner (the mapping thread; export runs it on its own).

#include "litamin2/core/covariance_regularizer.hpp"
#include "litamin2/mapping/mapper.hpp"
#include "litamin2/mapping/tile_map.hpp"
#include "litamin2/store/keyframe_store.hpp"

#include <cstddef>
#include <functional>
#include <set>
#include <string>
#include <vector>

namespace litamin2::aggregator {

struct IngestResult {
  /// Keyframes new to the store and the mapper.
  std::size_t added = 0;
  std::size_t duplicates = 0;
  /// Loop edges verified while adding.
  std::size_t new_loops = 0;
  /// Streams that got a new keyframe, and the new keys.
  std::set<std::string> streams;
  std::vector<KeyframeKey> keys;
  mapping::OptimizeSummary optimization;
  double store_ms = 0.0;
  double mapper_ms = 0.0;
};

/// CPU time (of the calling thread) spent by ingest() in its stages since construction, seconds.
struct IngestCpu {
  /// Duplicate filtering and canonical ordering.
  double sort_s = 0.0;
  /// The store transaction of the new keyframes.
  double store_s = 0.0;
  /// Covariance regularisation of the new keyframes (what the store applies on load).
  double regularize_s = 0.0;
  /// Mapper::add_keyframe (stages in Mapper::cpu()).
  double add_keyframe_s = 0.0;
  /// Mapper::optimize.
  double optimize_s = 0.0;
  /// Storing the loop edges and corrected poses after loops or an optimisation.
  double save_graph_s = 0.0;
  /// Applying full passes (moving the keyframes, storing the moved poses).
  double full_pass_apply_s = 0.0;
  /// update_map(): fusing keyframes into the tiles ...
  double map_fuse_s = 0.0;
  /// ... and storing the changed tiles and map poses.
  double map_store_s = 0.0;
};

struct CoreOptions {
  enum class Recovery {
    /// From the indexed tables (a version-1 store is replayed once).
    kTables,
    /// Every keyframe through a new mapper, in canonical order.
    kReplay,
  };
  Recovery recovery = Recovery::kTables;
  /// Bytes of distributions the mapper's cache holds (0 = unbounded).
  std::size_t distribution_cache_bytes = 512u << 20;
  /// The map tiles, and the bytes of tiles held in memory (0 = unbounded).
  mapping::TileMapConfig tiles;
  std::size_t tile_cache_bytes = 256u << 20;
  /// Evicted segments' moments spilled to a scratch file beside the store (segment_spill.hpp)
  /// instead of recomputed from their keyframes (never when read-only).
  bool spill_segments = true;
};

/// What update_map() did.
struct MapUpdate {
  /// Keyframes fused into or subtracted from the tiles.
  std::size_t keyframes = 0;
  /// Tiles this call changed (to publish; stored now or at a later update_map with persist).
  std::vector<mapping::TileKey> tiles;
};

class AggregatorCore {
 public:
  /// Called during recovery with (keyframes added, keyframes in total).
  using Progress = std::function<void(std::size_t, std::size_t)>;

  /// Opens the store at `store_path` (`mode`; StoreError if it is not a keyframe store),
  /// rebuilds the mapper from it and optimises. Throws ConfigError for an invalid mapper config.
  AggregatorCore(const std::string& store_path, store::OpenMode mode,
                 const mapping::MapperConfig& mapper_config,
                 const store::StoreOptions& store_options = {}, const Progress& progress = {},
                 const CoreOptions& options = {});
  // The cache and tile loaders refer to the store: not copyable, not movable.
  AggregatorCore(const AggregatorCore&) = delete;
  AggregatorCore& operator=(const AggregatorCore&) = delete;

  /// Commits the keyframes of `batch` not known yet to the store (one transaction), then adds
  /// them to the mapper in canonical order, optimises when loops were found and stores the new
  /// loop edges and corrected poses. `batch` is consumed.
  IngestResult ingest(std::vector<Keyframe>& batch);

  /// Moves the keyframes by a solved full pass (Mapper::full_pass_problem, solved elsewhere)
  /// and stores the moved poses. Returns how many keyframes moved.
  std::size_t apply_full_pass(const mapping::FullPassProblem& problem);

  /// Fuses at most `max_keyframes` of the keyframes that arrived or moved into the map tiles
  /// (0: all), then, when `persist`, stores the tiles changed since the last store and the
  /// poses their keyframes are fused at in one transaction (not when open read-only: the
  /// tiles then change in memory only). Without `persist` the changes wait in memory (changed
  /// tiles are not evicted) for a later call with it: the store keeps the tiles and map poses
  /// of the last one, consistent with each other, and a restart fuses the rest again.
  MapUpdate update_map(std::size_t max_keyframes, bool persist = true);
  /// Whether changed tiles or fused poses wait to be stored (update_map without persist).
  bool map_unsaved() const { return tiles_.has_changes(); }
  /// Keyframes still to be fused (or moved) in the tiles.
  std::size_t map_pending() const { return tiles_.pending(); }
  const mapping::TileMap& tiles() const { return tiles_; }
  mapping::TileMap& tiles() { return tiles_; }

  /// Nodes (KeyframeGraph numbering) added or moved since the last call, ascending: what the
  /// corrected-pose publication has to send again.
  std::vector<std::uint32_t> take_moved();

  const mapping::Mapper& mapper() const { return mapper_; }
  mapping::Mapper& mapper() { return mapper_; }
  const store::KeyframeStore& store() const { return store_; }
  std::size_t recovered() const { return recovered_; }
  std::size_t duplicates() const { return duplicates_; }
  const IngestCpu& cpu() const { return cpu_; }

  /// What the store does to a distribution's covariance on load, applied to freshly received
  /// keyframes so that a live mapper sees exactly what a recovered one would.
  static const RegularizerConfig& regularizer();

 private:
  void recover_from_tables(const Progress& progress);
  /// The mapper reads descriptor cells back from the store (every node's is there).
  void keep_descriptor_cells_in_store();
  void replay(const Progress& progress);
  /// Stores the loops from index `first_new` on and the poses that changed.
  void save_changes(std::size_t first_new);

  store::KeyframeStore store_;
  bool read_only_ = false;
  mapping::Mapper mapper_;
  mapping::TileMap tiles_;
  std::vector<std::uint32_t> moved_;
  std::size_t recovered_ = 0;
  /// Mapper::pending_merges_version() as last stored.
  std::uint64_t saved_pending_merges_ = 0;
  std::size_t duplicates_ = 0;
  IngestCpu cpu_;
};

}  // namespace litamin2::aggregator
