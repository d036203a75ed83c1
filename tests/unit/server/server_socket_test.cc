// The real server on 127.0.0.1 with a free port, driven end to end by proto's ApiClient, on each
// storage engine (SQLite with blobs in the database or as files; PostgreSQL where the tests'
// cluster can be started).
#include "server/http/http_server.h"

#include <thread>

#include <gtest/gtest.h>

#include "proto/api/api_client.h"
#include "tests/unit/server/server_test_util.h"

namespace reenact::server {
namespace {

using testing::MakeTestClip;
using testing::TestClip;

class ServerSocketTest : public testing::EngineServiceFixture {
 protected:
  void SetUp() override {
    EngineServiceFixture::SetUp();
    if (IsSkipped() || HasFatalFailure()) return;
    ServerOptions options;
    options.host = "127.0.0.1";
    options.port = 0;
    server_ = std::make_unique<HttpServer>(*context_, options);
    auto port = server_->Listen();
    ASSERT_TRUE(port.ok()) << port.error().message;
    ASSERT_NE(*port, 0);
    port_ = *port;
    url_ = "http://127.0.0.1:" + std::to_string(port_);
    thread_ = std::thread([this] { server_->Run(false); });
  }
  void TearDown() override {
    if (thread_.joinable()) {
      server_->Stop();
      thread_.join();
    }
  }

  std::unique_ptr<HttpServer> server_;
  uint16_t port_ = 0;
  std::string url_;
  std::thread thread_;
};

INSTANTIATE_TEST_SUITE_P(Engines, ServerSocketTest,
                         ::testing::Values(testing::Engine::kSqlite, testing::Engine::kPostgres,
                                           testing::Engine::kSqliteFiles),
                         testing::EngineName);

TEST_P(ServerSocketTest, UploadPublishBrowseDownloadDelete) {
  const TestClip clip = MakeTestClip(35.0, 139.0, 3, "tokyo");
  proto::ApiClient alice(url_, alice_);
  auto id = alice.CreateClip(clip.manifest_json);
  ASSERT_TRUE(id.ok()) << id.error().message;

  auto early = alice.Publish(*id);
  ASSERT_FALSE(early.ok());
  EXPECT_EQ(early.error().code, "incomplete");
  EXPECT_NE(early.error().message.find("frames 0, 1, 2 and the map"), std::string::npos);

  for (int n = 0; n < 3; ++n) ASSERT_TRUE(alice.PutFrame(*id, n, clip.frames[n]).ok());
  ASSERT_TRUE(alice.PutFrame(*id, 0, clip.frames[0]).ok());  // resumed upload: idempotent
  ASSERT_TRUE(alice.PutMap(*id, clip.map).ok());
  ASSERT_TRUE(alice.Publish(*id).ok());

  proto::ApiClient anonymous(url_, "");
  auto nearby = anonymous.Nearby(35.0, 139.001, 1000, 10);
  ASSERT_TRUE(nearby.ok()) << nearby.error().message;
  ASSERT_EQ(nearby->size(), 1u);
  EXPECT_EQ((*nearby)[0].id, *id);
  EXPECT_EQ((*nearby)[0].title, "tokyo");
  EXPECT_EQ((*nearby)[0].frame_count, 3);
  // 0.001 deg of longitude at 35 deg N: R * cos(35 deg) * 0.001 deg = 91.09 m (the
  // great-circle distance is shorter than the parallel's arc by far less than a millimetre).
  EXPECT_NEAR((*nearby)[0].distance_m, 91.0858, 0.01);

  auto manifest = anonymous.GetManifest(*id);
  ASSERT_TRUE(manifest.ok());
  EXPECT_EQ(*manifest, clip.manifest_json);
  auto frame = anonymous.GetFrame(*id, 2);
  ASSERT_TRUE(frame.ok());
  EXPECT_EQ(*frame, clip.frames[2]);
  auto map = anonymous.GetMap(*id);
  ASSERT_TRUE(map.ok());
  EXPECT_EQ(*map, clip.map);

  proto::ApiClient bob(url_, bob_);
  auto forbidden = bob.DeleteClip(*id);
  ASSERT_FALSE(forbidden.ok());
  EXPECT_EQ(forbidden.error().code, "forbidden");

  ASSERT_TRUE(alice.DeleteClip(*id).ok());
  auto gone = anonymous.GetManifest(*id);
  ASSERT_FALSE(gone.ok());
  EXPECT_EQ(gone.error().code, "not_found");
}

TEST_P(ServerSocketTest, ServerErrorsReachTheClient) {
  proto::ApiClient bad_token(url_, "rnk_wrong");
  auto created = bad_token.CreateClip(MakeTestClip(0, 0).manifest_json);
  ASSERT_FALSE(created.ok());
  EXPECT_EQ(created.error().code, "unauthorized");
  EXPECT_NE(created.error().message.find("unknown token"), std::string::npos);
}

TEST_P(ServerSocketTest, OversizedBodyGets413) {
  const TestClip clip = MakeTestClip(0, 0, 1);
  proto::ApiClient alice(url_, alice_);
  auto id = alice.CreateClip(clip.manifest_json);
  ASSERT_TRUE(id.ok());
  const std::string huge(context_->limits.max_frame_bytes + 1, 'z');
  auto put = alice.PutFrame(*id, 0, huge);
  ASSERT_FALSE(put.ok());
  EXPECT_EQ(put.error().code, "too_large") << put.error().message;
}

TEST_P(ServerSocketTest, MetricsCountRequestsByRoute) {
  proto::HttpClient http(url_);
  ASSERT_EQ(http.Send({"GET", "/healthz", {}, "", ""})->status, 200);
  auto metrics = http.Send({"GET", "/metrics", {}, "", ""});
  ASSERT_TRUE(metrics.ok());
  EXPECT_NE(metrics->body.find("reenact_http_requests_total{route=\"GET /healthz\",status=\"200\"} 1"),
            std::string::npos)
      << metrics->body;
  EXPECT_NE(metrics->body.find("reenact_http_request_duration_seconds_bucket"), std::string::npos);
}

TEST_P(ServerSocketTest, TakenPortIsAClearError) {
  ServerOptions options;
  options.port = port_;
  HttpServer second(*context_, options);
  auto port = second.Listen();
  ASSERT_FALSE(port.ok());
  EXPECT_EQ(port.error().code, "address_in_use");
}

TEST_P(ServerSocketTest, StopReturnsFromRunWithIdleConnectionsOpen) {
  proto::HttpClient http(url_);
  ASSERT_TRUE(http.Send({"GET", "/healthz", {}, "", ""}).ok());
  server_->Stop();
  thread_.join();
  auto after = http.Send({"GET", "/healthz", {}, "", ""});
  ASSERT_FALSE(after.ok());
  EXPECT_EQ(after.error().code, "unreachable");
}

TEST(ListenAddress, Parses) {
  auto a = ParseListenAddress("127.0.0.1:0");
  ASSERT_TRUE(a.ok());
  EXPECT_EQ(a->first, "127.0.0.1");
  EXPECT_EQ(a->second, 0);
  EXPECT_EQ(ParseListenAddress("[::1]:8080")->first, "::1");
  EXPECT_FALSE(ParseListenAddress("localhost").ok());
  EXPECT_FALSE(ParseListenAddress("host:99999").ok());
  EXPECT_FALSE(ParseListenAddress(":80").ok());
}

}  // namespace
}  // namespace reenact::server
