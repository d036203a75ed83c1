#include "proto/api/http_client.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include "proto/api/api_client.h"
#include "proto/api/api_types.h"

namespace reenact::proto {
namespace {

// A loopback port that nothing listens on: bound by the OS, then released.
uint16_t ClosedPort() {
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  addr.sin_port = 0;
  EXPECT_EQ(bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof(addr)), 0);
  socklen_t length = sizeof(addr);
  getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &length);
  close(fd);
  return ntohs(addr.sin_port);
}

TEST(HttpClient, ServerDownIsUnreachable) {
  const std::string url = "http://127.0.0.1:" + std::to_string(ClosedPort());
  HttpClient client(url);
  auto response = client.Send({"GET", "/healthz", {}, "", ""});
  ASSERT_FALSE(response.ok());
  EXPECT_EQ(response.error().code, "unreachable");
  EXPECT_EQ(response.error().message, "cannot reach server at " + url +
                                          ": connection refused; is reenact-server running?");
  ApiClient api(url, "token");
  auto nearby = api.Nearby(0, 0, 100);
  ASSERT_FALSE(nearby.ok());
  EXPECT_EQ(nearby.error().code, "unreachable");
}

TEST(HttpClient, MalformedUrlIsInvalidArgument) {
  for (const char* url : {"127.0.0.1:8080", "https://example.org", "http://", "http://host:",
                          "http://host:70000", "http://host:80/path", "http://ho st:80"}) {
    auto parsed = ParseBaseUrl(url);
    ASSERT_FALSE(parsed.ok()) << url;
    EXPECT_EQ(parsed.error().code, "invalid_argument");
    EXPECT_NE(parsed.error().message.find("http://HOST:PORT"), std::string::npos);
    HttpClient client(url);
    auto response = client.Send({"GET", "/", {}, "", ""});
    ASSERT_FALSE(response.ok());
    EXPECT_EQ(response.error().code, "invalid_argument");
  }
}

TEST(HttpClient, ParsesBaseUrls) {
  auto a = ParseBaseUrl("http://127.0.0.1:8080/");
  ASSERT_TRUE(a.ok());
  EXPECT_EQ(a->host, "127.0.0.1");
  EXPECT_EQ(a->port, 8080);
  EXPECT_EQ(a->text, "http://127.0.0.1:8080");
  auto b = ParseBaseUrl("HTTP://example.org");
  ASSERT_TRUE(b.ok());
  EXPECT_EQ(b->port, 80);
  auto c = ParseBaseUrl("http://[::1]:9000");
  ASSERT_TRUE(c.ok());
  EXPECT_EQ(c->host, "::1");
  EXPECT_EQ(c->text, "http://[::1]:9000");
}

TEST(HttpClient, OptionsCheckRejectsZeroTimeouts) {
  HttpClientOptions options;
  options.read_timeout = std::chrono::milliseconds(0);
  EXPECT_THROW(options.Check(), CheckError);
}

TEST(ApiTypes, ErrorBodyRoundTrips) {
  const std::string body = ErrorBodyJson("not_found", "no clip \"x\"");
  EXPECT_EQ(nlohmann::json::parse(body)["error"]["code"], "not_found");
  auto error = ParseErrorBody(body);
  ASSERT_TRUE(error.has_value());
  EXPECT_EQ(error->code, "not_found");
  EXPECT_EQ(error->message, "no clip \"x\"");
  EXPECT_FALSE(ParseErrorBody("<html>").has_value());
  EXPECT_FALSE(ParseErrorBody("{\"error\": 3}").has_value());
}

TEST(ApiTypes, ClipSummaryRoundTripsAndRejectsMissingFields) {
  ClipSummary clip{"id1", "t", "a", 1.5, -2.5, 3.0, 4.25, 5.0, 6};
  const nlohmann::json json = ClipSummaryToJson(clip);
  EXPECT_EQ(json["location"]["lat_deg"], 1.5);
  auto back = ClipSummaryFromJson(json);
  ASSERT_TRUE(back.ok());
  EXPECT_EQ(back->id, "id1");
  EXPECT_EQ(back->lon_deg, -2.5);
  EXPECT_EQ(back->frame_count, 6);
  nlohmann::json broken = json;
  broken.erase("distance_m");
  auto error = ClipSummaryFromJson(broken);
  ASSERT_FALSE(error.ok());
  EXPECT_NE(error.error().message.find("distance_m"), std::string::npos);
  EXPECT_FALSE(ParseNearbyPage("[]").ok());
}

}  // namespace
}  // namespace reenact::proto
