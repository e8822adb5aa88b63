#include "schema.hpp"

#include <array>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <vector>

#include "litamin2/store/keyframe_store.hpp"
#include "sqlite.hpp"

namespace litamin2::store {

namespace fs = std::filesystem;

namespace {

// Tables are created in this order in one transaction; a store missing any of them is corrupt.
// Within the keyframes table the large BLOBs come last: SQLite reads a row's columns in order,
// so small columns after a large BLOB would cost a walk through its overflow pages.
constexpr const char* kSchema = R"sql(
CREATE TABLE keyframes (
  stream TEXT NOT NULL,
  id INTEGER NOT NULL,
  stamp_ns INTEGER NOT NULL,
  received_seq INTEGER NOT NULL,
  voxel_size REAL NOT NULL,
  pose BLOB NOT NULL,
  covariance BLOB NOT NULL,
  distributions BLOB NOT NULL,
  PRIMARY KEY (stream, id)
);
CREATE UNIQUE INDEX keyframes_by_arrival ON keyframes (received_seq);
CREATE INDEX keyframes_by_canonical_order ON keyframes (stamp_ns, stream, id);
CREATE TABLE loop_edges (
  from_stream TEXT NOT NULL,
  from_id INTEGER NOT NULL,
  to_stream TEXT NOT NULL,
  to_id INTEGER NOT NULL,
  fitness REAL NOT NULL,
  rmse REAL NOT NULL,
  relative BLOB NOT NULL,
  information BLOB NOT NULL,
  PRIMARY KEY (from_stream, from_id, to_stream, to_id)
);
CREATE TABLE corrected_poses (
  stream TEXT NOT NULL,
  id INTEGER NOT NULL,
  frame TEXT NOT NULL,
  pose BLOB NOT NULL,
  PRIMARY KEY (stream, id)
);
)sql";
// Version 2: what a restart needs of every keyframe besides its distributions, in small rows
// read without touching the keyframes' large BLOBs (descriptor NULL: to be made from the
// distributions, as after a migration from version 1; map_pose: the pose the keyframe is
// fused into the map tiles at, NULL when it is not), and the map's persisted tiles: their
// summary first (what a restart reads), the voxel moments last.
constexpr const char* kSchemaV2 = R"sql(
CREATE TABLE nodes (
  stream TEXT NOT NULL,
  id INTEGER NOT NULL,
  stamp_ns INTEGER NOT NULL,
  voxel_size REAL NOT NULL,
  pose BLOB NOT NULL,
  covariance BLOB NOT NULL,
  map_pose BLOB,
  descriptor BLOB,
  PRIMARY KEY (stream, id)
);
CREATE TABLE tiles (
  ix INTEGER NOT NULL,
  iy INTEGER NOT NULL,
  keyframes INTEGER NOT NULL,
  distributions INTEGER NOT NULL,
  summary BLOB NOT NULL,
  voxels BLOB NOT NULL,
  PRIMARY KEY (ix, iy)
);
)sql";
// Version 3: the verified loops between two groups that wait for their merge's confirmation
// (mapping/merge_confirmation.hpp), oldest first (seq), so that a restart keeps them.
constexpr const char* kSchemaV3 = R"sql(
CREATE TABLE pending_merges (
  seq INTEGER PRIMARY KEY,
  from_stream TEXT NOT NULL,
  from_id INTEGER NOT NULL,
  to_stream TEXT NOT NULL,
  to_id INTEGER NOT NULL,
  fitness REAL NOT NULL,
  rmse REAL NOT NULL,
  relative BLOB NOT NULL,
  information BLOB NOT NULL
);
)sql";
constexpr std::array<const char*, 6> kTables = {"keyframes", "loop_edges", "corrected_poses",
                                                "nodes",     "tiles",      "pending_merges"};
/// Tables of each version (kTables' first n).
std::size_t tables_of_version(std::int64_t version) {
  return version >= 3 ? 6 : version == 2 ? 5 : 3;
}

std::string hex32(std::uint32_t v) {
  char buf[16];
  std::snprintf(buf, sizeof(buf), "0x%08X", v);
  return buf;
}

std::uint32_t big_endian32(const unsigned char* p) {
  return (std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) | (std::uint32_t{p[2]} << 8) |
         std::uint32_t{p[3]};
}

/// Throws unless the database is a keyframe store of this build's schema version.
void check_identity(const std::string& path, std::uint32_t application_id,
                    std::int64_t user_version) {
  if (application_id != static_cast<std::uint32_t>(KeyframeStore::kApplicationId)) {
    throw StoreError(path,
                     "not a keyframe store: an SQLite database of another application "
                     "(application_id " +
                         hex32(application_id) + ", a keyframe store has " +
                         hex32(KeyframeStore::kApplicationId) + ")");
  }
  if (user_version > KeyframeStore::kSchemaVersion ||
      user_version < KeyframeStore::kOldestSchemaVersion) {
    throw StoreError(path, "keyframe store schema version " + std::to_string(user_version) +
                               (user_version > KeyframeStore::kSchemaVersion
                                    ? " is newer than this build's "
                                    : " is not supported; this build reads ") +
                               std::to_string(KeyframeStore::kSchemaVersion));
  }
}

/// Checks, by reading the file itself, that an existing non-empty file is a whole SQLite
/// database of a keyframe store, before SQLite touches it: SQLite would report random bytes
/// only on first use, would read a truncated file's missing pages as zeros, and opening another
/// application's database in WAL mode would leave -wal and -shm files next to it.
void check_file_header(const std::string& path, std::uintmax_t file_size) {
  // https://www.sqlite.org/fileformat.html#the_database_header
  constexpr std::size_t kHeaderSize = 100;
  static const char kMagic[] = "SQLite format 3";  // 16 bytes with the terminating NUL
  if (file_size < kHeaderSize) {
    throw StoreError(path, "not a keyframe store: " + std::to_string(file_size) +
                               " bytes, too short to be an SQLite database");
  }
  unsigned char header[kHeaderSize];
  std::ifstream in(path, std::ios::binary);
  if (!in.read(reinterpret_cast<char*>(header), kHeaderSize)) {
    throw StoreError(path, "cannot read the file header");
  }
  if (std::memcmp(header, kMagic, sizeof(kMagic)) != 0) {
    throw StoreError(path, "not a keyframe store: not an SQLite database (no SQLite header)");
  }
  const std::uint32_t page_size_field = (std::uint32_t{header[16]} << 8) | header[17];
  const std::uint32_t page_size = page_size_field == 1 ? 65536u : page_size_field;
  if (page_size < 512 || page_size > 65536 || (page_size & (page_size - 1)) != 0) {
    throw StoreError(path, "corrupt SQLite database: invalid page size " +
                               std::to_string(page_size_field) + " in the header");
  }
  if (file_size % page_size != 0) {
    throw StoreError(path, "truncated or corrupt SQLite database: " + std::to_string(file_size) +
                               " bytes is not a whole number of " + std::to_string(page_size) +
                               "-byte pages");
  }
  // The page count in the header is valid when the change counter matches version-valid-for.
  // It can legitimately exceed the file while a write-ahead log holds pages not yet copied
  // into the file (a checkpoint interrupted by a crash), so it is checked only without a log.
  const std::uint32_t change_counter = big_endian32(header + 24);
  const std::uint32_t page_count = big_endian32(header + 28);
  const std::uint32_t valid_for = big_endian32(header + 92);
  std::error_code ec;
  const std::uintmax_t wal_size = fs::file_size(path + "-wal", ec);
  const bool has_wal = !ec && wal_size > 0;
  if (!has_wal && page_count > 0 && change_counter == valid_for &&
      std::uintmax_t{page_count} * page_size > file_size) {
    throw StoreError(path, "truncated SQLite database: the header says " +
                               std::to_string(page_count) + " pages of " +
                               std::to_string(page_size) + " bytes but the file has " +
                               std::to_string(file_size) + " bytes");
  }
  // Both are written when the store is created (before it switches to WAL) and never change,
  // so the file's own header has them even while a log holds newer pages.
  const std::int32_t user_version = static_cast<std::int32_t>(big_endian32(header + 60));
  const std::uint32_t application_id = big_endian32(header + 68);
  check_identity(path, application_id, user_version);
}

/// Checks through SQLite that the database at `path`, whose header says it is a keyframe
/// store, is one: readable, with its tables. A read-only connection, so that nothing (not even
/// a hot journal's rollback) writes to a file that is not ours.
void check_is_keyframe_store(const std::string& path) {
  Connection db = open_connection(path, SQLITE_OPEN_READONLY);
  std::uint32_t application_id = 0;
  std::int64_t user_version = 0;
  std::vector<std::string> missing_tables;
  try {
    application_id = static_cast<std::uint32_t>(query_int(db.get(), path, "PRAGMA application_id"));
    user_version = query_int(db.get(), path, "PRAGMA user_version");
    Statement tables(db.get(), path,
                     "SELECT count(*) FROM sqlite_master WHERE type = 'table' AND name = ?");
    for (std::size_t t = 0; t < tables_of_version(user_version); ++t) {
      const char* table = kTables[t];
      ResetOnExit reset{tables};
      sqlite3_bind_text(tables.get(), 1, table, -1, SQLITE_STATIC);
      tables.step("cannot read the schema");
      if (sqlite3_column_int64(tables.get(), 0) != 1) missing_tables.emplace_back(table);
    }
  } catch (const StoreError&) {
    // SQLite's own reason: "file is not a database", "database disk image is malformed".
    throw StoreError(path, std::string("corrupt keyframe store: not a valid SQLite database (") +
                               sqlite3_errmsg(db.get()) + ")");
  }
  check_identity(path, application_id, user_version);
  if (!missing_tables.empty()) {
    throw StoreError(path,
                     "corrupt keyframe store: table " + missing_tables.front() + " is missing");
  }
}

}  // namespace

void check_keyframe_store(const std::string& path, std::uintmax_t file_size) {
  check_file_header(path, file_size);
  check_is_keyframe_store(path);
}

void create_schema(sqlite3* db, const std::string& path, int page_size) {
  // Takes effect only in an empty database, before its first table.
  exec(db, path, ("PRAGMA page_size = " + std::to_string(page_size)).c_str());
  Transaction tx(db, path);
  if (query_int(db, path, "SELECT count(*) FROM sqlite_master") != 0) {
    throw StoreError(path, "was initialised by another connection while being created; reopen it");
  }
  exec(db, path, kSchema);
  exec(db, path, kSchemaV2);
  exec(db, path, kSchemaV3);
  exec(db, path,
       ("PRAGMA application_id = " + std::to_string(KeyframeStore::kApplicationId)).c_str());
  exec(db, path,
       ("PRAGMA user_version = " + std::to_string(KeyframeStore::kSchemaVersion)).c_str());
  tx.commit();
}

int schema_version(sqlite3* db, const std::string& path) {
  return static_cast<int>(query_int(db, path, "PRAGMA user_version"));
}

void migrate_schema(sqlite3* db, const std::string& path) {
  const int version = schema_version(db, path);
  if (version >= KeyframeStore::kSchemaVersion) return;
  Transaction tx(db, path);
  if (version < 2) {
    exec(db, path, kSchemaV2);
    exec(db, path,
         "INSERT INTO nodes (stream, id, stamp_ns, voxel_size, pose, covariance, descriptor) "
         "SELECT stream, id, stamp_ns, voxel_size, pose, covariance, NULL FROM keyframes");
  }
  exec(db, path, kSchemaV3);
  exec(db, path,
       ("PRAGMA user_version = " + std::to_string(KeyframeStore::kSchemaVersion)).c_str());
  tx.commit();
}

}  // namespace litamin2::store
