// A thin RAII layer over SQLite: one connection, prepared statements, typed
// errors. Only storage/ sees it.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>

struct sqlite3;
struct sqlite3_stmt;

namespace rrlab::storage {

// What kind of failure a StorageError is. full: the disk (or the file's
// page limit) is full (SQLITE_FULL, or an I/O error with ENOSPC);
// readonly: the file or its directory cannot be written (SQLITE_READONLY*,
// SQLITE_CANTOPEN on a write). Reads keep working in both.
enum class StorageFault { other, full, readonly };

const char* to_string(StorageFault fault);  // "other" | "full" | "readonly"

class StorageError : public std::runtime_error {
 public:
  explicit StorageError(const std::string& what, StorageFault fault = StorageFault::other)
      : std::runtime_error(what), fault_(fault) {}
  StorageFault fault() const { return fault_; }
  // full or readonly: the write may succeed once space is freed or permissions fixed
  bool write_fault() const { return fault_ != StorageFault::other; }

 private:
  StorageFault fault_;
};

// The fault a SQLite result code (extended or primary) stands for, with the
// OS errno of the failed call for I/O errors (ENOSPC: full).
StorageFault fault_of(int sqlite_code, int system_errno = 0);

// Now in UTC, ISO 8601 (the created columns).
std::string utc_now();

class Statement {
 public:
  Statement(sqlite3* db, std::string_view sql);
  ~Statement();
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;
  Statement(Statement&& other) noexcept;

  Statement& bind(int index, double value);
  Statement& bind(int index, std::int64_t value);
  Statement& bind(int index, int value) { return bind(index, std::int64_t(value)); }
  Statement& bind(int index, std::string_view text);
  Statement& bind_blob(int index, std::string_view bytes);
  Statement& bind_null(int index);
  // true: a row is ready; false: done. Throws StorageError.
  bool step();
  void reset();  // also clears bindings

  bool is_null(int column) const;
  double column_double(int column) const;
  std::int64_t column_int(int column) const;
  std::string column_text(int column) const;
  std::string_view column_blob(int column) const;

 private:
  sqlite3* db_;
  sqlite3_stmt* stmt_ = nullptr;
};

class Database {
 public:
  explicit Database(const std::string& path);  // creates the file if missing
  ~Database();
  Database(const Database&) = delete;
  Database& operator=(const Database&) = delete;

  void exec(std::string_view sql);
  Statement prepare(std::string_view sql) { return Statement(db_, sql); }
  std::int64_t last_insert_id() const;
  int changes() const;  // rows changed by the last statement
  sqlite3* handle() const { return db_; }

 private:
  sqlite3* db_ = nullptr;
};

// BEGIN ... COMMIT, rolled back if left by an exception.
class Transaction {
 public:
  explicit Transaction(Database& db);
  ~Transaction();
  void commit();

 private:
  Database& db_;
  bool done_ = false;
};

}  // namespace rrlab::storage
