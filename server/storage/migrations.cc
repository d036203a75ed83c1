#include "server/storage/migrations.h"

#include <cctype>
#include <string>

namespace reenact::server {

Expected<int> MigrationVersion(const char* file_name) {
  const std::string name = file_name ? file_name : "";
  size_t digits = 0;
  while (digits < name.size() && std::isdigit(static_cast<unsigned char>(name[digits]))) ++digits;
  if (digits == 0 || digits > 6 || name.size() < 4 || name.substr(name.size() - 4) != ".sql") {
    return MakeError("invalid_argument",
                     "migration file '" + name + "' is not named NNNN_name.sql");
  }
  return std::stoi(name.substr(0, digits));
}

Expected<int> SchemaVersion(sqlite::Database& db) {
  auto stmt = db.Prepare("PRAGMA user_version");
  if (!stmt) return stmt.error();
  auto row = stmt->Step();
  if (!row) return row.error();
  return static_cast<int>(stmt->ColumnInt(0));
}

Status CheckMigrationSequence(const std::vector<MigrationFile>& files) {
  for (size_t i = 0; i < files.size(); ++i) {
    auto version = MigrationVersion(files[i].name);
    if (!version) return version.error();
    if (*version != static_cast<int>(i) + 1) {
      return MakeError("invalid_argument", std::string("migration ") + files[i].name +
                                               " is out of sequence: expected version " +
                                               std::to_string(i + 1));
    }
  }
  return {};
}

Error SchemaTooNew(const std::string& database, int version, int newest) {
  return MakeError("schema_too_new", database + " has schema version " + std::to_string(version) +
                                         " but this reenact-server knows only up to version " +
                                         std::to_string(newest) + "; run a newer reenact-server");
}

Status ApplyMigrations(sqlite::Database& db, const std::vector<MigrationFile>& files) {
  if (Status s = CheckMigrationSequence(files); !s) return s;
  auto current = SchemaVersion(db);
  if (!current) return current.error();
  const int newest = static_cast<int>(files.size());
  if (*current > newest) return SchemaTooNew("database " + db.path(), *current, newest);
  for (int version = *current + 1; version <= newest; ++version) {
    const MigrationFile& file = files[version - 1];
    auto tx = sqlite::Transaction::Begin(db);
    if (!tx) return tx.error();
    if (Status s = db.Exec(file.sql); !s) {
      return MakeError("migration_failed",
                       std::string("migration ") + file.name + " failed: " + s.error().message);
    }
    if (Status s = db.Exec("PRAGMA user_version = " + std::to_string(version)); !s) {
      return s.error();
    }
    if (Status s = tx->Commit(); !s) return s.error();
  }
  return {};
}

}  // namespace reenact::server
