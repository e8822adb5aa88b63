#include "sqlite.hpp"

#include <stdexcept>

#include "litamin2/store/store_error.hpp"

namespace litamin2::store {

void throw_sqlite(sqlite3* db, const std::string& path, const std::string& context) {
  throw StoreError(path, context + ": " + (db ? sqlite3_errmsg(db) : "out of memory"));
}

Connection open_connection(const std::string& path, int flags) {
  sqlite3* raw = nullptr;
  const int rc = sqlite3_open_v2(path.c_str(), &raw, flags | SQLITE_OPEN_NOMUTEX, nullptr);
  Connection db(raw);
  if (rc != SQLITE_OK) throw_sqlite(db.get(), path, "cannot open");
  sqlite3_extended_result_codes(db.get(), 1);
  return db;
}

void exec(sqlite3* db, const std::string& path, const char* sql) {
  if (sqlite3_exec(db, sql, nullptr, nullptr, nullptr) != SQLITE_OK) {
    throw_sqlite(db, path, std::string("'") + sql + "' failed");
  }
}

Statement::Statement(sqlite3* db, const std::string& path, const char* sql)
    : db_(db), path_(&path) {
  if (sqlite3_prepare_v3(db, sql, -1, SQLITE_PREPARE_PERSISTENT, &stmt_, nullptr) != SQLITE_OK) {
    throw_sqlite(db, path, std::string("cannot prepare '") + sql + "'");
  }
}

Statement::~Statement() {
  sqlite3_finalize(stmt_);
}

bool Statement::step(const std::string& context) {
  const int rc = sqlite3_step(stmt_);
  if (rc == SQLITE_ROW) return true;
  if (rc == SQLITE_DONE) return false;
  throw_sqlite(db_, *path_, context);
}

void Statement::reset() {
  sqlite3_reset(stmt_);
  sqlite3_clear_bindings(stmt_);
}

void Statement::bind(int i, std::int64_t v) {
  sqlite3_bind_int64(stmt_, i, v);
}
void Statement::bind(int i, double v) {
  sqlite3_bind_double(stmt_, i, v);
}
// SQLITE_STATIC: no copy of large BLOBs; the caller keeps the bytes alive until the step.
void Statement::bind_text(int i, const std::string& s) {
  sqlite3_bind_text(stmt_, i, s.data(), static_cast<int>(s.size()), SQLITE_STATIC);
}
void Statement::bind_blob(int i, const std::string& s) {
  sqlite3_bind_blob(stmt_, i, s.data(), static_cast<int>(s.size()), SQLITE_STATIC);
}

Transaction::Transaction(sqlite3* db, const std::string& path) : db_(db), path_(path) {
  exec(db_, path_, "BEGIN IMMEDIATE");
}

Transaction::~Transaction() {
  if (!done_) sqlite3_exec(db_, "ROLLBACK", nullptr, nullptr, nullptr);
}

void Transaction::commit() {
  exec(db_, path_, "COMMIT");
  done_ = true;
}

std::int64_t query_int(sqlite3* db, const std::string& path, const char* sql) {
  Statement s(db, path, sql);
  if (!s.step(std::string("'") + sql + "' failed")) {
    throw StoreError(path, std::string("'") + sql + "' returned no row");
  }
  return sqlite3_column_int64(s.get(), 0);
}

std::string column_text(sqlite3_stmt* s, int i, const char* name) {
  if (sqlite3_column_type(s, i) != SQLITE_TEXT) {
    throw std::invalid_argument(std::string(name) + " is not text");
  }
  const auto* text = reinterpret_cast<const char*>(sqlite3_column_text(s, i));
  return std::string(text, static_cast<std::size_t>(sqlite3_column_bytes(s, i)));
}

std::int64_t column_int(sqlite3_stmt* s, int i, const char* name) {
  if (sqlite3_column_type(s, i) != SQLITE_INTEGER) {
    throw std::invalid_argument(std::string(name) + " is not an integer");
  }
  return sqlite3_column_int64(s, i);
}

std::uint64_t column_id(sqlite3_stmt* s, int i, const char* name) {
  const std::int64_t id = column_int(s, i, name);
  if (id < 0) throw std::invalid_argument(std::string(name) + " is negative");
  return static_cast<std::uint64_t>(id);
}

double column_real(sqlite3_stmt* s, int i, const char* name) {
  const int type = sqlite3_column_type(s, i);
  if (type != SQLITE_FLOAT && type != SQLITE_INTEGER) {
    throw std::invalid_argument(std::string(name) + " is not a number");
  }
  return sqlite3_column_double(s, i);
}

std::pair<const void*, std::size_t> column_blob(sqlite3_stmt* s, int i, const char* name) {
  if (sqlite3_column_type(s, i) != SQLITE_BLOB) {
    throw std::invalid_argument(std::string(name) + " is not a blob");
  }
  const void* data = sqlite3_column_blob(s, i);
  return {data, static_cast<std::size_t>(sqlite3_column_bytes(s, i))};
}

}  // namespace litamin2::store
