#include "server/storage/open_storage.h"

#include "server/storage/sqlite_blob_store.h"
#include "server/storage/sqlite_metadata_store.h"

namespace reenact::server {

Expected<Storage> OpenSqliteStorage(const std::string& db_path, const StorageOptions& options) {
  const sqlite::Sync sync =
      options.fsync_each_commit ? sqlite::Sync::kFull : sqlite::Sync::kNormal;
  auto metadata = SqliteMetadataStore::Open(db_path, sync);
  if (!metadata) return metadata.error();
  auto blobs = SqliteBlobStore::Open(db_path, sync);
  if (!blobs) return blobs.error();
  return Storage{std::move(*metadata), std::move(*blobs)};
}

}  // namespace reenact::server
