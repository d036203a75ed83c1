#pragma once
// BlobStore in the server's SQLite database (table blobs). Writes go through its own
// connection under a mutex, so large payload writes do not hold the metadata connection's
// mutex; reads (Get, and every Read of the readers OpenReader returns) go through a pool of
// read-only connections and never wait for that mutex. The schema must already exist (open
// SqliteMetadataStore first, which applies the migrations). WAL checkpoints run on the file's
// WalCheckpointer thread, not in Put().

#include <memory>
#include <mutex>
#include <string>

#include "server/storage/blob_store.h"
#include "server/storage/reader_pool.h"
#include "server/storage/sqlite.h"
#include "server/storage/wal_checkpointer.h"

namespace reenact::server {

class SqliteBlobStore : public BlobStore {
 public:
  // Opens the blob store of the database at path; every connection commits as `sync` says.
  static Expected<std::unique_ptr<SqliteBlobStore>> Open(const std::string& path,
                                                         sqlite::Sync sync = sqlite::Sync::kFull);

  Status Put(const std::string& key, std::string_view bytes) override;
  Expected<std::optional<std::string>> Get(const std::string& key) override;
  Expected<std::unique_ptr<BlobReader>> OpenReader(const std::string& key) override;
  Status DeletePrefix(const std::string& prefix) override;
  Expected<std::vector<std::string>> ListKeys() override;

 private:
  SqliteBlobStore(std::shared_ptr<sqlite::WalCheckpointer> checkpointer, sqlite::Database db,
                  std::shared_ptr<sqlite::ReaderPool> readers)
      : checkpointer_(std::move(checkpointer)), db_(std::move(db)), readers_(std::move(readers)) {}

  std::mutex mutex_;                                       // guards db_
  std::shared_ptr<sqlite::WalCheckpointer> checkpointer_;  // outlives db_
  sqlite::Database db_;                                    // the writer
  std::shared_ptr<sqlite::ReaderPool> readers_;            // shared with the BlobReaders it opened
};

}  // namespace reenact::server
