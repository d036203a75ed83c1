#pragma once
// Internal to the HTTP server: what every connection of one server shares. Owned by
// HttpServer::Impl, which outlives every connection and every queued handler.

#include <atomic>
#include <boost/asio/thread_pool.hpp>
#include <string>

#include "server/http/address_limiter.h"
#include "server/http/http_server.h"
#include "server/http/memory_budget.h"
#include "server/http/rate_limiter.h"
#include "server/http/service_context.h"

namespace reenact::server {

struct ServerCore {
  ServerCore(ServiceContext& context_in, const ServerOptions& options_in)
      : context(context_in),
        options(options_in),
        limiter(options.rate_limit),
        addresses(options.max_connections_per_address),
        body_memory(options.max_body_memory),
        handlers(static_cast<size_t>(options.ResolvedHandlerThreads())) {}

  ServiceContext& context;
  const ServerOptions options;
  RateLimiter limiter;
  AddressLimiter addresses;
  MemoryBudget body_memory;
  // Runs the route handlers and storage reads, off the network threads: a slow handler
  // never delays accepting, reading or writing other connections.
  boost::asio::thread_pool handlers;
  std::atomic<bool> stopping{false};
  std::atomic<int> live{0};    // connection objects alive, refused ones included
  std::atomic<int> served{0};  // connections being served, against max_connections
};

}  // namespace reenact::server
