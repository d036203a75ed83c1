#include "server/storage/open_storage.h"

#include "server/storage/sqlite_blob_store.h"
#include "server/storage/sqlite_metadata_store.h"

namespace reenact::server {

Expected<Storage> OpenSqliteStorage(const std::string& db_path) {
  auto metadata = SqliteMetadataStore::Open(db_path);
  if (!metadata) return metadata.error();
  auto blobs = SqliteBlobStore::Open(db_path);
  if (!blobs) return blobs.error();
  return Storage{std::move(*metadata), std::move(*blobs)};
}

}  // namespace reenact::server
