#include "server/storage/postgres_pool.h"

#include <utility>

#include "common/error/check.h"

namespace reenact::server::pg {

Expected<std::shared_ptr<ConnectionPool>> ConnectionPool::Open(const std::string& url, int count) {
  REENACT_CHECK(count >= 1, "a connection pool needs at least one connection");
  std::vector<std::unique_ptr<Connection>> connections;
  for (int i = 0; i < count; ++i) {
    auto connection = Connection::Open(url);
    if (!connection) return connection.error();
    connections.push_back(std::make_unique<Connection>(std::move(*connection)));
  }
  return std::shared_ptr<ConnectionPool>(new ConnectionPool(std::move(connections)));
}

ConnectionPool::Lease ConnectionPool::Acquire() {
  std::unique_lock lock(mutex_);
  returned_.wait(lock, [&] { return !free_.empty(); });
  std::unique_ptr<Connection> connection = std::move(free_.back());
  free_.pop_back();
  return Lease(this, std::move(connection));
}

void ConnectionPool::Return(std::unique_ptr<Connection> connection) {
  {
    std::lock_guard lock(mutex_);
    free_.push_back(std::move(connection));
  }
  returned_.notify_one();
}

ConnectionPool::Lease::Lease(Lease&& other) noexcept
    : pool_(std::exchange(other.pool_, nullptr)), connection_(std::move(other.connection_)) {}

ConnectionPool::Lease::~Lease() {
  if (pool_ && connection_) pool_->Return(std::move(connection_));
}

}  // namespace reenact::server::pg
