#pragma once
// The real reenact-server as a child process for the server's integration tests: started on
// an ephemeral loopback port, stopped with SIGTERM or killed with SIGKILL (crash tests), and
// helpers to talk to it (proto's HTTP client, raw sockets) and to check its database.

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cmath>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "proto/clip/manifest.h"
#include "server/storage/sqlite.h"
#include "tests/integration/process.h"

namespace reenact::testing {

class ServerProcess {
 public:
  ServerProcess() = default;
  ServerProcess(const ServerProcess&) = delete;
  ServerProcess& operator=(const ServerProcess&) = delete;
  ~ServerProcess() { Kill(SIGKILL); }

  // Starts `reenact-server serve --db DB --listen 127.0.0.1:0 EXTRA...`; the base URL, or
  // nullopt when it did not print its ready line within 20 s.
  std::optional<std::string> Start(const std::string& db,
                                   const std::vector<std::string>& extra = {}) {
    int fds[2];
    if (pipe(fds) != 0) return std::nullopt;
    std::vector<std::string> args = {kServer, "serve", "--db", db, "--listen", "127.0.0.1:0"};
    args.insert(args.end(), extra.begin(), extra.end());
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    pid_ = fork();
    if (pid_ == 0) {
      dup2(fds[1], 1);
      close(fds[0]);
      execv(argv[0], argv.data());
      _exit(127);
    }
    close(fds[1]);
    out_fd_ = fds[0];
    std::string text;
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    while (std::chrono::steady_clock::now() < until) {
      pollfd pfd{out_fd_, POLLIN, 0};
      if (poll(&pfd, 1, 50) <= 0) continue;
      char chunk[256];
      const ssize_t n = read(out_fd_, chunk, sizeof chunk);
      if (n <= 0) return std::nullopt;
      text.append(chunk, static_cast<size_t>(n));
      const size_t nl = text.find('\n');
      if (nl == std::string::npos) continue;
      const std::string line = text.substr(0, nl);
      const std::string prefix = "listening on ";
      if (line.rfind(prefix, 0) != 0) return std::nullopt;
      url_ = line.substr(prefix.size());
      port_ = std::stoi(url_.substr(url_.rfind(':') + 1));
      return url_;
    }
    return std::nullopt;
  }

  // Sends `signal` and reaps the process; returns its exit code (-1 when killed by a signal).
  int Kill(int signal) {
    if (pid_ <= 0) return -1;
    kill(pid_, signal);
    int status = 0;
    waitpid(pid_, &status, 0);
    pid_ = -1;
    close(out_fd_);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }

  const std::string& url() const { return url_; }
  int port() const { return port_; }
  int pid() const { return pid_; }

 private:
  int pid_ = -1;
  int out_fd_ = -1;
  std::string url_;
  int port_ = 0;
};

// A blocking loopback TCP connection for hand-written (malformed, slow, truncated) requests.
class RawSocket {
 public:
  // from: the local address to connect from (any of 127.0.0.0/8 reaches the server), so that
  // a test can play several client addresses.
  explicit RawSocket(int port, int receive_timeout_ms = 5000, const char* from = nullptr) {
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
    addr.sin_port = htons(static_cast<uint16_t>(port));
    connected_ = connect(fd_, reinterpret_cast<sockaddr*>(&addr), sizeof addr) == 0;
    timeval tv{receive_timeout_ms / 1000, (receive_timeout_ms % 1000) * 1000};
    setsockopt(fd_, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
    setsockopt(fd_, SOL_SOCKET, SO_SNDTIMEO, &tv, sizeof tv);
  }
  ~RawSocket() { Close(); }
  RawSocket(const RawSocket&) = delete;
  RawSocket& operator=(const RawSocket&) = delete;

  bool connected() const { return connected_; }
  // False once the peer has closed or reset the connection.
  bool Send(const std::string& bytes) {
    return send(fd_, bytes.data(), bytes.size(), MSG_NOSIGNAL) ==
           static_cast<ssize_t>(bytes.size());
  }
  // Everything until the peer closes or the receive timeout passes.
  std::string ReadAll() {
    std::string got;
    char buffer[4096];
    for (;;) {
      const ssize_t n = recv(fd_, buffer, sizeof buffer, 0);
      if (n <= 0) break;
      got.append(buffer, static_cast<size_t>(n));
    }
    return got;
  }
  // True if the peer closed the connection (read returned 0 or reset) within the timeout.
  bool PeerClosed() {
    char c;
    const ssize_t n = recv(fd_, &c, 1, 0);
    return n == 0 || (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK);
  }
  // Reads until `needle` appears, the peer closes, or the receive timeout passes.
  std::string ReadUntil(const std::string& needle) {
    std::string got;
    char buffer[4096];
    while (got.find(needle) == std::string::npos) {
      const ssize_t n = recv(fd_, buffer, sizeof buffer, 0);
      if (n <= 0) break;
      got.append(buffer, static_cast<size_t>(n));
    }
    return got;
  }
  void Close() {
    if (fd_ >= 0) close(fd_);
    fd_ = -1;
  }
  int fd() const { return fd_; }

 private:
  int fd_ = -1;
  bool connected_ = false;
};

// The resident memory of process `pid` in MiB (VmRSS of /proc/PID/status); -1 if unreadable.
inline double ResidentMiB(int pid) {
  FILE* file = std::fopen(("/proc/" + std::to_string(pid) + "/status").c_str(), "r");
  if (!file) return -1;
  char line[256];
  double kib = -1;
  while (std::fgets(line, sizeof line, file)) {
    if (std::sscanf(line, "VmRSS: %lf kB", &kib) == 1) break;
  }
  std::fclose(file);
  return kib < 0 ? -1 : kib / 1024.0;
}

// "ok" from PRAGMA integrity_check, or the first problem it reports.
inline std::string IntegrityCheck(const std::string& db_path) {
  auto db = server::sqlite::Database::Open(db_path);
  if (!db) return db.error().message;
  auto stmt = db->Prepare("PRAGMA integrity_check");
  if (!stmt) return stmt.error().message;
  auto row = stmt->Step();
  if (!row || !*row) return "integrity_check returned nothing";
  return stmt->ColumnText(0);
}

// Great-circle distance on the sphere of radius 6371008.8 m (the API's documented model),
// written out here independently of the server's implementation: haversine formula.
inline double ReferenceDistanceM(double lat1, double lon1, double lat2, double lon2) {
  constexpr double kR = 6371008.8, kRad = M_PI / 180.0;
  const double dlat = (lat2 - lat1) * kRad, dlon = (lon2 - lon1) * kRad;
  const double a =
      std::sin(dlat / 2) * std::sin(dlat / 2) +
      std::cos(lat1 * kRad) * std::cos(lat2 * kRad) * std::sin(dlon / 2) * std::sin(dlon / 2);
  return 2 * kR * std::asin(std::min(1.0, std::sqrt(a)));
}

// The bytes of a file ("" when it cannot be read).
inline std::string ReadFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

// Payload of part `index` (frame n, or proto::kMapPartIndex) of a clip recorded in `clip`.
inline std::string PartOnDisk(const std::string& clip, int index) {
  if (index == proto::kMapPartIndex) return ReadFile(clip + "/map.rmap");
  char name[32];
  std::snprintf(name, sizeof(name), "/frames/%06d.rfrm", index);
  return ReadFile(clip + name);
}

}  // namespace reenact::testing

#include <random>

#include "proto/api/api_client.h"
#include "proto/clip/content_hash.h"
#include "proto/clip/manifest.h"
#include "tests/unit/server/server_test_util.h"

namespace reenact::testing {

// Every part of clip `id` (`frames` frames and the map), downloaded anonymously from `url`,
// has the SHA-256 of the part recorded in `clip` (PartOnDisk).
inline void ExpectClipWholeOn(const std::string& url, const std::string& id,
                              const std::string& clip, int frames) {
  SCOPED_TRACE("downloaded from " + url);
  const proto::ApiClient anonymous(url, "");
  for (int n = 0; n < frames; ++n) {
    auto frame = anonymous.GetFrame(id, n);
    ASSERT_TRUE(frame.ok()) << "frame " << n << ": " << frame.error().message;
    EXPECT_EQ(proto::Sha256Hex(*frame), proto::Sha256Hex(PartOnDisk(clip, n))) << "frame " << n;
  }
  auto map = anonymous.GetMap(id);
  ASSERT_TRUE(map.ok()) << map.error().message;
  EXPECT_EQ(proto::Sha256Hex(*map), proto::Sha256Hex(PartOnDisk(clip, proto::kMapPartIndex)));
}

struct SyntheticClip {
  std::string manifest_json;
  std::vector<std::string> frames;
  std::string map;
  double lat = 0, lon = 0;
};

// A valid clip at (lat, lon) whose frames are `frame_bytes` pseudo-random bytes from `seed`.
inline SyntheticClip MakeSyntheticClip(double lat, double lon, int frames, size_t frame_bytes,
                                       uint32_t seed, const std::string& title) {
  std::mt19937 rng(seed);
  auto bytes = [&](size_t n) {
    std::string s(n, '\0');
    for (char& c : s) c = static_cast<char>(rng() & 0xff);
    return s;
  };
  SyntheticClip clip;
  clip.lat = lat;
  clip.lon = lon;
  for (int i = 0; i < frames; ++i)
    clip.frames.push_back(bytes(frame_bytes + static_cast<size_t>(i)));
  clip.map = bytes(frame_bytes / 2 + 7);
  clip.manifest_json =
      server::testing::TestManifestJson(lat, lon, title, "load", clip.frames, clip.map);
  return clip;
}

}  // namespace reenact::testing
