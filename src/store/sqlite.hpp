#pragma once
/// Thin RAII wrappers of the SQLite C API as the keyframe store uses it: connections,
/// prepared statements, transactions and typed column readers. Every failure is a StoreError
/// naming the store file and SQLite's reason. Private to the store (the public headers do not
/// include sqlite3.h).

#include <sqlite3.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>

namespace litamin2::store {

/// Throws StoreError(path, "<context>: <SQLite's message of db>").
[[noreturn]] void throw_sqlite(sqlite3* db, const std::string& path, const std::string& context);

/// Closes a connection (sqlite3_close_v2).
struct ConnectionCloser {
  void operator()(sqlite3* db) const { sqlite3_close_v2(db); }
};
/// An open database connection, closed on destruction.
using Connection = std::unique_ptr<sqlite3, ConnectionCloser>;

/// Opens `path` with the sqlite3_open_v2 `flags` (no mutex: one thread per connection) and
/// extended result codes.
Connection open_connection(const std::string& path, int flags);

/// Runs one or more SQL statements that return no rows.
void exec(sqlite3* db, const std::string& path, const char* sql);

/// A prepared statement, finalised on destruction.
class Statement {
 public:
  /// Prepares `sql` (persistent: the statement is meant to be reused). `path` names the store
  /// in errors and must outlive the statement.
  Statement(sqlite3* db, const std::string& path, const char* sql);
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;
  ~Statement();

  /// The SQLite statement, for reading columns.
  sqlite3_stmt* get() const { return stmt_; }

  /// Steps once: true if a row is available, false when done. Throws on error, naming
  /// `context`.
  bool step(const std::string& context);
  /// Resets the statement and clears its bindings.
  void reset();

  /// Binds parameter i (1-based).
  void bind(int i, std::int64_t v);
  /// Binds parameter i (1-based).
  void bind(int i, double v);
  /// Binds parameter i to text without copying it: `s` must outlive the step.
  void bind_text(int i, const std::string& s);
  /// Binds parameter i to a BLOB without copying it (large BLOBs): `s` must outlive the step.
  void bind_blob(int i, const std::string& s);

 private:
  sqlite3* db_;
  const std::string* path_;
  sqlite3_stmt* stmt_ = nullptr;
};

/// Resets a statement (and clears its bindings) when leaving the scope that used it.
struct ResetOnExit {
  Statement& statement;
  ~ResetOnExit() { statement.reset(); }
};

/// BEGIN IMMEDIATE ... COMMIT, rolled back if commit() is not reached.
class Transaction {
 public:
  /// Begins the transaction. `path` names the store in errors and must outlive it.
  Transaction(sqlite3* db, const std::string& path);
  Transaction(const Transaction&) = delete;
  Transaction& operator=(const Transaction&) = delete;
  /// Rolls back unless committed.
  ~Transaction();
  /// Commits.
  void commit();

 private:
  sqlite3* db_;
  const std::string& path_;
  bool done_ = false;
};

/// The integer in the first column of the first row `sql` returns; throws if there is none.
std::int64_t query_int(sqlite3* db, const std::string& path, const char* sql);

// Column readers of a row being loaded; they throw std::invalid_argument (turned into a
// StoreError naming the row by the caller) when the stored value has the wrong type. `name`
// is the column's name in that message.

/// The TEXT at column i.
std::string column_text(sqlite3_stmt* s, int i, const char* name);
/// The INTEGER at column i.
std::int64_t column_int(sqlite3_stmt* s, int i, const char* name);
/// The non-negative INTEGER at column i (a keyframe id).
std::uint64_t column_id(sqlite3_stmt* s, int i, const char* name);
/// The REAL (or INTEGER) at column i.
double column_real(sqlite3_stmt* s, int i, const char* name);
/// The BLOB at column i: {data, size}. Pointer valid until the next step.
std::pair<const void*, std::size_t> column_blob(sqlite3_stmt* s, int i, const char* name);

}  // namespace litamin2::store
