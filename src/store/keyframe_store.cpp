#include "litamin2/store/keyframe_store.hpp"

#include <sqlite3.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <stdexcept>
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
    s.bind_text(1, kf.key.stream);
    s.bind(2, static_cast<std::int64_t>(kf.key.id));
    s.bind(3, kf.stamp.nanoseconds);
    s.bind(4, kf.voxel_size);
    s.bind_blob(5, pose);
    s.bind_blob(6, covariance);
    s.bind_blob(7, distributions);
    s.step(what);
    return sqlite3_changes(db.get()) > 0;
  }
};

KeyframeStore KeyframeStore::open(const std::string& path, OpenMode mode,
                                  const StoreOptions& options) {
  if (path.empty()) throw StoreError(path, "empty store path");
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
  const int flags = impl->read_only ? SQLITE_OPEN_READONLY
                                    : SQLITE_OPEN_READWRITE | (create ? SQLITE_OPEN_CREATE : 0);
  impl->db = open_connection(path, flags);
  sqlite3* db = impl->db.get();
  sqlite3_busy_timeout(db, options.busy_timeout_ms);
  if (create) create_schema(db, path);
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

std::size_t KeyframeStore::insert_keyframes(const std::vector<const Keyframe*>& keyframes) {
  Impl& im = impl();
  im.require_writable("insert_keyframes");
  if (keyframes.empty()) return 0;
  Transaction tx(im.db.get(), im.path);
  std::size_t inserted = 0;
  for (std::size_t i = 0; i < keyframes.size(); ++i) {
    if (keyframes[i] == nullptr) {
      throw StoreError(im.path, "insert_keyframes: null keyframe at index " + std::to_string(i));
    }
    if (im.insert(*keyframes[i])) ++inserted;
  }
  tx.commit();
  return inserted;
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
  Transaction tx(im.db.get(), im.path);
  exec(im.db.get(), im.path, "DELETE FROM loop_edges");
  Statement s(im.db.get(), im.path,
              "INSERT INTO loop_edges (from_stream, from_id, to_stream, to_id, fitness, rmse, "
              "relative, information) VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8)");
  for (const mapping::LoopEdge& e : edges) {
    const std::string what = "cannot store loop edge " + describe(e.from) + " -> " + describe(e.to);
    for (const KeyframeKey* key : {&e.from, &e.to}) {
      if (key->id > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max())) {
        throw StoreError(im.path, what + ": id exceeds the largest storable id 2^63-1");
      }
    }
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
  tx.commit();
}

std::vector<mapping::LoopEdge> KeyframeStore::load_loop_edges() const {
  Impl& im = impl();
  Statement s(im.db.get(), im.path,
              "SELECT from_stream, from_id, to_stream, to_id, fitness, rmse, relative, "
              "information FROM loop_edges ORDER BY rowid");
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
  Transaction tx(im.db.get(), im.path);
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
  tx.commit();
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
