#pragma once
// Opens the embedded storage of a server: the SQLite metadata store (applying migrations)
// and the SQLite blob store, both in one database file.

#include <memory>
#include <string>

#include "common/error/expected.h"
#include "server/storage/blob_store.h"
#include "server/storage/metadata_store.h"

namespace reenact::server {

struct Storage {
  std::unique_ptr<MetadataStore> metadata;
  std::unique_ptr<BlobStore> blobs;
};

// code "io" for a missing directory or unopenable file, "schema_too_new" for a database
// written by a newer server, "migration_failed" when a migration fails (nothing applied).
Expected<Storage> OpenSqliteStorage(const std::string& db_path);

}  // namespace reenact::server
