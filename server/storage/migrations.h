#pragma once
// Schema migration runner. Each migration file "NNNN_what.sql" produces schema version NNNN;
// versions must run 1, 2, 3, ... without gaps. The database's version is PRAGMA user_version.
// Pending files are applied in order, each in its own transaction together with the version
// bump, so a failing file leaves the database at the previous version, untouched.

#include <vector>

#include "common/error/expected.h"
#include "server/storage/embedded_migrations.h"
#include "server/storage/sqlite.h"

namespace reenact::server {

// The schema version a file name declares ("0003_x.sql" -> 3), or an error for a bad name.
Expected<int> MigrationVersion(const char* file_name);

// Checks that the files' names declare versions 1, 2, 3, ... in order (code
// "invalid_argument" otherwise).
Status CheckMigrationSequence(const std::vector<MigrationFile>& files);

// The error for a database (described as `database`, e.g. "database FILE") whose schema
// version is newer than the newest this binary knows.
Error SchemaTooNew(const std::string& database, int version, int newest);

// The database's current schema version (0 for a new file).
Expected<int> SchemaVersion(sqlite::Database& db);

// Applies every file newer than the database's version. A database whose version is newer
// than the newest file is refused (code "schema_too_new") without being changed.
Status ApplyMigrations(sqlite::Database& db, const std::vector<MigrationFile>& files);

}  // namespace reenact::server
