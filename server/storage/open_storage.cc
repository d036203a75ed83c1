#include "server/storage/open_storage.h"

#include "server/storage/file_blob_store.h"
#include "server/storage/postgres_blob_store.h"
#include "server/storage/postgres_metadata_store.h"
#include "server/storage/sqlite_blob_store.h"
#include "server/storage/sqlite_metadata_store.h"

namespace reenact::server {

namespace {

// The file blob store of options.blob_dir, or null when the blobs stay in the database.
Expected<std::unique_ptr<BlobStore>> OpenBlobDirectory(const StorageOptions& options) {
  if (options.blob_dir.empty()) return std::unique_ptr<BlobStore>();
  auto files = FileBlobStore::Open(options.blob_dir);
  if (!files) return files.error();
  return std::unique_ptr<BlobStore>(std::move(*files));
}

}  // namespace

Expected<Storage> OpenSqliteStorage(const std::string& db_path, const StorageOptions& options) {
  const sqlite::Sync sync =
      options.fsync_each_commit ? sqlite::Sync::kFull : sqlite::Sync::kNormal;
  auto files = OpenBlobDirectory(options);
  if (!files) return files.error();
  auto metadata = SqliteMetadataStore::Open(db_path, sync);
  if (!metadata) return metadata.error();
  if (*files) return Storage{std::move(*metadata), std::move(*files)};
  auto blobs = SqliteBlobStore::Open(db_path, sync);
  if (!blobs) return blobs.error();
  return Storage{std::move(*metadata), std::move(*blobs)};
}

bool IsPostgresUrl(const std::string& db) {
  return db.rfind("postgresql://", 0) == 0 || db.rfind("postgres://", 0) == 0;
}

Expected<Storage> OpenPostgresStorage(const std::string& url, const StorageOptions& options) {
  auto files = OpenBlobDirectory(options);
  if (!files) return files.error();
  auto metadata = PostgresMetadataStore::Open(url);
  if (!metadata) return metadata.error();
  if (*files) return Storage{std::move(*metadata), std::move(*files)};
  auto blobs = PostgresBlobStore::Open(url);
  if (!blobs) return blobs.error();
  return Storage{std::move(*metadata), std::move(*blobs)};
}

Expected<Storage> OpenStorage(const std::string& db, const StorageOptions& options) {
  if (IsPostgresUrl(db)) return OpenPostgresStorage(db, options);
  return OpenSqliteStorage(db, options);
}

}  // namespace reenact::server
