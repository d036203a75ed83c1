#include "server/storage/postgres.h"

#include <libpq-fe.h>
#include <poll.h>

#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>
#include <utility>

namespace reenact::server::pg {

namespace {

// libpq's messages span lines ("connection to server ... failed: FATAL:  ...\n"): one line.
std::string OneLine(const char* message) {
  std::string out;
  for (const char* p = message ? message : ""; *p; ++p) {
    if (*p == '\n' || *p == '\r' || *p == '\t') {
      if (!out.empty() && out.back() != ' ') out += "; ";
    } else if (*p == ' ' && !out.empty() && out.back() == ' ') {
      continue;
    } else {
      out += *p;
    }
  }
  while (!out.empty() && (out.back() == ' ' || out.back() == ';')) out.pop_back();
  return out.empty() ? "unknown error" : out;
}

void IgnoreNotice(void*, const char*) {}

// SQLSTATEs of a server that cannot serve this session: class 08 (connection exception),
// 57P01 admin_shutdown, 57P02 crash_shutdown, 57P03 cannot_connect_now.
bool IsUnavailableState(std::string_view state) {
  return state.substr(0, 2) == "08" || state == "57P01" || state == "57P02" || state == "57P03";
}

}  // namespace

Expected<std::string> DescribeTarget(const std::string& url) {
  char* parse_error = nullptr;
  PQconninfoOption* options = PQconninfoParse(url.c_str(), &parse_error);
  if (!options) {
    std::string detail = parse_error ? OneLine(parse_error) : "out of memory";
    PQfreemem(parse_error);
    return MakeError("invalid_argument",
                     "invalid PostgreSQL URL: " + detail +
                         "; expected postgresql://user:password@host:port/database");
  }
  std::string dbname, user, host, port;
  for (PQconninfoOption* o = options; o->keyword; ++o) {
    if (!o->val || !*o->val) continue;
    const std::string key = o->keyword;
    if (key == "dbname") dbname = o->val;
    if (key == "user") user = o->val;
    if (key == "host" || (key == "hostaddr" && host.empty())) host = o->val;
    if (key == "port") port = o->val;
  }
  PQconninfoFree(options);
  std::string target = "database '" + (dbname.empty() ? user : dbname) + "'";
  if (!user.empty()) target += " as user '" + user + "'";
  if (host.empty()) host = "the default socket";
  target += " on " + host;
  if (!port.empty()) target += ":" + port;
  return target;
}

Expected<std::string> AsUrl(const std::string& conninfo) {
  char* parse_error = nullptr;
  PQconninfoOption* options = PQconninfoParse(conninfo.c_str(), &parse_error);
  if (!options) {
    std::string detail = parse_error ? OneLine(parse_error) : "out of memory";
    PQfreemem(parse_error);
    return MakeError("invalid_argument", "invalid PostgreSQL URL: " + detail);
  }
  constexpr char kHex[] = "0123456789ABCDEF";
  std::string url = "postgresql:///";
  char separator = '?';
  for (PQconninfoOption* o = options; o->keyword; ++o) {
    if (!o->val) continue;
    url += separator;
    separator = '&';
    url += o->keyword;
    url += '=';
    for (unsigned char c : std::string_view(o->val)) {
      if (std::isalnum(c) || c == '-' || c == '.' || c == '_' || c == '~' || c == '/') {
        url += static_cast<char>(c);
      } else {
        url += '%';
        url += kHex[c >> 4];
        url += kHex[c & 15];
      }
    }
  }
  PQconninfoFree(options);
  return url;
}

Expected<std::string> WithDatabase(const std::string& url, const std::string& dbname) {
  char* parse_error = nullptr;
  PQconninfoOption* options = PQconninfoParse(url.c_str(), &parse_error);
  if (!options) {
    std::string detail = parse_error ? OneLine(parse_error) : "out of memory";
    PQfreemem(parse_error);
    return MakeError("invalid_argument", "invalid PostgreSQL URL: " + detail);
  }
  // Built step by step: GCC 12 misreports one-line concatenations (-Werror=restrict).
  auto append = [](std::string& out, const char* key, const std::string& value) {
    if (!out.empty()) out += ' ';
    out += key;
    out += "='";
    for (char c : value) {
      if (c == '\\' || c == '\'') out += '\\';
      out += c;
    }
    out += '\'';
  };
  std::string conninfo;
  append(conninfo, "dbname", dbname);
  for (PQconninfoOption* o = options; o->keyword; ++o) {
    if (!o->val || std::string(o->keyword) == "dbname") continue;
    append(conninfo, o->keyword, o->val);
  }
  PQconninfoFree(options);
  return conninfo;
}

Param::Param(int64_t number) : value(std::to_string(number)) {}

Param::Param(double number) {
  if (std::isnan(number)) {
    value = "NaN";
  } else if (std::isinf(number)) {
    value = number > 0 ? "Infinity" : "-Infinity";
  } else {
    char buffer[64];
    // Shortest text that reads back as the same double (PostgreSQL's float8 input is exact).
    auto [end, ec] = std::to_chars(buffer, buffer + sizeof(buffer), number);
    REENACT_CHECK(ec == std::errc(), "double to text failed");
    value = std::string(buffer, end);
  }
}

Param Param::Bytes(std::string_view bytes) {
  Param p;
  p.value = std::string(bytes);
  p.binary = true;
  return p;
}

Param Param::Null() { return Param(); }

Result::Result(Result&& other) noexcept : result_(std::exchange(other.result_, nullptr)) {}

Result& Result::operator=(Result&& other) noexcept {
  if (this != &other) {
    PQclear(result_);
    result_ = std::exchange(other.result_, nullptr);
  }
  return *this;
}

Result::~Result() { PQclear(result_); }

int Result::rows() const { return PQntuples(result_); }

int64_t Result::affected() const {
  const char* n = PQcmdTuples(result_);
  int64_t value = 0;
  if (n && *n) std::from_chars(n, n + std::char_traits<char>::length(n), value);
  return value;
}

bool Result::IsNull(int row, int column) const {
  REENACT_CHECK(row >= 0 && row < PQntuples(result_) && column >= 0 && column < PQnfields(result_),
                "result cell out of range");
  return PQgetisnull(result_, row, column) != 0;
}

std::string Result::Text(int row, int column) const {
  if (IsNull(row, column)) return {};
  return std::string(PQgetvalue(result_, row, column),
                     static_cast<size_t>(PQgetlength(result_, row, column)));
}

int64_t Result::Int(int row, int column) const {
  const std::string text = Text(row, column);
  if (text == "t") return 1;
  if (text == "f") return 0;
  int64_t value = 0;
  std::from_chars(text.data(), text.data() + text.size(), value);
  return value;
}

double Result::Double(int row, int column) const {
  const std::string text = Text(row, column);
  if (text == "NaN") return std::numeric_limits<double>::quiet_NaN();
  if (text == "Infinity") return std::numeric_limits<double>::infinity();
  if (text == "-Infinity") return -std::numeric_limits<double>::infinity();
  double value = 0.0;
  std::from_chars(text.data(), text.data() + text.size(), value);
  return value;
}

std::string Result::Bytes(int row, int column) const {
  if (IsNull(row, column)) return {};
  size_t length = 0;
  unsigned char* bytes = PQunescapeBytea(
      reinterpret_cast<const unsigned char*>(PQgetvalue(result_, row, column)), &length);
  REENACT_CHECK(bytes != nullptr, "cannot decode a BYTEA value");
  std::string out(reinterpret_cast<const char*>(bytes), length);
  PQfreemem(bytes);
  return out;
}

Expected<Connection> Connection::Open(const std::string& url) {
  auto target = DescribeTarget(url);
  if (!target) return target.error();
  // connect_timeout first, so that one in `url` overrides it; PQreset reuses both.
  const char* const keywords[] = {"connect_timeout", "dbname", nullptr};
  const std::string timeout = std::to_string(kDefaultConnectTimeoutSeconds);
  const char* const values[] = {timeout.c_str(), url.c_str(), nullptr};
  pg_conn* conn = PQconnectdbParams(keywords, values, /*expand_dbname=*/1);
  if (!conn) return MakeError("io", "cannot connect to PostgreSQL " + *target + ": out of memory");
  if (PQstatus(conn) != CONNECTION_OK) {
    std::string detail = OneLine(PQerrorMessage(conn));
    PQfinish(conn);
    return MakeError("io", "cannot connect to PostgreSQL " + *target + ": " + detail +
                               "; check the URL (postgresql://user:password@host:port/database)"
                               " and that the server runs");
  }
  PQsetNoticeProcessor(conn, IgnoreNotice, nullptr);
  return Connection(conn, std::move(*target));
}

Connection::Connection(Connection&& other) noexcept
    : conn_(std::exchange(other.conn_, nullptr)),
      target_(std::move(other.target_)),
      last_sqlstate_(std::move(other.last_sqlstate_)),
      in_transaction_(std::exchange(other.in_transaction_, false)),
      prepared_(std::move(other.prepared_)) {}

Connection& Connection::operator=(Connection&& other) noexcept {
  if (this != &other) {
    PQfinish(conn_);
    conn_ = std::exchange(other.conn_, nullptr);
    target_ = std::move(other.target_);
    last_sqlstate_ = std::move(other.last_sqlstate_);
    in_transaction_ = std::exchange(other.in_transaction_, false);
    prepared_ = std::move(other.prepared_);
  }
  return *this;
}

Connection::~Connection() { PQfinish(conn_); }

void Connection::ReconnectIfBroken() {
  if (in_transaction_) return;
  if (PQstatus(conn_) == CONNECTION_OK) {
    // An idle connection has nothing to read unless the server closed it (or sent it a
    // notice of shutdown): read that now, so the statement goes to a live session.
    // A stopping server sends its FATAL message first and closes after, so read until the
    // socket has nothing more (a few rounds at most) or libpq sees the end.
    for (int round = 0; round < 4 && PQstatus(conn_) == CONNECTION_OK; ++round) {
      pollfd fd{PQsocket(conn_), POLLIN, 0};
      if (fd.fd < 0 || ::poll(&fd, 1, 0) <= 0 || PQconsumeInput(conn_) == 0) break;
    }
  }
  if (PQstatus(conn_) == CONNECTION_BAD) {
    prepared_.clear();  // a new session has none of the old one's prepared statements
    PQreset(conn_);
    if (PQstatus(conn_) == CONNECTION_OK) PQsetNoticeProcessor(conn_, IgnoreNotice, nullptr);
  }
}

Error Connection::Fail(std::string_view what, pg_result* result) {
  const char* state = result ? PQresultErrorField(result, PG_DIAG_SQLSTATE) : nullptr;
  last_sqlstate_ = state ? state : "";
  const char* message = result ? PQresultErrorMessage(result) : nullptr;
  if (!message || !*message) message = PQerrorMessage(conn_);
  // No SQLSTATE: libpq itself failed, on its link to the server (lost, or never reopened).
  const bool unavailable = PQstatus(conn_) == CONNECTION_BAD || last_sqlstate_.empty() ||
                           IsUnavailableState(last_sqlstate_);
  Error error =
      unavailable
          ? MakeError("unavailable", std::string(what) + " is unavailable: " + OneLine(message) +
                                         "; the connection is reopened on the next request "
                                         "once the server runs again")
          : MakeError("storage", std::string(what) + ": " + OneLine(message));
  PQclear(result);
  return error;
}

Status Connection::Exec(const std::string& sql) {
  ReconnectIfBroken();
  last_sqlstate_.clear();
  pg_result* result = PQexec(conn_, sql.c_str());
  const ExecStatusType status = result ? PQresultStatus(result) : PGRES_FATAL_ERROR;
  if (status != PGRES_COMMAND_OK && status != PGRES_TUPLES_OK) {
    return Fail("PostgreSQL " + target_, result);
  }
  PQclear(result);
  return {};
}

Expected<Result> Connection::Query(const std::string& sql, const std::vector<Param>& params,
                                   bool binary_result) {
  ReconnectIfBroken();
  last_sqlstate_.clear();
  std::vector<const char*> values(params.size());
  std::vector<int> lengths(params.size());
  std::vector<int> formats(params.size());
  for (size_t i = 0; i < params.size(); ++i) {
    values[i] = params[i].value ? params[i].value->data() : nullptr;
    lengths[i] = params[i].value ? static_cast<int>(params[i].value->size()) : 0;
    formats[i] = params[i].binary ? 1 : 0;
  }
  auto name = prepared_.find(sql);
  if (name == prepared_.end() && prepared_.size() < kMaxPreparedStatements) {
    std::string next = "reenact_" + std::to_string(prepared_.size());
    pg_result* prepared =
        PQprepare(conn_, next.c_str(), sql.c_str(), static_cast<int>(params.size()), nullptr);
    if (!prepared || PQresultStatus(prepared) != PGRES_COMMAND_OK) {
      return Fail("PostgreSQL " + target_, prepared);
    }
    PQclear(prepared);
    name = prepared_.emplace(sql, std::move(next)).first;
  }
  pg_result* result =
      name != prepared_.end()
          ? PQexecPrepared(conn_, name->second.c_str(), static_cast<int>(params.size()),
                           values.data(), lengths.data(), formats.data(), binary_result ? 1 : 0)
          : PQexecParams(conn_, sql.c_str(), static_cast<int>(params.size()), nullptr,
                         values.data(), lengths.data(), formats.data(), binary_result ? 1 : 0);
  const ExecStatusType status = result ? PQresultStatus(result) : PGRES_FATAL_ERROR;
  if (status != PGRES_COMMAND_OK && status != PGRES_TUPLES_OK) {
    return Fail("PostgreSQL " + target_, result);
  }
  return Result(result);
}

Expected<Transaction> Transaction::Begin(Connection& db) {
  if (Status s = db.Exec("BEGIN"); !s) return s.error();
  db.in_transaction_ = true;
  return Transaction(&db);
}

Transaction::Transaction(Transaction&& other) noexcept : db_(std::exchange(other.db_, nullptr)) {}

Transaction::~Transaction() {
  if (!db_) return;
  (void)db_->Exec("ROLLBACK");
  db_->in_transaction_ = false;
}

Status Transaction::Commit() {
  REENACT_CHECK(db_ != nullptr, "commit of a finished transaction");
  Connection* db = std::exchange(db_, nullptr);
  // in_transaction_ stays set until COMMIT is answered: a connection lost part way must not
  // be reopened first, which would send COMMIT to a new session with no transaction.
  Status committed;
  if (PQtransactionStatus(db->conn_) == PQTRANS_INERROR) {
    // COMMIT of a transaction that saw an error answers ROLLBACK, not an error: refuse it first.
    (void)db->Exec("ROLLBACK");
    committed = MakeError("storage", "PostgreSQL " + db->target_ +
                                         ": the transaction failed earlier and was rolled back");
  } else {
    committed = db->Exec("COMMIT");
  }
  db->in_transaction_ = false;
  return committed;
}

}  // namespace reenact::server::pg
