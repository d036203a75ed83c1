#pragma once
// Thin RAII wrappers over libpq, the PostgreSQL client library. Only code inside
// server/storage/ (and its tests) uses them; libpq-fe.h stays out of every header.
//
// Parameters travel as text ($1, $2, ... in the SQL) except those given as bytes, which travel
// in binary (for BYTEA). Errors the server reports at run time come back as Expected values
// with code "storage" and the SQLSTATE kept apart, so callers can tell a unique violation
// (23505) from other failures; misuse (a bad row or column index) is a CHECK failure.
//
// A server that went away (stopped, restarted, the network cut) gives code "unavailable"
// instead, for every statement until it runs again; the connection is reopened before the
// next statement outside a transaction, so the same Connection works again once the server
// is back. A transaction cut part way is never resumed on a new session: its remaining
// statements and its COMMIT fail "unavailable", and PostgreSQL discards all it wrote.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "common/error/expected.h"

struct pg_conn;
struct pg_result;

namespace reenact::server::pg {

// SQLSTATE of a unique constraint violation.
inline constexpr std::string_view kUniqueViolation = "23505";

// Where a connection string points, without its password: "database D as user U on H:P".
// Code "invalid_argument" when `url` is not a libpq connection string or URI.
Expected<std::string> DescribeTarget(const std::string& url);

// The connection string `url` aimed at database `dbname` instead, as key=value pairs (for
// tools and tests that create databases). Code "invalid_argument" for a malformed URL.
Expected<std::string> WithDatabase(const std::string& url, const std::string& dbname);

// The connection string `conninfo` (key=value pairs or a URL) as an equivalent
// postgresql:// URL, every setting a percent-encoded query parameter (for places that take
// URLs only, such as reenact-server --db). Code "invalid_argument" for a malformed string.
Expected<std::string> AsUrl(const std::string& conninfo);

// Seconds a connection (or its reopening) may take unless the URL sets connect_timeout, so a
// database host that stopped answering costs a request at most this long.
inline constexpr int kDefaultConnectTimeoutSeconds = 10;

// One statement parameter: text, binary bytes, or NULL.
struct Param {
  Param(std::string_view text) : value(text) {}  // NOLINT: implicit by design
  Param(const char* text) : value(text) {}        // NOLINT: implicit by design
  Param(const std::string& text) : value(text) {}  // NOLINT: implicit by design
  Param(int64_t number);                           // NOLINT: implicit by design
  Param(int number) : Param(static_cast<int64_t>(number)) {}  // NOLINT: implicit by design
  Param(double number);                            // NOLINT: implicit by design
  static Param Bytes(std::string_view bytes);
  static Param Null();

  std::optional<std::string> value;  // nullopt: SQL NULL
  bool binary = false;

 private:
  Param() = default;
};

// The rows of one statement. Rows and columns are 0-based.
class Result {
 public:
  Result(Result&& other) noexcept;
  Result& operator=(Result&& other) noexcept;
  Result(const Result&) = delete;
  Result& operator=(const Result&) = delete;
  ~Result();

  int rows() const;
  // Rows an INSERT/UPDATE/DELETE changed.
  int64_t affected() const;

  bool IsNull(int row, int column) const;
  std::string Text(int row, int column) const;  // the bytes as sent (binary results too)
  int64_t Int(int row, int column) const;  // an integer column ("t"/"f" of a boolean: 1/0)
  double Double(int row, int column) const;
  // A BYTEA column of a text-format result, decoded.
  std::string Bytes(int row, int column) const;

 private:
  friend class Connection;
  explicit Result(pg_result* result) : result_(result) {}
  pg_result* result_ = nullptr;
};

// One connection; not thread-safe (one thread at a time).
class Connection {
 public:
  // Connects to `url` (postgresql://user:password@host:port/database, or key=value pairs).
  // code "invalid_argument" for a malformed URL; "io" when the server cannot be reached or
  // refuses the login, with one line naming the target (never the password) and the reason.
  static Expected<Connection> Open(const std::string& url);

  Connection(Connection&& other) noexcept;
  Connection& operator=(Connection&& other) noexcept;
  Connection(const Connection&) = delete;
  Connection& operator=(const Connection&) = delete;
  ~Connection();

  // Runs one or more statements without parameters (a migration file).
  Status Exec(const std::string& sql);
  // Runs one statement with parameters. binary_result: every column comes back in binary
  // (for reading one BYTEA column as raw bytes with Result::Text). The first
  // kMaxPreparedStatements distinct statements are prepared once per session and executed by
  // name after that (no parse and plan per call); any further one is sent whole each time.
  Expected<Result> Query(const std::string& sql, const std::vector<Param>& params = {},
                         bool binary_result = false);
  // The SQLSTATE of the last failed Exec or Query ("" when it succeeded or the connection
  // itself failed).
  const std::string& last_sqlstate() const { return last_sqlstate_; }

  // "database D as user U on H:P".
  const std::string& target() const { return target_; }

 private:
  Connection(pg_conn* conn, std::string target) : conn_(conn), target_(std::move(target)) {}
  friend class Transaction;
  Error Fail(std::string_view what, pg_result* result);
  // Reconnects a connection the server dropped or is closing (read from the socket without
  // waiting), unless a transaction was open on it.
  void ReconnectIfBroken();

  static constexpr size_t kMaxPreparedStatements = 64;

  pg_conn* conn_ = nullptr;
  std::string target_;
  std::string last_sqlstate_;
  bool in_transaction_ = false;
  std::unordered_map<std::string, std::string> prepared_;  // statement text -> name
};

// BEGIN on construction via Begin(); ROLLBACK on destruction unless committed.
class Transaction {
 public:
  static Expected<Transaction> Begin(Connection& db);

  Transaction(Transaction&& other) noexcept;
  Transaction& operator=(Transaction&&) = delete;
  Transaction(const Transaction&) = delete;
  Transaction& operator=(const Transaction&) = delete;
  ~Transaction();

  Status Commit();

 private:
  explicit Transaction(Connection* db) : db_(db) {}
  Connection* db_ = nullptr;  // null once committed or moved from
};

}  // namespace reenact::server::pg
