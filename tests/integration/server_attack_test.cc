// The real reenact-server under the attacks a hostile client can mount cheaply, each with a
// bound justified beside it: slow headers cannot lock others out, anonymous bodies are refused
// before they are read, slow senders are cut off in seconds, one heavy reader does not delay
// others, and each malformed request gets its status and a close.
#include <gtest/gtest.h>
#include <poll.h>
#include <sys/stat.h>

#include <algorithm>
#include <atomic>
#include <random>
#include <thread>

#include "proto/api/api_client.h"
#include "server/auth/token.h"
#include "server/storage/open_storage.h"
#include "tests/integration/server_harness.h"

namespace reenact {
namespace {

using Clock = std::chrono::steady_clock;
using testing::RawSocket;

class ServerAttack : public ::testing::Test {
 protected:
  void StartWith(const std::vector<std::string>& extra) {
    db_ = tmp_.path() + "/attack.db";
    {
      auto storage = server::OpenSqliteStorage(db_);
      ASSERT_TRUE(storage.ok()) << storage.error().message;
      token_ = *server::AddUserWithToken(*storage->metadata, "alice");
    }
    auto url = server_.Start(db_, extra);
    ASSERT_TRUE(url.has_value());
    url_ = *url;
  }

  // A draft of alice's with `frames` frames of `frame_bytes` random bytes, none uploaded.
  std::string Draft(int frames, size_t frame_bytes) {
    clip_ = testing::MakeSyntheticClip(34.7, 135.7, frames, frame_bytes, 7, "target");
    auto id = proto::ApiClient(url_, token_).CreateClip(clip_.manifest_json);
    EXPECT_TRUE(id.ok()) << id.error().message;
    return id.ok() ? *id : std::string();
  }

  int Health() {
    auto r = proto::HttpClient(url_).Send({"GET", "/healthz", {}, "", ""});
    return r.ok() ? r->status : -1;
  }

  std::string PutHeader(const std::string& target, size_t length, bool with_token) {
    return "PUT " + target + " HTTP/1.1\r\nHost: x\r\n" +
           (with_token ? "Authorization: Bearer " + token_ + "\r\n" : std::string()) +
           "Content-Type: application/octet-stream\r\nContent-Length: " +
           std::to_string(length) + "\r\n\r\n";
  }

  testing::TempDir tmp_;
  testing::ServerProcess server_;
  std::string db_, url_, token_;
  testing::SyntheticClip clip_;
};

// Seconds until the server closes `socket` while `dribble` is sent one byte every 300 ms;
// negative when still open after `give_up_s`.
double SecondsUntilCutOff(RawSocket& socket, const std::string& dribble, double give_up_s) {
  const auto start = Clock::now();
  for (size_t i = 0;; ++i) {
    if (i < dribble.size()) socket.Send(dribble.substr(i, 1));
    pollfd pfd{socket.fd(), POLLIN, 0};
    if (poll(&pfd, 1, 300) > 0) {
      char c[512];
      if (recv(socket.fd(), c, sizeof c, 0) <= 0) {
        return std::chrono::duration<double>(Clock::now() - start).count();
      }
    }
    if (Clock::now() - start > std::chrono::duration<double>(give_up_s)) return -1;
  }
}

TEST_F(ServerAttack, SlowHeadersCannotLockOthersOut) {
  // 8 slots; an attacker on another address keeps 24 connections dribbling header bytes and
  // reconnects whenever one is closed. A connection that never completes its header is always
  // the one closed to make room, so every normal request is answered.
  StartWith({"--max-connections", "8"});
  std::atomic<bool> stop{false};
  std::atomic<int> reconnects{0};
  std::thread attacker([&] {
    std::vector<std::unique_ptr<RawSocket>> slow;
    auto open = [&] {
      auto s = std::make_unique<RawSocket>(server_.port(), 100, "127.0.0.2");
      s->Send("GET /v1/clips?near=1,2 HTTP/1.1\r\nHo");
      return s;
    };
    for (int i = 0; i < 24; ++i) slow.push_back(open());
    while (!stop) {
      for (auto& s : slow) {
        pollfd pfd{s->fd(), POLLIN, 0};
        char c;
        if (poll(&pfd, 1, 0) > 0 && recv(s->fd(), &c, 1, MSG_DONTWAIT) <= 0) {
          s = open();
          ++reconnects;
        } else {
          s->Send("o");
        }
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  int answered = 0;
  std::string failures;
  for (int i = 0; i < 20; ++i) {
    auto r = proto::HttpClient(url_).Send({"GET", "/healthz", {}, "", ""});
    if (r.ok() && r->status == 200) {
      ++answered;
    } else {
      failures += (r.ok() ? std::to_string(r->status) + " " + r->body : r.error().message) + "; ";
    }
  }
  stop = true;
  attacker.join();
  EXPECT_EQ(answered, 20) << failures;
  EXPECT_GT(reconnects.load(), 0) << "the attack never filled the server";
}

TEST_F(ServerAttack, AnonymousBodiesAreRefusedBeforeTheyAreRead) {
  StartWith({});
  const std::string id = Draft(1, 1000);
  const double before_mib = testing::ResidentMiB(server_.pid());
  ASSERT_GT(before_mib, 0);
  // 8 anonymous uploads announcing 60 MiB maps: answered 401 from the header alone. The server
  // then discards at most 1 MiB of each into a shared scratch buffer and closes, so what a
  // client gets to send is bounded by that plus the loopback socket buffers (a few MiB).
  constexpr size_t kAnnounced = size_t{60} << 20;
  const std::string chunk(256 * 1024, 'x');
  std::vector<std::thread> clients;
  std::vector<size_t> accepted(8, 0);
  std::vector<std::string> answers(8);
  double peak_mib = before_mib;
  std::atomic<bool> done{false};
  std::thread sampler([&] {
    while (!done) {
      peak_mib = std::max(peak_mib, testing::ResidentMiB(server_.pid()));
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
  });
  for (int c = 0; c < 8; ++c) {
    clients.emplace_back([&, c] {
      RawSocket raw(server_.port(), 5000);
      raw.Send(PutHeader("/v1/clips/" + id + "/map", kAnnounced, false));
      answers[c] = raw.ReadUntil("}}");
      while (accepted[c] < kAnnounced && raw.Send(chunk)) accepted[c] += chunk.size();
    });
  }
  for (auto& client : clients) client.join();
  done = true;
  sampler.join();
  for (int c = 0; c < 8; ++c) {
    EXPECT_NE(answers[c].find("401"), std::string::npos) << answers[c];
    EXPECT_LT(accepted[c], size_t{20} << 20) << "client " << c << " was read far past its refusal";
  }
  // Reading those bodies would take 480 MiB; refusing them costs the server next to nothing.
  EXPECT_LT(peak_mib - before_mib, 64.0) << "before " << before_mib << " MiB, peak " << peak_mib;
  EXPECT_EQ(Health(), 200);
}

TEST_F(ServerAttack, SlowSendersAreCutOffWithinSeconds) {
  // At least 1000 B/s after a 1 s grace: one byte every 300 ms falls behind at once, so the
  // cut comes at about 1 s; 5 s leaves room for a loaded machine.
  StartWith({"--min-transfer-rate", "1000", "--min-rate-grace-s", "1"});
  const std::string id = Draft(1, 1000);
  RawSocket header_only(server_.port(), 1000);
  const double header_s =
      SecondsUntilCutOff(header_only, "GET /v1/clips?near=1,2 HTTP/1.1\r\nHost: x\r\n", 10);
  EXPECT_GT(header_s, 0) << "a header dribbled one byte every 300 ms was never cut off";
  EXPECT_LT(header_s, 5.0);

  RawSocket body(server_.port(), 1000);
  body.Send(PutHeader("/v1/clips/" + id + "/frames/0", clip_.frames[0].size(), true));
  const double body_s = SecondsUntilCutOff(body, clip_.frames[0], 10);
  EXPECT_GT(body_s, 0) << "a body dribbled one byte every 300 ms was never cut off";
  EXPECT_LT(body_s, 5.0);
  auto frame = proto::HttpClient(url_).Send(
      {"GET", "/v1/clips/" + id + "/frames/0", {{"Authorization", "Bearer " + token_}}, "", ""});
  ASSERT_TRUE(frame.ok());
  EXPECT_EQ(frame->status, 404) << "a cut-off upload stored something";
  EXPECT_EQ(Health(), 200);
}

TEST_F(ServerAttack, AHeavyReaderDoesNotDelayOthers) {
  // The owner lists the parts of a 64 MiB clip over and over (each listing re-reads and
  // hashes every stored byte) while another client asks for health: with handlers on a pool,
  // no health answer waits for a listing, so the slowest one stays well under one listing.
  StartWith({"--threads", "2", "--handler-threads", "4"});
  const std::string id = Draft(8, (size_t{8} << 20) - 16);  // frame n has n more bytes
  proto::ApiClient api(url_, token_);
  for (int n = 0; n < 8; ++n) ASSERT_TRUE(api.PutFrame(id, n, clip_.frames[n]).ok());
  const std::string parts = "/v1/clips/" + id + "/parts";
  std::atomic<bool> stop{false};
  std::vector<double> listing_s;
  std::thread heavy([&] {
    proto::HttpClient http(url_);
    while (!stop) {
      const auto t0 = Clock::now();
      auto r = http.Send({"GET", parts, {{"Authorization", "Bearer " + token_}}, "", ""});
      if (!r.ok() || r->status != 200) break;
      listing_s.push_back(std::chrono::duration<double>(Clock::now() - t0).count());
    }
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  std::vector<double> health_s;
  proto::HttpClient http(url_);
  for (int i = 0; i < 40; ++i) {
    const auto t0 = Clock::now();
    auto r = http.Send({"GET", "/healthz", {}, "", ""});
    ASSERT_TRUE(r.ok() && r->status == 200);
    health_s.push_back(std::chrono::duration<double>(Clock::now() - t0).count());
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  stop = true;
  heavy.join();
  ASSERT_GE(listing_s.size(), 1u);
  std::sort(listing_s.begin(), listing_s.end());
  const double listing_median = listing_s[listing_s.size() / 2];
  const double slowest_health = *std::max_element(health_s.begin(), health_s.end());
  EXPECT_LT(slowest_health, listing_median / 2)
      << "a health check took " << slowest_health << " s; a listing takes " << listing_median;
}

struct Malformed {
  std::string what;
  std::string request;
  int status;
};

TEST_F(ServerAttack, EachMalformedRequestGetsItsStatusAndAClose) {
  StartWith({});
  const std::string auth = "Authorization: Bearer " + token_ + "\r\n";
  const std::vector<Malformed> cases = {
      {"bad request line", "GARBAGE\r\n\r\n", 400},
      {"request line without a version", "GET /healthz\r\n\r\n", 400},
      {"negative Content-Length", "GET / HTTP/1.1\r\nHost: x\r\nContent-Length: -5\r\n\r\n", 400},
      {"oversized header",
       "GET /healthz HTTP/1.1\r\nHost: x\r\nX-Pad: " + std::string(20000, 'a') + "\r\n\r\n", 431},
      {"Content-Length and Transfer-Encoding",
       "POST /v1/clips HTTP/1.1\r\nHost: x\r\n" + auth +
           "Content-Type: application/json\r\nContent-Length: 5\r\nTransfer-Encoding: "
           "chunked\r\n\r\n0\r\n\r\n",
       400},
      {"obfuscated Transfer-Encoding",
       "POST /v1/clips HTTP/1.1\r\nHost: x\r\n" + auth +
           "Content-Type: application/json\r\nTransfer-Encoding: xchunked\r\n\r\n",
       400},
      {"coding before chunked",
       "POST /v1/clips HTTP/1.1\r\nHost: x\r\n" + auth +
           "Content-Type: application/json\r\nTransfer-Encoding: gzip, chunked\r\n\r\n",
       501},
      {"HTTP/2.0 in an HTTP/1 request line", "GET /healthz HTTP/2.0\r\nHost: x\r\n\r\n", 400},
      {"malformed chunk size",
       "POST /v1/clips HTTP/1.1\r\nHost: x\r\n" + auth +
           "Content-Type: application/json\r\nTransfer-Encoding: chunked\r\n\r\nzz\r\n{}\r\n",
       400},
  };
  for (const Malformed& c : cases) {
    RawSocket raw(server_.port(), 3000);
    raw.Send(c.request);
    const std::string answer = raw.ReadUntil("}}");
    EXPECT_EQ(answer.rfind("HTTP/1.1 " + std::to_string(c.status) + " ", 0), 0u)
        << c.what << ": " << answer.substr(0, 200);
    EXPECT_NE(answer.find("\"error\""), std::string::npos) << c.what;
    EXPECT_TRUE(raw.PeerClosed()) << c.what << ": the connection stayed open";
  }
  EXPECT_EQ(Health(), 200);
}

TEST_F(ServerAttack, AManifestWithARepeatedKeyIs422) {
  // {"title":"a","title":"b"} means different things to different JSON readers: refused, not
  // silently read as one of them.
  StartWith({});
  clip_ = testing::MakeSyntheticClip(34.7, 135.7, 1, 100, 3, "twice");
  const std::string repeated = "{\"title\":\"shadow\"," + clip_.manifest_json.substr(1);
  auto r = proto::HttpClient(url_).Send({"POST",
                                         "/v1/clips",
                                         {{"Authorization", "Bearer " + token_}},
                                         "application/json",
                                         repeated});
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->status, 422) << r->body;
  EXPECT_NE(r->body.find("invalid_manifest"), std::string::npos) << r->body;
  EXPECT_NE(r->body.find("title"), std::string::npos) << r->body;
  auto mine = proto::ApiClient(url_, token_).MyClips();
  ASSERT_TRUE(mine.ok());
  EXPECT_TRUE(mine->empty()) << "a refused manifest left a draft";
}

TEST_F(ServerAttack, OtherLocalUsersCannotReadTheDatabase) {
  const mode_t before = ::umask(022);  // a permissive umask, as on most systems
  StartWith({});
  ::umask(before);
  ASSERT_FALSE(Draft(1, 100).empty());  // the server has written (WAL and shm exist)
  for (const char* suffix : {"", "-wal", "-shm"}) {
    struct stat st {};
    ASSERT_EQ(::stat((db_ + suffix).c_str(), &st), 0) << db_ << suffix;
    EXPECT_EQ(st.st_mode & 0777, 0600u) << db_ << suffix;
  }
}

}  // namespace
}  // namespace reenact
