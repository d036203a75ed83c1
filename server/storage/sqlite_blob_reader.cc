#include "server/storage/sqlite_blob_reader.h"

#include <sqlite3.h>

#include <algorithm>
#include <optional>

namespace reenact::server {

namespace {

// Where a payload sits: its row in blobs and its size in bytes.
struct Location {
  int64_t rowid = 0;
  uint64_t size = 0;
};

// The row and size of the payload under key, or nullopt when absent. Uses the lease's kept
// statement and leaves it on its row: that keeps the connection's read transaction open, so
// a blob handle opened next on the same lease reads the same snapshot. The lease's end
// resets the statement and ends the transaction.
Expected<std::optional<Location>> Locate(sqlite::ReaderPool::Lease& lease, const std::string& key) {
  // length() of a BLOB comes from the record header; the payload is not read.
  auto stmt = lease.Prepared("SELECT rowid, length(data) FROM blobs WHERE key = ?1");
  if (!stmt) return stmt.error();
  (*stmt)->BindText(1, key);
  auto row = (*stmt)->Step();
  if (!row) return row.error();
  if (!*row) return std::optional<Location>();
  Location location;
  location.rowid = (*stmt)->ColumnInt(0);
  location.size = static_cast<uint64_t>((*stmt)->ColumnInt(1));
  return std::optional<Location>(location);
}

}  // namespace

Expected<std::unique_ptr<BlobReader>> SqliteBlobReader::Open(
    std::shared_ptr<sqlite::ReaderPool> readers, const std::string& key) {
  auto lease = readers->Acquire();
  auto location = Locate(lease, key);
  if (!location) return location.error();
  if (!*location) return std::unique_ptr<BlobReader>();
  return std::unique_ptr<BlobReader>(
      new SqliteBlobReader(std::move(readers), key, (*location)->rowid, (*location)->size));
}

Expected<size_t> SqliteBlobReader::Read(uint64_t offset, std::span<char> out) {
  if (offset >= size_ || out.empty()) return size_t{0};
  auto lease = readers_->Acquire();
  auto location = Locate(lease, key_);
  if (!location) return location.error();
  // A replacement of the same size keeps the rowid (Put updates in place) and, the parts
  // being content-addressed, the same bytes; anything else makes the earlier pieces stale.
  if (!*location || (*location)->rowid != rowid_ || (*location)->size != size_) {
    return MakeError("changed",
                     "blob " + key_ + " was replaced or deleted while being read; read it again");
  }
  // SQLite limits a BLOB to under 2^31 bytes, so offset and count fit an int.
  const int count = static_cast<int>(std::min<uint64_t>(out.size(), size_ - offset));
  sqlite3* db = lease.db().raw();
  sqlite3_blob* blob = nullptr;
  if (sqlite3_blob_open(db, "main", "blobs", "data", rowid_, /*flags=*/0, &blob) != SQLITE_OK) {
    return MakeError("storage", "cannot open blob " + key_ + ": " + sqlite3_errmsg(db));
  }
  const int rc = sqlite3_blob_read(blob, out.data(), count, static_cast<int>(offset));
  std::string error = rc == SQLITE_OK ? "" : sqlite3_errmsg(db);
  sqlite3_blob_close(blob);
  if (rc != SQLITE_OK) return MakeError("storage", "cannot read blob " + key_ + ": " + error);
  return static_cast<size_t>(count);
}

}  // namespace reenact::server
