// reenact-bench server --attacks: the server's defences, measured.
//
// One HttpServer with default ServerOptions (only the port is 0) on loopback, over a database
// of `clips` published clips (Seed) plus a few clips of its own (SeedAttackClips). Normal
// clients: `clients` keep-alive threads from 127.0.0.1 sending nearby queries, each request
// with a 2 s deadline (connecting included); a request is answered when a 200 comes back in
// time. p50/p99 are over the answered requests, max over all (a timeout counts 2 s). Each
// scenario measures the normal clients for `seconds` without the attack (baseline), then for
// `seconds` while the attack runs; the process's resident memory is sampled every 25 ms in
// both: VmRSS, and its anonymous part RssAnon (VmRSS also counts the database file's pages
// that SQLite's readers map, which grow with what was read, not with what a client holds).
//
// Scenarios (the goals are the server issue's):
//  1. slow headers: 1,000 and 2,000 connections from 127.0.0.2-33 each send one byte of a
//     never-ending request header per second and reconnect as soon as the server closes them.
//     Figure: connections the attacker has open on average (established, whether the server
//     serves them or they wait in its listen queue), server closes per second, the attacker
//     thread's CPU. Goal: normal requests >= 99 % answered, p99 < 50 ms. Once more at 2,000
//     with normal clients that open a new connection per request, as proto's HttpClient does.
//  2. bodies: 64 connections PUT a 60 MiB map and push body bytes as fast as the socket takes
//     them, reconnecting when closed: without a token, and with another user's token (both
//     refused from the header); and, for comparison, with the owner's token and a body whose
//     hash is wrong (admitted into max_body_memory, read whole, answered 422). Figure: the
//     process's peak anonymous RSS. Goal (refused bodies): under 200 MB.
//  3. slow body: the owner PUTs a 1 MiB frame's header, then one body byte every 3 s; and a
//     request header sent one byte every 3 s. Figure: seconds until the server closes the
//     connection. Goal: within 10 s.
//  4. heavy reads by one client: GET /v1/clips/{id}/parts in a loop (each call reads and
//     hashes 30 stored frames of 8 MiB) with the owner's token; or downloads of an 8 MiB frame
//     in a loop. Goal: normal p99 under 20 ms.
//  5. stalled downloads (no goal in the issue): 64 connections GET an 8 MiB frame and never
//     read it; the measurement starts with them. Figure: the process's peak anonymous RSS.
// The attackers are non-blocking sockets on one epoll thread (Flood) whose buffers are shared
// and small, so the memory figures are the server's. The attacker, the normal clients and the
// server share the machine's cores.
#include "tests/bench/server_attack_bench.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/epoll.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <limits>
#include <mutex>
#include <optional>
#include <thread>

#include "proto/clip/content_hash.h"
#include "server/app/open_file_limit.h"
#include "server/auth/token.h"
#include "server/http/http_server.h"
#include "server/storage/open_storage.h"
#include "tests/bench/bench_support.h"
#include "tests/bench/server_bench_support.h"

namespace reenact::bench {
namespace {

namespace beast = boost::beast;
namespace http = beast::http;
using tcp = boost::asio::ip::tcp;
using namespace std::chrono_literals;

constexpr auto kNormalTimeout = 2s;
constexpr auto kSamplePeriod = 25ms;
constexpr int kHeavyFrames = 30;
constexpr size_t kHeavyFrameBytes = size_t{8} << 20;
constexpr size_t kSlowFrameBytes = size_t{1} << 20;
constexpr uint64_t kBigBodyBytes = 62'914'560;  // 60 MiB, under the map limit of 64 MiB
constexpr int kBodyConnections = 64;
// Clips of the attacks: a published one with heavy frames, a draft with a 1 MiB frame (the
// slow body) and a draft promising a 60 MiB map (the bodies).
constexpr const char* kHeavyClip = "attack-heavy";
constexpr const char* kSlowDraft = "attack-slow";
constexpr const char* kBigDraft = "attack-big";

double SecondsOf(Clock::duration d) { return std::chrono::duration<double>(d).count(); }

// Resident memory of this process, MB (10^6 bytes): all of it (VmRSS, which counts the pages
// of the database file that SQLite's readers map) and its anonymous part (RssAnon: the heap,
// what a client can make the server allocate). 0 where unreadable.
struct Resident {
  double all_mb = 0, anon_mb = 0;
};

Resident ResidentNow() {
  std::ifstream status("/proc/self/status");
  std::string line;
  Resident r;
  while (std::getline(status, line)) {
    if (line.rfind("VmRSS:", 0) == 0) r.all_mb = std::stod(line.substr(6)) * 1024.0 / 1e6;
    if (line.rfind("RssAnon:", 0) == 0) r.anon_mb = std::stod(line.substr(8)) * 1024.0 / 1e6;
  }
  return r;
}

// Thousands of sockets on each side of loopback need more descriptors than a default soft limit.
std::string Fixed(double value, int decimals) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

// Samples the peak resident memory, and the mean of an optional gauge, every 25 ms until
// stopped.
class Sampler {
 public:
  explicit Sampler(std::function<double()> gauge = {}) : gauge_(std::move(gauge)) {
    thread_ = std::thread([this] {
      while (!stop_) {
        const Resident now = ResidentNow();
        peak_rss_mb_ = std::max(peak_rss_mb_, now.all_mb);
        peak_anon_mb_ = std::max(peak_anon_mb_, now.anon_mb);
        if (gauge_) {
          gauge_sum_ += gauge_();
          ++gauge_samples_;
        }
        std::this_thread::sleep_for(kSamplePeriod);
      }
    });
  }
  ~Sampler() { Stop(); }
  void Stop() {
    stop_ = true;
    if (thread_.joinable()) thread_.join();
  }
  // Valid after Stop().
  double peak_rss_mb() const { return peak_rss_mb_; }
  double peak_anon_mb() const { return peak_anon_mb_; }
  double gauge_mean() const { return gauge_samples_ ? gauge_sum_ / gauge_samples_ : 0; }

 private:
  std::function<double()> gauge_;
  std::atomic<bool> stop_{false};
  double peak_rss_mb_ = 0, peak_anon_mb_ = 0, gauge_sum_ = 0;
  long long gauge_samples_ = 0;
  std::thread thread_;
};

// What the normal clients saw in one measurement.
struct NormalFigures {
  long long sent = 0, answered = 0;
  double p50_ms = 0, p99_ms = 0;             // of the answered requests
  double max_ms = 0;                         // the longest wait of any request, answered or not
  double peak_rss_mb = 0, peak_anon_mb = 0;  // the process's resident memory (Resident)
  double gauge_mean = 0;                     // the mean of the Sampler's gauge, if one was given
  double answered_pct() const {
    return sent ? 100.0 * static_cast<double>(answered) / static_cast<double>(sent) : 0;
  }
};

// `clients` keep-alive threads send nearby queries for `seconds`, each with a 2 s deadline;
// with `fresh`, each request on a new connection (as proto's HttpClient does).
NormalFigures MeasureNormal(uint16_t port, int clients, double seconds, bool fresh,
                            std::function<double()> gauge = {}) {
  std::mutex mutex;
  std::vector<double> latencies_ms;
  std::atomic<long long> sent{0};
  double max_ms = 0;
  Sampler sampler(std::move(gauge));
  const auto until = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                        std::chrono::duration<double>(seconds));
  std::vector<std::thread> threads;
  for (int c = 0; c < clients; ++c) {
    threads.emplace_back([&, c] {
      std::mt19937_64 rng(2000 + static_cast<uint64_t>(c));
      std::vector<double> mine;
      std::optional<KeepAliveClient> client;
      long long count = 0;
      double longest_ms = 0;
      while (Clock::now() < until) {
        const std::string target = NearbyTarget(rng);
        const auto start = Clock::now();
        if (fresh || !client) client.emplace(port, kNormalTimeout);
        const int status = client->Send(http::verb::get, target, "", "");
        const double ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
        ++count;
        longest_ms = std::max(longest_ms, ms);
        if (status == 200) {
          mine.push_back(ms);
        } else {
          std::this_thread::sleep_for(10ms);  // a refused connection does not spin
        }
      }
      sent += count;
      std::lock_guard lock(mutex);
      max_ms = std::max(max_ms, longest_ms);
      latencies_ms.insert(latencies_ms.end(), mine.begin(), mine.end());
    });
  }
  for (auto& t : threads) t.join();
  sampler.Stop();
  NormalFigures f;
  f.sent = sent;
  f.answered = static_cast<long long>(latencies_ms.size());
  f.p50_ms = Percentile(latencies_ms, 0.50);
  f.p99_ms = Percentile(latencies_ms, 0.99);
  f.max_ms = max_ms;
  f.peak_rss_mb = sampler.peak_rss_mb();
  f.peak_anon_mb = sampler.peak_anon_mb();
  f.gauge_mean = sampler.gauge_mean();
  return f;
}

// ---- Flood: many attacker connections on one epoll thread.

struct FloodPlan {
  int connections = 0;
  std::vector<std::string> from;  // local addresses; connection i binds from[i % size]
  std::string head;               // what each connection sends first
  uint64_t body_bytes = 0;        // then this many zero bytes, as fast as the socket takes them
  // > 0: instead, the head one byte per interval, then 'a' forever (a header never finished).
  std::chrono::milliseconds byte_every{0};
  // false: never read (a small receive buffer, so the server cannot hand off what it sends).
  bool read = true;
};

class Flood {
 public:
  Flood(uint16_t port, FloodPlan plan) : port_(port), plan_(std::move(plan)) {
    for (const std::string& address : plan_.from) {
      sockaddr_in local{};
      local.sin_family = AF_INET;
      inet_pton(AF_INET, address.c_str(), &local.sin_addr);
      locals_.push_back(local);
    }
    conns_.resize(static_cast<size_t>(plan_.connections));
    // Slow connections start spread over one interval, as independent clients would.
    const auto start = Clock::now();
    for (size_t i = 0; i < conns_.size(); ++i) {
      conns_[i].retry_at = start + plan_.byte_every * static_cast<long>(i) / plan_.connections;
    }
    epoll_ = epoll_create1(EPOLL_CLOEXEC);
    thread_ = std::thread([this] { Loop(); });
  }
  ~Flood() { Stop(); }
  Flood(const Flood&) = delete;
  Flood& operator=(const Flood&) = delete;

  void Stop() {
    stop_ = true;
    if (thread_.joinable()) thread_.join();
    for (Conn& c : conns_) {
      if (c.fd >= 0) close(c.fd);
      c.fd = -1;
    }
    if (epoll_ >= 0) close(epoll_);
    epoll_ = -1;
  }

  // Connections established and not closed yet.
  int open() const { return open_; }
  long long connects() const { return connects_; }
  // Closed or reset by the server after they were established.
  long long server_closes() const { return server_closes_; }
  // Connections the attacker ended itself after an answer came (bodies sent whole).
  long long answered() const { return answered_; }
  long long connect_failures() const { return failures_; }
  uint64_t bytes_sent() const { return bytes_sent_; }
  // CPU time the attacker's thread has used, seconds.
  double cpu_s() const { return static_cast<double>(cpu_ns_.load()) / 1e9; }

  // Waits until every connection was established once (at most `limit`).
  void WaitConnected(Clock::duration limit) const {
    const auto until = Clock::now() + limit;
    while (connects_ < plan_.connections && Clock::now() < until) std::this_thread::sleep_for(20ms);
  }

 private:
  enum class State { kWaiting, kConnecting, kOpen };
  struct Conn {
    int fd = -1;
    State state = State::kWaiting;
    Clock::time_point retry_at{};
    Clock::time_point next_byte{};
    uint64_t head_sent = 0;
    uint64_t body_sent = 0;
    bool got_response = false;
  };

  bool Slow() const { return plan_.byte_every.count() > 0; }
  bool SentAll(const Conn& c) const {
    return c.head_sent >= plan_.head.size() && c.body_sent >= plan_.body_bytes;
  }

  void Watch(size_t i, uint32_t events, int op) {
    epoll_event ev{};
    ev.events = events;
    ev.data.u64 = i;
    epoll_ctl(epoll_, op, conns_[i].fd, &ev);
  }

  void Open(size_t i, Clock::time_point now) {
    Conn& c = conns_[i];
    c = Conn{};
    c.fd = socket(AF_INET, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
    if (c.fd < 0) return Failed(i, now);
    const int one = 1;
    setsockopt(c.fd, IPPROTO_IP, IP_BIND_ADDRESS_NO_PORT, &one, sizeof one);
    setsockopt(c.fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
    if (!plan_.read) {
      const int small = 4096;
      setsockopt(c.fd, SOL_SOCKET, SO_RCVBUF, &small, sizeof small);
    }
    const sockaddr_in& local = locals_[i % locals_.size()];
    if (bind(c.fd, reinterpret_cast<const sockaddr*>(&local), sizeof local) != 0) {
      return Failed(i, now);
    }
    sockaddr_in server{};
    server.sin_family = AF_INET;
    server.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    server.sin_port = htons(port_);
    if (connect(c.fd, reinterpret_cast<const sockaddr*>(&server), sizeof server) != 0 &&
        errno != EINPROGRESS) {
      return Failed(i, now);
    }
    c.state = State::kConnecting;
    Watch(i, EPOLLOUT, EPOLL_CTL_ADD);
  }

  void Failed(size_t i, Clock::time_point now) {
    Conn& c = conns_[i];
    if (c.fd >= 0) close(c.fd);
    c.fd = -1;
    c.state = State::kWaiting;
    c.retry_at = now + 10ms;  // a failing connect does not spin
    ++failures_;
  }

  // Closes connection i; it connects again at once.
  void Drop(size_t i, bool by_server, Clock::time_point now) {
    Conn& c = conns_[i];
    close(c.fd);  // also leaves the epoll set
    c.fd = -1;
    if (c.state == State::kOpen) {
      --open_;
      if (by_server) {
        ++server_closes_;
      } else {
        ++answered_;
      }
    }
    c.state = State::kWaiting;
    c.retry_at = now;
  }

  void Connected(size_t i, Clock::time_point now) {
    Conn& c = conns_[i];
    c.state = State::kOpen;
    ++open_;
    ++connects_;
    if (Slow()) {
      Watch(i, EPOLLIN | EPOLLRDHUP, EPOLL_CTL_MOD);
      c.next_byte = now;
      return SendByte(i, now);
    }
    Watch(i, EPOLLOUT | (plan_.read ? EPOLLIN | EPOLLRDHUP : 0u), EPOLL_CTL_MOD);
    Pump(i, now);
  }

  void SendByte(size_t i, Clock::time_point now) {
    Conn& c = conns_[i];
    const char byte = c.head_sent < plan_.head.size() ? plan_.head[c.head_sent] : 'a';
    if (send(c.fd, &byte, 1, MSG_NOSIGNAL) != 1) return Drop(i, true, now);
    ++c.head_sent;
    ++bytes_sent_;
    c.next_byte += plan_.byte_every;
  }

  // Sends what the socket takes of the head and then the body.
  void Pump(size_t i, Clock::time_point now) {
    static const std::vector<char> zeros(64 * 1024, '\0');  // one for every connection
    Conn& c = conns_[i];
    while (!SentAll(c)) {
      const char* data;
      size_t size;
      if (c.head_sent < plan_.head.size()) {
        data = plan_.head.data() + c.head_sent;
        size = plan_.head.size() - c.head_sent;
      } else {
        data = zeros.data();
        size =
            static_cast<size_t>(std::min<uint64_t>(zeros.size(), plan_.body_bytes - c.body_sent));
      }
      const ssize_t n = send(c.fd, data, size, MSG_NOSIGNAL);
      if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) return;
      if (n <= 0) return Drop(i, true, now);
      const uint64_t head_part =
          std::min<uint64_t>(static_cast<uint64_t>(n), plan_.head.size() - c.head_sent);
      c.head_sent += head_part;
      c.body_sent += static_cast<uint64_t>(n) - head_part;
      bytes_sent_ += static_cast<uint64_t>(n);
    }
    if (!plan_.read) return Watch(i, 0, EPOLL_CTL_MOD);
    if (c.got_response) return Drop(i, false, now);
    Watch(i, EPOLLIN | EPOLLRDHUP, EPOLL_CTL_MOD);
  }

  void Receive(size_t i, Clock::time_point now) {
    static char scratch[64 * 1024];  // what comes back is never looked at
    Conn& c = conns_[i];
    for (;;) {
      const ssize_t n = recv(c.fd, scratch, sizeof scratch, 0);
      if (n > 0) {
        c.got_response = true;
        continue;
      }
      if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) break;
      return Drop(i, true, now);  // closed (0) or reset
    }
    // A whole body sent and answered: start again.
    if (!Slow() && c.got_response && SentAll(c)) Drop(i, false, now);
  }

  void Loop() {
    std::vector<epoll_event> events(512);
    while (!stop_) {
      timespec cpu{};
      clock_gettime(CLOCK_THREAD_CPUTIME_ID, &cpu);
      cpu_ns_ = static_cast<int64_t>(cpu.tv_sec) * 1'000'000'000 + cpu.tv_nsec;
      const int n = epoll_wait(epoll_, events.data(), static_cast<int>(events.size()), 10);
      auto now = Clock::now();
      for (int k = 0; k < n; ++k) {
        const size_t i = static_cast<size_t>(events[k].data.u64);
        const uint32_t ev = events[k].events;
        Conn& c = conns_[i];
        if (c.state == State::kConnecting) {
          int error = 0;
          socklen_t size = sizeof error;
          getsockopt(c.fd, SOL_SOCKET, SO_ERROR, &error, &size);
          if (error != 0 || (ev & (EPOLLERR | EPOLLHUP))) {
            Failed(i, now);
          } else {
            Connected(i, now);
          }
          continue;
        }
        if (c.state != State::kOpen) continue;
        if (!plan_.read) {
          if (ev & (EPOLLERR | EPOLLHUP)) Drop(i, true, now);
          continue;
        }
        if (ev & (EPOLLIN | EPOLLRDHUP | EPOLLHUP | EPOLLERR)) Receive(i, now);
        if (c.state == State::kOpen && (ev & EPOLLOUT)) Pump(i, now);
      }
      now = Clock::now();
      for (size_t i = 0; i < conns_.size() && !stop_; ++i) {
        Conn& c = conns_[i];
        if (c.state == State::kWaiting && now >= c.retry_at) {
          Open(i, now);
        } else if (c.state == State::kOpen && Slow() && now >= c.next_byte) {
          SendByte(i, now);
        }
      }
    }
  }

  const uint16_t port_;
  const FloodPlan plan_;
  std::vector<sockaddr_in> locals_;
  std::vector<Conn> conns_;  // touched by the flood thread only
  int epoll_ = -1;
  std::atomic<bool> stop_{false};
  std::atomic<int> open_{0};
  std::atomic<long long> connects_{0}, server_closes_{0}, answered_{0}, failures_{0};
  std::atomic<uint64_t> bytes_sent_{0};
  std::atomic<int64_t> cpu_ns_{0};
  std::thread thread_;
};

// "127.0.0.first" ... "127.0.0.(first + count - 1)"
std::vector<std::string> Addresses(int first, int count) {
  std::vector<std::string> out;
  for (int i = 0; i < count; ++i) out.push_back("127.0.0." + std::to_string(first + i));
  return out;
}

// ---- One slow connection, blocking.

// Connects from `from`, sends `prefix` whole, then `trickle` one byte every `every` (zeros
// once it runs out): the seconds from the first trickled byte until the server closes the
// connection, or nullopt when it is still open after `limit_s`.
std::optional<double> SecondsUntilCut(uint16_t port, const char* from, const std::string& prefix,
                                      const std::string& trickle, std::chrono::milliseconds every,
                                      double limit_s) {
  const int fd = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd < 0) return std::nullopt;
  sockaddr_in local{};
  local.sin_family = AF_INET;
  inet_pton(AF_INET, from, &local.sin_addr);
  sockaddr_in server{};
  server.sin_family = AF_INET;
  server.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  server.sin_port = htons(port);
  const int one = 1;
  setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
  if (bind(fd, reinterpret_cast<sockaddr*>(&local), sizeof local) != 0 ||
      connect(fd, reinterpret_cast<sockaddr*>(&server), sizeof server) != 0 ||
      (!prefix.empty() && send(fd, prefix.data(), prefix.size(), MSG_NOSIGNAL) !=
                              static_cast<ssize_t>(prefix.size()))) {
    close(fd);
    return std::nullopt;
  }
  const auto start = Clock::now();
  std::optional<double> cut;
  for (size_t sent = 0; !cut && SecondsOf(Clock::now() - start) < limit_s; ++sent) {
    const char byte = sent < trickle.size() ? trickle[sent] : '\0';
    if (send(fd, &byte, 1, MSG_NOSIGNAL) != 1) {
      cut = SecondsOf(Clock::now() - start);
      break;
    }
    const auto next = Clock::now() + every;
    while (!cut && Clock::now() < next) {
      pollfd pfd{fd, POLLIN, 0};
      const auto wait = std::chrono::duration_cast<std::chrono::milliseconds>(next - Clock::now());
      if (poll(&pfd, 1, static_cast<int>(std::max<int64_t>(1, wait.count()))) <= 0) continue;
      char buffer[4096];
      if (recv(fd, buffer, sizeof buffer, 0) <= 0) cut = SecondsOf(Clock::now() - start);
    }
  }
  close(fd);
  return cut;
}

// ---- The attack clips.

struct AttackUsers {
  std::string owner_token;  // owns the attack clips
  std::string other_token;  // a user who owns none of them
};

Status StorePart(server::Storage& storage, const std::string& clip, int index,
                 const std::string& bytes) {
  if (Status s = storage.blobs->Put(server::BlobKey(clip, index), bytes); !s) return s;
  return storage.metadata->MarkPartPresent(clip, index);
}

// A draft owned by `owner` whose parts are `frames` and `map` (sizes and hashes).
Status CreateDraft(server::Storage& storage, int64_t owner, const std::string& id,
                   const std::vector<proto::PartInfo>& frames, const proto::PartInfo& map) {
  server::NewClip clip;
  clip.record.id = id;
  clip.record.owner_id = owner;
  clip.record.title = id;
  clip.record.author = "bench";
  clip.record.lat_deg = 40;
  clip.record.lon_deg = 5;
  clip.record.frame_count = static_cast<int>(frames.size());
  clip.record.duration_s = static_cast<double>(frames.size()) / 30.0;
  clip.manifest_json = BenchManifest(id, frames, map);
  clip.record.manifest_sha256 = proto::Sha256Hex(clip.manifest_json);
  for (size_t i = 0; i < frames.size(); ++i) {
    clip.parts.push_back(
        {static_cast<int>(i), static_cast<int64_t>(frames[i].bytes), frames[i].sha256});
  }
  clip.parts.push_back({server::kMapPart, static_cast<int64_t>(map.bytes), map.sha256});
  return storage.metadata->CreateClip(clip);
}

// The owner and another user; kHeavyClip published with 30 random frames of 8 MiB, and the
// drafts kSlowDraft (one 1 MiB frame) and kBigDraft (a 60 MiB map whose hash no body has).
Expected<AttackUsers> SeedAttackClips(server::Storage& storage) {
  AttackUsers users;
  auto owner = server::AddUserWithToken(*storage.metadata, "attack-owner");
  auto other = server::AddUserWithToken(*storage.metadata, "attack-other");
  if (!owner) return owner.error();
  if (!other) return other.error();
  users.owner_token = *owner;
  users.other_token = *other;
  auto user = server::Authenticate(*storage.metadata, users.owner_token);
  if (!user) return user.error();
  if (!*user) return MakeError("internal", "the owner's token does not authenticate");
  const int64_t owner_id = (*user)->id;

  std::string frame(kHeavyFrameBytes, '\0');
  std::mt19937_64 rng(11);
  for (size_t at = 0; at + 8 <= frame.size(); at += 8) {
    const uint64_t word = rng();
    std::memcpy(frame.data() + at, &word, 8);
  }
  std::vector<proto::PartInfo> frames;
  for (int n = 0; n < kHeavyFrames; ++n) {
    std::memcpy(frame.data(), &n, sizeof n);  // each frame its own bytes
    frames.push_back({frame.size(), proto::Sha256Hex(frame)});
  }
  const std::string map = "attack map";
  if (Status s =
          CreateDraft(storage, owner_id, kHeavyClip, frames, {map.size(), proto::Sha256Hex(map)});
      !s) {
    return s.error();
  }
  for (int n = 0; n < kHeavyFrames; ++n) {
    std::memcpy(frame.data(), &n, sizeof n);
    if (Status s = StorePart(storage, kHeavyClip, n, frame); !s) return s.error();
  }
  if (Status s = StorePart(storage, kHeavyClip, server::kMapPart, map); !s) return s.error();
  auto published = storage.metadata->Publish(kHeavyClip);
  if (!published) return published.error();
  if (!published->published) return MakeError("internal", "the heavy clip did not publish");

  const std::string slow_frame(kSlowFrameBytes, 's');
  if (Status s = CreateDraft(storage, owner_id, kSlowDraft,
                             {{slow_frame.size(), proto::Sha256Hex(slow_frame)}},
                             {map.size(), proto::Sha256Hex(map)});
      !s) {
    return s.error();
  }
  if (Status s = CreateDraft(storage, owner_id, kBigDraft, {{map.size(), proto::Sha256Hex(map)}},
                             {kBigBodyBytes, proto::Sha256Hex("no body hashes to this")});
      !s) {
    return s.error();
  }
  return users;
}

// ---- Heavy clients.

// Loops `body` on its own thread until destroyed.
class BackgroundLoop {
 public:
  explicit BackgroundLoop(std::function<void(const std::atomic<bool>& stop)> body)
      : thread_([this, body = std::move(body)] { body(stop_); }) {}
  ~BackgroundLoop() {
    stop_ = true;
    thread_.join();
  }

 private:
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

// Downloads `target` over `socket` into a small scratch buffer; the bytes of the body, or -1.
long long DownloadOnce(tcp::socket& socket, beast::flat_buffer& buffer, const std::string& target) {
  http::request<http::empty_body> request(http::verb::get, target, 11);
  request.set(http::field::host, "127.0.0.1");
  beast::error_code ec;
  http::write(socket, request, ec);
  if (ec) return -1;
  http::response_parser<http::buffer_body> parser;
  parser.body_limit(std::numeric_limits<std::uint64_t>::max());
  http::read_header(socket, buffer, parser, ec);
  if (ec || parser.get().result_int() != 200) return -1;
  static thread_local char scratch[64 * 1024];
  long long bytes = 0;
  while (!parser.is_done()) {
    parser.get().body().data = scratch;
    parser.get().body().size = sizeof scratch;
    http::read(socket, buffer, parser, ec);
    if (ec == http::error::need_buffer) ec = {};
    if (ec) return -1;
    bytes += static_cast<long long>(sizeof scratch - parser.get().body().size);
  }
  return bytes;
}

// ---- The report.

struct Row {
  std::string scenario;
  std::string attack;
  NormalFigures under, base;
  std::string goal;
  std::optional<bool> met;  // nullopt: no goal
};

void AddRow(proto::Report& report, const Row& row) {
  report.rows.push_back(proto::ReportRow()
                            .Add("scenario", row.scenario)
                            .Add("attack", row.attack)
                            .Add("answered_pct", row.under.answered_pct())
                            .Add("p50_ms", row.under.p50_ms)
                            .Add("p99_ms", row.under.p99_ms)
                            .Add("max_ms", row.under.max_ms)
                            .Add("base_answered_pct", row.base.answered_pct())
                            .Add("base_p50_ms", row.base.p50_ms)
                            .Add("base_p99_ms", row.base.p99_ms)
                            .Add("base_max_ms", row.base.max_ms)
                            .Add("anon_mb", row.under.peak_anon_mb)
                            .Add("base_anon_mb", row.base.peak_anon_mb)
                            .Add("rss_mb", row.under.peak_rss_mb)
                            .Add("base_rss_mb", row.base.peak_rss_mb)
                            .Add("goal", row.goal)
                            .Add("met", std::string(row.met ? (*row.met ? "yes" : "no") : "-")));
  std::cerr << "reenact-bench: " << row.scenario << ": " << row.attack << "; answered "
            << Fixed(row.under.answered_pct(), 2) << " % (base "
            << Fixed(row.base.answered_pct(), 2) << " %), p50/p99/max "
            << Fixed(row.under.p50_ms, 2) << "/" << Fixed(row.under.p99_ms, 2) << "/"
            << Fixed(row.under.max_ms, 0) << " ms (base " << Fixed(row.base.p50_ms, 2) << "/"
            << Fixed(row.base.p99_ms, 2) << "/" << Fixed(row.base.max_ms, 0) << ")" << std::endl;
}

class Scenarios {
 public:
  Scenarios(const AttackBenchOptions& options, uint16_t port, AttackUsers users,
            proto::Report& report)
      : options_(options), port_(port), users_(std::move(users)), report_(report) {}

  NormalFigures Normal(std::function<double()> gauge = {}, bool fresh = false) {
    return MeasureNormal(port_, options_.clients, options_.seconds, fresh, std::move(gauge));
  }

  // Lets the server close what an attack left behind.
  static void Settle() { std::this_thread::sleep_for(1s); }

  // fresh: the normal clients open a new connection for each request.
  void SlowHeaders(int connections, bool fresh) {
    const NormalFigures base = Normal({}, fresh);
    FloodPlan plan;
    plan.connections = connections;
    plan.from = Addresses(2, 32);
    plan.head = "GET /v1/clips?near=40,5 HTTP/1.1\r\nHost: 127.0.0.1\r\nX-Slow: ";
    plan.byte_every = 1s;
    Flood flood(port_, plan);
    flood.WaitConnected(5s);
    std::this_thread::sleep_for(1s);
    const long long closes0 = flood.server_closes();
    const double cpu0 = flood.cpu_s();
    const auto t0 = Clock::now();
    const NormalFigures under = Normal([&] { return static_cast<double>(flood.open()); }, fresh);
    const double seconds = SecondsOf(Clock::now() - t0);
    const double closes_per_s = static_cast<double>(flood.server_closes() - closes0) / seconds;
    const double cpu_pct = 100.0 * (flood.cpu_s() - cpu0) / seconds;
    const long long failures = flood.connect_failures();
    flood.Stop();
    Settle();
    const bool met = under.answered_pct() >= 99.0 && under.p99_ms < 50.0;
    AddRow(report_,
           {"slow headers x" + std::to_string(connections) + (fresh ? ", new conn/request" : ""),
            Fixed(under.gauge_mean, 0) + " open, " + Fixed(closes_per_s, 0) +
                " closes/s, attacker CPU " + Fixed(cpu_pct, 0) + "%" +
                (failures ? ", " + std::to_string(failures) + " connects failed" : ""),
            under, base, ">=99% answered, p99<50ms", met});
  }

  // 64 connections PUT a 60 MiB map body as fast as they can.
  // has_goal: the memory goal applies (bodies refused from their header).
  void Bodies(const std::string& name, const std::string& token, int first_address, bool has_goal) {
    const NormalFigures base = Normal();
    FloodPlan plan;
    plan.connections = kBodyConnections;
    plan.from = Addresses(first_address, 4);
    plan.head = std::string("PUT /v1/clips/") + kBigDraft + "/map HTTP/1.1\r\nHost: 127.0.0.1\r\n" +
                (token.empty() ? std::string() : "Authorization: Bearer " + token + "\r\n") +
                "Content-Type: application/octet-stream\r\nContent-Length: " +
                std::to_string(kBigBodyBytes) + "\r\n\r\n";
    plan.body_bytes = kBigBodyBytes;
    Flood flood(port_, plan);
    flood.WaitConnected(5s);
    std::this_thread::sleep_for(500ms);
    const uint64_t bytes0 = flood.bytes_sent();
    const double cpu0 = flood.cpu_s();
    const auto t0 = Clock::now();
    const NormalFigures under = Normal();
    const double seconds = SecondsOf(Clock::now() - t0);
    const double mb_per_s = static_cast<double>(flood.bytes_sent() - bytes0) / 1e6 / seconds;
    const double cpu_pct = 100.0 * (flood.cpu_s() - cpu0) / seconds;
    flood.Stop();
    Settle();
    std::optional<bool> met;
    if (has_goal) met = under.peak_anon_mb < 200.0;
    AddRow(report_, {name,
                     "peak anon RSS " + Fixed(under.peak_anon_mb, 0) + " MB, " +
                         Fixed(mb_per_s, 0) + " MB/s sent, attacker CPU " + Fixed(cpu_pct, 0) + "%",
                     under, base, has_goal ? "anon RSS<200MB" : "none", met});
  }

  void SlowBodyAndHeader() {
    const NormalFigures base = Normal();
    std::optional<double> body_cut, header_cut;
    constexpr double kLimitS = 40;
    std::thread body([&] {
      const std::string head = std::string("PUT /v1/clips/") + kSlowDraft +
                               "/frames/0 HTTP/1.1\r\nHost: 127.0.0.1\r\nAuthorization: Bearer " +
                               users_.owner_token +
                               "\r\nContent-Type: application/octet-stream\r\nContent-Length: " +
                               std::to_string(kSlowFrameBytes) + "\r\n\r\n";
      body_cut = SecondsUntilCut(port_, "127.0.0.60", head, "", 3s, kLimitS);
    });
    std::thread header([&] {
      header_cut =
          SecondsUntilCut(port_, "127.0.0.61", "",
                          "GET /v1/clips?near=40,5 HTTP/1.1\r\nHost: 127.0.0.1\r\n", 3s, kLimitS);
    });
    const NormalFigures under = Normal();
    body.join();
    header.join();
    auto figure = [&](const std::optional<double>& cut) {
      return cut ? "cut after " + Fixed(*cut, 1) + " s" : "open after " + Fixed(kLimitS, 0) + " s";
    };
    AddRow(report_, {"slow body 1B/3s", figure(body_cut), under, base, "cut<=10s",
                     body_cut && *body_cut <= 10.0});
    AddRow(report_, {"slow header 1B/3s", figure(header_cut), under, base, "cut<=10s",
                     header_cut && *header_cut <= 10.0});
  }

  void HeavyParts() {
    const NormalFigures base = Normal();
    std::atomic<long long> calls{0}, failed{0};
    NormalFigures under;
    double seconds = 0;
    {
      BackgroundLoop heavy([&](const std::atomic<bool>& stop) {
        KeepAliveClient client(port_, 60s);
        const std::string target = std::string("/v1/clips/") + kHeavyClip + "/parts";
        while (!stop) {
          if (client.Send(http::verb::get, target, users_.owner_token, "") == 200) {
            ++calls;
          } else {
            ++failed;
          }
        }
      });
      std::this_thread::sleep_for(500ms);
      const long long calls0 = calls;
      const auto t0 = Clock::now();
      under = Normal();
      seconds = SecondsOf(Clock::now() - t0);
      calls -= calls0;
    }
    Settle();
    const double per_s = static_cast<double>(calls) / seconds;
    AddRow(report_, {"heavy: parts loop",
                     Fixed(per_s, 1) + " calls/s (" +
                         Fixed(per_s * kHeavyFrames * kHeavyFrameBytes / 1e6, 0) + " MB/s hashed)" +
                         (failed ? ", " + std::to_string(failed) + " failed" : ""),
                     under, base, "p99<20ms", under.p99_ms < 20.0});
  }

  void HeavyDownloads() {
    const NormalFigures base = Normal();
    std::atomic<long long> bytes{0}, failed{0};
    NormalFigures under;
    double seconds = 0;
    {
      BackgroundLoop heavy([&](const std::atomic<bool>& stop) {
        boost::asio::io_context ioc;
        std::optional<tcp::socket> socket;
        beast::flat_buffer buffer;
        const std::string target = std::string("/v1/clips/") + kHeavyClip + "/frames/3";
        while (!stop) {
          if (!socket) {
            socket.emplace(ioc);
            beast::error_code ec;
            socket->connect(tcp::endpoint(boost::asio::ip::make_address("127.0.0.1"), port_), ec);
            buffer.clear();
          }
          const long long got = DownloadOnce(*socket, buffer, target);
          if (got < 0) {
            ++failed;
            socket.reset();
            std::this_thread::sleep_for(10ms);
          } else {
            bytes += got;
          }
        }
      });
      std::this_thread::sleep_for(500ms);
      const long long bytes0 = bytes;
      const auto t0 = Clock::now();
      under = Normal();
      seconds = SecondsOf(Clock::now() - t0);
      bytes -= bytes0;
    }
    Settle();
    AddRow(report_, {"heavy: 8MiB downloads",
                     Fixed(static_cast<double>(bytes) / 1e6 / seconds, 0) + " MB/s downloaded" +
                         (failed ? ", " + std::to_string(failed) + " failed" : ""),
                     under, base, "p99<20ms", under.p99_ms < 20.0});
  }

  // 64 connections each GET an 8 MiB frame and never read it; the measurement starts with
  // them (their requests are handled at once, then they only hold memory).
  void StalledDownloads() {
    const NormalFigures base = Normal();
    FloodPlan plan;
    plan.connections = kBodyConnections;
    plan.from = Addresses(52, 4);
    plan.read = false;
    plan.head = std::string("GET /v1/clips/") + kHeavyClip +
                "/frames/5 HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n";
    Flood flood(port_, plan);
    const NormalFigures under = Normal([&] { return static_cast<double>(flood.open()); });
    flood.Stop();
    Settle();
    AddRow(report_, {"stalled 8MiB downloads x64",
                     "peak anon RSS " + Fixed(under.peak_anon_mb, 0) + " MB, " +
                         Fixed(under.gauge_mean, 0) + " held",
                     under, base, "none", std::nullopt});
  }

 private:
  const AttackBenchOptions& options_;
  const uint16_t port_;
  const AttackUsers users_;
  proto::Report& report_;
};

}  // namespace

Status RunAttackBench(const AttackBenchOptions& options, proto::Report& report) {
  if (!options.only.empty() && std::find(std::begin(kAttackGroups), std::end(kAttackGroups),
                                         options.only) == std::end(kAttackGroups)) {
    return MakeError("usage", "--only: unknown group '" + options.only +
                                  "'; groups: slow-headers, bodies, slow-body, heavy, stalled");
  }
  // Both ends of up to 2,000 attacker connections live in this process, beside the server's.
  if (Status s = server::RaiseOpenFileLimit(2 * 2000 + server::ServerOptions{}.max_connections);
      !s) {
    return s.error();
  }
  const std::string db_path = options.db_dir + "/attack-" + std::to_string(getpid()) + ".db";
  auto remove_db = [&] {
    for (const char* suffix : {"", "-wal", "-shm"}) std::filesystem::remove(db_path + suffix);
  };
  remove_db();
  const auto seed_start = Clock::now();
  if (Status s = Seed(db_path, options.clips); !s) return s;
  auto storage = server::OpenSqliteStorage(db_path);
  if (!storage) return storage.error();
  auto users = SeedAttackClips(*storage);
  if (!users) return users.error();
  std::cerr << "reenact-bench: seeded " << options.clips << " clips and the attack clips in "
            << Fixed(SecondsOf(Clock::now() - seed_start), 1) << " s" << std::endl;

  // The defaults, as deployed.
  Status served = WithServer(*storage, server::ServerOptions{}, [&](uint16_t port,
                                                                    const std::string&) -> Status {
    Scenarios scenarios(options, port, *users, report);
    auto runs = [&](const char* group) { return options.only.empty() || options.only == group; };
    if (runs("slow-headers")) {
      scenarios.SlowHeaders(1000, false);
      scenarios.SlowHeaders(2000, false);
      scenarios.SlowHeaders(2000, true);
    }
    if (runs("bodies")) {
      scenarios.Bodies("anonymous bodies x64", "", 40, true);
      scenarios.Bodies("wrong-owner bodies x64", users->other_token, 44, true);
      scenarios.Bodies("owner bodies x64 (bad hash)", users->owner_token, 48, false);
    }
    if (runs("slow-body")) scenarios.SlowBodyAndHeader();
    if (runs("heavy")) {
      scenarios.HeavyParts();
      scenarios.HeavyDownloads();
    }
    if (runs("stalled")) scenarios.StalledDownloads();
    return {};
  });
  if (!served) return served;
  storage->metadata.reset();
  storage->blobs.reset();
  remove_db();
  return {};
}

}  // namespace reenact::bench
