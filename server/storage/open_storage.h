#pragma once
// Opens the storage of a server: by default the embedded SQLite metadata store (applying
// migrations) and the SQLite blob store, both in one database file; or, for a PostgreSQL URL,
// the metadata and blob stores in that PostgreSQL/PostGIS database. With
// StorageOptions::blob_dir, on either engine, the blobs are files in that directory instead
// (FileBlobStore) and the database holds the metadata alone.

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
  // hosts whose disks have a battery-backed write cache). SQLite only: PostgreSQL commits as
  // its server is configured.
  bool fsync_each_commit = true;
  // Empty (default): blobs in the database. Else an existing directory, writable by the
  // server, that holds the blobs as files (file_blob_store.h); every server process of one
  // database must see the same directory.
  std::string blob_dir;
};

struct Storage {
  std::unique_ptr<MetadataStore> metadata;
  std::unique_ptr<BlobStore> blobs;
};

// code "io" for a missing directory or unopenable file (or an unusable blob_dir, checked
// first: then nothing is created), "schema_too_new" for a database written by a newer server,
// "migration_failed" when a migration fails (nothing applied). Every connection of both
// stores commits as `options` says.
Expected<Storage> OpenSqliteStorage(const std::string& db_path,
                                    const StorageOptions& options = {});

// Whether `db` names a PostgreSQL database: it starts with "postgresql://" or "postgres://".
bool IsPostgresUrl(const std::string& db);

// Both stores in the PostgreSQL database at `url` (postgresql://user:password@host:port/db),
// applying migrations. Codes: "invalid_argument" for a malformed URL, "io" when the server
// cannot be reached or refuses the login (one line naming the target, never the password),
// "schema_too_new", "migration_failed", "storage"; "io" for an unusable options.blob_dir
// (checked before connecting).
Expected<Storage> OpenPostgresStorage(const std::string& url, const StorageOptions& options = {});

// OpenPostgresStorage for a PostgreSQL URL, else OpenSqliteStorage of the file `db`.
Expected<Storage> OpenStorage(const std::string& db, const StorageOptions& options = {});

}  // namespace reenact::server
