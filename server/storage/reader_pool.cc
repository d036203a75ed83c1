#include "server/storage/reader_pool.h"

#include <algorithm>
#include <thread>

namespace reenact::server::sqlite {

namespace {

// Readers see the file through a shared read-only mapping: a query touches pages scattered
// over the file (R*Tree, clips, blob overflow pages), and a page from the map costs no pread
// (SQLite's own cache per connection is 2 MB).
constexpr long long kReaderMmapBytes = 1LL << 30;

}  // namespace

Expected<std::unique_ptr<ReaderPool>> ReaderPool::Open(const std::string& path, unsigned count,
                                                       Sync sync) {
  REENACT_CHECK(count >= 1, "a reader pool needs at least one connection");
  std::unique_ptr<ReaderPool> pool(new ReaderPool());
  for (unsigned i = 0; i < count; ++i) {
    auto db = Database::Open(path, sync);
    if (!db) return db.error();
    if (Status s = db->Exec("PRAGMA query_only = ON"); !s) return s.error();
    if (Status s = db->Exec("PRAGMA mmap_size = " + std::to_string(kReaderMmapBytes)); !s) {
      return s.error();
    }
    pool->readers_.push_back(std::make_unique<Reader>(std::move(*db)));
  }
  return pool;
}

unsigned ReaderPool::DefaultCount() { return std::max(2u, std::thread::hardware_concurrency()); }

ReaderPool::Lease ReaderPool::Acquire() {
  const unsigned first = next_.fetch_add(1, std::memory_order_relaxed);
  for (size_t i = 0; i < readers_.size(); ++i) {
    Reader& reader = *readers_[(first + i) % readers_.size()];
    std::unique_lock lock(reader.mutex, std::try_to_lock);
    if (lock.owns_lock()) return Lease(reader, std::move(lock));
  }
  Reader& reader = *readers_[first % readers_.size()];
  return Lease(reader, std::unique_lock(reader.mutex));
}

ReaderPool::Lease::~Lease() {
  if (!lock_.owns_lock()) return;  // moved from
  for (auto& [sql, statement] : reader_->statements) statement.Reset();
}

Database& ReaderPool::Lease::db() { return reader_->db; }

Expected<Statement*> ReaderPool::Lease::Prepared(std::string_view sql) {
  auto found = reader_->statements.find(sql);
  if (found == reader_->statements.end()) {
    auto prepared = reader_->db.Prepare(sql);
    if (!prepared) return prepared.error();
    found = reader_->statements.emplace(std::string(sql), std::move(*prepared)).first;
  }
  found->second.Reset();
  return &found->second;
}

}  // namespace reenact::server::sqlite
