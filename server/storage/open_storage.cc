#include "server/storage/open_storage.h"

#include "server/storage/postgres_blob_store.h"
#include "server/storage/postgres_metadata_store.h"
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

bool IsPostgresUrl(const std::string& db) {
  return db.rfind("postgresql://", 0) == 0 || db.rfind("postgres://", 0) == 0;
}

Expected<Storage> OpenPostgresStorage(const std::string& url) {
  auto metadata = PostgresMetadataStore::Open(url);
  if (!metadata) return metadata.error();
  auto blobs = PostgresBlobStore::Open(url);
  if (!blobs) return blobs.error();
  return Storage{std::move(*metadata), std::move(*blobs)};
}

Expected<Storage> OpenStorage(const std::string& db, const StorageOptions& options) {
  if (IsPostgresUrl(db)) return OpenPostgresStorage(db);
  return OpenSqliteStorage(db, options);
}

}  // namespace reenact::server
