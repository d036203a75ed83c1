#include "server/storage/postgres_migrations.h"

#include <string>

#include "server/storage/migrations.h"

namespace reenact::server {

namespace {

// Key of the advisory lock that serializes migrations (any constant unique to reenact).
constexpr int64_t kMigrationLockKey = 0x7265656e61637431;  // "reenact1"

}  // namespace

Expected<int> PostgresSchemaVersion(pg::Connection& db) {
  auto exists = db.Query("SELECT to_regclass('reenact_schema_version') IS NOT NULL");
  if (!exists) return exists.error();
  if (exists->Int(0, 0) == 0) return 0;
  auto version = db.Query("SELECT COALESCE(MAX(version), 0) FROM reenact_schema_version");
  if (!version) return version.error();
  return static_cast<int>(version->Int(0, 0));
}

Status ApplyPostgresMigrations(pg::Connection& db, const std::vector<MigrationFile>& files) {
  if (Status s = CheckMigrationSequence(files); !s) return s;
  const int newest = static_cast<int>(files.size());
  for (;;) {
    auto tx = pg::Transaction::Begin(db);
    if (!tx) return tx.error();
    if (auto lock = db.Query("SELECT pg_advisory_xact_lock($1)", {kMigrationLockKey}); !lock) {
      return lock.error();
    }
    auto current = PostgresSchemaVersion(db);
    if (!current) return current.error();
    if (*current > newest) return SchemaTooNew("PostgreSQL " + db.target(), *current, newest);
    if (*current == newest) return tx->Commit();
    const MigrationFile& file = files[*current];
    if (Status s = db.Exec(file.sql); !s) {
      return MakeError("migration_failed",
                       std::string("migration ") + file.name + " failed: " + s.error().message);
    }
    if (Status s = db.Exec(
            "CREATE TABLE IF NOT EXISTS reenact_schema_version (version INTEGER NOT NULL); "
            "DELETE FROM reenact_schema_version;");
        !s) {
      return s.error();
    }
    if (auto set = db.Query("INSERT INTO reenact_schema_version(version) VALUES ($1)",
                            {*current + 1});
        !set) {
      return set.error();
    }
    if (Status s = tx->Commit(); !s) return s.error();
  }
}

}  // namespace reenact::server
