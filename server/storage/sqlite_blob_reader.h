#pragma once
// BlobReader of SqliteBlobStore: SQLite incremental blob I/O on table blobs. Each Read leases
// a connection of the store's ReaderPool, checks that the key still names the row and size
// found when the reader was opened, and reads the bytes through a blob handle in one short
// read transaction that ends before Read returns.

#include <cstdint>
#include <memory>
#include <string>

#include "server/storage/blob_store.h"
#include "server/storage/reader_pool.h"

namespace reenact::server {

class SqliteBlobReader : public BlobReader {
 public:
  // A reader of the payload under key, or a null pointer when absent. `readers` are
  // connections to a database with the blobs table.
  static Expected<std::unique_ptr<BlobReader>> Open(std::shared_ptr<sqlite::ReaderPool> readers,
                                                    const std::string& key);

  uint64_t size() const override { return size_; }
  Expected<size_t> Read(uint64_t offset, std::span<char> out) override;

 private:
  SqliteBlobReader(std::shared_ptr<sqlite::ReaderPool> readers, std::string key, int64_t rowid,
                   uint64_t size)
      : readers_(std::move(readers)), key_(std::move(key)), rowid_(rowid), size_(size) {}

  std::shared_ptr<sqlite::ReaderPool> readers_;  // may outlive the store
  std::string key_;
  int64_t rowid_;  // the payload's row in blobs
  uint64_t size_;  // bytes
};

}  // namespace reenact::server
