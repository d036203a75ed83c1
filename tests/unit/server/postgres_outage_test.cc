// A PostgreSQL that goes away while the stores and routes serve, and comes back: the test
// cluster (postgres_test_cluster.h) is stopped, immediately (as a crash) or fast (sessions
// told first), and started again on the same data: always the test process's own cluster,
// never REENACT_TEST_POSTGRES_URL's server. Skipped where no cluster can be started.
#include <gtest/gtest.h>

#include "server/http/handlers.h"
#include "server/storage/postgres.h"
#include "tests/unit/server/server_test_util.h"

namespace reenact::server {
namespace {

using testing::MakeTestClip;

enum class StopMode { kImmediate, kFast };

std::string StopModeName(const ::testing::TestParamInfo<StopMode>& info) {
  return info.param == StopMode::kImmediate ? "Immediate" : "Fast";
}

// Starts the cluster again if a test ends (or fails) while it is stopped.
class ClusterRestarter {
 public:
  ~ClusterRestarter() {
    if (stopped_) {
      EXPECT_TRUE(testing::StartPostgresTestCluster().ok());
    }
  }
  // Stops the cluster; remembers to start it again.
  Status Stop(StopMode mode) {
    Status s = testing::StopPostgresTestCluster(mode == StopMode::kImmediate);
    stopped_ = s.ok();
    return s;
  }
  Status Start() {
    Status s = testing::StartPostgresTestCluster();
    if (s.ok()) stopped_ = false;
    return s;
  }

 private:
  bool stopped_ = false;
};

class PostgresOutageTest : public testing::ServiceFixture,
                           public ::testing::WithParamInterface<StopMode> {
 protected:
  testing::Engine engine() const override { return testing::Engine::kPostgres; }
  testing::TestCluster postgres_cluster() const override { return testing::TestCluster::kOwn; }

  // Stops the cluster, skipping where the tests may not.
  void StopCluster() {
    Status s = restarter_.Stop(GetParam());
    if (!s && s.error().code == "unavailable") GTEST_SKIP() << s.error().message;
    ASSERT_TRUE(s.ok()) << s.error().message;
  }

  ClusterRestarter restarter_;
};
INSTANTIATE_TEST_SUITE_P(Stops, PostgresOutageTest,
                         ::testing::Values(StopMode::kImmediate, StopMode::kFast), StopModeName);

void ExpectUnavailable(const Error& error) {
  EXPECT_EQ(error.code, "unavailable") << error.message;
  EXPECT_NE(error.message.find("PostgreSQL"), std::string::npos) << error.message;
  EXPECT_NE(error.message.find("is unavailable"), std::string::npos) << error.message;
}

TEST_P(PostgresOutageTest, StoresFailUnavailableWhileStoppedAndWorkAgainAfterwards) {
  const testing::TestClip clip = MakeTestClip(46.5, 6.6, 2, "kept");
  const std::string id = Publish(clip, alice_);
  ASSERT_TRUE(storage_.blobs->Put("outage/kept", "kept bytes").ok());

  StopCluster();
  if (IsSkipped() || HasFatalFailure()) return;

  // Twice: the first statement finds the session gone, the second finds no server to reopen.
  for (int attempt = 0; attempt < 2; ++attempt) {
    auto got = storage_.metadata->GetClip(id);
    ASSERT_FALSE(got.ok());
    ExpectUnavailable(got.error());
  }
  auto blob = storage_.blobs->Get("outage/kept");
  ASSERT_FALSE(blob.ok());
  ExpectUnavailable(blob.error());
  Status put = storage_.blobs->Put("outage/lost", "lost bytes");
  ASSERT_FALSE(put.ok());
  ExpectUnavailable(put.error());
  auto user = storage_.metadata->AddUser("carol", std::string(64, 'c'));
  ASSERT_FALSE(user.ok());
  ExpectUnavailable(user.error());

  ASSERT_TRUE(restarter_.Start().ok());

  // The same store objects, without reopening them.
  auto got = storage_.metadata->GetClip(id);
  ASSERT_TRUE(got.ok()) << got.error().message;
  ASSERT_TRUE(got->has_value());
  EXPECT_EQ((*got)->state, ClipState::kPublished);
  auto kept = storage_.blobs->Get("outage/kept");
  ASSERT_TRUE(kept.ok()) << kept.error().message;
  EXPECT_EQ(kept->value_or(""), "kept bytes");
  auto lost = storage_.blobs->Get("outage/lost");
  ASSERT_TRUE(lost.ok()) << lost.error().message;
  EXPECT_FALSE(lost->has_value());
  auto users = storage_.metadata->ListUsers();
  ASSERT_TRUE(users.ok()) << users.error().message;
  ASSERT_EQ(users->size(), 2u);  // alice and bob; carol was never written
  auto published = storage_.metadata->CountClips(ClipState::kPublished);
  ASSERT_TRUE(published.ok()) << published.error().message;
  EXPECT_EQ(*published, 1);
}

TEST_P(PostgresOutageTest, RoutesAnswer503WithRetryAfterWhileStoppedAnd200Afterwards) {
  const testing::TestClip clip = MakeTestClip(46.5, 6.6, 2, "kept");
  const std::string id = Publish(clip, alice_);

  StopCluster();
  if (IsSkipped() || HasFatalFailure()) return;

  for (const auto& [method, target, token] :
       {std::tuple<std::string, std::string, std::string>{"GET", "/v1/clips/" + id, ""},
        {"GET", "/v1/clips/" + id + "/frames/0", ""},
        {"GET", "/v1/me/clips", alice_},
        {"GET", "/healthz", ""}}) {
    Response r = Call(method, target, token);
    EXPECT_EQ(r.status, 503) << method << " " << target << ": " << r.body;
    EXPECT_EQ(ErrorCode(r), "unavailable") << target;
    if (target != "/healthz") {
      EXPECT_NE(ErrorMessage(r).find("database is not reachable"), std::string::npos)
          << ErrorMessage(r);
      EXPECT_EQ(proto::FindHeader(r.headers, "Retry-After"),
                std::to_string(handlers::kDatabaseRetryAfterSeconds))
          << target;
    }
  }
  const testing::TestClip lost = MakeTestClip(1.0, 2.0, 1, "lost");
  Response create = Call("POST", "/v1/clips", alice_, lost.manifest_json, "application/json");
  EXPECT_EQ(create.status, 503) << create.body;

  ASSERT_TRUE(restarter_.Start().ok());

  Response r = Call("GET", "/v1/clips/" + id);
  EXPECT_EQ(r.status, 200) << r.body;
  Response frame = Call("GET", "/v1/clips/" + id + "/frames/1");
  EXPECT_EQ(frame.status, 200) << frame.body;
  EXPECT_EQ(frame.body, clip.frames[1]);
  Response mine = Call("GET", "/v1/me/clips", alice_);
  ASSERT_EQ(mine.status, 200) << mine.body;
  const nlohmann::json listed = nlohmann::json::parse(mine.body);
  const nlohmann::json& clips = listed.at("clips");
  ASSERT_EQ(clips.size(), 1u) << mine.body;  // the clip created during the outage does not exist
  EXPECT_EQ(clips[0].at("id").get<std::string>(), id);
  EXPECT_EQ(Call("GET", "/healthz").status, 200);
  Publish(MakeTestClip(1.0, 2.0, 1, "after"), alice_);
}

TEST_P(PostgresOutageTest, ATransactionCutPartWayWritesNothingAndIsNotCommittedOnANewSession) {
  auto url = testing::NewPostgresTestDatabase(testing::TestCluster::kOwn);
  if (!url && url.error().code == "unavailable") GTEST_SKIP() << url.error().message;
  ASSERT_TRUE(url.ok()) << url.error().message;
  auto db = pg::Connection::Open(*url);
  ASSERT_TRUE(db.ok()) << db.error().message;
  ASSERT_TRUE(db->Exec("CREATE TABLE rows_written (n integer)").ok());
  {
    auto tx = pg::Transaction::Begin(*db);
    ASSERT_TRUE(tx.ok()) << tx.error().message;
    ASSERT_TRUE(db->Query("INSERT INTO rows_written VALUES (1)").ok());

    StopCluster();
    if (IsSkipped() || HasFatalFailure()) return;
    ASSERT_TRUE(restarter_.Start().ok());

    // The server is back, but the transaction's session is gone: the rest of it fails, and
    // COMMIT must not go to a new session (where it would answer success for nothing).
    auto second = db->Query("INSERT INTO rows_written VALUES (2)");
    ASSERT_FALSE(second.ok());
    ExpectUnavailable(second.error());
    Status committed = tx->Commit();
    ASSERT_FALSE(committed.ok());
    ExpectUnavailable(committed.error());
  }
  auto rows = db->Query("SELECT count(*) FROM rows_written");
  ASSERT_TRUE(rows.ok()) << rows.error().message;
  EXPECT_EQ(rows->Int(0, 0), 0);
}

}  // namespace
}  // namespace reenact::server
