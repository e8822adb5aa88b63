#include "litamin2/store/keyframe_store.hpp"

#include <sqlite3.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <optional>
#include <set>
#include <stdexcept>
#include <thread>
#include <utility>
#include <vector>

#include "litamin2/store/record_codec.hpp"
#include "schema.hpp"
#include "sqlite.hpp"

namespace litamin2::store {

namespace fs = std::filesystem;

namespace {

/// 'stream'/id, for messages.
std::string describe(const KeyframeKey& key) {
  return "'" + key.stream + "'/" + std::to_string(key.id);
}

}  // namespace

/// The open store: its connection and the statements every call reuses.
struct KeyframeStore::Impl {
  /// The path given to open().
  std::string path;
  bool read_only = false;
  // Declared before the statements, so destroyed (closed) after they are finalised.
  Connection db;
  /// INSERT OR IGNORE of one keyframe.
  std::unique_ptr<Statement> insert_keyframe;
  /// Whether a key is stored.
  std::unique_ptr<Statement> contains;
  /// Number of keyframes.
  std::unique_ptr<Statement> count;
  /// INSERT OR IGNORE of a node row (schema version 2).
  std::unique_ptr<Statement> insert_node;
  /// One keyframe's distributions.
  std::unique_ptr<Statement> distributions;
  /// One keyframe's descriptor (schema version 2 on).
  std::unique_ptr<Statement> descriptor;
  /// UPSERT of a corrected pose.
  std::unique_ptr<Statement> upsert_pose;
  /// Map tiles: UPSERT, DELETE, one tile's voxels; a node's map pose.
  std::unique_ptr<Statement> upsert_tile;
  std::unique_ptr<Statement> delete_tile;
  std::unique_ptr<Statement> load_tile;
  std::unique_ptr<Statement> set_map_pose;
  /// The open Batch, if any.
  std::unique_ptr<Transaction> batch;
  int version = KeyframeStore::kSchemaVersion;
  /// StoreOptions::restart_readers.
  int restart_readers = 1;
  /// PRAGMA cache_size of StoreOptions::sqlite_cache_mb, for every connection.
  std::string cache_size_pragma;

  /// A transaction of its own unless a Batch is open.
  std::unique_ptr<Transaction> transaction() {
    if (batch) return nullptr;
    return std::make_unique<Transaction>(db.get(), path);
  }
  static void commit(std::unique_ptr<Transaction>& tx) {
    if (tx) tx->commit();
  }

  void require_version2(const char* operation) const {
    if (version < 2) {
      throw StoreError(path, std::string(operation) + ": the store is of schema version " +
                                 std::to_string(version) + " (open it for writing to upgrade it)");
    }
  }

  void insert_node_row(const Keyframe& kf, const mapping::PlaceDescriptor& descriptor) {
    const std::string what = "cannot store the node of keyframe " + describe(kf.key);
    const std::string pose = encode_pose(kf.odom_pose);
    const std::string covariance = encode_matrix6(kf.covariance);
    std::string d;
    try {
      d = encode_descriptor(descriptor);
    } catch (const std::invalid_argument& e) {
      throw StoreError(path, what + ": " + e.what());
    }
    Statement& s = *insert_node;
    ResetOnExit reset{s};
    bind_keyframe_row(s, kf, pose, covariance, d);
    s.step(what);
  }

  /// The columns keyframes and nodes share: (stream, id, stamp, voxel size, pose, covariance)
  /// and, seventh, the row's own blob (distributions or descriptor).
  static void bind_keyframe_row(Statement& s, const Keyframe& kf, const std::string& pose,
                                const std::string& covariance, const std::string& blob) {
    s.bind_text(1, kf.key.stream);
    s.bind(2, static_cast<std::int64_t>(kf.key.id));
    s.bind(3, kf.stamp.nanoseconds);
    s.bind(4, kf.voxel_size);
    s.bind_blob(5, pose);
    s.bind_blob(6, covariance);
    s.bind_blob(7, blob);
  }

  void require_writable(const char* operation) const {
    if (read_only) throw StoreError(path, std::string(operation) + ": the store is open read-only");
  }

  /// Inserts one keyframe in the current transaction (or its own). True if it was new.
  bool insert(const Keyframe& kf) {
    const std::string what = "cannot store keyframe " + describe(kf.key);
    if (kf.key.stream.empty()) throw StoreError(path, what + ": empty stream name");
    if (kf.key.id > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max())) {
      throw StoreError(path, what + ": id exceeds the largest storable id 2^63-1");
    }
    if (!kf.odom_pose.matrix().allFinite()) throw StoreError(path, what + ": non-finite pose");
    if (!std::isfinite(kf.voxel_size)) throw StoreError(path, what + ": non-finite voxel size");
    std::string distributions;
    try {
      distributions = encode_distributions(kf.distributions);
    } catch (const std::invalid_argument& e) {
      throw StoreError(path, what + ": " + e.what());
    }
    const std::string pose = encode_pose(kf.odom_pose);
    const std::string covariance = encode_matrix6(kf.covariance);
    Statement& s = *insert_keyframe;
    ResetOnExit reset{s};
    bind_keyframe_row(s, kf, pose, covariance, distributions);
    s.step(what);
    return sqlite3_changes(db.get()) > 0;
  }
};

KeyframeStore KeyframeStore::open(const std::string& path, OpenMode mode,
                                  const StoreOptions& options) {
  if (path.empty()) throw StoreError(path, "empty store path");
  if (options.page_size < 512 || options.page_size > 65536 ||
      (options.page_size & (options.page_size - 1)) != 0) {
    throw StoreError(path, "page_size " + std::to_string(options.page_size) +
                               " is not a power of two in [512, 65536]");
  }
  if (options.sqlite_cache_mb < 1 || options.sqlite_cache_mb > 65536) {
    throw StoreError(path, "sqlite_cache_mb " + std::to_string(options.sqlite_cache_mb) +
                               " is outside [1, 65536]");
  }
  if (options.restart_readers < 1 || options.restart_readers > 64) {
    throw StoreError(
        path, "restart_readers " + std::to_string(options.restart_readers) + " is outside [1, 64]");
  }
  if (options.busy_timeout_ms < 0) {
    throw StoreError(path, "negative busy_timeout_ms " + std::to_string(options.busy_timeout_ms));
  }
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  bool create = false;
  if (!fs::exists(status)) {
    if (mode != OpenMode::kCreateIfMissing) throw StoreError(path, "keyframe store does not exist");
    create = true;
  } else if (!fs::is_regular_file(status)) {
    throw StoreError(path, "is not a regular file");
  } else {
    const std::uintmax_t size = fs::file_size(path, ec);
    if (ec) throw StoreError(path, "cannot read the file size: " + ec.message());
    if (size == 0) {
      if (mode != OpenMode::kCreateIfMissing) {
        throw StoreError(path, "file is empty, not a keyframe store");
      }
      create = true;
    } else {
      check_keyframe_store(path, size);
    }
  }

  auto impl = std::make_unique<Impl>();
  impl->path = path;
  impl->read_only = mode == OpenMode::kReadOnly;
  impl->restart_readers = options.restart_readers;
  impl->cache_size_pragma =
      "PRAGMA cache_size = -" + std::to_string(options.sqlite_cache_mb * 1024);
  const int flags = impl->read_only ? SQLITE_OPEN_READONLY
                                    : SQLITE_OPEN_READWRITE | (create ? SQLITE_OPEN_CREATE : 0);
  impl->db = open_connection(path, flags);
  sqlite3* db = impl->db.get();
  sqlite3_busy_timeout(db, options.busy_timeout_ms);
  if (create) create_schema(db, path, options.page_size);
  if (!impl->read_only) migrate_schema(db, path);
  impl->version = schema_version(db, path);
  if (!impl->read_only) {
    // WAL is a property of the file (it persists); setting it again is a no-op. It lets readers
    // work while a writer commits and makes a commit one append to the log.
    Statement wal(db, path, "PRAGMA journal_mode = WAL");
    wal.step("cannot switch to WAL mode");
    const auto* journal_mode = reinterpret_cast<const char*>(sqlite3_column_text(wal.get(), 0));
    if (journal_mode == nullptr || std::string(journal_mode) != "wal") {
      throw StoreError(path, std::string("cannot switch to WAL mode (journal mode stays ") +
                                 (journal_mode ? journal_mode : "unknown") +
                                 "; is the file on a network file system?)");
    }
  }
  // NORMAL: in WAL mode a commit is durable across a crash of the process (kill -9 included);
  // only a power loss may lose the last commits since a checkpoint. FULL fsyncs every commit.
  exec(db, path,
       options.synchronous_full ? "PRAGMA synchronous = FULL" : "PRAGMA synchronous = NORMAL");
  exec(db, path, impl->cache_size_pragma.c_str());

  // received_seq numbers keyframes in arrival order; computed in the statement so that
  // several writers (each in its own transaction) never reuse a number.
  impl->insert_keyframe = std::make_unique<Statement>(
      db, impl->path,
      "INSERT OR IGNORE INTO keyframes (stream, id, stamp_ns, voxel_size, pose, covariance, "
      "distributions, received_seq) VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, "
      "(SELECT coalesce(max(received_seq), 0) + 1 FROM keyframes))");
  impl->contains = std::make_unique<Statement>(
      db, impl->path, "SELECT 1 FROM keyframes WHERE stream = ?1 AND id = ?2");
  impl->count = std::make_unique<Statement>(db, impl->path, "SELECT count(*) FROM keyframes");
  impl->distributions = std::make_unique<Statement>(
      db, impl->path, "SELECT distributions FROM keyframes WHERE stream = ?1 AND id = ?2");
  if (impl->version >= 2) {
    impl->descriptor = std::make_unique<Statement>(
        db, impl->path, "SELECT descriptor FROM nodes WHERE stream = ?1 AND id = ?2");
    impl->insert_node = std::make_unique<Statement>(
        db, impl->path,
        "INSERT OR IGNORE INTO nodes (stream, id, stamp_ns, voxel_size, pose, covariance, "
        "descriptor) VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7)");
    impl->upsert_pose = std::make_unique<Statement>(
        db, impl->path,
        "INSERT INTO corrected_poses (stream, id, frame, pose) VALUES (?1, ?2, ?3, ?4) "
        "ON CONFLICT (stream, id) DO UPDATE SET frame = excluded.frame, pose = excluded.pose");
    impl->upsert_tile = std::make_unique<Statement>(
        db, impl->path,
        "INSERT INTO tiles (ix, iy, keyframes, distributions, summary, voxels) "
        "VALUES (?1, ?2, ?3, ?4, ?5, ?6) ON CONFLICT (ix, iy) DO UPDATE SET "
        "keyframes = excluded.keyframes, distributions = excluded.distributions, "
        "summary = excluded.summary, voxels = excluded.voxels");
    impl->delete_tile =
        std::make_unique<Statement>(db, impl->path, "DELETE FROM tiles WHERE ix = ?1 AND iy = ?2");
    impl->load_tile = std::make_unique<Statement>(
        db, impl->path, "SELECT keyframes, voxels FROM tiles WHERE ix = ?1 AND iy = ?2");
    impl->set_map_pose = std::make_unique<Statement>(
        db, impl->path, "UPDATE nodes SET map_pose = ?3 WHERE stream = ?1 AND id = ?2");
  }
  return KeyframeStore(std::move(impl));
}

KeyframeStore::KeyframeStore(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
KeyframeStore::KeyframeStore(KeyframeStore&&) noexcept = default;
KeyframeStore& KeyframeStore::operator=(KeyframeStore&&) noexcept = default;
KeyframeStore::~KeyframeStore() = default;

KeyframeStore::Impl& KeyframeStore::impl() const {
  if (!impl_) throw std::logic_error("use of a moved-from KeyframeStore");
  return *impl_;
}

const std::string& KeyframeStore::path() const {
  return impl().path;
}

bool KeyframeStore::insert_keyframe(const Keyframe& keyframe) {
  Impl& im = impl();
  im.require_writable("insert_keyframe");
  return im.insert(keyframe);
}

std::size_t KeyframeStore::insert_keyframes(
    const std::vector<const Keyframe*>& keyframes,
    const std::vector<const mapping::PlaceDescriptor*>& descriptors) {
  Impl& im = impl();
  im.require_writable("insert_keyframes");
  if (keyframes.empty()) return 0;
  if (!descriptors.empty() && descriptors.size() != keyframes.size()) {
    throw StoreError(im.path, "insert_keyframes: " + std::to_string(descriptors.size()) +
                                  " descriptors for " + std::to_string(keyframes.size()) +
                                  " keyframes");
  }
  auto tx = im.transaction();
  std::size_t inserted = 0;
  for (std::size_t i = 0; i < keyframes.size(); ++i) {
    if (keyframes[i] == nullptr) {
      throw StoreError(im.path, "insert_keyframes: null keyframe at index " + std::to_string(i));
    }
    if (!im.insert(*keyframes[i])) continue;
    ++inserted;
    if (!descriptors.empty() && descriptors[i]) im.insert_node_row(*keyframes[i], *descriptors[i]);
  }
  Impl::commit(tx);
  return inserted;
}

KeyframeStore::Batch::Batch(KeyframeStore& store) : store_(store) {
  Impl& im = store.impl();
  im.require_writable("batch");
  if (im.batch) throw std::logic_error("KeyframeStore: a batch is open already");
  im.batch = std::make_unique<Transaction>(im.db.get(), im.path);
}

KeyframeStore::Batch::~Batch() {
  if (!done_) store_.impl().batch.reset();  // rolls back
}

void KeyframeStore::Batch::commit() {
  Impl& im = store_.impl();
  im.batch->commit();
  im.batch.reset();
  done_ = true;
}

namespace {

/// Binds `key` to `s` (?1 stream, ?2 id) and steps to its row; throws StoreError ("`what`: no
/// such keyframe") when there is none. The caller holds a ResetOnExit on `s` while it reads.
void step_to_keyframe(const std::string& path, Statement& s, const KeyframeKey& key,
                      const std::string& what) {
  if (key.id > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()))
    throw StoreError(path, what + ": no such keyframe");
  s.bind_text(1, key.stream);
  s.bind(2, static_cast<std::int64_t>(key.id));
  if (!s.step(what)) throw StoreError(path, what + ": no such keyframe");
}

}  // namespace

std::vector<Distribution> KeyframeStore::load_distributions(
    const KeyframeKey& key, const RegularizerConfig& regularizer) const {
  Impl& im = impl();
  const std::string what = "cannot read the distributions of keyframe " + describe(key);
  Statement& s = *im.distributions;
  ResetOnExit reset{s};
  step_to_keyframe(im.path, s, key, what);
  try {
    const auto blob = column_blob(s.get(), 0, "distributions");
    return decode_distributions(blob.first, blob.second, regularizer);
  } catch (const std::invalid_argument& e) {
    throw StoreError(im.path, "corrupt keyframe row " + describe(key) + ": " + e.what());
  }
}

mapping::PlaceDescriptor KeyframeStore::load_descriptor(const KeyframeKey& key) const {
  Impl& im = impl();
  const std::string what = "cannot read the descriptor of keyframe " + describe(key);
  if (!im.descriptor) throw StoreError(im.path, what + ": the store has no descriptors");
  Statement& s = *im.descriptor;
  ResetOnExit reset{s};
  step_to_keyframe(im.path, s, key, what);
  if (sqlite3_column_type(s.get(), 0) == SQLITE_NULL)
    throw StoreError(im.path, what + ": none stored");
  try {
    const auto blob = column_blob(s.get(), 0, "descriptor");
    return decode_descriptor(blob.first, blob.second);
  } catch (const std::invalid_argument& e) {
    throw StoreError(im.path, "corrupt node row " + describe(key) + ": " + e.what());
  }
}

namespace {

/// load_graph's nodes query over the rows whose rowid lies in [?1, ?2], the rowid last. A
/// version-1 store opened read-only has no nodes table: the same columns of keyframes.
const char* nodes_query(int version) {
  return version >= 2
             ? "SELECT n.stream, n.id, n.stamp_ns, n.voxel_size, n.pose, n.covariance, "
               "n.descriptor, c.frame, c.pose, n.map_pose, n.rowid FROM nodes n LEFT JOIN "
               "corrected_poses c ON c.stream = n.stream AND c.id = n.id WHERE n.rowid BETWEEN ?1 "
               "AND ?2"
             : "SELECT k.stream, k.id, k.stamp_ns, k.voxel_size, k.pose, k.covariance, NULL, "
               "c.frame, c.pose, NULL, k.rowid FROM keyframes k LEFT JOIN corrected_poses c "
               "ON c.stream = k.stream AND c.id = k.id WHERE k.rowid BETWEEN ?1 AND ?2";
}

/// One row of nodes_query.
KeyframeStore::GraphRecords::Node decode_node_row(sqlite3_stmt* row, const std::string& path,
                                                  bool descriptor_cells) {
  KeyframeStore::GraphRecords::Node rec;
  mapping::KeyframeNode& n = rec.node;
  try {
    n.key.stream = column_text(row, 0, "stream");
    n.key.id = column_id(row, 1, "id");
    n.stamp.nanoseconds = column_int(row, 2, "stamp_ns");
    n.voxel_size = column_real(row, 3, "voxel_size");
    const auto pose = column_blob(row, 4, "pose");
    n.odom_pose = decode_pose(pose.first, pose.second);
    const auto covariance = column_blob(row, 5, "covariance");
    n.covariance = decode_matrix6(covariance.first, covariance.second).cast<float>();
    if (sqlite3_column_type(row, 6) != SQLITE_NULL) {
      const auto d = column_blob(row, 6, "descriptor");
      n.descriptor = decode_descriptor(d.first, d.second, descriptor_cells);
      rec.has_descriptor = true;
    }
    n.pose = n.odom_pose;
    if (sqlite3_column_type(row, 8) != SQLITE_NULL) {
      rec.frame = column_text(row, 7, "frame");
      const auto corrected = column_blob(row, 8, "corrected pose");
      n.pose = decode_pose(corrected.first, corrected.second);
      rec.has_pose = true;
    }
    if (sqlite3_column_type(row, 9) != SQLITE_NULL) {
      const auto fused = column_blob(row, 9, "map pose");
      rec.map_pose = decode_pose(fused.first, fused.second);
    }
  } catch (const std::invalid_argument& e) {
    throw StoreError(path, "corrupt node row " + describe(n.key) + ": " + e.what());
  }
  return rec;
}

/// Calls `row(rowid, stmt)` for each row of nodes_query with rowid in [first, last], in
/// rowid order.
template <typename Row>
void scan_nodes(sqlite3* db, const std::string& path, int version, std::int64_t first,
                std::int64_t last, Row&& row) {
  Statement s(db, path, nodes_query(version));
  s.bind(1, first);
  s.bind(2, last);
  while (s.step("cannot read the nodes")) row(sqlite3_column_int64(s.get(), 10), s.get());
}

}  // namespace

KeyframeStore::GraphRecords KeyframeStore::load_graph(bool descriptor_cells) const {
  Impl& im = impl();
  GraphRecords out;
  const char* table = im.version >= 2 ? "nodes" : "keyframes";
  std::int64_t first = 0, last = -1, count = 0;
  {
    Statement range(im.db.get(), im.path,
                    (std::string("SELECT min(rowid), max(rowid), count(*) FROM ") + table).c_str());
    if (range.step("cannot count the nodes") &&
        sqlite3_column_type(range.get(), 0) != SQLITE_NULL) {
      first = sqlite3_column_int64(range.get(), 0);
      last = sqlite3_column_int64(range.get(), 1);
      count = sqlite3_column_int64(range.get(), 2);
    }
  }
  // Rows without gaps in their rowids (as the store writes them: appended, never deleted) go
  // to their slot by rowid, so ranges read side by side land in the one scan's order. Only a
  // store opened for writing, outside a transaction, is read so: its connection is the only
  // writer and has nothing uncommitted, so the ranges all see the rows counted.
  const bool dense = count > 0 && last - first + 1 == count;
  const std::int64_t kMinRowsPerReader = 4096;
  const bool one_writer = !im.read_only && sqlite3_get_autocommit(im.db.get()) != 0;
  const std::int64_t readers =
      dense && one_writer
          ? std::clamp<std::int64_t>(count / kMinRowsPerReader, 1, im.restart_readers)
          : 1;
  out.readers = static_cast<int>(readers);
  if (readers == 1) {
    // Reserved: growing a vector of a million ~1.8 kB records copied it and faulted in fresh
    // pages at every doubling (a fifth of a 10^6-keyframe restart's time in a profile).
    out.nodes.reserve(static_cast<std::size_t>(count));
    scan_nodes(im.db.get(), im.path, im.version, first, last, [&](std::int64_t, sqlite3_stmt* row) {
      out.nodes.push_back(decode_node_row(row, im.path, descriptor_cells));
    });
  } else {
    out.nodes.resize(static_cast<std::size_t>(count));
    std::vector<std::exception_ptr> errors(static_cast<std::size_t>(readers));
    std::vector<std::thread> threads;
    const std::int64_t per_reader = (count + readers - 1) / readers;
    for (std::int64_t r = 0; r < readers; ++r) {
      const std::int64_t from = first + r * per_reader;
      const std::int64_t to = std::min(last, from + per_reader - 1);
      threads.emplace_back([&, r, from, to] {
        try {
          // A connection of its own: SQLite connections are not shared between threads here
          // (SQLITE_OPEN_NOMUTEX).
          Connection db = open_connection(im.path, SQLITE_OPEN_READONLY);
          exec(db.get(), im.path, im.cache_size_pragma.c_str());
          scan_nodes(db.get(), im.path, im.version, from, to,
                     [&](std::int64_t rowid, sqlite3_stmt* row) {
                       if (rowid < from || rowid > to)
                         throw StoreError(im.path, "nodes scan returned a row out of range");
                       out.nodes[static_cast<std::size_t>(rowid - first)] =
                           decode_node_row(row, im.path, descriptor_cells);
                     });
        } catch (...) {
          errors[static_cast<std::size_t>(r)] = std::current_exception();
        }
      });
    }
    for (std::thread& t : threads) t.join();
    for (const std::exception_ptr& e : errors)
      if (e) std::rethrow_exception(e);
  }
  out.loops = load_loop_edges();
  out.pending_merges = load_pending_merges();
  return out;
}

void KeyframeStore::store_descriptors(
    const std::vector<std::pair<KeyframeKey, const mapping::PlaceDescriptor*>>& descriptors) {
  Impl& im = impl();
  im.require_writable("store_descriptors");
  im.require_version2("store_descriptors");
  auto tx = im.transaction();
  Statement s(im.db.get(), im.path,
              "UPDATE nodes SET descriptor = ?3 WHERE stream = ?1 AND id = ?2");
  for (const auto& [key, d] : descriptors) {
    const std::string blob = encode_descriptor(*d);
    ResetOnExit reset{s};
    s.bind_text(1, key.stream);
    s.bind(2, static_cast<std::int64_t>(key.id));
    s.bind_blob(3, blob);
    s.step("cannot store the descriptor of " + describe(key));
  }
  Impl::commit(tx);
}

void KeyframeStore::insert_loop_edges(const std::vector<mapping::LoopEdge>& edges) {
  Impl& im = impl();
  im.require_writable("insert_loop_edges");
  auto tx = im.transaction();
  write_loop_edges(edges);
  Impl::commit(tx);
}

void KeyframeStore::upsert_corrected_poses(const std::vector<CorrectedPose>& poses) {
  Impl& im = impl();
  im.require_writable("upsert_corrected_poses");
  im.require_version2("upsert_corrected_poses");
  auto tx = im.transaction();
  Statement& s = *im.upsert_pose;
  for (const CorrectedPose& p : poses) {
    const std::string what = "cannot store the corrected pose of " + describe(p.key);
    if (p.key.id > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()))
      throw StoreError(im.path, what + ": id exceeds the largest storable id 2^63-1");
    if (!p.pose.matrix().allFinite()) throw StoreError(im.path, what + ": non-finite pose");
    const std::string pose = encode_pose(p.pose);
    ResetOnExit reset{s};
    s.bind_text(1, p.key.stream);
    s.bind(2, static_cast<std::int64_t>(p.key.id));
    s.bind_text(3, p.frame);
    s.bind_blob(4, pose);
    s.step(what);
  }
  Impl::commit(tx);
}

void KeyframeStore::upsert_tiles(const std::vector<std::shared_ptr<const mapping::MapTile>>& tiles,
                                 const mapping::TileGeometry& geometry) {
  Impl& im = impl();
  im.require_writable("upsert_tiles");
  im.require_version2("upsert_tiles");
  auto tx = im.transaction();
  for (const auto& t : tiles) {
    const mapping::TileKey key = t->key();
    const std::string what =
        "cannot store tile (" + std::to_string(key.ix) + ", " + std::to_string(key.iy) + ")";
    if (t->empty()) {
      Statement& erase = *im.delete_tile;
      ResetOnExit reset{erase};
      erase.bind(1, std::int64_t{key.ix});
      erase.bind(2, std::int64_t{key.iy});
      erase.step(what);
      continue;
    }
    const mapping::TileSummary summary = t->summary(geometry);
    std::string voxels;
    try {
      voxels = encode_tile_voxels(t->voxels());
    } catch (const std::invalid_argument& e) {
      throw StoreError(im.path, what + ": " + e.what());
    }
    const std::string encoded_summary = encode_tile_summary(summary);
    Statement& put = *im.upsert_tile;
    ResetOnExit reset{put};
    put.bind(1, std::int64_t{key.ix});
    put.bind(2, std::int64_t{key.iy});
    put.bind(3, t->keyframes());
    put.bind(4, summary.distributions);
    put.bind_blob(5, encoded_summary);
    put.bind_blob(6, voxels);
    put.step(what);
  }
  Impl::commit(tx);
}

std::optional<mapping::MapTile> KeyframeStore::load_tile(
    mapping::TileKey key, const mapping::TileGeometry& geometry) const {
  Impl& im = impl();
  if (im.version < 2) return std::nullopt;
  const std::string what = "tile (" + std::to_string(key.ix) + ", " + std::to_string(key.iy) + ")";
  Statement& s = *im.load_tile;
  ResetOnExit reset{s};
  s.bind(1, std::int64_t{key.ix});
  s.bind(2, std::int64_t{key.iy});
  if (!s.step("cannot read " + what)) return std::nullopt;
  try {
    const std::int64_t keyframes = column_int(s.get(), 0, "keyframes");
    const auto blob = column_blob(s.get(), 1, "voxels");
    return mapping::MapTile::restore(
        key, keyframes, decode_tile_voxels(blob.first, blob.second, geometry.voxels.voxel_size));
  } catch (const std::invalid_argument& e) {
    throw StoreError(im.path, "corrupt " + what + ": " + e.what());
  }
}

std::vector<mapping::TileSummary> KeyframeStore::load_tile_index() const {
  Impl& im = impl();
  std::vector<mapping::TileSummary> out;
  if (im.version < 2) return out;
  Statement s(im.db.get(), im.path,
              "SELECT ix, iy, keyframes, distributions, summary FROM tiles ORDER BY ix, iy");
  while (s.step("cannot read the tile index")) {
    mapping::TileSummary t;
    sqlite3_stmt* row = s.get();
    try {
      t.key.ix = static_cast<std::int32_t>(column_int(row, 0, "ix"));
      t.key.iy = static_cast<std::int32_t>(column_int(row, 1, "iy"));
      t.keyframes = column_int(row, 2, "keyframes");
      t.distributions = column_int(row, 3, "distributions");
      const auto blob = column_blob(row, 4, "summary");
      decode_tile_summary(blob.first, blob.second, t);
    } catch (const std::invalid_argument& e) {
      throw StoreError(im.path, "corrupt tile row (" + std::to_string(t.key.ix) + ", " +
                                    std::to_string(t.key.iy) + "): " + e.what());
    }
    out.push_back(std::move(t));
  }
  return out;
}

std::size_t KeyframeStore::tile_count() const {
  Impl& im = impl();
  if (im.version < 2) return 0;
  return static_cast<std::size_t>(query_int(im.db.get(), im.path, "SELECT count(*) FROM tiles"));
}

void KeyframeStore::clear_map() {
  Impl& im = impl();
  im.require_writable("clear_map");
  if (im.version < 2) return;
  auto tx = im.transaction();
  exec(im.db.get(), im.path, "DELETE FROM tiles; UPDATE nodes SET map_pose = NULL");
  Impl::commit(tx);
}

void KeyframeStore::set_map_poses(
    const std::vector<std::pair<KeyframeKey, std::optional<Eigen::Isometry3d>>>& poses) {
  Impl& im = impl();
  im.require_writable("set_map_poses");
  im.require_version2("set_map_poses");
  auto tx = im.transaction();
  Statement& s = *im.set_map_pose;
  for (const auto& [key, pose] : poses) {
    const std::string what = "cannot store the map pose of " + describe(key);
    if (key.id > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()))
      throw StoreError(im.path, what + ": no such keyframe");
    std::string blob;
    if (pose) {
      if (!pose->matrix().allFinite()) throw StoreError(im.path, what + ": non-finite pose");
      blob = encode_pose(*pose);
    }
    ResetOnExit reset{s};
    s.bind_text(1, key.stream);
    s.bind(2, static_cast<std::int64_t>(key.id));
    if (pose) s.bind_blob(3, blob);  // else NULL
    s.step(what);
  }
  Impl::commit(tx);
}

std::vector<Keyframe> KeyframeStore::load_keyframes(const RegularizerConfig& regularizer) const {
  Impl& im = impl();
  // The index on (stamp_ns, stream, id) gives the canonical order: SQLite compares TEXT with
  // memcmp, as std::string does, and ids are stored non-negative.
  Statement s(im.db.get(), im.path,
              "SELECT stream, id, stamp_ns, voxel_size, pose, covariance, distributions "
              "FROM keyframes ORDER BY stamp_ns, stream, id");
  std::vector<Keyframe> out;
  while (s.step("cannot read the keyframes")) {
    Keyframe kf;
    sqlite3_stmt* row = s.get();
    try {
      kf.key.stream = column_text(row, 0, "stream");
      kf.key.id = column_id(row, 1, "id");
      kf.stamp.nanoseconds = column_int(row, 2, "stamp_ns");
      kf.voxel_size = column_real(row, 3, "voxel_size");
      const auto pose = column_blob(row, 4, "pose");
      kf.odom_pose = decode_pose(pose.first, pose.second);
      const auto covariance = column_blob(row, 5, "covariance");
      kf.covariance = decode_matrix6(covariance.first, covariance.second);
      const auto distributions = column_blob(row, 6, "distributions");
      kf.distributions =
          decode_distributions(distributions.first, distributions.second, regularizer);
    } catch (const std::invalid_argument& e) {
      throw StoreError(im.path, "corrupt keyframe row " + describe(kf.key) + ": " + e.what());
    }
    out.push_back(std::move(kf));
  }
  return out;
}

std::size_t KeyframeStore::keyframe_count() const {
  Impl& im = impl();
  ResetOnExit reset{*im.count};
  im.count->step("cannot count the keyframes");
  return static_cast<std::size_t>(sqlite3_column_int64(im.count->get(), 0));
}

bool KeyframeStore::contains(const KeyframeKey& key) const {
  Impl& im = impl();
  if (key.id > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max())) return false;
  ResetOnExit reset{*im.contains};
  im.contains->bind_text(1, key.stream);
  im.contains->bind(2, static_cast<std::int64_t>(key.id));
  return im.contains->step("cannot look up keyframe " + describe(key));
}

void KeyframeStore::replace_loop_edges(const std::vector<mapping::LoopEdge>& edges) {
  Impl& im = impl();
  im.require_writable("replace_loop_edges");
  auto tx = im.transaction();
  exec(im.db.get(), im.path, "DELETE FROM loop_edges");
  write_loop_edges(edges);
  Impl::commit(tx);
}

void KeyframeStore::replace_pending_merges(const std::vector<mapping::LoopEdge>& edges) {
  Impl& im = impl();
  im.require_writable("replace_pending_merges");
  if (im.version < 3) {
    throw StoreError(im.path, "replace_pending_merges: the store is of schema version " +
                                  std::to_string(im.version) +
                                  " (open it for writing to upgrade it)");
  }
  auto tx = im.transaction();
  exec(im.db.get(), im.path, "DELETE FROM pending_merges");
  write_loop_edges(edges, "pending_merges");
  Impl::commit(tx);
}

std::vector<mapping::LoopEdge> KeyframeStore::load_pending_merges() const {
  if (impl().version < 3) return {};
  return read_loop_edges("pending_merges");
}

void KeyframeStore::write_loop_edges(const std::vector<mapping::LoopEdge>& edges,
                                     const char* table) {
  Impl& im = impl();
  const std::string sql = std::string("INSERT INTO ") + table +
                          " (from_stream, from_id, to_stream, to_id, fitness, rmse, "
                          "relative, information) VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8)";
  Statement s(im.db.get(), im.path, sql.c_str());
  // pending_merges has no key over the edge: refuse the same edge twice here.
  std::set<std::pair<KeyframeKey, KeyframeKey>> seen;
  for (const mapping::LoopEdge& e : edges) {
    const std::string what = "cannot store loop edge " + describe(e.from) + " -> " + describe(e.to);
    for (const KeyframeKey* key : {&e.from, &e.to}) {
      if (key->id > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max())) {
        throw StoreError(im.path, what + ": id exceeds the largest storable id 2^63-1");
      }
    }
    if (!seen.emplace(e.from, e.to).second)
      throw StoreError(im.path, what + ": the edge is given twice");
    const std::string relative = encode_pose(e.relative);
    const std::string information = encode_matrix6(e.information);
    ResetOnExit reset{s};
    s.bind_text(1, e.from.stream);
    s.bind(2, static_cast<std::int64_t>(e.from.id));
    s.bind_text(3, e.to.stream);
    s.bind(4, static_cast<std::int64_t>(e.to.id));
    s.bind(5, e.fitness);
    s.bind(6, e.rmse);
    s.bind_blob(7, relative);
    s.bind_blob(8, information);
    if (sqlite3_step(s.get()) != SQLITE_DONE) {
      if (sqlite3_extended_errcode(im.db.get()) == SQLITE_CONSTRAINT_PRIMARYKEY) {
        throw StoreError(im.path, what + ": the edge is given twice");
      }
      throw_sqlite(im.db.get(), im.path, what);
    }
  }
}

std::vector<mapping::LoopEdge> KeyframeStore::load_loop_edges() const {
  return read_loop_edges("loop_edges");
}

std::vector<mapping::LoopEdge> KeyframeStore::read_loop_edges(const char* table) const {
  Impl& im = impl();
  const std::string sql =
      std::string(
          "SELECT from_stream, from_id, to_stream, to_id, fitness, rmse, relative, "
          "information FROM ") +
      table + " ORDER BY rowid";
  Statement s(im.db.get(), im.path, sql.c_str());
  std::vector<mapping::LoopEdge> out;
  while (s.step("cannot read the loop edges")) {
    mapping::LoopEdge e;
    sqlite3_stmt* row = s.get();
    try {
      e.from.stream = column_text(row, 0, "from_stream");
      e.from.id = column_id(row, 1, "from_id");
      e.to.stream = column_text(row, 2, "to_stream");
      e.to.id = column_id(row, 3, "to_id");
      e.fitness = column_real(row, 4, "fitness");
      e.rmse = column_real(row, 5, "rmse");
      const auto relative = column_blob(row, 6, "relative");
      e.relative = decode_pose(relative.first, relative.second);
      const auto information = column_blob(row, 7, "information");
      e.information = decode_matrix6(information.first, information.second);
    } catch (const std::invalid_argument& ex) {
      throw StoreError(im.path, "corrupt loop edge row " + describe(e.from) + " -> " +
                                    describe(e.to) + ": " + ex.what());
    }
    out.push_back(std::move(e));
  }
  return out;
}

void KeyframeStore::replace_corrected_poses(const std::vector<CorrectedPose>& poses) {
  Impl& im = impl();
  im.require_writable("replace_corrected_poses");
  auto tx = im.transaction();
  exec(im.db.get(), im.path, "DELETE FROM corrected_poses");
  Statement s(im.db.get(), im.path,
              "INSERT INTO corrected_poses (stream, id, frame, pose) VALUES (?1, ?2, ?3, ?4)");
  for (const CorrectedPose& p : poses) {
    const std::string what = "cannot store the corrected pose of " + describe(p.key);
    if (p.key.id > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max())) {
      throw StoreError(im.path, what + ": id exceeds the largest storable id 2^63-1");
    }
    if (!p.pose.matrix().allFinite()) throw StoreError(im.path, what + ": non-finite pose");
    const std::string pose = encode_pose(p.pose);
    ResetOnExit reset{s};
    s.bind_text(1, p.key.stream);
    s.bind(2, static_cast<std::int64_t>(p.key.id));
    s.bind_text(3, p.frame);
    s.bind_blob(4, pose);
    if (sqlite3_step(s.get()) != SQLITE_DONE) {
      if (sqlite3_extended_errcode(im.db.get()) == SQLITE_CONSTRAINT_PRIMARYKEY) {
        throw StoreError(im.path, what + ": the keyframe is given twice");
      }
      throw_sqlite(im.db.get(), im.path, what);
    }
  }
  Impl::commit(tx);
}

std::vector<CorrectedPose> KeyframeStore::load_corrected_poses() const {
  Impl& im = impl();
  Statement s(im.db.get(), im.path,
              "SELECT stream, id, frame, pose FROM corrected_poses ORDER BY stream, id");
  std::vector<CorrectedPose> out;
  while (s.step("cannot read the corrected poses")) {
    CorrectedPose p;
    sqlite3_stmt* row = s.get();
    try {
      p.key.stream = column_text(row, 0, "stream");
      p.key.id = column_id(row, 1, "id");
      p.frame = column_text(row, 2, "frame");
      const auto pose = column_blob(row, 3, "pose");
      p.pose = decode_pose(pose.first, pose.second);
    } catch (const std::invalid_argument& e) {
      throw StoreError(im.path, "corrupt corrected pose row " + describe(p.key) + ": " + e.what());
    }
    out.push_back(std::move(p));
  }
  return out;
}

}  // namespace litamin2::store
