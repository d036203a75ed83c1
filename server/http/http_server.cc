#include "server/http/http_server.h"

#include <algorithm>
#include <atomic>
#include <boost/asio/dispatch.hpp>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/signal_set.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/asio/strand.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <charconv>
#include <cmath>
#include <csignal>
#include <limits>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "server/auth/token.h"
#include "server/http/routes.h"

namespace reenact::server {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
using tcp = asio::ip::tcp;

class Session;

class HttpServer::Impl : public std::enable_shared_from_this<HttpServer::Impl> {
 public:
  Impl(ServiceContext& context_in, ServerOptions options_in)
      : context(context_in),
        options(std::move(options_in)),
        limiter(options.rate_limit),
        loops(MakeLoops(options.ResolvedThreads())),
        control(asio::make_strand(*loops.front())),
        acceptor(control),
        signals(control),
        drain_timer(control) {}

  Expected<uint16_t> Listen();
  void Run(bool stop_on_signals);
  void Stop();

  ServiceContext& context;
  const ServerOptions options;
  std::atomic<bool> stopping{false};
  RateLimiter limiter;
  std::shared_ptr<std::atomic<int>> live = std::make_shared<std::atomic<int>>(0);
  // Sessions being served (refused ones not counted), against max_connections.
  std::shared_ptr<std::atomic<int>> served = std::make_shared<std::atomic<int>>(0);

 private:
  static std::vector<std::unique_ptr<asio::io_context>> MakeLoops(int count);
  void DoAccept();
  void OnAccept(beast::error_code ec, tcp::socket socket);
  void PollDrain();
  void StopLoops();

  // One event loop per thread (concurrency hint 1): a connection lives on one loop, so its
  // handlers need no strand and no thread hands a ready socket to another: a third more
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

// One connection: read header, check the body limit, read body, handle, write, repeat.
class Session : public std::enable_shared_from_this<Session> {
 public:
  static constexpr size_t kReadChunkBytes = 64 * 1024;
  static constexpr size_t kSmallBodyBytes = 8 * 1024;

  // refuse: answer 503 at once and close (the server is at max_connections).
  Session(tcp::socket&& socket, HttpServer::Impl& server, bool refuse)
      : stream_(std::move(socket)),
        server_(server),
        live_(server.live),
        served_(refuse ? nullptr : server.served) {
    ++*live_;
    if (served_) ++*served_;
  }
  ~Session() {
    if (served_) --*served_;
    --*live_;
  }

  void Start() {
    if (!served_) {
      asio::dispatch(stream_.get_executor(), [self = shared_from_this()] {
        self->route_ = "refused";
        self->started_ = std::chrono::steady_clock::now();
        self->drain_after_reply_ = true;
        self->Reply(ErrorResponse(503, "unavailable",
                                  "the server is at its connection limit; retry shortly"),
                    false);
      });
      return;
    }
    asio::dispatch(stream_.get_executor(),
                   beast::bind_front_handler(&Session::ReadHeader, shared_from_this()));
  }

  // Closes the connection now if it is between requests; otherwise after the response.
  void Shutdown() {
    asio::dispatch(stream_.get_executor(), [self = shared_from_this()] {
      if (!self->busy_) self->Close();
    });
  }

 private:
  void ReadHeader() {
    busy_ = false;
    if (server_.stopping) return Close();
    parser_.emplace();
    parser_->header_limit(16 * 1024);
    // The route's limit is applied once the header names the route (OnHeader).
    parser_->body_limit(std::numeric_limits<std::uint64_t>::max());
    stream_.expires_after(server_.options.idle_timeout);
    http::async_read_header(stream_, buffer_, *parser_,
                            beast::bind_front_handler(&Session::OnHeader, shared_from_this()));
  }

  void OnHeader(beast::error_code ec, size_t) {
    if (ec) return Close();
    busy_ = true;
    started_ = std::chrono::steady_clock::now();
    bytes_in_ = 0;
    const auto& header = parser_->get();
    const std::string method(header.method_string());
    const std::string target(header.target());
    route_ = RouteLabel(method, target);
    body_limit_ = BodyLimit(method, target, server_.context.limits);
    refusal_.reset();
    const auto authorization = header[http::field::authorization];
    if (auto token = ParseBearer(std::string_view(authorization.data(), authorization.size()))) {
      const RateDecision decision = server_.limiter.Acquire(HashToken(*token));
      if (!decision.allowed) refusal_ = TooManyRequests(decision.retry_after_s);
    }
    if (auto length = parser_->content_length(); length && *length > body_limit_) {
      drain_after_reply_ = true;
      return Reply(TooLarge(body_limit_), /*keep_alive=*/false);
    }
    parser_->body_limit(body_limit_);
    // Beast reads max(512, free buffer capacity) bytes at a time, at most 64 KiB: without
    // room, a 1 MiB body takes some two thousand 512-byte reads, each a syscall and a timer.
    // Idle connections keep the small buffer (OnBody gives the room back).
    if (parser_->content_length().value_or(0) > kSmallBodyBytes) buffer_.reserve(kReadChunkBytes);
    if (beast::iequals(header[http::field::expect], "100-continue")) {
      auto cont = std::make_shared<http::response<http::empty_body>>(http::status::continue_, 11);
      stream_.expires_after(server_.options.transfer_timeout);
      http::async_write(stream_, *cont,
                        [self = shared_from_this(), cont](beast::error_code ec2, size_t) {
                          if (ec2) return self->Close();
                          self->ReadBody();
                        });
      return;
    }
    ReadBody();
  }

  void ReadBody() {
    stream_.expires_after(server_.options.transfer_timeout);
    http::async_read(stream_, buffer_, *parser_,
                     beast::bind_front_handler(&Session::OnBody, shared_from_this()));
  }

  void OnBody(beast::error_code ec, size_t) {
    if (ec == http::error::body_limit) {
      drain_after_reply_ = true;
      return Reply(TooLarge(body_limit_), false);
    }
    if (ec) return Close();
    if (buffer_.capacity() > kReadChunkBytes / 2) buffer_.shrink_to_fit();
    http::request<http::string_body> message = parser_->release();
    Request request;
    request.method = std::string(message.method_string());
    request.target = std::string(message.target());
    for (const auto& field : message) {
      request.headers.emplace_back(std::string(field.name_string()), std::string(field.value()));
    }
    request.body = std::move(message.body());
    bytes_in_ = request.body.size();
    if (refusal_) return Reply(std::move(*refusal_), message.keep_alive());
    Reply(Handle(request, server_.context), message.keep_alive());
  }

  static Response TooLarge(size_t limit) {
    return ErrorResponse(
        413, "too_large",
        "request body exceeds this route's limit of " + std::to_string(limit) + " bytes");
  }

  static Response TooManyRequests(double retry_after_s) {
    const long long seconds = std::max(1LL, static_cast<long long>(std::ceil(retry_after_s)));
    Response response = ErrorResponse(
        429, "rate_limited",
        "too many requests with this token; retry in " + std::to_string(seconds) + " s");
    response.headers.emplace_back("Retry-After", std::to_string(seconds));
    return response;
  }

  void Reply(Response response, bool keep_alive) {
    status_ = response.status;
    response_ = std::make_shared<http::response<http::string_body>>(
        static_cast<http::status>(response.status), 11);
    response_->set(http::field::server, "reenact-server");
    if (!response.content_type.empty()) {
      response_->set(http::field::content_type, response.content_type);
    }
    for (const auto& [name, value] : response.headers) response_->set(name, value);
    response_->body() = std::move(response.body);
    response_->keep_alive(keep_alive && !server_.stopping);
    response_->prepare_payload();
    stream_.expires_after(server_.options.transfer_timeout);
    http::async_write(stream_, *response_,
                      beast::bind_front_handler(&Session::OnWrite, shared_from_this()));
  }

  void OnWrite(beast::error_code ec, size_t) {
    if (ec == http::error::end_of_stream) ec = {};  // a Connection: close reply went out whole
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
    server_.context.metrics.Record(route_, status_, seconds, bytes_in_, response_->body().size());
    const bool close = response_->need_eof();
    response_.reset();
    if (!served_) {
      max_drain_bytes_ = 64 * 1024;  // a refused connection gets little patience
    }
    if (!ec && drain_after_reply_) return Drain();
    if (ec || close) return Close();
    ReadHeader();
  }

  // After refusing a body unread: stop sending, then read and discard what the client still
  // sends (up to kMaxDrainBytes, under a short deadline) so that it gets to read our answer
  // instead of a connection reset.
  void Drain() {
    if (drained_ == 0) {
      beast::error_code ignored;
      stream_.socket().shutdown(tcp::socket::shutdown_send, ignored);
    }
    if (drained_ > max_drain_bytes_) return Close();
    stream_.expires_after(std::chrono::seconds(5));
    drain_buffer_.resize(64 * 1024);
    stream_.async_read_some(asio::buffer(drain_buffer_),
                            [self = shared_from_this()](beast::error_code ec, size_t n) {
                              if (ec) return self->Close();
                              self->drained_ += n + 1;
                              self->Drain();
                            });
  }

  void Close() {
    busy_ = false;
    beast::error_code ignored;
    stream_.socket().shutdown(tcp::socket::shutdown_send, ignored);
    stream_.socket().close(ignored);
  }

  beast::tcp_stream stream_;
  HttpServer::Impl& server_;
  std::shared_ptr<std::atomic<int>> live_;
  std::shared_ptr<std::atomic<int>> served_;  // null for a refused connection
  beast::flat_buffer buffer_;
  std::optional<http::request_parser<http::string_body>> parser_;
  std::shared_ptr<http::response<http::string_body>> response_;
  bool busy_ = false;
  std::string route_;
  int status_ = 0;
  size_t bytes_in_ = 0;
  size_t body_limit_ = 0;
  bool drain_after_reply_ = false;
  std::optional<Response> refusal_;  // 429 decided at the header, sent after the body
  size_t max_drain_bytes_ = size_t{256} << 20;
  size_t drained_ = 0;
  std::vector<char> drain_buffer_;
  std::chrono::steady_clock::time_point started_;
};

Expected<uint16_t> HttpServer::Impl::Listen() {
  beast::error_code ec;
  tcp::resolver resolver(*loops.front());
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
    if (self->stopping) return;
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
    if (self->stopping.exchange(true)) return;
    beast::error_code ignored;
    self->acceptor.close(ignored);
    self->signals.cancel(ignored);
    for (auto& weak : self->sessions) {
      if (auto session = weak.lock()) session->Shutdown();
    }
    self->sessions.clear();
    self->drain_deadline = std::chrono::steady_clock::now() + self->options.drain_timeout;
    self->PollDrain();
  });
}

void HttpServer::Impl::PollDrain() {
  if (*live == 0) {  // nothing left: the loops run out of work and Run() returns
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
  if (stopping || ec == asio::error::operation_aborted) return;
  if (!ec) {
    const bool refuse = *served >= options.max_connections;
    auto session = std::make_shared<Session>(std::move(socket), *this, refuse);
    std::erase_if(sessions, [](const std::weak_ptr<Session>& s) { return s.expired(); });
    sessions.push_back(session);
    session->Start();
  }
  DoAccept();
}

void ServerOptions::Check() const {
  REENACT_CHECK(!host.empty(), "host must not be empty");
  REENACT_CHECK(threads >= 0, "threads must be >= 0");
  REENACT_CHECK(max_connections >= 1, "max_connections must be >= 1");
  rate_limit.Check();
  REENACT_CHECK(idle_timeout.count() > 0, "idle_timeout must be > 0");
  REENACT_CHECK(transfer_timeout.count() > 0, "transfer_timeout must be > 0");
  REENACT_CHECK(drain_timeout.count() > 0, "drain_timeout must be > 0");
}

int ServerOptions::ResolvedThreads() const {
  if (threads > 0) return threads;
  return std::max(2, static_cast<int>(std::thread::hardware_concurrency()));
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
  impl_ = std::make_shared<Impl>(context, std::move(options));
}

HttpServer::~HttpServer() = default;

Expected<uint16_t> HttpServer::Listen() { return impl_->Listen(); }

void HttpServer::Run(bool stop_on_signals) { impl_->Run(stop_on_signals); }

void HttpServer::Stop() { impl_->Stop(); }

}  // namespace reenact::server
