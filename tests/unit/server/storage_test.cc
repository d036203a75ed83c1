// Storage on real SQLite files in a temp dir: migrations, transactions, file modes.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>

#include "server/storage/migrations.h"
#include "server/storage/sqlite.h"
#include "tests/unit/server/server_test_util.h"

namespace reenact::server {
namespace {

using testing::TempDir;

int64_t CountRows(sqlite::Database& db, const std::string& sql) {
  auto stmt = db.Prepare(sql);
  EXPECT_TRUE(stmt.ok());
  auto row = stmt->Step();
  EXPECT_TRUE(row.ok() && *row);
  return stmt->ColumnInt(0);
}

bool TableExists(sqlite::Database& db, const std::string& name) {
  return CountRows(db, "SELECT COUNT(*) FROM sqlite_master WHERE type='table' AND name='" +
                           name + "'") == 1;
}

TEST(Migrations, EmbeddedSchemaAppliesOnceAndReopens) {
  TempDir dir;
  const std::string path = (dir.path() / "db.sqlite").string();
  ASSERT_TRUE(OpenSqliteStorage(path).ok());
  ASSERT_TRUE(OpenSqliteStorage(path).ok());
  auto db = sqlite::Database::Open(path);
  ASSERT_TRUE(db.ok());
  EXPECT_EQ(*SchemaVersion(*db), static_cast<int>(EmbeddedMigrations().size()));
  EXPECT_TRUE(TableExists(*db, "clips"));
  EXPECT_EQ(CountRows(*db, "PRAGMA foreign_keys"), 1);
}

TEST(Migrations, EachFileRunsExactlyOnce) {
  TempDir dir;
  auto db = sqlite::Database::Open((dir.path() / "m.sqlite").string());
  ASSERT_TRUE(db.ok());
  const std::vector<MigrationFile> files = {
      {"0001_t.sql", "CREATE TABLE t(x); INSERT INTO t VALUES (1);"}};
  ASSERT_TRUE(ApplyMigrations(*db, files).ok());
  ASSERT_TRUE(ApplyMigrations(*db, files).ok());
  EXPECT_EQ(CountRows(*db, "SELECT COUNT(*) FROM t"), 1);
  EXPECT_EQ(*SchemaVersion(*db), 1);
}

TEST(Migrations, FailingFileRollsBackAndKeepsVersion) {
  TempDir dir;
  auto db = sqlite::Database::Open((dir.path() / "m.sqlite").string());
  ASSERT_TRUE(db.ok());
  const std::vector<MigrationFile> files = {
      {"0001_t.sql", "CREATE TABLE t(x);"},
      {"0002_bad.sql", "CREATE TABLE u(x); INSERT INTO missing_table VALUES (1);"}};
  Status s = ApplyMigrations(*db, files);
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.error().code, "migration_failed");
  EXPECT_NE(s.error().message.find("0002_bad.sql"), std::string::npos);
  EXPECT_EQ(*SchemaVersion(*db), 1);
  EXPECT_TRUE(TableExists(*db, "t"));
  EXPECT_FALSE(TableExists(*db, "u"));
}

TEST(Migrations, NewerDatabaseIsRefused) {
  TempDir dir;
  const std::string path = (dir.path() / "db.sqlite").string();
  {
    auto db = sqlite::Database::Open(path);
    ASSERT_TRUE(db.ok());
    ASSERT_TRUE(db->Exec("PRAGMA user_version = 99").ok());
  }
  auto storage = OpenSqliteStorage(path);
  ASSERT_FALSE(storage.ok());
  EXPECT_EQ(storage.error().code, "schema_too_new");
  EXPECT_NE(storage.error().message.find("99"), std::string::npos);
  EXPECT_NE(storage.error().message.find("newer reenact-server"), std::string::npos);
}

TEST(Migrations, BadFileNamesAreRejected) {
  EXPECT_FALSE(MigrationVersion("init.sql").ok());
  EXPECT_FALSE(MigrationVersion("0001_init.txt").ok());
  EXPECT_EQ(*MigrationVersion("0012_x.sql"), 12);
  TempDir dir;
  auto db = sqlite::Database::Open((dir.path() / "m.sqlite").string());
  const std::vector<MigrationFile> gap = {{"0002_x.sql", "SELECT 1;"}};
  EXPECT_FALSE(ApplyMigrations(*db, gap).ok());
}

TEST(Sqlite, TransactionRollsBackUnlessCommitted) {
  TempDir dir;
  auto db = sqlite::Database::Open((dir.path() / "t.sqlite").string());
  ASSERT_TRUE(db.ok());
  ASSERT_TRUE(db->Exec("CREATE TABLE t(x)").ok());
  {
    auto tx = sqlite::Transaction::Begin(*db);
    ASSERT_TRUE(tx.ok());
    ASSERT_TRUE(db->Exec("INSERT INTO t VALUES (1)").ok());
  }
  EXPECT_EQ(CountRows(*db, "SELECT COUNT(*) FROM t"), 0);
  {
    auto tx = sqlite::Transaction::Begin(*db);
    ASSERT_TRUE(db->Exec("INSERT INTO t VALUES (2)").ok());
    ASSERT_TRUE(tx->Commit().ok());
  }
  EXPECT_EQ(CountRows(*db, "SELECT COUNT(*) FROM t"), 1);
  auto mode = db->Prepare("PRAGMA journal_mode");
  ASSERT_TRUE(mode.ok() && *mode->Step());
  EXPECT_EQ(mode->ColumnText(0), "wal");
}

// The permission bits of a file (e.g. 0600).
unsigned ModeBits(const std::string& path) {
  struct stat st {};
  EXPECT_EQ(::stat(path.c_str(), &st), 0) << path;
  return st.st_mode & 0777;
}

// Sets the process umask for one scope.
class ScopedUmask {
 public:
  explicit ScopedUmask(mode_t mask) : old_(::umask(mask)) {}
  ~ScopedUmask() { ::umask(old_); }

 private:
  mode_t old_;
};

TEST(Sqlite, NewDatabaseFilesAreOwnerOnly) {
  TempDir dir;
  const std::string path = (dir.path() / "private.sqlite").string();
  ScopedUmask umask(022);  // would give 0644 to a file created with mode 0666
  auto db = sqlite::Database::Open(path);
  ASSERT_TRUE(db.ok()) << db.error().message;
  ASSERT_TRUE(db->Exec("CREATE TABLE t(x); INSERT INTO t VALUES (1);").ok());
  ASSERT_TRUE(std::filesystem::exists(path + "-wal"));  // open: not yet checkpointed away
  ASSERT_TRUE(std::filesystem::exists(path + "-shm"));
  EXPECT_EQ(ModeBits(path), 0600u);
  EXPECT_EQ(ModeBits(path + "-wal"), 0600u);
  EXPECT_EQ(ModeBits(path + "-shm"), 0600u);
}

TEST(Sqlite, ExistingDatabaseKeepsItsMode) {
  TempDir dir;
  const std::string path = (dir.path() / "shared.sqlite").string();
  { ASSERT_TRUE(sqlite::Database::Open(path).ok()); }
  ASSERT_EQ(::chmod(path.c_str(), 0640), 0);
  auto db = sqlite::Database::Open(path);
  ASSERT_TRUE(db.ok()) << db.error().message;
  ASSERT_TRUE(db->Exec("CREATE TABLE t(x)").ok());
  EXPECT_EQ(ModeBits(path), 0640u);
}

TEST(Sqlite, CommitsSyncFullyUnlessAskedNotTo) {
  TempDir dir;
  const std::string path = (dir.path() / "sync.sqlite").string();
  auto full = sqlite::Database::Open(path);
  auto normal = sqlite::Database::Open(path, sqlite::Sync::kNormal);
  ASSERT_TRUE(full.ok() && normal.ok());
  EXPECT_EQ(CountRows(*full, "PRAGMA synchronous"), 2);  // FULL
  EXPECT_EQ(CountRows(*normal, "PRAGMA synchronous"), 1);  // NORMAL
}

TEST(Sqlite, MissingDirectoryIsAClearError) {
  auto storage = OpenSqliteStorage("/nonexistent-reenact-dir/sub/db.sqlite");
  ASSERT_FALSE(storage.ok());
  EXPECT_EQ(storage.error().code, "io");
  EXPECT_NE(storage.error().message.find("does not exist"), std::string::npos);
}

}  // namespace
}  // namespace reenact::server
