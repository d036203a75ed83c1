#pragma once
// A fixed set of connections to one PostgreSQL database, lent to one user at a time, so that
// several threads run statements at once (PostgreSQL serves each connection in its own
// process). A lease that is never returned blocks nobody but the callers that wait for it.

#include <condition_variable>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "common/error/expected.h"
#include "server/storage/postgres.h"

namespace reenact::server::pg {

class ConnectionPool {
 public:
  // Opens `count` >= 1 connections to `url` at once (Connection::Open's codes and lines).
  static Expected<std::shared_ptr<ConnectionPool>> Open(const std::string& url, int count);

  // A connection for the lease's lifetime; returned to the pool at its end.
  class Lease {
   public:
    Lease(Lease&& other) noexcept;
    Lease& operator=(Lease&&) = delete;
    Lease(const Lease&) = delete;
    Lease& operator=(const Lease&) = delete;
    ~Lease();

    Connection& operator*() const { return *connection_; }
    Connection* operator->() const { return connection_.get(); }

   private:
    friend class ConnectionPool;
    Lease(ConnectionPool* pool, std::unique_ptr<Connection> connection)
        : pool_(pool), connection_(std::move(connection)) {}
    ConnectionPool* pool_;
    std::unique_ptr<Connection> connection_;
  };

  // A free connection, waiting until one is returned when all are lent.
  Lease Acquire();

  int size() const { return size_; }

 private:
  explicit ConnectionPool(std::vector<std::unique_ptr<Connection>> free)
      : size_(static_cast<int>(free.size())), free_(std::move(free)) {}
  void Return(std::unique_ptr<Connection> connection);

  const int size_;
  std::mutex mutex_;
  std::condition_variable returned_;
  std::vector<std::unique_ptr<Connection>> free_;  // guarded by mutex_
};

}  // namespace reenact::server::pg
