#pragma once
// Shared pieces of `reenact-bench server` (server_bench.cc) and its adversarial section
// (server_attack_bench.cc): the seeded database, nearby query targets, a keep-alive HTTP
// client with a deadline, percentiles, a valid manifest and a server on loopback.

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "common/error/expected.h"
#include "proto/clip/manifest.h"
#include "server/http/http_server.h"
#include "server/storage/open_storage.h"

namespace reenact::bench {

// The box the seeded clips lie in (southern Europe) and the nearby query the clients send.
inline constexpr double kMinLat = 35, kMaxLat = 45, kMinLon = -5, kMaxLon = 15;
inline constexpr double kQueryRadiusM = 2500;
inline constexpr int kQueryLimit = 20;

// Seeds `count` published clips' metadata at uniformly random places in the box, owned by
// one user named "seed", in one transaction. Their ids are "seed" + 20 digits.
Status Seed(const std::string& db_path, long long count);

// The same on the PostgreSQL database at `url` (applying the migrations): replaces the clips
// of the "seed" user by `count` new ones in one statement, at places drawn by PostgreSQL's own
// seeded random() (the same distribution as Seed, not the same places). Other users' clips stay.
Status SeedPostgres(const std::string& url, long long count);

// The number of published clips of the "seed" user in the database `db` (a SQLite file or a
// PostgreSQL URL), or -1 when there is no usable one (absent, another schema, unreadable).
long long SeededClips(const std::string& db);

// The sample at fraction p (0..1) of the sorted samples; 0 for none.
double Percentile(std::vector<double> v, double p);

// GET /v1/clips?near=... at a random place inside the box.
std::string NearbyTarget(std::mt19937_64& rng);

// A valid manifest (ParseManifest accepts it) at (lat_deg, lon_deg) whose parts are `frames`
// and `map`.
std::string BenchManifest(const std::string& title, const std::vector<proto::PartInfo>& frames,
                          const proto::PartInfo& map, double lat_deg = 40, double lon_deg = 5);

// Runs `body(port, url)` against an HttpServer with `options` (its port replaced by a free
// one) listening on loopback over `storage`; stops the server after and returns body's status.
Status WithServer(server::Storage& storage, server::ServerOptions options,
                  const std::function<Status(uint16_t, const std::string&)>& body);

// One keep-alive HTTP/1.1 connection to 127.0.0.1:port (the project's HttpClient opens one
// per request, which would measure connection setup rather than the server). It connects on
// the first request and again after a failure; each request, its connection included, must
// be done within `timeout` (0: no deadline, blocking calls, which cost the least).
class KeepAliveClient {
 public:
  explicit KeepAliveClient(uint16_t port,
                           std::chrono::milliseconds timeout = std::chrono::milliseconds(0));
  // The status, or -1 on a transport error or when the deadline passed. `hits`: the number
  // of "id" keys in the response body.
  int Send(boost::beast::http::verb verb, const std::string& target, const std::string& token,
           const std::string& body, size_t* hits = nullptr);

 private:
  bool Connect();
  // Runs the queued operations to their end.
  void RunAll();

  uint16_t port_;
  std::chrono::milliseconds timeout_;
  boost::asio::io_context ioc_;
  std::optional<boost::beast::tcp_stream> stream_;
  boost::beast::flat_buffer buffer_;
};

}  // namespace reenact::bench
