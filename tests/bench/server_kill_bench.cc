#include "tests/bench/server_kill_bench.h"

#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <map>
#include <mutex>
#include <optional>
#include <random>
#include <set>
#include <thread>
#include <vector>

#include "proto/api/api_client.h"
#include "proto/clip/content_hash.h"
#include "proto/clip/manifest.h"
#include "server/auth/token.h"
#include "server/storage/open_storage.h"
#include "tests/bench/server_bench_support.h"

namespace reenact::bench {
namespace {

using Clock = std::chrono::steady_clock;

constexpr int kFrames = 6;
constexpr size_t kFrameBytes = size_t{256} << 10;
constexpr double kLat = 60, kLon = 25;

// One `reenact-server serve` child process on loopback.
class ServerChild {
 public:
  ServerChild() = default;
  ServerChild(const ServerChild&) = delete;
  ServerChild& operator=(const ServerChild&) = delete;
  ~ServerChild() { Kill(); }

  // Starts it and waits for its "listening on URL" line (20 s).
  Status Start(const std::string& binary, const std::string& db) {
    int fds[2];
    if (::pipe(fds) != 0) return MakeError("io", "pipe failed");
    std::vector<std::string> args = {binary,         "serve",        "--db", db, "--listen",
                                     "127.0.0.1:0", "--rate-limit", "0"};
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    const pid_t parent = ::getpid();
    pid_ = ::fork();
    if (pid_ < 0) return MakeError("io", "fork failed");
    if (pid_ == 0) {
      ::dup2(fds[1], STDOUT_FILENO);
      ::close(fds[0]);
      ::prctl(PR_SET_PDEATHSIG, SIGKILL);
      if (::getppid() != parent) ::_exit(125);
      ::execv(argv[0], argv.data());
      ::_exit(127);
    }
    ::close(fds[1]);
    std::string text;
    const auto until = Clock::now() + std::chrono::seconds(20);
    while (Clock::now() < until && text.find('\n') == std::string::npos) {
      pollfd pfd{fds[0], POLLIN, 0};
      if (::poll(&pfd, 1, 50) <= 0) continue;
      char chunk[256];
      const ssize_t n = ::read(fds[0], chunk, sizeof chunk);
      if (n <= 0) break;
      text.append(chunk, static_cast<size_t>(n));
    }
    ::close(fds[0]);
    const std::string prefix = "listening on ";
    const size_t nl = text.find('\n');
    if (nl == std::string::npos || text.rfind(prefix, 0) != 0) {
      Kill();
      return MakeError("io", binary + " serve did not start (run it by hand with --db to see why)");
    }
    url_ = text.substr(prefix.size(), nl - prefix.size());
    return {};
  }

  void Kill() {
    if (pid_ <= 0) return;
    ::kill(pid_, SIGKILL);
    int status = 0;
    ::waitpid(pid_, &status, 0);
    pid_ = 0;
  }

  const std::string& url() const { return url_; }

 private:
  pid_t pid_ = 0;
  std::string url_;
};

struct TestClip {
  std::vector<std::string> frames;
  std::string map;
  std::string manifest;
};

TestClip MakeClip(int round, std::mt19937& rng) {
  TestClip clip;
  std::vector<proto::PartInfo> infos;
  for (int n = 0; n < kFrames; ++n) {
    std::string frame(kFrameBytes, '\0');
    for (char& ch : frame) ch = static_cast<char>(rng() & 0xff);
    infos.push_back({frame.size(), proto::Sha256Hex(frame)});
    clip.frames.push_back(std::move(frame));
  }
  clip.map = "map of round " + std::to_string(round);
  clip.manifest = BenchManifest("kill " + std::to_string(round), infos,
                                {clip.map.size(), proto::Sha256Hex(clip.map)}, kLat, kLon);
  return clip;
}

// Sends what the server lacks of `clip` and publishes it, creating the draft or finding the one
// an interrupted upload left (by the manifest's hash). The clip id, or the first failure.
Expected<std::string> UploadWhole(const proto::ApiClient& api, const TestClip& clip) {
  auto mine = api.MyClipsWithManifest(proto::Sha256Hex(clip.manifest));
  if (!mine) return mine.error();
  std::string id;
  if (mine->empty()) {
    auto created = api.CreateClip(clip.manifest);
    if (!created) return created.error();
    id = *created;
  } else {
    id = mine->front().summary.id;
    if (mine->front().published) return id;
  }
  auto parts = api.ListParts(id);
  if (!parts) return parts.error();
  for (const proto::PartStatus& part : parts->parts) {
    if (part.Complete()) continue;
    const Status sent = part.index == proto::kMapPartIndex
                            ? api.PutMap(id, clip.map)
                            : api.PutFrame(id, part.index, clip.frames[part.index]);
    if (!sent) return sent.error();
  }
  if (Status s = api.Publish(id); !s) return s.error();
  return id;
}

// Whether an error is the server's answer (as opposed to a connection a kill cut).
bool IsServerAnswer(const Error& e) { return e.code == "not_found"; }

// Every part of clip `id` from `api` against its manifest's hashes: true whole, false a part
// missing or other bytes, nullopt when the server could not be asked (killed meanwhile).
std::optional<bool> CheckWhole(const proto::ApiClient& api, const std::string& id,
                               const TestClip* sent) {
  auto manifest_json = api.GetManifest(id);
  if (!manifest_json) {
    if (IsServerAnswer(manifest_json.error())) return false;
    return std::nullopt;
  }
  auto manifest = proto::ParseManifest(*manifest_json);
  if (!manifest) return false;
  for (size_t n = 0; n < manifest->frame_parts.size(); ++n) {
    auto frame = api.GetFrame(id, static_cast<int64_t>(n));
    if (!frame) {
      if (IsServerAnswer(frame.error())) return false;
      return std::nullopt;
    }
    if (proto::Sha256Hex(*frame) != manifest->frame_parts[n].sha256) return false;
    if (sent && (n >= sent->frames.size() || *frame != sent->frames[n])) return false;
  }
  auto map = api.GetMap(id);
  if (!map) {
    if (IsServerAnswer(map.error())) return false;
    return std::nullopt;
  }
  if (proto::Sha256Hex(*map) != manifest->map_part.sha256) return false;
  if (sent && *map != sent->map) return false;
  return true;
}

// Every clip anonymous browsing sees at the clips' place, page by page.
Expected<std::vector<proto::ClipSummary>> VisibleClips(const proto::ApiClient& api) {
  std::vector<proto::ClipSummary> all;
  std::string cursor;
  for (;;) {
    auto page = api.NearbyPageAt(kLat, kLon, 1000, 100, cursor);
    if (!page) return page.error();
    all.insert(all.end(), page->clips.begin(), page->clips.end());
    if (!page->next_cursor) return all;
    cursor = *page->next_cursor;
  }
}

bool VisibleOn(const proto::ApiClient& api, const std::string& id) {
  auto near = VisibleClips(api);
  if (!near) return false;
  for (const auto& c : *near) {
    if (c.id == id) return true;
  }
  return false;
}

}  // namespace

std::string DefaultServerBinary() {
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) return "reenact-server";
  return (self.parent_path().parent_path().parent_path() / "server" / "reenact-server").string();
}

Expected<KillBenchResult> RunKillBench(const KillBenchOptions& options) {
  auto storage = server::OpenStorage(options.db);
  if (!storage) return storage.error();
  auto token =
      server::AddUserWithToken(*storage->metadata, "kill-run-" + std::to_string(::getpid()));
  if (!token) return token.error();
  storage->metadata.reset();
  storage->blobs.reset();

  ServerChild servers[2];
  std::mutex urls_mutex;
  std::string urls[2];
  for (int i = 0; i < 2; ++i) {
    if (Status s = servers[i].Start(options.server_binary, options.db); !s) return s.error();
    urls[i] = servers[i].url();
  }
  auto url_of = [&](int i) {
    std::lock_guard lock(urls_mutex);
    return urls[i];
  };

  KillBenchResult result;
  std::atomic<bool> done{false};
  std::atomic<int> half_visible{0};
  std::atomic<long long> observed{0};
  std::thread observer([&] {
    std::set<std::string> whole;
    for (int turn = 0; !done; ++turn) {
      const proto::ApiClient api(url_of(turn % 2), "");
      auto near = VisibleClips(api);
      if (!near) {  // that server is down: the other one next, after a breath
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
        continue;
      }
      for (const auto& c : *near) {
        if (whole.count(c.id)) continue;
        const std::optional<bool> ok = CheckWhole(api, c.id, nullptr);
        if (!ok) break;  // this server went away: the other one next
        if (*ok) {
          whole.insert(c.id);
          ++observed;
        } else {
          ++half_visible;
          std::cerr << "reenact-bench: clip " << c.id << " visible before it is whole on "
                    << api.base_url() << std::endl;
          whole.insert(c.id);  // counted once
        }
      }
    }
  });

  std::mt19937 rng(options.seed);
  std::map<std::string, TestClip> published;
  std::optional<Error> failure;
  double undisturbed_s = 0.2;
  const auto t0 = Clock::now();
  for (int round = 0; round < options.kills && !failure; ++round) {
    const int target = round % 2;
    TestClip clip = MakeClip(round, rng);
    const double delay_s =
        std::uniform_real_distribution<double>(0, 1.5 * undisturbed_s)(rng);
    std::atomic<bool> killed{false};
    std::thread killer([&] {
      std::this_thread::sleep_for(std::chrono::duration<double>(delay_s));
      servers[target].Kill();
      killed = true;
    });
    const auto upload_start = Clock::now();
    auto id = UploadWhole(proto::ApiClient(url_of(target), *token), clip);
    const double upload_s = std::chrono::duration<double>(Clock::now() - upload_start).count();
    const bool undisturbed = id.ok() && !killed;
    killer.join();
    ++result.kills;
    if (undisturbed) undisturbed_s = 0.8 * undisturbed_s + 0.2 * upload_s;
    if (!id.ok()) {
      ++result.mid_upload;
      id = UploadWhole(proto::ApiClient(url_of(1 - target), *token), clip);
    }
    if (!id.ok()) {
      failure = MakeError("io", "the upload did not finish through the live server: " +
                                    id.error().message);
    } else {
      published.emplace(*id, std::move(clip));
    }
    if (Status s = servers[target].Start(options.server_binary, options.db); !s) {
      failure = s.error();
    } else {
      std::lock_guard lock(urls_mutex);
      urls[target] = servers[target].url();
    }
  }
  done = true;
  observer.join();
  result.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  result.published = static_cast<int>(published.size());
  result.half_visible = half_visible;
  result.observed = observed;
  if (failure) return *failure;

  for (const auto& [id, clip] : published) {
    bool whole = true;
    for (int i = 0; i < 2 && whole; ++i) {
      const proto::ApiClient api(url_of(i), "");
      const std::optional<bool> ok = CheckWhole(api, id, &clip);
      whole = ok.value_or(false) && VisibleOn(api, id);
    }
    if (!whole) ++result.lost;
  }
  const proto::ApiClient owner(url_of(0), *token);
  for (const auto& entry : published) {
    if (Status s = owner.DeleteClip(entry.first); !s) return s.error();
  }
  return result;
}

}  // namespace reenact::bench
