#pragma once
/// The aggregator's durable store of keyframes, loop edges and corrected poses: one SQLite
/// file in WAL mode.
///
/// Every keyframe received is inserted once (idempotently, so a patch published twice is
/// harmless) and survives a crash of the process; on restart the mapper is rebuilt from
/// load_keyframes(), which returns them in canonical order. Loop edges and corrected poses are
/// derived data, replaced as a whole after each optimisation so the latest result is available
/// without recomputation.
///
/// Durability: the file is in WAL mode with synchronous=NORMAL by default. A transaction is
/// in the write-ahead log (the operating system's cache) when its commit returns, so it survives
/// the process crashing or being killed (kill -9); only a power loss or kernel crash can lose
/// the last transactions since the latest checkpoint, and even then the file stays consistent.
/// StoreOptions::synchronous_full makes every commit wait for fsync (FULL), which also survives
/// power loss at the cost of one disk flush per transaction.
///
/// A file that is not a keyframe store (not SQLite, truncated, another application's database,
/// an unknown schema version) is refused with StoreError and never modified.
///
/// Not thread-safe: use one KeyframeStore per thread (several may open the same file, also
/// from several processes; writers then wait for each other up to busy_timeout_ms).

#include "litamin2/core/covariance_regularizer.hpp"
#include "litamin2/core/keyframe.hpp"
#include "litamin2/mapping/loop_edge.hpp"
#include "litamin2/mapping/map_tile.hpp"
#include "litamin2/mapping/mapper.hpp"
#include "litamin2/store/store_error.hpp"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace litamin2::store {

enum class OpenMode {
  /// Opens an existing store, or creates one if the file is missing or empty (0 bytes).
  kCreateIfMissing,
  /// Opens an existing store for reading and writing; a missing or empty file is an error.
  kMustExist,
  /// Opens an existing store for reading only; every write throws StoreError.
  kReadOnly,
};

struct StoreOptions {
  /// synchronous=FULL instead of NORMAL: commits also survive power loss (see the file comment).
  bool synchronous_full = false;
  /// How long a write waits for another connection's transaction before failing.
  int busy_timeout_ms = 5000;
  /// Connections that read the nodes table side by side at a restart (load_graph), each a
  /// range of its rows: on a cold page cache the rows lie scattered through the keyframes'
  /// large file, and reads in flight together finish sooner than one after another. Used only
  /// by a store opened for writing (the one writer: no commit can land between the ranges).
  int restart_readers = 4;
  /// Bytes of an SQLite page in a store this call creates (a power of two in [512, 65536]; an
  /// existing store keeps its own). Large pages: the graph's small rows, interleaved in the
  /// file with the keyframes' large ones, are read at a restart in far fewer requests (the
  /// request count, not the bytes, bounds a cold read: docs/benchmarks.md).
  int page_size = 65536;
  /// MiB of SQLite's page cache per connection (PRAGMA cache_size). SQLite's default, 2 MB, is
  /// 31 pages of 64 KiB: too few for a restart's lookups of corrected poses across ~100
  /// vehicles' rows, each miss then a 64 KiB copy from the OS (docs/benchmarks.md).
  int sqlite_cache_mb = 64;
};

/// A keyframe's latest optimised pose, as the mapper reports it.
using CorrectedPose = mapping::KeyframePose;

class KeyframeStore {
 public:
  /// SQLite application_id (file header offset 68) of a keyframe store: "LT2K".
  static constexpr std::int32_t kApplicationId = 0x4C54324B;
  /// Schema version (PRAGMA user_version) this build reads and writes.
  static constexpr int kSchemaVersion = 3;
  /// The oldest version it opens: an older store opened for writing is upgraded in place
  /// (version 2: nodes and tiles tables; 3: pending_merges; migrate_schema), one opened
  /// read-only is read as it is.
  static constexpr int kOldestSchemaVersion = 1;

  /// Opens or creates the store at `path`. Throws StoreError naming the path and the reason.
  static KeyframeStore open(const std::string& path, OpenMode mode,
                            const StoreOptions& options = {});

  KeyframeStore(KeyframeStore&&) noexcept;
  KeyframeStore& operator=(KeyframeStore&&) noexcept;
  KeyframeStore(const KeyframeStore&) = delete;
  KeyframeStore& operator=(const KeyframeStore&) = delete;
  /// Closes the file; the write-ahead log is checkpointed into it when this is the last
  /// connection.
  ~KeyframeStore();

  const std::string& path() const;

  /// Inserts `keyframe` in its own transaction unless a keyframe with its key is stored
  /// already (then the stored one is kept unchanged). Returns true if it was new.
  bool insert_keyframe(const Keyframe& keyframe);
  /// Inserts the keyframes not stored yet, all in one transaction (all or none on error).
  /// Returns how many were new. With `descriptors` (one per keyframe), each new keyframe's
  /// node row (what a restart reads instead of the distributions) is written too.
  std::size_t insert_keyframes(
      const std::vector<const Keyframe*>& keyframes,
      const std::vector<const mapping::PlaceDescriptor*>& descriptors = {});

  /// A transaction spanning several calls (the aggregator's batch: its keyframes, then the
  /// graph changes they caused), committed by commit(), else rolled back on destruction.
  /// Calls made meanwhile join it instead of committing on their own.
  class Batch {
   public:
    explicit Batch(KeyframeStore& store);
    Batch(const Batch&) = delete;
    Batch& operator=(const Batch&) = delete;
    ~Batch();
    void commit();

   private:
    KeyframeStore& store_;
    bool done_ = false;
  };

  /// One keyframe's distributions (what the mapper's DistributionCache reads on a miss).
  /// Throws StoreError if the keyframe is missing or its row is corrupt.
  std::vector<Distribution> load_distributions(const KeyframeKey& key,
                                               const RegularizerConfig& regularizer = {}) const;

  /// What a restart rebuilds the mapper from, without the distributions: every keyframe's
  /// node (descriptor empty where none is stored: made from the distributions by the caller),
  /// its corrected pose if one is stored, and the loop edges.
  struct GraphRecords {
    struct Node {
      mapping::KeyframeNode node;
      /// The node's descriptor was stored (else node.descriptor is empty).
      bool has_descriptor = false;
      /// A corrected pose was stored (node.pose; else it is the odometry pose).
      bool has_pose = false;
      std::string frame;
      /// The pose the keyframe is fused into the map tiles at.
      std::optional<Eigen::Isometry3d> map_pose;
    };
    std::vector<Node> nodes;
    std::vector<mapping::LoopEdge> loops;
    /// The loops between groups waiting for their merge's confirmation, oldest first.
    std::vector<mapping::LoopEdge> pending_merges;
    /// Connections that read the nodes (StoreOptions::restart_readers, or 1).
    int readers = 1;
  };
  /// `descriptor_cells` false: each node's descriptor keeps its ring key only (a mapper that
  /// reads the cells back with load_descriptor, Mapper::keep_descriptor_cells_outside).
  GraphRecords load_graph(bool descriptor_cells = true) const;
  /// One keyframe's stored descriptor, cells included. Throws StoreError if the keyframe has
  /// none (missing, or a store of schema version 1) or its blob is corrupt.
  mapping::PlaceDescriptor load_descriptor(const KeyframeKey& key) const;
  /// Stores descriptors of nodes that have none (after a migration).
  void store_descriptors(
      const std::vector<std::pair<KeyframeKey, const mapping::PlaceDescriptor*>>& descriptors);

  /// Inserts loop edges (an edge stored already is an error).
  void insert_loop_edges(const std::vector<mapping::LoopEdge>& edges);
  /// Inserts or replaces the corrected poses given (the others stay).
  void upsert_corrected_poses(const std::vector<CorrectedPose>& poses);

  /// Map tiles (mapping/tile_map.hpp). Inserts or replaces each tile with its summary; an
  /// empty tile is deleted.
  void upsert_tiles(const std::vector<std::shared_ptr<const mapping::MapTile>>& tiles,
                    const mapping::TileGeometry& geometry);
  /// One tile's voxels (nullopt: no such tile). Throws StoreError for a corrupt row.
  std::optional<mapping::MapTile> load_tile(mapping::TileKey key,
                                            const mapping::TileGeometry& geometry) const;
  /// Every tile's summary (without reading the voxels), by key.
  std::vector<mapping::TileSummary> load_tile_index() const;
  std::size_t tile_count() const;
  /// Deletes every tile and map pose (the tiles are to be made again).
  void clear_map();
  /// Sets the poses the keyframes are fused into the tiles at (nullopt: not fused).
  void set_map_poses(
      const std::vector<std::pair<KeyframeKey, std::optional<Eigen::Isometry3d>>>& poses);

  /// Every keyframe, in canonical order (canonical_before). Distributions get their
  /// cov, shape_cov and shape_cov_inv from the stored covariance with `regularizer`.
  std::vector<Keyframe> load_keyframes(const RegularizerConfig& regularizer = {}) const;
  std::size_t keyframe_count() const;
  bool contains(const KeyframeKey& key) const;

  /// Replaces every stored loop edge with `edges`, in one transaction. Two edges with the same
  /// (from, to) are an error.
  void replace_loop_edges(const std::vector<mapping::LoopEdge>& edges);
  /// The loop edges of the latest replace_loop_edges, in the order given to it.
  std::vector<mapping::LoopEdge> load_loop_edges() const;

  /// Replaces the loops waiting for a merge's confirmation (Mapper::pending_merges), in the
  /// order given (oldest first). The same edge twice is an error.
  void replace_pending_merges(const std::vector<mapping::LoopEdge>& edges);
  /// Those of the latest replace_pending_merges, in its order (none before schema version 3).
  std::vector<mapping::LoopEdge> load_pending_merges() const;

  /// Replaces every stored corrected pose with `poses`, in one transaction. Two poses of the
  /// same keyframe are an error.
  void replace_corrected_poses(const std::vector<CorrectedPose>& poses);
  /// The corrected poses of the latest replace_corrected_poses, ordered by key.
  std::vector<CorrectedPose> load_corrected_poses() const;

 private:
  struct Impl;
  explicit KeyframeStore(std::unique_ptr<Impl> impl);
  Impl& impl() const;
  void write_loop_edges(const std::vector<mapping::LoopEdge>& edges,
                        const char* table = "loop_edges");
  std::vector<mapping::LoopEdge> read_loop_edges(const char* table) const;
  std::unique_ptr<Impl> impl_;
  friend class Batch;
};

}  // namespace litamin2::store
