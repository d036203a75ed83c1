#pragma once
// BlobStore in a PostgreSQL database (table blobs of migrations/postgresql/0001_init.sql), with
// the semantics of SqliteBlobStore. Every method is one statement in its own implicit
// transaction on a connection of a small pool, so a Put is stored whole or not at all, no
// transaction stays open between a reader's Reads, and several threads read and write at once.
//
// A BlobReader remembers the row version (xmin) and size it found at OpenReader; each Read
// fetches only its slice (substring of an uncompressed TOAST value reads just the chunks it
// covers) from that same row version, else fails with code "changed". A Put of the bytes
// already stored writes nothing, so it keeps readers of that payload going; any other Put or a
// delete makes them "changed".

#include <memory>
#include <string>

#include "server/storage/blob_store.h"
#include "server/storage/postgres_pool.h"

namespace reenact::server {

class PostgresBlobStore : public BlobStore {
 public:
  // Default number of connections: enough for the handler threads to read parts in parallel.
  static constexpr int kDefaultConnections = 4;

  // Connects to `url` with `connections` connections. The schema must already exist (open
  // PostgresMetadataStore first, which applies the migrations): code "storage" otherwise.
  // Connection failures as pg::Connection::Open reports them ("invalid_argument", "io").
  static Expected<std::unique_ptr<PostgresBlobStore>> Open(
      const std::string& url, int connections = kDefaultConnections);

  Status Put(const std::string& key, std::string_view bytes) override;
  Expected<std::optional<std::string>> Get(const std::string& key) override;
  Expected<std::unique_ptr<BlobReader>> OpenReader(const std::string& key) override;
  Status DeletePrefix(const std::string& prefix) override;
  Expected<std::vector<std::string>> ListKeys() override;

 private:
  explicit PostgresBlobStore(std::shared_ptr<pg::ConnectionPool> pool) : pool_(std::move(pool)) {}

  std::shared_ptr<pg::ConnectionPool> pool_;  // shared with the BlobReaders it opened
};

}  // namespace reenact::server
