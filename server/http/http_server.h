#pragma once
// The asynchronous HTTP/1.1 server (Boost.Beast, after its async server example): a listener
// and one session per connection, running Handle() (routes.h) for every request. Each thread
// runs its own event loop; connections are dealt to the loops in turn and stay on theirs. Bodies are limited per route (BodyLimit) before they are read; every read
// and write has a deadline. Stop() is graceful: no new connections, idle connections close,
// requests in flight finish and are answered, then Run() returns.
// Beyond max_connections, a new connection is answered 503 "unavailable" and closed. Requests
// carrying a bearer token spend that token's rate-limit credit (rate_limiter.h); without
// credit they are answered 429 "rate_limited" with Retry-After. Connections are kept alive
// between requests unless the client asks otherwise.

#include <chrono>
#include <cstdint>
#include <memory>
#include <string>

#include "common/error/expected.h"
#include "server/http/rate_limiter.h"
#include "server/http/service_context.h"

namespace reenact::server {

struct ServerOptions {
  // Address to bind: an IPv4/IPv6 literal or a host name. Default 127.0.0.1.
  std::string host = "127.0.0.1";
  // TCP port; 0 = let the system pick a free one (Listen() returns it). Default 8080.
  uint16_t port = 8080;
  // Threads, each running an event loop and its connections' handlers; >= 0, 0 = one per
  // hardware thread (at least 2, since handlers block on the database). Default 0.
  int threads = 0;
  // Connections served at once; >= 1. More are answered 503 and closed. Default 1024.
  int max_connections = 1024;
  // Per-token request rate limit; per_second 0 turns it off. Default 200/s, burst 400.
  RateLimitOptions rate_limit;
  // How long a connection may sit without a complete request header; > 0. Default 30 s.
  std::chrono::milliseconds idle_timeout{30'000};
  // Deadline to receive a request's body and to send its response; > 0. Default 120 s.
  std::chrono::milliseconds transfer_timeout{120'000};
  // After Stop(), how long in-flight requests may take before connections are cut; > 0.
  // Default 30 s.
  std::chrono::milliseconds drain_timeout{30'000};

  void Check() const;
  // threads with 0 resolved to the machine's hardware threads.
  int ResolvedThreads() const;
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
