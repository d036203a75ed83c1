#pragma once
// BlobStore in the server's SQLite database (table blobs). Uses its own connection, so large
// payload writes do not hold the metadata connection's mutex. The schema must already exist
// (open SqliteMetadataStore first, which applies the migrations).

#include <memory>
#include <mutex>
#include <string>

#include "server/storage/blob_store.h"
#include "server/storage/sqlite.h"

namespace reenact::server {

class SqliteBlobStore : public BlobStore {
 public:
  static Expected<std::unique_ptr<SqliteBlobStore>> Open(const std::string& path);

  Status Put(const std::string& key, std::string_view bytes) override;
  Expected<std::optional<std::string>> Get(const std::string& key) override;
  Status DeletePrefix(const std::string& prefix) override;

 private:
  explicit SqliteBlobStore(sqlite::Database db) : db_(std::move(db)) {}

  std::mutex mutex_;
  sqlite::Database db_;
};

}  // namespace reenact::server
