#include "server/http/http_server.h"

#include <algorithm>
#include <boost/asio/dispatch.hpp>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/signal_set.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/asio/strand.hpp>
#include <boost/beast/core.hpp>
#include <charconv>
#include <csignal>
#include <optional>
#include <thread>
#include <vector>

#include "server/http/server_core.h"
#include "server/http/session.h"

namespace reenact::server {

namespace asio = boost::asio;
namespace beast = boost::beast;
using tcp = asio::ip::tcp;

// How long a connection waiting for its first request counts as just opened (evicted last).
constexpr auto kFreshConnection = std::chrono::seconds(1);

class HttpServer::Impl : public std::enable_shared_from_this<HttpServer::Impl> {
 public:
  Impl(ServiceContext& context, const ServerOptions& options)
      : core(context, options),
        loops(MakeLoops(options.ResolvedThreads())),
        control(asio::make_strand(*loops.front())),
        acceptor(control),
        signals(control),
        drain_timer(control) {}

  Expected<uint16_t> Listen();
  void Run(bool stop_on_signals);
  void Stop();

  // Declared first, destroyed last: connections and queued handlers refer to it.
  ServerCore core;

 private:
  static std::vector<std::unique_ptr<asio::io_context>> MakeLoops(int count);
  void DoAccept();
  void OnAccept(beast::error_code ec, tcp::socket socket);
  std::optional<Response> Admission(const std::string& address);
  bool EvictOne();
  void PollDrain();
  void StopLoops();

  // One event loop per thread (concurrency hint 1): a connection lives on one loop, so its
  // steps need no strand and no thread hands a ready socket to another: a third more
  // nearby queries per second on 2 cores (docs/decisions.md, Server throughput).
  std::vector<std::unique_ptr<asio::io_context>> loops;
  // Keeps loops 1..n-1 running while they have no connection; released once drained.
  std::vector<asio::executor_work_guard<asio::io_context::executor_type>> idle_guards;
  size_t next_loop = 0;                                   // round robin, on control
  asio::strand<asio::io_context::executor_type> control;  // acceptor, signals, timer, list
  tcp::acceptor acceptor;
  asio::signal_set signals;
  asio::steady_timer drain_timer;
  std::chrono::steady_clock::time_point drain_deadline;
  std::vector<std::weak_ptr<Session>> sessions;
};

Expected<uint16_t> HttpServer::Impl::Listen() {
  beast::error_code ec;
  tcp::resolver resolver(*loops.front());
  const ServerOptions& options = core.options;
  auto results = resolver.resolve(options.host, std::to_string(options.port),
                                  tcp::resolver::passive | tcp::resolver::numeric_service, ec);
  const std::string where = options.host + ":" + std::to_string(options.port);
  if (ec || results.empty()) {
    return MakeError("invalid_argument", "cannot listen on " + where + ": unknown host");
  }
  const tcp::endpoint endpoint = results.begin()->endpoint();
  acceptor.open(endpoint.protocol(), ec);
  if (!ec) acceptor.set_option(asio::socket_base::reuse_address(true), ec);
  if (!ec) acceptor.bind(endpoint, ec);
  if (ec == asio::error::address_in_use) {
    return MakeError("address_in_use", "cannot listen on " + where +
                                           ": address already in use (is another server "
                                           "running? pick another port or use port 0)");
  }
  if (!ec) acceptor.listen(asio::socket_base::max_listen_connections, ec);
  if (ec) return MakeError("io", "cannot listen on " + where + ": " + ec.message());
  return acceptor.local_endpoint().port();
}

void HttpServer::Impl::Run(bool stop_on_signals) {
  REENACT_CHECK(acceptor.is_open(), "Run() before a successful Listen()");
  asio::dispatch(control, [self = shared_from_this(), stop_on_signals] {
    if (self->core.stopping) return;
    if (stop_on_signals) {
      self->signals.add(SIGINT);
      self->signals.add(SIGTERM);
      self->signals.async_wait([self](beast::error_code ec, int) {
        if (!ec) self->Stop();
      });
    }
    self->DoAccept();
  });
  for (size_t i = 1; i < loops.size(); ++i) idle_guards.push_back(asio::make_work_guard(*loops[i]));
  std::vector<std::thread> threads;
  for (size_t i = 1; i < loops.size(); ++i) threads.emplace_back([this, i] { loops[i]->run(); });
  loops.front()->run();
  for (auto& thread : threads) thread.join();
  core.handlers.join();
}

std::vector<std::unique_ptr<asio::io_context>> HttpServer::Impl::MakeLoops(int count) {
  std::vector<std::unique_ptr<asio::io_context>> loops;
  for (int i = 0; i < count; ++i) loops.push_back(std::make_unique<asio::io_context>(1));
  return loops;
}

void HttpServer::Impl::StopLoops() {
  for (auto& loop : loops) loop->stop();
}

void HttpServer::Impl::Stop() {
  asio::post(control, [self = shared_from_this()] {
    if (self->core.stopping.exchange(true)) return;
    beast::error_code ignored;
    self->acceptor.close(ignored);
    self->signals.cancel(ignored);
    for (auto& weak : self->sessions) {
      if (auto session = weak.lock()) session->Shutdown();
    }
    self->sessions.clear();
    self->drain_deadline = std::chrono::steady_clock::now() + self->core.options.drain_timeout;
    self->PollDrain();
  });
}

void HttpServer::Impl::PollDrain() {
  if (core.live == 0) {  // nothing left: the loops run out of work and Run() returns
    idle_guards.clear();
    return;
  }
  if (std::chrono::steady_clock::now() >= drain_deadline) {
    StopLoops();
    return;
  }
  drain_timer.expires_after(std::chrono::milliseconds(20));
  drain_timer.async_wait([self = shared_from_this()](beast::error_code) { self->PollDrain(); });
}

void HttpServer::Impl::DoAccept() {
  asio::io_context& loop = *loops[next_loop];
  next_loop = (next_loop + 1) % loops.size();
  acceptor.async_accept(loop.get_executor(),
                        beast::bind_front_handler(&Impl::OnAccept, shared_from_this()));
}

void HttpServer::Impl::OnAccept(beast::error_code ec, tcp::socket socket) {
  if (core.stopping || ec == asio::error::operation_aborted) return;
  if (!ec) {
    beast::error_code peer_ec;
    const tcp::endpoint peer = socket.remote_endpoint(peer_ec);
    const std::string address = peer_ec ? std::string() : peer.address().to_string();
    std::optional<Response> refusal = Admission(address);
    auto session = std::make_shared<Session>(std::move(socket), core, address, std::move(refusal));
    std::erase_if(sessions, [](const std::weak_ptr<Session>& s) { return s.expired(); });
    sessions.push_back(session);
    session->Start();
  }
  DoAccept();
}

std::optional<Response> HttpServer::Impl::Admission(const std::string& address) {
  if (!core.addresses.Acquire(address)) {
    return ErrorResponse(503, "unavailable",
                         "this address holds " +
                             std::to_string(core.options.max_connections_per_address) +
                             " connections, the most one address may; close some or retry");
  }
  if (core.served < core.options.max_connections || EvictOne()) return std::nullopt;
  core.addresses.Release(address);
  return ErrorResponse(503, "unavailable",
                       "the server is at its connection limit; retry shortly");
}

bool HttpServer::Impl::EvictOne() {
  // A connection part way through a header is the likelier slow sender (honest clients send
  // a header in one piece), so those go first; then connections idle for over a second; last
  // the ones just opened, whose first request may be on its way. Oldest first in each.
  const int64_t fresh_since =
      (std::chrono::steady_clock::now() - kFreshConnection).time_since_epoch().count();
  auto rank = [fresh_since](const Session& session) {
    const int64_t since = session.phase_since();
    const int group = session.phase() == Session::Phase::kHeader ? 0
                      : since < fresh_since                     ? 1
                                                                : 2;
    return std::make_pair(group, since);
  };
  std::shared_ptr<Session> chosen;
  for (const auto& weak : sessions) {
    auto session = weak.lock();
    if (!session || !session->Evictable()) continue;
    if (!chosen || rank(*session) < rank(*chosen)) chosen = std::move(session);
  }
  return chosen && chosen->Evict();
}

void ServerOptions::Check() const {
  REENACT_CHECK(!host.empty(), "host must not be empty");
  REENACT_CHECK(threads >= 0, "threads must be >= 0");
  REENACT_CHECK(handler_threads >= 0, "handler_threads must be >= 0");
  REENACT_CHECK(max_connections >= 1, "max_connections must be >= 1");
  REENACT_CHECK(max_connections_per_address >= 0, "max_connections_per_address must be >= 0");
  REENACT_CHECK(max_body_memory > 0, "max_body_memory must be > 0");
  REENACT_CHECK(min_transfer_rate.bytes_per_s >= 0 && min_transfer_rate.grace.count() >= 0,
                "min_transfer_rate needs bytes_per_s >= 0 and grace >= 0");
  rate_limit.Check();
  REENACT_CHECK(idle_timeout.count() > 0, "idle_timeout must be > 0");
  REENACT_CHECK(transfer_timeout.count() > 0, "transfer_timeout must be > 0");
  REENACT_CHECK(drain_timeout.count() > 0, "drain_timeout must be > 0");
}

int ServerOptions::ResolvedThreads() const {
  if (threads > 0) return threads;
  return std::max(2, static_cast<int>(std::thread::hardware_concurrency()));
}

int ServerOptions::ResolvedHandlerThreads() const {
  if (handler_threads > 0) return handler_threads;
  return std::max(4, 2 * static_cast<int>(std::thread::hardware_concurrency()));
}

Expected<std::pair<std::string, uint16_t>> ParseListenAddress(const std::string& text) {
  const Error bad = MakeError("invalid_argument",
                              "--listen wants HOST:PORT (e.g. 127.0.0.1:8080, "
                              "port 0 = any free port), got '" +
                                  text + "'");
  const size_t colon = text.rfind(':');
  if (colon == std::string::npos || colon == 0 || colon + 1 == text.size()) return bad;
  std::string host = text.substr(0, colon);
  if (host.front() == '[') {
    if (host.back() != ']' || host.size() < 3) return bad;
    host = host.substr(1, host.size() - 2);
  } else if (host.find(':') != std::string::npos) {
    return bad;
  }
  unsigned port = 0;
  const char* first = text.data() + colon + 1;
  const char* last = text.data() + text.size();
  auto [end, ec] = std::from_chars(first, last, port);
  if (ec != std::errc() || end != last || port > 65535) return bad;
  return std::make_pair(host, static_cast<uint16_t>(port));
}

HttpServer::HttpServer(ServiceContext& context, ServerOptions options) {
  options.Check();
  context.limits.Check();
  const size_t largest_body = std::max(
      {context.limits.max_manifest_bytes, context.limits.max_frame_bytes, context.limits.max_map_bytes});
  REENACT_CHECK(options.max_body_memory >= largest_body,
                "max_body_memory must hold the largest body a route accepts (" +
                    std::to_string(largest_body) + " bytes)");
  impl_ = std::make_shared<Impl>(context, std::move(options));
}

HttpServer::~HttpServer() = default;

Expected<uint16_t> HttpServer::Listen() { return impl_->Listen(); }

void HttpServer::Run(bool stop_on_signals) { impl_->Run(stop_on_signals); }

void HttpServer::Stop() { impl_->Stop(); }

}  // namespace reenact::server
