// The server's protective limits on real sockets: per-token rate limits (429), the cap on
// concurrent connections (a half-sent header, else the longest idle connection, makes room;
// 503 when all are busy), the per-address cap, keep-alive.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <thread>

#include "proto/api/api_client.h"
#include "proto/api/http_client.h"
#include "server/http/http_server.h"
#include "tests/unit/server/server_test_util.h"

namespace reenact::server {
namespace {

// A raw loopback connection to write requests by hand and read what comes back.
class RawConnection {
 public:
  // from: the local address to connect from (any of 127.0.0.0/8 reaches the server).
  explicit RawConnection(uint16_t port, const char* from = nullptr) {
    fd_ = socket(AF_INET, SOCK_STREAM, 0);
    if (from) {
      sockaddr_in local{};
      local.sin_family = AF_INET;
      inet_pton(AF_INET, from, &local.sin_addr);
      (void)!bind(fd_, reinterpret_cast<sockaddr*>(&local), sizeof local);
    }
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    addr.sin_port = htons(port);
    connected_ = connect(fd_, reinterpret_cast<sockaddr*>(&addr), sizeof addr) == 0;
    timeval tv{5, 0};
    setsockopt(fd_, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
  }
  ~RawConnection() { close(fd_); }
  bool connected() const { return connected_; }
  void Send(const std::string& bytes) { (void)!write(fd_, bytes.data(), bytes.size()); }
  // Reads until `needle` appears, the peer closes, or 5 s pass.
  // True if the peer closed the connection (read returned 0 or an error) within 5 s.
  bool PeerClosed() {
    char c;
    return read(fd_, &c, 1) <= 0;
  }
  std::string ReadUntil(const std::string& needle) {
    std::string got;
    char buffer[4096];
    while (got.find(needle) == std::string::npos) {
      const ssize_t n = read(fd_, buffer, sizeof buffer);
      if (n <= 0) break;
      got.append(buffer, static_cast<size_t>(n));
    }
    return got;
  }

 private:
  int fd_ = -1;
  bool connected_ = false;
};

class ServerLimitsTest : public testing::ServiceFixture {
 protected:
  void Start(ServerOptions options) {
    options.host = "127.0.0.1";
    options.port = 0;
    server_ = std::make_unique<HttpServer>(*context_, options);
    auto port = server_->Listen();
    ASSERT_TRUE(port.ok()) << port.error().message;
    port_ = *port;
    thread_ = std::thread([this] { server_->Run(false); });
  }
  void TearDown() override {
    if (thread_.joinable()) {
      server_->Stop();
      thread_.join();
    }
  }
  std::string Url() const { return "http://127.0.0.1:" + std::to_string(port_); }

  std::unique_ptr<HttpServer> server_;
  uint16_t port_ = 0;
  std::thread thread_;
};

TEST_F(ServerLimitsTest, TokenOverItsRateGets429WithRetryAfterAndOthersDoNot) {
  ServerOptions options;
  options.rate_limit = {/*per_second=*/0.5, /*burst=*/3.0, /*max_keys=*/100};
  Start(options);
  proto::HttpClient http(Url());
  const proto::HttpRequest mine{
      "GET", "/v1/me/clips", {{"Authorization", "Bearer " + alice_}}, "", ""};
  // Burst of 3 at 0.5/s: the first three pass; the fourth, sent well within 2 s, does not.
  for (int i = 0; i < 3; ++i) ASSERT_EQ(http.Send(mine)->status, 200) << i;
  auto refused = http.Send(mine);
  ASSERT_TRUE(refused.ok());
  EXPECT_EQ(refused->status, 429);
  EXPECT_EQ(nlohmann::json::parse(refused->body)["error"]["code"], "rate_limited");
  ASSERT_TRUE(refused->Header("Retry-After").has_value());
  EXPECT_GE(std::stoi(*refused->Header("Retry-After")), 1);
  // Another token, and anonymous reads, are not affected.
  const proto::HttpRequest bobs{
      "GET", "/v1/me/clips", {{"Authorization", "Bearer " + bob_}}, "", ""};
  EXPECT_EQ(http.Send(bobs)->status, 200);
  EXPECT_EQ(http.Send({"GET", "/healthz", {}, "", ""})->status, 200);
}

TEST_F(ServerLimitsTest, RateLimitedUploadStoresNothing) {
  ServerOptions options;
  options.rate_limit = {0.01, 1.0, 100};
  Start(options);
  const testing::TestClip clip = testing::MakeTestClip(1, 2, 1);
  proto::HttpClient http(Url());
  const proto::HttpRequest create{"POST",
                                  "/v1/clips",
                                  {{"Authorization", "Bearer " + alice_}},
                                  "application/json",
                                  clip.manifest_json};
  ASSERT_EQ(http.Send(create)->status, 201);
  EXPECT_EQ(http.Send(create)->status, 429);
  EXPECT_EQ(*storage_.metadata->CountClips(ClipState::kDraft), 1);
}

constexpr const char* kHealth = "GET /healthz HTTP/1.1\r\nHost: x\r\n\r\n";

TEST_F(ServerLimitsTest, AtTheCapTheLongestIdleConnectionMakesRoomForANewOne) {
  ServerOptions options;
  options.max_connections = 2;
  Start(options);
  RawConnection a(port_), b(port_);
  ASSERT_TRUE(a.connected() && b.connected());
  // Both are served and then sit idle between requests; b has waited longest.
  b.Send(kHealth);
  EXPECT_NE(b.ReadUntil("\"ok\"}").find("200 OK"), std::string::npos);
  a.Send(kHealth);
  EXPECT_NE(a.ReadUntil("\"ok\"}").find("200 OK"), std::string::npos);

  RawConnection third(port_);
  third.Send(kHealth);
  EXPECT_NE(third.ReadUntil("\"ok\"}").find("200 OK"), std::string::npos);
  EXPECT_TRUE(b.PeerClosed()) << "the longest idle connection should have made room";
  a.Send(kHealth);
  EXPECT_NE(a.ReadUntil("\"ok\"}").find("200 OK"), std::string::npos) << "a was not idle longest";
}

TEST_F(ServerLimitsTest, AtTheCapAHalfSentHeaderGoesBeforeAnOlderIdleConnection) {
  ServerOptions options;
  options.max_connections = 2;
  Start(options);
  RawConnection idle(port_), half(port_);
  idle.Send(kHealth);
  EXPECT_NE(idle.ReadUntil("\"ok\"}").find("200 OK"), std::string::npos);
  half.Send("GET /healthz HTTP/1.1\r\nHo");  // newer than idle's wait, but never finished
  std::this_thread::sleep_for(std::chrono::milliseconds(100));

  RawConnection third(port_);
  third.Send(kHealth);
  EXPECT_NE(third.ReadUntil("\"ok\"}").find("200 OK"), std::string::npos);
  EXPECT_TRUE(half.PeerClosed()) << "the half-sent header should have made room";
  idle.Send(kHealth);
  EXPECT_NE(idle.ReadUntil("\"ok\"}").find("200 OK"), std::string::npos);
}

TEST_F(ServerLimitsTest, WhenEveryConnectionIsBusyANewOneGets503AndServiceResumes) {
  ServerOptions options;
  options.max_connections = 2;
  Start(options);
  // Two uploads in progress: admitted, each with half its manifest body still to come.
  const testing::TestClip clip = testing::MakeTestClip(1, 2, 1);
  const std::string& body = clip.manifest_json;
  const std::string head = "POST /v1/clips HTTP/1.1\r\nHost: x\r\nAuthorization: Bearer " +
                           alice_ + "\r\nContent-Type: application/json\r\nContent-Length: " +
                           std::to_string(body.size()) + "\r\n\r\n";
  RawConnection a(port_), b(port_);
  a.Send(head + body.substr(0, body.size() / 2));
  b.Send(head + body.substr(0, body.size() / 2));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // both are reading bodies

  RawConnection third(port_);
  third.Send(kHealth);
  const std::string answer = third.ReadUntil("}}");
  EXPECT_NE(answer.find("503"), std::string::npos) << answer;
  EXPECT_NE(answer.find("\"code\":\"unavailable\""), std::string::npos) << answer;

  // The busy ones finish normally; afterwards a new connection is served again.
  a.Send(body.substr(body.size() / 2));
  EXPECT_NE(a.ReadUntil("}").find("201 Created"), std::string::npos);
  b.Send(body.substr(body.size() / 2));
  EXPECT_NE(b.ReadUntil("}").find("201 Created"), std::string::npos);
  RawConnection fourth(port_);
  fourth.Send(kHealth);
  EXPECT_NE(fourth.ReadUntil("\"ok\"}").find("200 OK"), std::string::npos);
}

TEST_F(ServerLimitsTest, OneAddressHoldsAtMostItsShareWhileOthersAreServed) {
  ServerOptions options;
  options.max_connections_per_address = 2;
  Start(options);
  RawConnection a(port_, "127.0.0.1"), b(port_, "127.0.0.1");
  a.Send(kHealth);
  b.Send(kHealth);
  a.ReadUntil("\"ok\"}");
  b.ReadUntil("\"ok\"}");
  RawConnection third(port_, "127.0.0.1");
  third.Send(kHealth);
  const std::string refused = third.ReadUntil("}}");
  EXPECT_NE(refused.find("503"), std::string::npos) << refused;
  EXPECT_NE(refused.find("this address holds 2 connections"), std::string::npos) << refused;
  RawConnection other(port_, "127.0.0.2");
  other.Send(kHealth);
  EXPECT_NE(other.ReadUntil("\"ok\"}").find("200 OK"), std::string::npos);
  // A closed connection gives its address's slot back.
  a.Send("GET /healthz HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n");
  EXPECT_TRUE(a.ReadUntil("\"ok\"}").find("200 OK") != std::string::npos);
  for (int attempt = 0; attempt < 100; ++attempt) {
    RawConnection again(port_, "127.0.0.1");
    again.Send(kHealth);
    if (again.ReadUntil("}").find("200 OK") != std::string::npos) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ADD_FAILURE() << "the address's slot did not come back after one of its connections closed";
}

TEST(ServerOptions, ThreadsDefaultToTheMachineAndBadValuesAreRefused) {
  ServerOptions options;
  EXPECT_EQ(options.threads, 0);
  EXPECT_GE(options.ResolvedThreads(), 2);
  EXPECT_GE(options.ResolvedThreads(), static_cast<int>(std::thread::hardware_concurrency()));
  options.max_connections = 0;
  EXPECT_ANY_THROW(options.Check());
  options.max_connections = 1;
  options.max_connections_per_address = -1;
  EXPECT_ANY_THROW(options.Check());
  options.max_connections_per_address = 0;
  options.handler_threads = -1;
  EXPECT_ANY_THROW(options.Check());
  options.handler_threads = 0;
  EXPECT_GE(options.ResolvedHandlerThreads(), 4);
  options.min_transfer_rate.bytes_per_s = -1;
  EXPECT_ANY_THROW(options.Check());
  options.min_transfer_rate.bytes_per_s = 0;
  options.max_connections = 1;
  options.threads = -1;
  EXPECT_ANY_THROW(options.Check());
}

}  // namespace
}  // namespace reenact::server

namespace reenact::server {
namespace {

TEST_F(ServerLimitsTest, ApiClientWaitsOutA429AndSucceeds) {
  ServerOptions options;
  options.rate_limit = {/*per_second=*/4.0, /*burst=*/1.0, /*max_keys=*/100};
  Start(options);
  const proto::ApiClient alice(Url(), alice_);
  // Burst 1: the second call is refused at first; the client waits the Retry-After (the
  // server rounds 0.25 s up to 1 s) and sends it again, so both calls succeed.
  const auto start = std::chrono::steady_clock::now();
  ASSERT_TRUE(alice.MyClips().ok());
  const auto second = alice.MyClips();
  ASSERT_TRUE(second.ok()) << second.error().message;
  EXPECT_GE(std::chrono::steady_clock::now() - start, std::chrono::milliseconds(200));
}

}  // namespace
}  // namespace reenact::server
