#pragma once
/// The keyframe store's file format: the SQLite schema (tables keyframes, loop_edges,
/// corrected_poses, nodes, tiles, pending_merges) with the store's application_id and schema
/// version, its creation, and the checks that refuse a file that is not a keyframe store before
/// anything writes to it. Private to the store.

#include <cstdint>
#include <string>

struct sqlite3;

namespace litamin2::store {

/// Throws StoreError unless the existing non-empty file at `path` (of `file_size` bytes) is a
/// whole keyframe store of this build's schema version: first from its SQLite header, read as
/// a plain file (not SQLite, truncated, another application's database, another version),
/// then through a read-only SQLite connection (readable, every table present). Writes nothing.
void check_keyframe_store(const std::string& path, std::uintmax_t file_size);

/// Creates the schema in a new (missing or empty) file, in one transaction: a crash leaves
/// either an empty file or a complete store. Run in the default rollback-journal mode;
/// the caller switches to WAL afterwards. `page_size`: bytes of an SQLite page.
void create_schema(sqlite3* db, const std::string& path, int page_size);

/// The file's schema version (PRAGMA user_version).
int schema_version(sqlite3* db, const std::string& path);

/// Upgrades an older store to this build's version in one transaction: from version 1 the
/// nodes table (filled from the keyframes, descriptors NULL) and the tiles table, from 1 or 2
/// the pending_merges table (empty). No-op on the current version.
void migrate_schema(sqlite3* db, const std::string& path);

}  // namespace litamin2::store
