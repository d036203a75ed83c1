// reenact-server's command line on both storage engines: --db FILE opens the SQLite file as
// always, --db postgresql://... the PostgreSQL database (the tests' throwaway cluster, skipped
// with a message where none is installed), and a wrong URL or password is one line at start.
#include "server/app/cli.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

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

TEST(ServerCli, UserAndTokenCommandsWorkOnAPostgresUrl) {
  auto database = testing::NewPostgresTestDatabase();
  if (!database && database.error().code == "unavailable") {
    GTEST_SKIP() << database.error().message;
  }
  ASSERT_TRUE(database.ok()) << database.error().message;
  auto url = pg::AsUrl(*database);
  ASSERT_TRUE(url.ok()) << url.error().message;
  ASSERT_EQ(url->rfind("postgresql://", 0), 0u) << *url;

  const CliRun added = RunCli({"user", "add", "alice", "--db", *url});
  ASSERT_EQ(added.code, 0) << added.err;
  const std::string token = added.out.substr(0, added.out.find('\n'));
  const CliRun second = RunCli({"token", "add", "alice", "--db", *url});
  ASSERT_EQ(second.code, 0) << second.err;

  auto storage = OpenPostgresStorage(*database);
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

}  // namespace
}  // namespace reenact::server
