#pragma once
// A fixed set of read-only connections to one SQLite database file, each lent to one thread
// at a time. In WAL mode they read committed data concurrently with each other and with the
// file's writer, whose mutex they never take. When a lease ends it resets the statements it
// was handed, which ends the connection's read transaction: a connection between leases pins
// no WAL frames (see wal_checkpointer.h).

#include <atomic>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include "common/error/expected.h"
#include "server/storage/sqlite.h"

namespace reenact::server::sqlite {

class ReaderPool {
 private:
  struct Reader;

 public:
  // `count` >= 1 connections to the database at path (which must exist), each with
  // PRAGMA query_only and opened with `sync`. Fails like Database::Open.
  static Expected<std::unique_ptr<ReaderPool>> Open(const std::string& path, unsigned count,
                                                    Sync sync);

  // The size of a server's pools: one connection per hardware thread, at least 2.
  static unsigned DefaultCount();

  // One connection, held until destruction; movable, not copyable.
  class Lease {
   public:
    Lease(Lease&&) noexcept = default;
    Lease& operator=(Lease&&) = delete;
    ~Lease();

    Database& db();
    // The statement for `sql` on this connection, compiled on its first use and kept with the
    // connection; reset, with the bindings of its last use.
    Expected<Statement*> Prepared(std::string_view sql);

   private:
    friend class ReaderPool;
    Lease(Reader& reader, std::unique_lock<std::mutex> lock)
        : reader_(&reader), lock_(std::move(lock)) {}

    Reader* reader_;
    std::unique_lock<std::mutex> lock_;  // does not own the mutex once moved from
  };

  // A free connection if there is one, else waits for the next in turn.
  Lease Acquire();

  unsigned size() const { return static_cast<unsigned>(readers_.size()); }

 private:
  struct Reader {
    explicit Reader(Database database) : db(std::move(database)) {}
    std::mutex mutex;
    Database db;
    std::map<std::string, Statement, std::less<>> statements;  // by SQL text
  };

  ReaderPool() = default;

  std::vector<std::unique_ptr<Reader>> readers_;
  std::atomic<unsigned> next_{0};
};

}  // namespace reenact::server::sqlite
