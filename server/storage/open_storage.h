#pragma once
// Opens the embedded storage of a server: the SQLite metadata store (applying migrations)
// and the SQLite blob store, both in one database file.

#include <memory>
#include <string>

#include "common/error/expected.h"
#include "server/storage/blob_store.h"
#include "server/storage/metadata_store.h"

namespace reenact::server {

struct StorageOptions {
  // true (default): every commit is fsynced before it returns (PRAGMA synchronous=FULL), so
  // a 204 means stored even across a power failure. false: synchronous=NORMAL, a commit
  // survives a crash of the process but the last commits may be lost on power failure (for
  // hosts whose disks have a battery-backed write cache).
  bool fsync_each_commit = true;
};

struct Storage {
  std::unique_ptr<MetadataStore> metadata;
  std::unique_ptr<BlobStore> blobs;
};

// code "io" for a missing directory or unopenable file, "schema_too_new" for a database
// written by a newer server, "migration_failed" when a migration fails (nothing applied).
// Every connection of both stores commits as `options` says.
Expected<Storage> OpenSqliteStorage(const std::string& db_path,
                                    const StorageOptions& options = {});

}  // namespace reenact::server
