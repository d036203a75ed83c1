#pragma once
// Thin RAII wrappers over the SQLite C API (in the spirit of SQLiteCpp). Only code inside
// server/storage/ uses them; sqlite3.h stays out of every header.
//
// Errors the database reports at run time (busy, constraint, I/O, corrupt file) come back as
// Expected values with code "storage"; misuse (binding a bad index) is a CHECK failure.

#include <cstdint>
#include <string>
#include <string_view>

#include "common/error/expected.h"

struct sqlite3;
struct sqlite3_stmt;

namespace reenact::server::sqlite {

class Statement;

// When a connection's commits reach the disk (its PRAGMA synchronous, in WAL mode).
enum class Sync {
  // synchronous=FULL: every commit fsyncs the WAL before it returns, so a committed
  // transaction survives a power failure.
  kFull,
  // synchronous=NORMAL: the WAL is synced only at checkpoints; a committed transaction
  // survives a crash of the process, but the last ones can be lost on power failure.
  kNormal,
};

// One connection. Open() turns on WAL journaling, foreign keys and a busy timeout.
class Database {
 public:
  // Opens (creating if needed) the file at `path`. A file it creates has mode 0600 (owner
  // read/write) whatever the umask, and so have the -wal and -shm files SQLite creates
  // beside it; an existing file keeps its mode. A path whose directory does not exist is an
  // error naming the directory. sync: see Sync. busy_timeout_ms: how long a writer waits for
  // a lock.
  static Expected<Database> Open(const std::string& path, Sync sync = Sync::kFull,
                                 int busy_timeout_ms = 5000);

  Database(Database&& other) noexcept;
  Database& operator=(Database&& other) noexcept;
  Database(const Database&) = delete;
  Database& operator=(const Database&) = delete;
  ~Database();

  // Runs one or more statements that return no rows.
  Status Exec(std::string_view sql);
  // Compiles one statement.
  Expected<Statement> Prepare(std::string_view sql);

  int64_t LastInsertRowId() const;
  // Rows changed by the last INSERT/UPDATE/DELETE.
  int Changes() const;
  const std::string& path() const { return path_; }
  // The underlying connection, for code in server/storage/ that needs the C API.
  sqlite3* raw() const { return db_; }

 private:
  Database(sqlite3* db, std::string path) : db_(db), path_(std::move(path)) {}
  Error LastError(std::string_view what) const;

  sqlite3* db_ = nullptr;
  std::string path_;
};

// One compiled statement. Parameters are 1-based, columns 0-based (as in SQLite).
class Statement {
 public:
  Statement(Statement&& other) noexcept;
  Statement& operator=(Statement&& other) noexcept;
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;
  ~Statement();

  Statement& Bind(int index, int64_t value);
  Statement& Bind(int index, int value) { return Bind(index, static_cast<int64_t>(value)); }
  Statement& Bind(int index, double value);
  Statement& BindText(int index, std::string_view value);
  Statement& BindBlob(int index, std::string_view bytes);
  // As BindBlob, but SQLite reads the bytes in place instead of copying them first: they
  // must stay valid and unchanged until the statement is run and reset or destroyed.
  Statement& BindBlobInPlace(int index, std::string_view bytes);
  Statement& BindNull(int index);

  // Advances: true when a row is available, false when done.
  Expected<bool> Step();
  // Steps to completion, for statements that return no rows.
  Status Run();
  // Clears the bindings' results so the statement can run again (bindings are kept).
  void Reset();

  bool IsNull(int column) const;
  int64_t ColumnInt(int column) const;
  double ColumnDouble(int column) const;
  std::string ColumnText(int column) const;
  std::string ColumnBlob(int column) const;

 private:
  friend class Database;
  Statement(sqlite3_stmt* stmt, sqlite3* db) : stmt_(stmt), db_(db) {}

  sqlite3_stmt* stmt_ = nullptr;
  sqlite3* db_ = nullptr;
};

// BEGIN IMMEDIATE on construction via Begin(); rolls back on destruction unless committed.
class Transaction {
 public:
  static Expected<Transaction> Begin(Database& db);

  Transaction(Transaction&& other) noexcept;
  Transaction& operator=(Transaction&&) = delete;
  Transaction(const Transaction&) = delete;
  Transaction& operator=(const Transaction&) = delete;
  ~Transaction();

  Status Commit();

 private:
  explicit Transaction(Database* db) : db_(db) {}
  Database* db_ = nullptr;  // null once committed or moved from
};

}  // namespace reenact::server::sqlite
