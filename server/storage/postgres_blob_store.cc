#include "server/storage/postgres_blob_store.h"

#include <algorithm>
#include <cstring>
#include <limits>

namespace reenact::server {

namespace {

// The LIKE pattern matching every string that starts with `prefix`.
std::string PrefixPattern(const std::string& prefix) {
  std::string pattern;
  pattern.reserve(prefix.size() + 1);
  for (char c : prefix) {
    if (c == '\\' || c == '%' || c == '_') pattern += '\\';
    pattern += c;
  }
  pattern += '%';
  return pattern;
}

class PostgresBlobReader : public BlobReader {
 public:
  PostgresBlobReader(std::shared_ptr<pg::ConnectionPool> pool, std::string key,
                     std::string version, uint64_t size)
      : pool_(std::move(pool)), key_(std::move(key)), version_(std::move(version)), size_(size) {}

  uint64_t size() const override { return size_; }

  Expected<size_t> Read(uint64_t offset, std::span<char> out) override {
    if (offset >= size_ || out.empty()) return size_t{0};
    // A BYTEA holds under 1 GiB, so offset and count fit the int of substring().
    const uint64_t count = std::min<uint64_t>(out.size(), size_ - offset);
    auto db = pool_->Acquire();
    auto rows = db->Query(
        "SELECT substring(data FROM $2 FOR $3) FROM blobs "
        "WHERE key = $1 AND xmin::text = $4 AND octet_length(data) = $5",
        {key_, static_cast<int64_t>(offset + 1), static_cast<int64_t>(count), version_,
         static_cast<int64_t>(size_)},
        /*binary_result=*/true);
    if (!rows) return rows.error();
    if (rows->rows() == 0) {
      return MakeError("changed",
                       "blob " + key_ + " was replaced or deleted while being read; read it again");
    }
    const std::string bytes = rows->Text(0, 0);
    if (bytes.size() != count) {
      return MakeError("storage", "blob " + key_ + " gave " + std::to_string(bytes.size()) +
                                      " bytes where " + std::to_string(count) + " were asked");
    }
    std::memcpy(out.data(), bytes.data(), bytes.size());
    return static_cast<size_t>(count);
  }

 private:
  std::shared_ptr<pg::ConnectionPool> pool_;  // may outlive the store
  std::string key_;
  std::string version_;  // xmin of the row found at OpenReader
  uint64_t size_;        // bytes
};

}  // namespace

Expected<std::unique_ptr<PostgresBlobStore>> PostgresBlobStore::Open(const std::string& url,
                                                                     int connections) {
  auto pool = pg::ConnectionPool::Open(url, connections);
  if (!pool) return pool.error();
  {
    auto db = (*pool)->Acquire();
    if (!db->Query("SELECT 1 FROM blobs LIMIT 0")) {
      return MakeError("storage", "PostgreSQL " + db->target() +
                                      " has no blobs table; apply migrations first");
    }
  }
  return std::unique_ptr<PostgresBlobStore>(new PostgresBlobStore(std::move(*pool)));
}

Status PostgresBlobStore::Put(const std::string& key, std::string_view bytes) {
  if (bytes.size() >= (size_t{1} << 30)) {
    return MakeError("invalid_argument", "blob " + key + " has " + std::to_string(bytes.size()) +
                                             " bytes; PostgreSQL stores under 1 GiB per value");
  }
  auto db = pool_->Acquire();
  // Unchanged bytes write no new row version, so readers of them go on.
  auto done = db->Query(
      "INSERT INTO blobs(key, data) VALUES ($1, $2) "
      "ON CONFLICT (key) DO UPDATE SET data = excluded.data "
      "WHERE blobs.data IS DISTINCT FROM excluded.data",
      {key, pg::Param::Bytes(bytes)});
  if (!done) return done.error();
  return {};
}

Expected<std::optional<std::string>> PostgresBlobStore::Get(const std::string& key) {
  auto db = pool_->Acquire();
  auto rows = db->Query("SELECT data FROM blobs WHERE key = $1", {key}, /*binary_result=*/true);
  if (!rows) return rows.error();
  if (rows->rows() == 0) return std::optional<std::string>();
  return std::optional<std::string>(rows->Text(0, 0));
}

Expected<std::unique_ptr<BlobReader>> PostgresBlobStore::OpenReader(const std::string& key) {
  auto db = pool_->Acquire();
  // octet_length of a TOASTed value comes from its header; the payload is not read.
  auto rows = db->Query("SELECT xmin::text, octet_length(data) FROM blobs WHERE key = $1", {key});
  if (!rows) return rows.error();
  if (rows->rows() == 0) return std::unique_ptr<BlobReader>();
  return std::unique_ptr<BlobReader>(new PostgresBlobReader(
      pool_, key, rows->Text(0, 0), static_cast<uint64_t>(rows->Int(0, 1))));
}

Status PostgresBlobStore::DeletePrefix(const std::string& prefix) {
  auto db = pool_->Acquire();
  // LIKE with a fixed prefix is a range scan of the primary key (COLLATE "C").
  auto done = db->Query("DELETE FROM blobs WHERE key LIKE $1", {PrefixPattern(prefix)});
  if (!done) return done.error();
  return {};
}

Expected<std::vector<std::string>> PostgresBlobStore::ListKeys() {
  auto db = pool_->Acquire();
  auto rows = db->Query("SELECT key FROM blobs ORDER BY key", {});  // COLLATE "C": bytewise
  if (!rows) return rows.error();
  std::vector<std::string> keys;
  for (int i = 0; i < rows->rows(); ++i) keys.push_back(rows->Text(i, 0));
  return keys;
}

}  // namespace reenact::server
