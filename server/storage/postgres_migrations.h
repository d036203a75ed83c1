#pragma once
// Schema migrations on PostgreSQL, with the rules of migrations.h: file "NNNN_what.sql"
// produces schema version NNNN, versions run 1, 2, 3, ... and each pending file is applied in
// its own transaction together with the version bump (PostgreSQL's DDL is transactional, so a
// failing file leaves the database at the previous version, untouched). The version is the one
// row of table reenact_schema_version. Several servers starting at once are safe: each
// migration runs under a transaction-scoped advisory lock and rereads the version first.

#include <vector>

#include "common/error/expected.h"
#include "server/storage/embedded_migrations.h"
#include "server/storage/postgres.h"

namespace reenact::server {

// The database's current schema version (0 for a database without reenact's tables).
Expected<int> PostgresSchemaVersion(pg::Connection& db);

// Applies every file newer than the database's version. A database whose version is newer
// than the newest file is refused (code "schema_too_new") without being changed; a failing
// file gives code "migration_failed" naming it.
Status ApplyPostgresMigrations(pg::Connection& db, const std::vector<MigrationFile>& files);

}  // namespace reenact::server
