#include "server/storage/sqlite_blob_store.h"

#include "server/storage/sqlite_blob_reader.h"

namespace reenact::server {

Expected<std::unique_ptr<SqliteBlobStore>> SqliteBlobStore::Open(const std::string& path,
                                                                 sqlite::Sync sync) {
  auto db = sqlite::Database::Open(path, sync);
  if (!db) return db.error();
  auto probe = db->Prepare("SELECT 1 FROM blobs LIMIT 0");
  if (!probe) {
    return MakeError("storage", "database " + path + " has no blobs table; apply migrations first");
  }
  auto checkpointer = sqlite::WalCheckpointer::ForFile(path);
  if (!checkpointer) return checkpointer.error();
  (*checkpointer)->Attach(*db);
  auto readers = sqlite::ReaderPool::Open(path, sqlite::ReaderPool::DefaultCount(), sync);
  if (!readers) return readers.error();
  return std::unique_ptr<SqliteBlobStore>(
      new SqliteBlobStore(std::move(*checkpointer), std::move(*db),
                          std::shared_ptr<sqlite::ReaderPool>(std::move(*readers))));
}

Status SqliteBlobStore::Put(const std::string& key, std::string_view bytes) {
  std::lock_guard lock(mutex_);
  auto stmt = db_.Prepare(
      "INSERT INTO blobs(key, data) VALUES (?1, ?2) "
      "ON CONFLICT(key) DO UPDATE SET data = excluded.data");
  if (!stmt) return stmt.error();
  stmt->BindText(1, key).BindBlobInPlace(2, bytes);  // `bytes` outlives the statement
  return stmt->Run();
}

Expected<std::optional<std::string>> SqliteBlobStore::Get(const std::string& key) {
  auto lease = readers_->Acquire();  // its end resets the statement: no read stays open
  auto stmt = lease.Prepared("SELECT data FROM blobs WHERE key = ?1");
  if (!stmt) return stmt.error();
  (*stmt)->BindText(1, key);
  auto row = (*stmt)->Step();
  if (!row) return row.error();
  if (!*row) return std::optional<std::string>();
  return std::optional<std::string>((*stmt)->ColumnBlob(0));
}

Expected<std::unique_ptr<BlobReader>> SqliteBlobStore::OpenReader(const std::string& key) {
  return SqliteBlobReader::Open(readers_, key);
}

Status SqliteBlobStore::DeletePrefix(const std::string& prefix) {
  std::lock_guard lock(mutex_);
  // Range scan on the primary key: prefix <= key < prefix + U+10FFFF-ish sentinel.
  auto stmt = db_.Prepare("DELETE FROM blobs WHERE key >= ?1 AND key < ?2");
  if (!stmt) return stmt.error();
  stmt->BindText(1, prefix).BindText(2, prefix + "\xff");
  return stmt->Run();
}

Expected<std::vector<std::string>> SqliteBlobStore::ListKeys() {
  auto lease = readers_->Acquire();  // its end resets the statement: no read stays open
  auto stmt = lease.Prepared("SELECT key FROM blobs ORDER BY key");
  if (!stmt) return stmt.error();
  std::vector<std::string> keys;
  for (;;) {
    auto row = (*stmt)->Step();
    if (!row) return row.error();
    if (!*row) break;
    keys.push_back((*stmt)->ColumnText(0));
  }
  return keys;
}

}  // namespace reenact::server
