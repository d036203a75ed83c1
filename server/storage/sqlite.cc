#include "server/storage/sqlite.h"

#include <fcntl.h>
#include <sqlite3.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <utility>

namespace reenact::server::sqlite {

namespace {

Error StorageError(std::string_view what, std::string_view detail) {
  return MakeError("storage", std::string(what) + ": " + std::string(detail));
}

// Creates `path` empty with mode 0600 unless it exists. SQLite creates the -wal and -shm
// files with the mode of the database file, so they are private too.
Status CreatePrivateFile(const std::string& path) {
  const int fd = ::open(path.c_str(), O_CREAT | O_EXCL | O_RDWR | O_CLOEXEC, 0600);
  if (fd < 0) {
    if (errno == EEXIST) return {};  // exists already (or another process just created it)
    return MakeError("io", "cannot create database " + path + ": " + std::strerror(errno));
  }
  // open() applied the umask; a umask that removes owner bits must not lock the owner out.
  if (::fchmod(fd, 0600) != 0) {
    const int error = errno;
    ::close(fd);
    return MakeError("io", "cannot set mode 0600 on database " + path + ": " +
                               std::strerror(error));
  }
  ::close(fd);
  return {};
}

}  // namespace

Expected<Database> Database::Open(const std::string& path, Sync sync, int busy_timeout_ms) {
  REENACT_CHECK(busy_timeout_ms >= 0, "busy timeout must be >= 0");
  const std::filesystem::path file(path);
  const std::filesystem::path dir = file.has_parent_path() ? file.parent_path() : ".";
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) {
    return MakeError("io", "cannot open database " + path + ": directory " + dir.string() +
                               " does not exist; create it first");
  }
  if (Status s = CreatePrivateFile(path); !s) return s.error();
  sqlite3* db = nullptr;
  const int rc = sqlite3_open_v2(path.c_str(), &db,
                                 SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE |
                                     SQLITE_OPEN_NOMUTEX,
                                 nullptr);
  if (rc != SQLITE_OK) {
    std::string detail = db ? sqlite3_errmsg(db) : sqlite3_errstr(rc);
    sqlite3_close(db);
    return MakeError("io", "cannot open database " + path + ": " + detail);
  }
  Database database(db, path);
  sqlite3_busy_timeout(db, busy_timeout_ms);
  sqlite3_extended_result_codes(db, 1);
  const char* synchronous =
      sync == Sync::kFull ? "PRAGMA synchronous = FULL" : "PRAGMA synchronous = NORMAL";
  for (const char* pragma : {"PRAGMA journal_mode = WAL", "PRAGMA foreign_keys = ON",
                             synchronous}) {
    auto stmt = database.Prepare(pragma);
    if (!stmt) return MakeError("io", "cannot open database " + path + ": " + stmt.error().message);
    for (;;) {
      auto row = stmt->Step();
      if (!row) return MakeError("io", "cannot open database " + path + ": " + row.error().message);
      if (!*row) break;
    }
  }
  return database;
}

Database::Database(Database&& other) noexcept
    : db_(std::exchange(other.db_, nullptr)), path_(std::move(other.path_)) {}

Database& Database::operator=(Database&& other) noexcept {
  if (this != &other) {
    sqlite3_close_v2(db_);
    db_ = std::exchange(other.db_, nullptr);
    path_ = std::move(other.path_);
  }
  return *this;
}

Database::~Database() { sqlite3_close_v2(db_); }

Error Database::LastError(std::string_view what) const {
  return StorageError(what, sqlite3_errmsg(db_));
}

Status Database::Exec(std::string_view sql) {
  REENACT_CHECK(db_ != nullptr, "Exec on a closed database");
  const std::string text(sql);
  char* message = nullptr;
  if (sqlite3_exec(db_, text.c_str(), nullptr, nullptr, &message) != SQLITE_OK) {
    Error error = StorageError("exec failed", message ? message : sqlite3_errmsg(db_));
    sqlite3_free(message);
    return error;
  }
  return {};
}

Expected<Statement> Database::Prepare(std::string_view sql) {
  REENACT_CHECK(db_ != nullptr, "Prepare on a closed database");
  sqlite3_stmt* stmt = nullptr;
  if (sqlite3_prepare_v2(db_, sql.data(), static_cast<int>(sql.size()), &stmt, nullptr) !=
      SQLITE_OK) {
    return LastError("prepare failed");
  }
  return Statement(stmt, db_);
}

int64_t Database::LastInsertRowId() const { return sqlite3_last_insert_rowid(db_); }

int Database::Changes() const { return sqlite3_changes(db_); }

Statement::Statement(Statement&& other) noexcept
    : stmt_(std::exchange(other.stmt_, nullptr)), db_(other.db_) {}

Statement& Statement::operator=(Statement&& other) noexcept {
  if (this != &other) {
    sqlite3_finalize(stmt_);
    stmt_ = std::exchange(other.stmt_, nullptr);
    db_ = other.db_;
  }
  return *this;
}

Statement::~Statement() { sqlite3_finalize(stmt_); }

Statement& Statement::Bind(int index, int64_t value) {
  REENACT_CHECK(sqlite3_bind_int64(stmt_, index, value) == SQLITE_OK, "bad bind index");
  return *this;
}

Statement& Statement::Bind(int index, double value) {
  REENACT_CHECK(sqlite3_bind_double(stmt_, index, value) == SQLITE_OK, "bad bind index");
  return *this;
}

Statement& Statement::BindText(int index, std::string_view value) {
  REENACT_CHECK(sqlite3_bind_text64(stmt_, index, value.data(), value.size(), SQLITE_TRANSIENT,
                                    SQLITE_UTF8) == SQLITE_OK,
                "bad bind index");
  return *this;
}

Statement& Statement::BindBlob(int index, std::string_view bytes) {
  REENACT_CHECK(sqlite3_bind_blob64(stmt_, index, bytes.data(), bytes.size(), SQLITE_TRANSIENT) ==
                    SQLITE_OK,
                "bad bind index");
  return *this;
}

Statement& Statement::BindBlobInPlace(int index, std::string_view bytes) {
  REENACT_CHECK(
      sqlite3_bind_blob64(stmt_, index, bytes.data(), bytes.size(), SQLITE_STATIC) == SQLITE_OK,
      "bad bind index");
  return *this;
}

Statement& Statement::BindNull(int index) {
  REENACT_CHECK(sqlite3_bind_null(stmt_, index) == SQLITE_OK, "bad bind index");
  return *this;
}

Expected<bool> Statement::Step() {
  const int rc = sqlite3_step(stmt_);
  if (rc == SQLITE_ROW) return true;
  if (rc == SQLITE_DONE) return false;
  return StorageError("step failed", sqlite3_errmsg(db_));
}

Status Statement::Run() {
  for (;;) {
    auto row = Step();
    if (!row) return row.error();
    if (!*row) return {};
  }
}

void Statement::Reset() { sqlite3_reset(stmt_); }

bool Statement::IsNull(int column) const {
  return sqlite3_column_type(stmt_, column) == SQLITE_NULL;
}

int64_t Statement::ColumnInt(int column) const { return sqlite3_column_int64(stmt_, column); }

double Statement::ColumnDouble(int column) const { return sqlite3_column_double(stmt_, column); }

std::string Statement::ColumnText(int column) const {
  const auto* text = sqlite3_column_text(stmt_, column);
  const int size = sqlite3_column_bytes(stmt_, column);
  return text ? std::string(reinterpret_cast<const char*>(text), size) : std::string();
}

std::string Statement::ColumnBlob(int column) const {
  const void* data = sqlite3_column_blob(stmt_, column);
  const int size = sqlite3_column_bytes(stmt_, column);
  return data ? std::string(static_cast<const char*>(data), size) : std::string();
}

Expected<Transaction> Transaction::Begin(Database& db) {
  if (Status s = db.Exec("BEGIN IMMEDIATE"); !s) return s.error();
  return Transaction(&db);
}

Transaction::Transaction(Transaction&& other) noexcept : db_(std::exchange(other.db_, nullptr)) {}

Transaction::~Transaction() {
  if (db_ != nullptr) (void)db_->Exec("ROLLBACK");
}

Status Transaction::Commit() {
  REENACT_CHECK(db_ != nullptr, "Commit of a finished transaction");
  Status s = db_->Exec("COMMIT");
  if (s) db_ = nullptr;
  return s;
}

}  // namespace reenact::server::sqlite
