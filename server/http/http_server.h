#pragma once
// The asynchronous HTTP/1.1 server (Boost.Beast, after its async server example): a listener,
// network threads that each run an event loop of connections (session.h), and a pool of
// handler threads that run the routes (routes.h) and read storage, so a slow handler never
// delays accepting, reading or answering other connections.
//
// Defences against hostile and heavy clients, each bounded by an option below:
//  - A request's header must arrive within idle_timeout, and once its first byte is in, at
//    min_transfer_rate; bodies and responses likewise keep min_transfer_rate (and never run
//    past transfer_timeout). A slow sender or reader is cut off within seconds.
//  - Who may send a body is decided from the header, before it is read (routes.h, Admit):
//    401/403/404/413/415/422 are answered and the connection closed without reading it.
//  - Bodies are read only into memory reserved from max_body_memory (503 with Retry-After
//    when it is full); downloads of stored payloads are streamed in 64 KiB pieces.
//  - One address holds at most max_connections_per_address connections (503 beyond). At
//    max_connections, a connection waiting for a request header is closed to make room: the
//    oldest of those part way through a header, else the longest idle, connections opened
//    in the last second last; only when every connection is busy with a request is a new one
//    answered 503.
//  - Malformed requests are answered 400 (431 for an oversized header, 505 for an HTTP
//    version other than 1.x) and closed (request_framing.h).
// Requests carrying a bearer token spend that token's rate-limit credit (rate_limiter.h);
// without credit they are answered 429 with Retry-After. Connections are kept alive between
// requests unless the client asks otherwise. Stop() is graceful: no new connections, idle
// connections close, requests in flight finish and are answered, then Run() returns.

#include <chrono>
#include <cstdint>
#include <memory>
#include <string>

#include "common/error/expected.h"
#include "server/http/rate_limiter.h"
#include "server/http/service_context.h"
#include "server/http/transfer_deadline.h"

namespace reenact::server {

struct ServerOptions {
  // Address to bind: an IPv4/IPv6 literal or a host name. Default 127.0.0.1.
  std::string host = "127.0.0.1";
  // TCP port; 0 = let the system pick a free one (Listen() returns it). Default 8080.
  uint16_t port = 8080;
  // Network threads, each running an event loop of connections; >= 0, 0 = one per hardware
  // thread (at least 2). Default 0.
  int threads = 0;
  // Threads running route handlers and storage reads; >= 0, 0 = twice the hardware threads,
  // at least 4 (handlers wait on the disk). Default 0.
  int handler_threads = 0;
  // Connections served at once; >= 1. At the cap, a connection waiting for a header is closed
  // for a new one (see above); when all are busy, new ones get 503. Default 1024.
  int max_connections = 1024;
  // Connections one client address may hold at once; >= 0, 0 = no limit (behind a proxy,
  // where every connection comes from the proxy's address). More get 503. Default 128.
  int max_connections_per_address = 128;
  // Memory all request bodies being received may hold together, bytes; at least the largest
  // route limit (ServiceLimits). A body that does not fit is refused 503. Default 256 MiB.
  size_t max_body_memory = size_t{256} << 20;
  // Per-token request rate limit; per_second 0 turns it off. Default 200/s, burst 400.
  RateLimitOptions rate_limit;
  // How long a connection may wait for (and deliver) a request header; > 0. Default 30 s.
  std::chrono::milliseconds idle_timeout{30'000};
  // Slowest average rate a header (from its first byte), a body or a response may move at
  // after a grace; slower connections are closed. Default 1 KiB/s after 5 s.
  MinRate min_transfer_rate{1024.0, std::chrono::milliseconds(5000)};
  // Longest a body or a response may take whatever its rate; > 0. Default 120 s.
  std::chrono::milliseconds transfer_timeout{120'000};
  // After Stop(), how long in-flight requests may take before connections are cut; > 0.
  // Default 30 s.
  std::chrono::milliseconds drain_timeout{30'000};

  void Check() const;
  // threads with 0 resolved to the machine's hardware threads.
  int ResolvedThreads() const;
  // handler_threads with 0 resolved.
  int ResolvedHandlerThreads() const;
};

// "HOST:PORT" or "[V6]:PORT" into host and port; code "invalid_argument" otherwise.
Expected<std::pair<std::string, uint16_t>> ParseListenAddress(const std::string& text);

class HttpServer {
 public:
  // context must outlive the server.
  HttpServer(ServiceContext& context, ServerOptions options);
  ~HttpServer();
  HttpServer(const HttpServer&) = delete;
  HttpServer& operator=(const HttpServer&) = delete;

  // Binds and listens; returns the bound port. code "address_in_use" when the port is
  // taken, "invalid_argument" for a host that does not resolve, "io" otherwise.
  Expected<uint16_t> Listen();

  // Serves until Stop() (or, with stop_on_signals, SIGINT/SIGTERM), then drains and returns.
  // Precondition: Listen() succeeded.
  void Run(bool stop_on_signals);

  // Begins a graceful stop; safe from any thread, idempotent.
  void Stop();

  class Impl;  // defined in http_server.cc

 private:
  std::shared_ptr<Impl> impl_;
};

}  // namespace reenact::server
