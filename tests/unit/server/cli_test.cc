// reenact-server's command line on both storage engines: --db FILE opens the SQLite file as
// always, --db postgresql://... the PostgreSQL database (the tests' throwaway cluster, skipped
// with a message where none is installed), and a wrong URL or password is one line at start;
// --blobs and migrate-db's --from-blobs/--to-blobs keep the blobs as files in a directory.
#include "server/app/cli.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "proto/clip/content_hash.h"
#include "server/auth/token.h"
#include "server/storage/open_storage.h"
#include "server/storage/postgres.h"
#include "tests/unit/server/postgres_test_cluster.h"
#include "tests/unit/server/server_test_util.h"

namespace reenact::server {
namespace {

using testing::TempDir;

struct CliRun {
  int code = 0;
  std::string out;
  std::string err;
};

CliRun RunCli(const std::vector<std::string>& words) {
  std::vector<const char*> argv = {"reenact-server"};
  for (const std::string& w : words) argv.push_back(w.c_str());
  std::ostringstream out, err;
  CliRun run;
  run.code = RunServerCli(static_cast<int>(argv.size()), argv.data(), out, err);
  run.out = out.str();
  run.err = err.str();
  return run;
}

// Expects `run` to have failed at start with exactly one line on stderr and nothing on stdout.
void ExpectOneLineFailure(const CliRun& run) {
  EXPECT_EQ(run.code, 1) << run.err;
  EXPECT_EQ(run.out, "");
  ASSERT_FALSE(run.err.empty());
  EXPECT_EQ(run.err.find('\n'), run.err.size() - 1) << run.err;
  EXPECT_EQ(run.err.rfind("reenact-server: ", 0), 0u) << run.err;
}

TEST(ServerCli, UnreachablePostgresIsOneLineAtStartWithoutThePassword) {
  for (const char* scheme : {"postgresql://", "postgres://"}) {
    std::string url = scheme;
    url += "someone:topsecret@/reenact?host=/nonexistent-reenact-socket-dir";
    const CliRun run = RunCli({"serve", "--db", url, "--listen", "127.0.0.1:0"});
    ExpectOneLineFailure(run);
    EXPECT_NE(run.err.find("cannot connect to PostgreSQL database 'reenact' as user 'someone'"),
              std::string::npos)
        << run.err;
    EXPECT_EQ(run.err.find("topsecret"), std::string::npos) << run.err;
  }
}

TEST(ServerCli, MalformedPostgresUrlIsOneLineNamingTheProblem) {
  const CliRun run =
      RunCli({"user", "add", "alice", "--db", "postgresql://a@b/c?no_such_option=1"});
  ExpectOneLineFailure(run);
  EXPECT_NE(run.err.find("no_such_option"), std::string::npos) << run.err;
}

TEST(ServerCli, WrongPostgresPasswordIsOneLineAtStart) {
  auto login = testing::PostgresTestPasswordLogin("postgres", "right-secret");
  if (!login && login.error().code == "unavailable") GTEST_SKIP() << login.error().message;
  ASSERT_TRUE(login.ok()) << login.error().message;
  auto url = pg::AsUrl(*login + " password=wrong-secret");
  ASSERT_TRUE(url.ok()) << url.error().message;
  const CliRun run = RunCli({"serve", "--db", *url, "--listen", "127.0.0.1:0"});
  ExpectOneLineFailure(run);
  EXPECT_NE(run.err.find("password authentication failed"), std::string::npos) << run.err;
  EXPECT_EQ(run.err.find("wrong-secret"), std::string::npos) << run.err;
}

// `url`: a new database of the PostgreSQL test cluster as a postgresql:// URL; skips where
// none can be started.
#define REENACT_POSTGRES_URL_OR_SKIP(url)                                      \
  auto url##_conninfo = testing::NewPostgresTestDatabase();                    \
  if (!url##_conninfo && url##_conninfo.error().code == "unavailable") {       \
    GTEST_SKIP() << url##_conninfo.error().message;                            \
  }                                                                            \
  ASSERT_TRUE(url##_conninfo.ok()) << url##_conninfo.error().message;         \
  auto url = pg::AsUrl(*url##_conninfo);                                       \
  ASSERT_TRUE(url.ok()) << url.error().message

TEST(ServerCli, UserAndTokenCommandsWorkOnAPostgresUrl) {
  REENACT_POSTGRES_URL_OR_SKIP(url);
  ASSERT_EQ(url->rfind("postgresql://", 0), 0u) << *url;

  const CliRun added = RunCli({"user", "add", "alice", "--db", *url});
  ASSERT_EQ(added.code, 0) << added.err;
  const std::string token = added.out.substr(0, added.out.find('\n'));
  const CliRun second = RunCli({"token", "add", "alice", "--db", *url});
  ASSERT_EQ(second.code, 0) << second.err;

  auto storage = OpenPostgresStorage(*url);
  ASSERT_TRUE(storage.ok()) << storage.error().message;
  auto owner = storage->metadata->FindUserByTokenHash(HashToken(token));
  ASSERT_TRUE(owner.ok() && owner->has_value());
  EXPECT_EQ((*owner)->user.name, "alice");

  const CliRun revoked = RunCli({"token", "revoke", "alice", "--db", *url});
  ASSERT_EQ(revoked.code, 0) << revoked.err;
  EXPECT_EQ(revoked.out, "revoked 2 token(s) of 'alice'\n");
  EXPECT_FALSE(storage->metadata->FindUserByTokenHash(HashToken(token))->has_value());
}

TEST(ServerCli, AFileKeepsSqlite) {
  TempDir dir;
  const std::string path = (dir.path() / "reenact.db").string();
  const CliRun added = RunCli({"user", "add", "bob", "--db", path});
  ASSERT_EQ(added.code, 0) << added.err;
  ASSERT_TRUE(std::filesystem::exists(path));
  auto storage = OpenSqliteStorage(path);
  ASSERT_TRUE(storage.ok()) << storage.error().message;
  const std::string token = added.out.substr(0, added.out.find('\n'));
  auto owner = storage->metadata->FindUserByTokenHash(HashToken(token));
  ASSERT_TRUE(owner.ok() && owner->has_value());
  EXPECT_EQ((*owner)->user.name, "bob");
}

// A SQLite file at `path` with user alice and one published clip of one frame and a map;
// returns the bytes of its payloads.
int64_t MakeSourceFile(const std::string& path) {
  auto storage = OpenSqliteStorage(path);
  EXPECT_TRUE(storage.ok()) << storage.error().message;
  if (!storage.ok()) return 0;
  auto alice = storage->metadata->AddUser("alice", HashToken("rnk_alice"));
  EXPECT_TRUE(alice.ok());
  const testing::TestClip clip = testing::MakeTestClip(47.37, 8.54, 1, "zurich");
  NewClip draft;
  draft.record.id = "zurich";
  draft.record.owner_id = alice.ok() ? alice->id : 0;
  draft.record.frame_count = 1;
  draft.record.manifest_sha256 = proto::Sha256Hex(clip.manifest_json);
  draft.manifest_json = clip.manifest_json;
  draft.parts = {{0, static_cast<int64_t>(clip.frames[0].size()), proto::Sha256Hex(clip.frames[0])},
                 {kMapPart, static_cast<int64_t>(clip.map.size()), proto::Sha256Hex(clip.map)}};
  EXPECT_TRUE(storage->metadata->CreateClip(draft).ok());
  EXPECT_TRUE(storage->blobs->Put(BlobKey("zurich", 0), clip.frames[0]).ok());
  EXPECT_TRUE(storage->blobs->Put(BlobKey("zurich", kMapPart), clip.map).ok());
  EXPECT_TRUE(storage->metadata->MarkPartPresent("zurich", 0).ok());
  EXPECT_TRUE(storage->metadata->MarkPartPresent("zurich", kMapPart).ok());
  EXPECT_TRUE(storage->metadata->Publish("zurich")->published);
  return static_cast<int64_t>(clip.frames[0].size() + clip.map.size());
}

TEST(ServerCli, MigrateDbCopiesAFileIntoPostgresPrintsTheSummaryAndRefusesASecondRun) {
  REENACT_POSTGRES_URL_OR_SKIP(url);
  TempDir dir;
  const std::string path = (dir.path() / "reenact.db").string();
  const int64_t bytes = MakeSourceFile(path);

  const CliRun copied = RunCli({"migrate-db", "--from", path, "--to", *url});
  ASSERT_EQ(copied.code, 0) << copied.err;
  std::string expected = "copied 1 users, 1 tokens, 1 clips (1 published), 2 parts, 2 blobs, ";
  expected += std::to_string(bytes);
  expected += " bytes in ";
  EXPECT_EQ(copied.out.rfind(expected, 0), 0u) << copied.out;
  EXPECT_NE(copied.out.find(" s; verified by SHA-256\n"), std::string::npos) << copied.out;
  EXPECT_EQ(copied.out.find('\n'), copied.out.size() - 1);

  auto storage = OpenPostgresStorage(*url);
  ASSERT_TRUE(storage.ok()) << storage.error().message;
  auto owner = storage->metadata->FindUserByTokenHash(HashToken("rnk_alice"));
  ASSERT_TRUE(owner.ok() && owner->has_value());
  EXPECT_EQ((*owner)->user.name, "alice");
  EXPECT_EQ(*storage->metadata->CountClips(ClipState::kPublished), 1);

  const CliRun again = RunCli({"migrate-db", "--from", path, "--to", *url});
  ExpectOneLineFailure(again);
  EXPECT_NE(again.err.find("empty database"), std::string::npos) << again.err;
}

TEST(ServerCli, MigrateDbIntoAnotherFileWorksWithoutPostgres) {
  TempDir dir;
  const std::string from = (dir.path() / "from.db").string();
  const std::string to = (dir.path() / "to.db").string();
  const int64_t bytes = MakeSourceFile(from);
  const CliRun copied = RunCli({"migrate-db", "--from", from, "--to", to});
  ASSERT_EQ(copied.code, 0) << copied.err;
  EXPECT_NE(copied.out.find(", 2 blobs, " + std::to_string(bytes) + " bytes in "),
            std::string::npos)
      << copied.out;
}

TEST(ServerCli, MigrateDbFromAMissingFileIsOneLineAndCreatesNothing) {
  TempDir dir;
  const std::string missing = (dir.path() / "missing.db").string();
  const std::string to = (dir.path() / "to.db").string();
  const CliRun run = RunCli({"migrate-db", "--from", missing, "--to", to});
  EXPECT_EQ(run.code, 2);
  EXPECT_EQ(run.out, "");
  EXPECT_EQ(run.err.find('\n'), run.err.size() - 1) << run.err;
  EXPECT_NE(run.err.find("no database file at '" + missing + "'"), std::string::npos) << run.err;
  EXPECT_FALSE(std::filesystem::exists(missing));
  EXPECT_FALSE(std::filesystem::exists(to));
}

TEST(ServerCli, AMissingOrNonDirectoryBlobsPathIsOneLineAndCreatesNoDatabase) {
  TempDir dir;
  const std::string db = (dir.path() / "reenact.db").string();
  const std::string missing = (dir.path() / "missing").string();
  const std::string file = (dir.path() / "file").string();
  { std::ofstream(file) << "not a directory"; }
  for (const std::string& blobs : {missing, file}) {
    const CliRun run =
        RunCli({"serve", "--db", db, "--blobs", blobs, "--listen", "127.0.0.1:0"});
    ExpectOneLineFailure(run);
    EXPECT_NE(run.err.find("blob directory '" + blobs + "'"), std::string::npos) << run.err;
    EXPECT_FALSE(std::filesystem::exists(db));
  }
}

TEST(ServerCli, MigrateDbMovesTheBlobsIntoADirectory) {
  TempDir dir;
  const std::string from = (dir.path() / "from.db").string();
  const std::string to = (dir.path() / "to.db").string();
  const std::filesystem::path blobs = dir.path() / "blobs";
  std::filesystem::create_directory(blobs);
  const int64_t bytes = MakeSourceFile(from);
  const CliRun copied =
      RunCli({"migrate-db", "--from", from, "--to", to, "--to-blobs", blobs.string()});
  ASSERT_EQ(copied.code, 0) << copied.err;
  EXPECT_NE(copied.out.find(", 2 blobs, " + std::to_string(bytes) + " bytes in "),
            std::string::npos)
      << copied.out;
  const testing::TestClip clip = testing::MakeTestClip(47.37, 8.54, 1, "zurich");
  std::ifstream frame(blobs / "zurich" / "frames" / "0.blob", std::ios::binary);
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(frame), {}), clip.frames[0]);
  EXPECT_TRUE(std::filesystem::is_regular_file(blobs / "zurich" / "map.blob"));

  // And back into the database, reading the files.
  const std::string back = (dir.path() / "back.db").string();
  const CliRun returned =
      RunCli({"migrate-db", "--from", to, "--from-blobs", blobs.string(), "--to", back});
  ASSERT_EQ(returned.code, 0) << returned.err;
  auto storage = OpenSqliteStorage(back);
  ASSERT_TRUE(storage.ok()) << storage.error().message;
  EXPECT_EQ(**storage->blobs->Get(BlobKey("zurich", 0)), clip.frames[0]);
}

TEST(ServerCli, MigrateDbNeedsBothEnds) {
  const CliRun run = RunCli({"migrate-db", "--from", "a.db"});
  EXPECT_EQ(run.code, 2);
  EXPECT_NE(run.err.find("migrate-db needs --from FILE|URL and --to URL|FILE"), std::string::npos)
      << run.err;
}

}  // namespace
}  // namespace reenact::server
