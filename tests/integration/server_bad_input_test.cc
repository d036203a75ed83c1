// Hostile and broken requests against the real reenact-server: each answered with the right
// status and a JSON error body, and nothing stored or changed.
#include <algorithm>

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "proto/api/api_client.h"
#include "server/auth/token.h"
#include "server/storage/open_storage.h"
#include "tests/integration/server_harness.h"

namespace reenact {
namespace {

using testing::MakeSyntheticClip;
using testing::SyntheticClip;

class ServerBadInput : public ::testing::Test {
 protected:
  void SetUp() override { StartWith({}); }

  void StartWith(const std::vector<std::string>& extra) {
    db_ = tmp_.path() + "/bad.db";
    if (token_.empty()) {
      auto storage = server::OpenSqliteStorage(db_);
      ASSERT_TRUE(storage.ok());
      token_ = *server::AddUserWithToken(*storage->metadata, "alice");
    }
    auto url = server_.Start(db_, extra);
    ASSERT_TRUE(url.has_value());
    url_ = *url;
    clip_ = MakeSyntheticClip(34.7, 135.7, 2, 1000, 1, "victim");
    proto::ApiClient api(url_, token_);
    auto id = api.CreateClip(clip_.manifest_json);
    ASSERT_TRUE(id.ok());
    id_ = *id;
    ASSERT_TRUE(api.PutFrame(id_, 0, clip_.frames[0]).ok());
  }

  proto::HttpResponse Send(const std::string& method, const std::string& target,
                           bool with_token = true, const std::string& body = "",
                           const std::string& content_type = "") {
    proto::HttpRequest request{method, target, {}, content_type, body};
    if (with_token) request.headers.emplace_back("Authorization", "Bearer " + token_);
    auto response = proto::HttpClient(url_).Send(request);
    EXPECT_TRUE(response.ok()) << response.error().message;
    return response.ok() ? *response : proto::HttpResponse{};
  }

  // The status, and a JSON error body with this code and a message free of database internals
  // (the offending input itself may be echoed, quoted).
  static void ExpectError(const proto::HttpResponse& r, int status, const std::string& code) {
    EXPECT_EQ(r.status, status) << r.body;
    auto body = nlohmann::json::parse(r.body, nullptr, false);
    ASSERT_TRUE(body.is_object()) << r.body;
    EXPECT_EQ(body["error"]["code"], code) << r.body;
    const std::string message = body["error"]["message"].get<std::string>();
    for (const char* leak : {"sqlite", "SQLITE", "constraint failed", "syntax error"}) {
      EXPECT_EQ(message.find(leak), std::string::npos) << message;
    }
  }

  // What the store holds, as a client sees it: my clips and the uploaded frame/missing one.
  std::string StateFingerprint() {
    proto::ApiClient api(url_, token_);
    auto mine = api.MyClips();
    std::string fp = mine.ok() ? std::to_string(mine->size()) : "error";
    auto f0 = api.GetFrame(id_, 0);
    fp += f0.ok() && *f0 == clip_.frames[0] ? "+f0" : "-f0";
    fp += api.GetFrame(id_, 1).ok() ? "+f1" : "-f1";
    return fp;
  }

  testing::TempDir tmp_;
  std::string db_, url_, token_, id_;
  SyntheticClip clip_;
  testing::ServerProcess server_;
};

TEST_F(ServerBadInput, PathTraversalIsNotFoundAndTouchesNothing) {
  const std::string before = StateFingerprint();
  for (const std::string& target :
       std::vector<std::string>{"/v1/clips/..%2F..%2Fetc%2Fpasswd", "/v1/clips/%2e%2e/frames/0",
                                "/v1/clips/" + std::string("..%2F") + "/map", "/../../etc/passwd",
                                "/v1/clips/../../etc/passwd"}) {
    const auto r = Send("GET", target);
    EXPECT_TRUE(r.status == 404 || r.status == 400) << target << " -> " << r.status;
    ExpectError(r, r.status, r.status == 404 ? "not_found" : "bad_request");
  }
  ExpectError(Send("PUT", "/v1/clips/..%2F" + id_ + "/frames/1", true, clip_.frames[1],
                   "application/octet-stream"),
              404, "not_found");
  EXPECT_EQ(StateFingerprint(), before);
}

TEST_F(ServerBadInput, SqlInjectionStringsAreDataNeverCode) {
  const std::string before = StateFingerprint();
  for (const std::string& id :
       std::vector<std::string>{"%27%20OR%20%271%27%3D%271", "x%27%3B%20DROP%20TABLE%20clips%3B--",
                                "1%20UNION%20SELECT%20manifest%20FROM%20clips"}) {
    ExpectError(Send("GET", "/v1/clips/" + id), 404, "not_found");
    ExpectError(Send("DELETE", "/v1/clips/" + id), 404, "not_found");
  }
  ExpectError(Send("GET", "/v1/clips?near=1%27%20OR%201%3D1,2"), 400, "bad_request");
  ExpectError(Send("GET", "/v1/clips?near=1,2&cursor=%27%3B--"), 400, "bad_request");
  EXPECT_EQ(StateFingerprint(), before);
  // A title made of SQL is stored and returned byte for byte.
  SyntheticClip evil = MakeSyntheticClip(34.7, 135.7, 1, 10, 2, "'); DROP TABLE clips; --");
  proto::ApiClient api(url_, token_);
  auto id = api.CreateClip(evil.manifest_json);
  ASSERT_TRUE(id.ok());
  auto back = api.GetManifest(*id);
  ASSERT_TRUE(back.ok());
  EXPECT_EQ(*back, evil.manifest_json);
  EXPECT_TRUE(api.GetManifest(id_).ok()) << "the clips table survived";
}

TEST_F(ServerBadInput, TruncatedUploadStoresNothingAndTheServerCarriesOn) {
  const std::string before = StateFingerprint();
  {
    testing::RawSocket raw(server_.port());
    ASSERT_TRUE(raw.connected());
    const std::string& frame = clip_.frames[1];
    raw.Send("PUT /v1/clips/" + id_ + "/frames/1 HTTP/1.1\r\nHost: x\r\nAuthorization: Bearer " +
             token_ + "\r\nContent-Type: application/octet-stream\r\nContent-Length: " +
             std::to_string(frame.size()) + "\r\n\r\n" + frame.substr(0, frame.size() / 2));
  }  // the client vanishes half way through the body
  EXPECT_EQ(StateFingerprint(), before);
  ExpectError(Send("GET", "/v1/clips/" + id_ + "/frames/1"), 404, "not_found");
  // A complete upload afterwards works.
  EXPECT_TRUE(proto::ApiClient(url_, token_).PutFrame(id_, 1, clip_.frames[1]).ok());
}

TEST_F(ServerBadInput, MalformedHttpIsRefusedAndTheServerCarriesOn) {
  for (const std::string& junk :
       {std::string("\x16\x03\x01\x02\x00", 5), std::string("GET\r\n\r\n"),
        std::string("GET / HTTP/1.1\r\nContent-Length: -5\r\n\r\n")}) {
    testing::RawSocket raw(server_.port(), 2000);
    raw.Send(junk);
    raw.ReadAll();
  }
  EXPECT_EQ(Send("GET", "/healthz", false).status, 200);
}

TEST_F(ServerBadInput, SlowLorisClientsDoNotStarveOthersAndAreCutOff) {
  server_.Kill(SIGTERM);
  StartWith({"--header-timeout-s", "1", "--threads", "2"});
  std::vector<std::unique_ptr<testing::RawSocket>> slow;
  for (int i = 0; i < 40; ++i) {
    slow.push_back(std::make_unique<testing::RawSocket>(server_.port(), 3000));
    ASSERT_TRUE(slow.back()->connected());
    slow.back()->Send("GET /v1/clips?near=1,2 HTTP/1.1\r\nHost: x\r\n");
  }
  // While they dribble their headers a byte at a time, everyone else is served promptly.
  const auto start = std::chrono::steady_clock::now();
  int served = 0;
  for (int round = 0; round < 8; ++round) {
    for (auto& s : slow) s->Send("X");
    const auto t0 = std::chrono::steady_clock::now();
    if (Send("GET", "/healthz", false).status == 200) ++served;
    EXPECT_LT(std::chrono::steady_clock::now() - t0, std::chrono::seconds(2));
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  EXPECT_EQ(served, 8);
  // Past the header deadline (1 s) the server closes them all. Polled with a generous cap,
  // so a loaded CI machine does not turn scheduling delay into a failure.
  std::this_thread::sleep_until(start + std::chrono::milliseconds(1500));
  std::vector<bool> closed(slow.size(), false);
  for (const auto cap = start + std::chrono::seconds(15);
       std::count(closed.begin(), closed.end(), true) < 40 &&
       std::chrono::steady_clock::now() < cap;) {
    for (size_t i = 0; i < slow.size(); ++i)
      if (!closed[i]) closed[i] = slow[i]->PeerClosed();
  }
  EXPECT_EQ(std::count(closed.begin(), closed.end(), true), 40);
}

TEST_F(ServerBadInput, RevokedTokenIsRefusedAtOnceWhileTheServerRuns) {
  const std::string before = StateFingerprint();
  const auto revoke = testing::RunProcess(
      {testing::kServer, "token", "revoke", "alice", "--db", db_}, std::chrono::seconds(30));
  ASSERT_EQ(revoke.exit_code, 0) << revoke.err;
  EXPECT_NE(revoke.out.find("revoked 1"), std::string::npos) << revoke.out;
  ExpectError(Send("PUT", "/v1/clips/" + id_ + "/frames/1", true, clip_.frames[1],
                   "application/octet-stream"),
              401, "unauthorized");
  ExpectError(Send("POST", "/v1/clips", true, clip_.manifest_json, "application/json"), 401,
              "unauthorized");
  // A new token from the operator works again.
  const auto added = testing::RunProcess({testing::kServer, "token", "add", "alice", "--db", db_},
                                         std::chrono::seconds(30));
  ASSERT_EQ(added.exit_code, 0) << added.err;
  token_ = added.out.substr(0, added.out.find('\n'));
  EXPECT_EQ(StateFingerprint(), before);
  const auto unknown = testing::RunProcess(
      {testing::kServer, "token", "revoke", "nobody", "--db", db_}, std::chrono::seconds(30));
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_NE(unknown.err.find("nobody"), std::string::npos);
}

TEST_F(ServerBadInput, WrongAndMissingTokensAre401) {
  const std::string before = StateFingerprint();
  ExpectError(Send("POST", "/v1/clips/" + id_ + "/publish", false), 401, "unauthorized");
  proto::HttpRequest wrong{
      "DELETE", "/v1/clips/" + id_, {{"Authorization", "Bearer rnk_0000"}}, "", ""};
  ExpectError(*proto::HttpClient(url_).Send(wrong), 401, "unauthorized");
  proto::HttpRequest basic{"DELETE", "/v1/clips/" + id_, {{"Authorization", "Basic YTpi"}}, "", ""};
  ExpectError(*proto::HttpClient(url_).Send(basic), 401, "unauthorized");
  EXPECT_EQ(StateFingerprint(), before);
}

}  // namespace
}  // namespace reenact
