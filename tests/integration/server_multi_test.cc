// Two `reenact-server serve` processes on one PostgreSQL database (the throwaway test cluster
// of tests/unit/server/postgres_test_cluster.h): a clip published through one is browsed and
// downloaded whole through the other; an upload through one that is killed with SIGKILL part
// way resumes through the other, and the clip is never visible before it is whole. Where
// nginx is installed, the same through deploy/nginx-reenact-upstream.conf in front of both,
// and reads that reach the dead server go on to the live one.
// Skips where PostgreSQL cannot be started.
#include <gtest/gtest.h>
#include <sys/prctl.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <thread>

#include "proto/api/api_client.h"
#include "proto/clip/content_hash.h"
#include "server/storage/postgres.h"
#include "tests/integration/server_harness.h"
#include "tests/unit/server/postgres_test_cluster.h"

namespace reenact {
namespace {

using testing::ExpectClipWholeOn;
using testing::kCapture;
using testing::PartOnDisk;
using testing::kServer;
using testing::ReadFile;
using testing::RunProcess;
using testing::ServerProcess;

// Two recordings of different lengths (the same scene otherwise): different manifests, so
// the client never takes one for the other.
constexpr int kFrames[] = {0, 30, 40};  // by clip number
constexpr int kParts2 = kFrames[2] + 1;
constexpr double kLat = 34.7325, kLon = 135.7336;

// The one line a `user add` or `token add` prints on stdout: the token.
std::string AddToken(const std::string& command, const std::string& db) {
  const auto r = RunProcess({kServer, command, "add", "uploader", "--db", db});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  std::string token = r.out;
  while (!token.empty() && (token.back() == '\n' || token.back() == '\r')) token.pop_back();
  return token;
}

testing::ProcessResult Publish(const std::string& clip, const std::string& url,
                               const std::string& token,
                               const std::vector<std::string>& extra = {}) {
  std::vector<std::string> argv = {kCapture, "publish", clip,  "--server", url,
                                   "--token", token,    "--lat", "34.7325", "--lon",
                                   "135.7336"};
  argv.insert(argv.end(), extra.begin(), extra.end());
  return RunProcess(argv, std::chrono::seconds(120));
}

std::string ClipId(const std::string& out) {
  std::smatch m;
  return std::regex_search(out, m, std::regex(R"(clip_id=(\S+))")) ? m[1].str() : "";
}

long long SummaryValue(const std::string& out, const std::string& key) {
  std::smatch m;
  if (!std::regex_search(out, m, std::regex("(^|\\s)" + key + "=(\\d+)"))) return -1;
  return std::stoll(m[2].str());
}

// The ids of the clips near the recording place, as anonymous browsing sees them.
std::vector<std::string> VisibleNearby(const std::string& url) {
  auto clips = proto::ApiClient(url, "").Nearby(kLat, kLon, 1000);
  EXPECT_TRUE(clips.ok()) << clips.error().message;
  std::vector<std::string> ids;
  if (clips.ok()) {
    for (const auto& c : *clips) ids.push_back(c.id);
  }
  return ids;
}

// Complete parts of the caller's only draft or clip, polled until at least `want` or ~30 s.
int WaitForParts(const proto::ApiClient& observer, int want) {
  int held = 0;
  for (int i = 0; i < 600 && held < want; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    auto mine = observer.MyClips();
    if (!mine.ok() || mine->empty()) continue;
    auto parts = observer.ListParts(mine->front().id);
    if (!parts.ok()) continue;
    held = 0;
    for (const auto& part : parts->parts) held += part.Complete() ? 1 : 0;
  }
  return held;
}

// Polls anonymous browsing on `url` in the background and records whether a clip was ever
// listed while the owner's parts listing showed a part missing.
class HalfPublishedWatch {
 public:
  HalfPublishedWatch(std::string url, std::string observer_token)
      : url_(std::move(url)), observer_(url_, std::move(observer_token)) {
    thread_ = std::thread([this] {
      while (!stop_) {
        auto clips = proto::ApiClient(url_, "").Nearby(kLat, kLon, 1000);
        if (clips.ok()) {
          for (const auto& c : *clips) {
            auto parts = observer_.ListParts(c.id);
            if (!parts.ok()) continue;
            ++checks_;
            for (const auto& part : parts->parts) half_ = half_ || !part.Complete();
          }
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
      }
    });
  }
  ~HalfPublishedWatch() { Stop(); }
  void Stop() {
    stop_ = true;
    if (thread_.joinable()) thread_.join();
  }
  bool saw_half_published() const { return half_; }
  int checks() const { return checks_; }

 private:
  std::string url_;
  proto::ApiClient observer_;
  std::atomic<bool> stop_{false};
  std::atomic<bool> half_{false};
  std::atomic<int> checks_{0};
  std::thread thread_;
};

std::string WhichNginx() {
  for (const char* path : {"/usr/sbin/nginx", "/usr/bin/nginx", "/usr/local/sbin/nginx"}) {
    if (access(path, X_OK) == 0) return path;
  }
  return "";
}

void Replace(std::string& text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  ASSERT_NE(at, std::string::npos) << from << " is not in the shipped config";
  text.replace(at, from.size(), to);
}

// nginx in the foreground, one process (no workers, no user switch), with the shipped
// upstream config pointed at two servers and listening on a free loopback port.
class NginxProcess {
 public:
  ~NginxProcess() { Stop(); }
  // The base URL, or "" with `error` set.
  std::string Start(const std::string& binary, const std::string& dir, int port_a, int port_b,
                    std::string* error) {
    std::string conf = ReadFile(std::string(REENACT_SOURCE_DIR) +
                                "/deploy/nginx-reenact-upstream.conf");
    const int port = testing::UnusedLoopbackPort();
    std::string a = "127.0.0.1:", b = "127.0.0.1:", listen = "listen 127.0.0.1:";
    a += std::to_string(port_a);
    b += std::to_string(port_b);
    listen += std::to_string(port);
    Replace(conf, "127.0.0.1:8080", a);
    Replace(conf, "127.0.0.1:8081", b);
    Replace(conf, "listen 80", listen);
    std::ofstream(dir + "/reenact.conf") << conf;
    std::ofstream(dir + "/nginx.conf")
        << "daemon off;\nmaster_process off;\npid " << dir << "/nginx.pid;\nerror_log " << dir
        << "/error.log;\nevents {}\nhttp {\n  access_log off;\n  include " << dir
        << "/reenact.conf;\n}\n";
    pid_ = fork();
    if (pid_ == 0) {
      prctl(PR_SET_PDEATHSIG, SIGKILL);
      execl(binary.c_str(), binary.c_str(), "-p", dir.c_str(), "-c",
            (dir + "/nginx.conf").c_str(), static_cast<char*>(nullptr));
      _exit(127);
    }
    for (int i = 0; i < 200; ++i) {
      testing::RawSocket probe(port, 200);
      if (probe.connected()) {
        std::string url = "http://127.0.0.1:";
        url += std::to_string(port);
        return url;
      }
      int status = 0;
      if (waitpid(pid_, &status, WNOHANG) == pid_) {
        pid_ = -1;
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    *error = "nginx did not start: " + ReadFile(dir + "/error.log");
    return "";
  }
  void Stop() {
    if (pid_ <= 0) return;
    kill(pid_, SIGTERM);
    int status = 0;
    waitpid(pid_, &status, 0);
    pid_ = -1;
  }

 private:
  pid_t pid_ = -1;
};

class MultiServer : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new testing::TempDir();
    for (int n : {1, 2}) {
      const auto record = RunProcess({kCapture, "record", "--source", "synthetic:turn-and-kick",
                                      "--out", clip(n), "--frames", std::to_string(kFrames[n])},
                                     std::chrono::seconds(300));
      ASSERT_EQ(record.exit_code, 0) << record.err;
    }
  }
  static void TearDownTestSuite() {
    delete dir_;
    dir_ = nullptr;
  }
  static std::string clip(int n) { return dir_->path() + "/clip" + std::to_string(n); }

  void SetUp() override {
    auto database = server::testing::NewPostgresTestDatabase();
    if (!database && database.error().code == "unavailable") {
      GTEST_SKIP() << "no PostgreSQL for the test: " << database.error().message;
    }
    ASSERT_TRUE(database.ok()) << database.error().message;
    auto url = server::pg::AsUrl(*database);
    ASSERT_TRUE(url.ok()) << url.error().message;
    db_ = *url;
    token_ = AddToken("user", db_);
    observer_token_ = AddToken("token", db_);
  }

  std::string db_;
  std::string token_;           // the publishing client's
  std::string observer_token_;  // the test's own requests, never spending the client's credit

 private:
  static testing::TempDir* dir_;
};
testing::TempDir* MultiServer::dir_ = nullptr;

TEST_F(MultiServer, PublishedThroughOneServerIsDownloadedWholeThroughTheOther) {
  ServerProcess a, b;
  const auto url_a = a.Start(db_);
  ASSERT_TRUE(url_a);
  const auto url_b = b.Start(db_);
  ASSERT_TRUE(url_b);

  const auto r = Publish(clip(1), *url_a, token_);
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const std::string id = ClipId(r.out);
  ASSERT_FALSE(id.empty()) << r.out;

  EXPECT_EQ(VisibleNearby(*url_b), std::vector<std::string>{id});
  auto manifest_a = proto::ApiClient(*url_a, "").GetManifest(id);
  auto manifest_b = proto::ApiClient(*url_b, "").GetManifest(id);
  ASSERT_TRUE(manifest_a.ok() && manifest_b.ok());
  EXPECT_EQ(*manifest_b, *manifest_a);
  ExpectClipWholeOn(*url_b, id, clip(1), kFrames[1]);
}

TEST_F(MultiServer, UploadKilledOnOneServerResumesOnTheOther) {
  ServerProcess a, b;
  // A slow upload through A (8 requests per second for the client's token) so that the kill
  // lands in the middle of it.
  const auto url_a = a.Start(db_, {"--rate-limit", "8", "--rate-burst", "4"});
  ASSERT_TRUE(url_a);
  const auto url_b = b.Start(db_);
  ASSERT_TRUE(url_b);
  HalfPublishedWatch watch(*url_b, observer_token_);

  testing::ProcessResult first;
  std::thread client([&] { first = Publish(clip(2), *url_a, token_, {"--retries", "1"}); });
  const proto::ApiClient observer_b(*url_b, observer_token_);
  const int held_at_kill = WaitForParts(observer_b, 8);
  ASSERT_GE(held_at_kill, 8) << "the upload never got going";
  a.Kill(SIGKILL);
  client.join();
  EXPECT_EQ(first.exit_code, 1) << first.out << first.err;
  EXPECT_NE(first.err.find("run the same command again to resume"), std::string::npos)
      << first.err;

  EXPECT_TRUE(VisibleNearby(*url_b).empty()) << "a partial clip is visible";
  auto mine = observer_b.MyClips();
  ASSERT_TRUE(mine.ok() && mine->size() == 1u);
  const std::string draft = mine->front().id;
  auto parts = observer_b.ListParts(draft);
  ASSERT_TRUE(parts.ok()) << parts.error().message;
  int held = 0;
  for (const auto& part : parts->parts) held += part.Complete() ? 1 : 0;
  EXPECT_GE(held, held_at_kill);
  ASSERT_LT(held, kParts2) << "the kill came too late to test resuming";

  const auto second = Publish(clip(2), *url_b, token_);
  ASSERT_EQ(second.exit_code, 0) << second.out << second.err;
  EXPECT_EQ(ClipId(second.out), draft);
  EXPECT_EQ(SummaryValue(second.out, "resumed"), 1);
  EXPECT_EQ(SummaryValue(second.out, "parts_skipped"), held);
  EXPECT_EQ(SummaryValue(second.out, "parts_sent"), kParts2 - held);
  EXPECT_EQ(VisibleNearby(*url_b), std::vector<std::string>{draft});
  // Seen published at least once by the watch before it stops, and never with a part missing.
  for (int i = 0; i < 100 && watch.checks() == 0; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  watch.Stop();
  EXPECT_GT(watch.checks(), 0);
  EXPECT_FALSE(watch.saw_half_published());
  ExpectClipWholeOn(*url_b, draft, clip(2), kFrames[2]);

  // A restarted A serves the same clip.
  const auto again = a.Start(db_);
  ASSERT_TRUE(again);
  ExpectClipWholeOn(*again, draft, clip(2), kFrames[2]);
}

TEST_F(MultiServer, BehindNginxAKilledServerIsRoutedAroundAndTheUploadCompletes) {
  const std::string nginx = WhichNginx();
  if (nginx.empty()) GTEST_SKIP() << "nginx is not installed; the proxied setup is not tested";
  ServerProcess a, b;
  // Both slow for the client's token (rate limits are per process): the upload spans seconds.
  const auto url_a = a.Start(db_, {"--rate-limit", "8", "--rate-burst", "4"});
  ASSERT_TRUE(url_a);
  const auto url_b = b.Start(db_, {"--rate-limit", "8", "--rate-burst", "4"});
  ASSERT_TRUE(url_b);
  testing::TempDir tmp;
  NginxProcess proxy;
  std::string error;
  const std::string url = proxy.Start(nginx, tmp.path(), a.port(), b.port(), &error);
  ASSERT_FALSE(url.empty()) << error;

  // A first clip through the proxy, seen whole on the proxy and on each server directly.
  const auto r = Publish(clip(1), url, token_);
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const std::string first_id = ClipId(r.out);
  ExpectClipWholeOn(url, first_id, clip(1), kFrames[1]);
  ExpectClipWholeOn(*url_a, first_id, clip(1), kFrames[1]);
  ExpectClipWholeOn(*url_b, first_id, clip(1), kFrames[1]);

  // A second one; A is killed part way. Once nginx has marked A down every request goes to B.
  HalfPublishedWatch watch(*url_b, observer_token_);
  testing::ProcessResult second;
  std::thread client([&] { second = Publish(clip(2), url, token_); });
  const proto::ApiClient observer_b(*url_b, observer_token_);
  // The second clip's parts: the observer sees both clips; wait on the draft.
  int held = 0;
  std::string draft;
  for (int i = 0; i < 600 && held < 8; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    auto mine = observer_b.MyClips();
    if (!mine.ok()) continue;
    for (const auto& c : *mine) {
      if (c.id != first_id) draft = c.id;
    }
    if (draft.empty()) continue;
    auto parts = observer_b.ListParts(draft);
    if (!parts.ok()) continue;
    held = 0;
    for (const auto& part : parts->parts) held += part.Complete() ? 1 : 0;
  }
  ASSERT_GE(held, 8) << "the upload never got going";
  ASSERT_LT(held, kParts2) << "the upload ended before the kill";
  a.Kill(SIGKILL);
  client.join();
  // Requests that reached the dead server came back 502 (nginx does not retry writes); the
  // client's own retries land on B, so the one run completes.
  ASSERT_EQ(second.exit_code, 0) << second.out << second.err;
  EXPECT_EQ(ClipId(second.out), draft);
  watch.Stop();
  EXPECT_FALSE(watch.saw_half_published());
  ExpectClipWholeOn(url, draft, clip(2), kFrames[2]);
  ExpectClipWholeOn(*url_b, draft, clip(2), kFrames[2]);
  const auto visible = VisibleNearby(url);
  EXPECT_EQ(visible.size(), 2u);

  // A fresh nginx that has not seen A fail: reads sent to the dead A go on to B.
  proxy.Stop();
  testing::TempDir tmp2;
  NginxProcess fresh;
  const std::string url2 = fresh.Start(nginx, tmp2.path(), a.port(), b.port(), &error);
  ASSERT_FALSE(url2.empty()) << error;
  ExpectClipWholeOn(url2, draft, clip(2), kFrames[2]);
  EXPECT_EQ(VisibleNearby(url2).size(), 2u);
}

}  // namespace
}  // namespace reenact
