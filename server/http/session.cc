#include "server/http/session.h"

#include <algorithm>
#include <array>
#include <boost/asio/dispatch.hpp>
#include <boost/asio/post.hpp>
#include <cmath>
#include <iostream>
#include <limits>

#include "server/auth/token.h"
#include "server/http/request_framing.h"
#include "server/http/routes.h"
#include "server/storage/blob_store.h"

namespace reenact::server {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
using Clock = std::chrono::steady_clock;

namespace {

constexpr size_t kHeaderLimitBytes = 16 * 1024;
// Reads while waiting for a header are small, so that thousands of idle connections hold
// little memory; body reads take up to 64 KiB at a time.
constexpr size_t kHeaderReadBytes = 4 * 1024;
constexpr size_t kBodyReadBytes = 64 * 1024;
constexpr size_t kPieceBytes = 64 * 1024;
// A refused request's unread body is read and discarded up to this much, for this long, so
// that the client reads the answer rather than a reset; then the connection closes.
constexpr size_t kDrainBytes = 1024 * 1024;
constexpr size_t kRefusedConnectionDrainBytes = 64 * 1024;
constexpr auto kDrainTime = std::chrono::seconds(2);

Response TooLarge(size_t limit) {
  return ErrorResponse(
      413, "too_large",
      "request body exceeds this route's limit of " + std::to_string(limit) + " bytes");
}

Response TooManyRequests(double retry_after_s) {
  const long long seconds = std::max(1LL, static_cast<long long>(std::ceil(retry_after_s)));
  Response response = ErrorResponse(
      429, "rate_limited",
      "too many requests with this token; retry in " + std::to_string(seconds) + " s");
  response.headers.emplace_back("Retry-After", std::to_string(seconds));
  return response;
}

Response BodyMemoryExhausted() {
  Response response = ErrorResponse(
      503, "unavailable",
      "the server is receiving as many uploads as its memory allows; retry in a second");
  response.headers.emplace_back("Retry-After", "1");
  return response;
}

template <class Message>
void Dress(Message& message, const Response& response, bool keep_alive) {
  message.set(http::field::server, "reenact-server");
  if (!response.content_type.empty()) message.set(http::field::content_type, response.content_type);
  for (const auto& [name, value] : response.headers) message.set(name, value);
  message.keep_alive(keep_alive);
}

Request HeadOf(const http::request_header<>& header) {
  Request head;
  head.method = std::string(header.method_string());
  head.target = std::string(header.target());
  for (const auto& field : header) {
    head.headers.emplace_back(std::string(field.name_string()), std::string(field.value()));
  }
  return head;
}

}  // namespace

Session::Session(asio::ip::tcp::socket&& socket, ServerCore& core, std::string address,
                 std::optional<Response> refusal)
    : stream_(std::move(socket)),
      core_(core),
      address_(std::move(address)),
      counted_(!refusal),
      initial_refusal_(std::move(refusal)) {
  ++core_.live;
  if (counted_) ++core_.served;
  SetPhase(Phase::kIdle);
}

Session::~Session() {
  if (counted_) {
    --core_.served;
    core_.addresses.Release(address_);
  }
  --core_.live;
}

void Session::SetPhase(Phase phase) {
  phase_ = phase;
  phase_since_ = Clock::now().time_since_epoch().count();
}

void Session::Start() {
  asio::dispatch(stream_.get_executor(), [self = shared_from_this()] {
    if (!self->initial_refusal_) return self->NextRequest();
    self->SetPhase(Phase::kBusy);
    self->route_ = "refused";
    self->started_ = Clock::now();
    self->Refuse(std::move(*self->initial_refusal_));
    self->drain_budget_ = kRefusedConnectionDrainBytes;
  });
}

void Session::Shutdown() {
  asio::dispatch(stream_.get_executor(), [self = shared_from_this()] {
    if (self->phase_ != Phase::kBusy) self->Close();
  });
}

bool Session::Evict() {
  bool expected = false;
  if (phase_ == Phase::kBusy || !evicting_.compare_exchange_strong(expected, true)) return false;
  asio::dispatch(stream_.get_executor(), [self = shared_from_this()] {
    // A request that arrived but is not read yet (the loop is behind) keeps its connection.
    beast::error_code ec;
    const bool request_waiting = self->stream_.socket().available(ec) > 0 && !ec;
    if (self->phase_ != Phase::kBusy && !request_waiting) return self->Close();
    self->evicting_ = false;  // it began a request meanwhile: it stays
  });
  return true;
}

void Session::NextRequest() {
  SetPhase(Phase::kIdle);
  if (core_.stopping) return Close();
  parser_.emplace();
  parser_->header_limit(kHeaderLimitBytes);
  parser_->body_limit(std::numeric_limits<std::uint64_t>::max());  // set per route (OnHeader)
  header_seen_ = false;
  reading_body_ = false;
  transferred_ = 0;
  route_.clear();
  request_wait_start_ = Clock::now();
  if (buffer_.size() == 0 && buffer_.capacity() > kHeaderReadBytes) buffer_.shrink_to_fit();
  if (buffer_.size() > 0) {  // a pipelined request is already here
    header_seen_ = true;
    transfer_start_ = started_ = request_wait_start_;
    SetPhase(Phase::kHeader);
    return Parse();
  }
  ReadSome();
}

SteadyTime Session::ReadDeadline() const {
  const ServerOptions& o = core_.options;
  const SteadyTime cap = request_wait_start_ + o.idle_timeout;
  if (!header_seen_) return cap;
  const SteadyTime rate =
      TransferDeadline(transfer_start_, transferred_, o.min_transfer_rate, o.transfer_timeout);
  return reading_body_ ? rate : std::min(cap, rate);
}

SteadyTime Session::WriteDeadline(uint64_t bytes_after_this_write) const {
  return TransferDeadline(transfer_start_, bytes_after_this_write,
                          core_.options.min_transfer_rate, core_.options.transfer_timeout);
}

void Session::ReadSome() {
  stream_.expires_at(ReadDeadline());
  const size_t want = reading_body_ ? kBodyReadBytes : kHeaderReadBytes;
  stream_.async_read_some(buffer_.prepare(want),
                          [self = shared_from_this()](beast::error_code ec, size_t bytes) {
                            self->OnRead(ec, bytes);
                          });
}

void Session::OnRead(beast::error_code ec, size_t bytes) {
  if (ec) return Close();  // the peer left, or fell behind its deadline
  buffer_.commit(bytes);
  transferred_ += bytes;
  if (!header_seen_) {
    header_seen_ = true;
    transfer_start_ = started_ = Clock::now();
    transferred_ = bytes;
    SetPhase(Phase::kHeader);
  }
  Parse();
}

void Session::Parse() {
  while (buffer_.size() > 0 && !parser_->is_done()) {
    beast::error_code ec;
    const size_t used = parser_->put(buffer_.data(), ec);
    buffer_.consume(used);
    if (ec == http::error::need_more) break;
    if (ec == http::error::body_limit) return Refuse(TooLarge(body_limit_));
    if (ec) return Refuse(MalformedRequest(ec == http::error::header_limit, ec.message()));
    if (!reading_body_ && parser_->is_header_done()) return OnHeader();
    if (used == 0) break;
  }
  if (!reading_body_ && parser_->is_header_done()) return OnHeader();
  if (reading_body_ && parser_->is_done()) return OnRequest();
  ReadSome();
}

void Session::OnHeader() {
  SetPhase(Phase::kBusy);
  bytes_in_ = bytes_out_ = 0;
  close_after_reply_ = false;
  const auto& header = parser_->get();
  Request head = HeadOf(header);
  keep_alive_ = header.keep_alive();
  route_ = RouteLabel(head.method, head.target);
  if (auto refusal = FramingRefusal(header.version(), head.headers)) {
    return Refuse(std::move(*refusal));
  }
  body_limit_ = BodyLimit(head.method, head.target, core_.context.limits);
  std::optional<uint64_t> length;
  if (auto declared = parser_->content_length()) length = *declared;
  const bool has_body = parser_->chunked() || length.value_or(0) > 0;
  const auto authorization = header[http::field::authorization];
  if (auto token = ParseBearer(std::string_view(authorization.data(), authorization.size()))) {
    const RateDecision decision = core_.limiter.Acquire(HashToken(*token));
    if (!decision.allowed) {
      Response refusal = TooManyRequests(decision.retry_after_s);
      return has_body ? Refuse(std::move(refusal)) : Reply(std::move(refusal));
    }
  }
  if (length && *length > body_limit_) return Refuse(TooLarge(body_limit_));
  if (!has_body) return ReadBody();
  asio::post(core_.handlers, [self = shared_from_this(), head = std::move(head), length] {
    std::optional<Response> refusal = Admit(head, length, self->core_.context);
    asio::post(self->stream_.get_executor(), [self, refusal = std::move(refusal)]() mutable {
      self->OnAdmitted(std::move(refusal));
    });
  });
}

void Session::OnAdmitted(std::optional<Response> refusal) {
  if (closed_) return;
  if (refusal) return Refuse(std::move(*refusal));
  const size_t need = static_cast<size_t>(parser_->content_length().value_or(body_limit_));
  auto reservation = core_.body_memory.TryReserve(need);
  if (!reservation) return Refuse(BodyMemoryExhausted());
  body_memory_ = std::move(*reservation);
  parser_->body_limit(body_limit_);
  if (!beast::iequals(parser_->get()[http::field::expect], "100-continue")) return ReadBody();
  auto go_on = std::make_shared<http::response<http::empty_body>>(http::status::continue_, 11);
  transfer_start_ = Clock::now();
  stream_.expires_at(WriteDeadline(64));
  http::async_write(stream_, *go_on,
                    [self = shared_from_this(), go_on](beast::error_code ec, size_t) {
                      if (ec) return self->Close();
                      self->ReadBody();
                    });
}

void Session::ReadBody() {
  reading_body_ = true;
  transfer_start_ = Clock::now();
  transferred_ = 0;
  Parse();
}

void Session::OnRequest() {
  http::request<http::string_body> message = parser_->release();
  Request request = HeadOf(message);
  request.body = std::move(message.body());
  bytes_in_ = request.body.size();
  keep_alive_ = message.keep_alive();
  if (request.body.empty()) {
    if (auto quick = HandleQuick(request, core_.context)) return Reply(std::move(*quick));
  }
  // The body's memory stays reserved until the handler is done with it.
  asio::post(core_.handlers, [self = shared_from_this(), request = std::move(request),
                              memory = std::move(body_memory_)]() mutable {
    Response response = Handle(request, self->core_.context);
    request = Request();
    memory.Release();
    asio::post(self->stream_.get_executor(), [self, response = std::move(response)]() mutable {
      self->Reply(std::move(response));
    });
  });
}

void Session::Refuse(Response response) {
  close_after_reply_ = true;
  keep_alive_ = false;
  drain_budget_ = kDrainBytes;
  if (route_.empty()) route_ = "unmatched";
  Reply(std::move(response));
}

void Session::Reply(Response response) {
  if (closed_) return;
  SetPhase(Phase::kBusy);
  status_ = response.status;
  transfer_start_ = Clock::now();
  transferred_ = 0;
  const bool keep_alive = keep_alive_ && !close_after_reply_ && !core_.stopping;
  if (response.stream) {
    reader_ = std::move(response.stream);
    streamed_ = std::make_shared<http::response<http::buffer_body>>(
        static_cast<http::status>(response.status), 11);
    Dress(*streamed_, response, keep_alive);
    streamed_->content_length(reader_->size());
    streamed_->body().data = nullptr;
    streamed_->body().more = true;
    bytes_out_ = reader_->size();
    return WriteStreamed();
  }
  whole_ = std::make_shared<http::response<http::string_body>>(
      static_cast<http::status>(response.status), 11);
  Dress(*whole_, response, keep_alive);
  whole_->body() = std::move(response.body);
  whole_->prepare_payload();
  bytes_out_ = whole_->body().size();
  transferred_ = bytes_out_ + 512;
  stream_.expires_at(WriteDeadline(transferred_));
  http::async_write(stream_, *whole_,
                    [self = shared_from_this()](beast::error_code ec, size_t) {
                      self->OnWrite(ec);
                    });
}

void Session::WriteStreamed() {
  serializer_.emplace(*streamed_);
  streamed_offset_ = 0;
  transferred_ = 512;
  stream_.expires_at(WriteDeadline(transferred_));
  http::async_write_header(stream_, *serializer_,
                           [self = shared_from_this()](beast::error_code ec, size_t) {
                             if (ec) return self->Close();
                             self->NextPiece();
                           });
}

void Session::NextPiece() {
  if (streamed_offset_ >= reader_->size()) {
    streamed_->body().data = nullptr;
    streamed_->body().size = 0;
    streamed_->body().more = false;
    stream_.expires_at(WriteDeadline(transferred_ + 16));
    http::async_write(stream_, *serializer_,
                      [self = shared_from_this()](beast::error_code ec, size_t) {
                        self->OnWrite(ec);
                      });
    return;
  }
  piece_.resize(kPieceBytes);
  asio::post(core_.handlers, [self = shared_from_this()] {
    Expected<size_t> bytes = self->reader_->Read(self->streamed_offset_, self->piece_);
    asio::post(self->stream_.get_executor(), [self, bytes = std::move(bytes)]() mutable {
      self->OnPiece(std::move(bytes));
    });
  });
}

void Session::OnPiece(Expected<size_t> bytes) {
  if (closed_) return;
  if (!bytes || *bytes == 0) {
    std::cerr << "reenact-server: " << route_ << ": the stored payload could not be read to its "
              << "end (" << (bytes ? std::string("it is shorter than it was")
                                   : bytes.error().message)
              << "); the connection is closed and the client may retry" << std::endl;
    return Close();
  }
  streamed_->body().data = piece_.data();
  streamed_->body().size = *bytes;
  streamed_->body().more = true;
  streamed_offset_ += *bytes;
  transferred_ += *bytes;
  stream_.expires_at(WriteDeadline(transferred_));
  http::async_write(stream_, *serializer_,
                    [self = shared_from_this()](beast::error_code ec, size_t) {
                      if (ec == http::error::need_buffer) ec = {};
                      if (ec) return self->Close();
                      self->NextPiece();
                    });
}

void Session::OnWrite(beast::error_code ec) {
  if (ec == http::error::end_of_stream) ec = {};  // a Connection: close reply went out whole
  const double seconds = std::chrono::duration<double>(Clock::now() - started_).count();
  core_.context.metrics.Record(route_, status_, seconds, bytes_in_, bytes_out_);
  const bool need_eof = whole_ ? whole_->need_eof() : streamed_->need_eof();
  whole_.reset();
  streamed_.reset();
  serializer_.reset();
  reader_.reset();
  piece_ = {};
  if (!ec && close_after_reply_) return Drain();
  if (ec || need_eof) return Close();
  NextRequest();
}

void Session::Drain() {
  if (drain_until_ == SteadyTime()) {
    beast::error_code ignored;
    stream_.socket().shutdown(asio::ip::tcp::socket::shutdown_send, ignored);
    drain_until_ = Clock::now() + kDrainTime;
    const size_t buffered = std::min(drain_budget_, buffer_.size());
    drain_budget_ -= buffered;
    buffer_.consume(buffer_.size());
  }
  if (drain_budget_ == 0) return Close();
  // What is drained is never looked at: one scratch area per network thread serves all.
  static thread_local std::array<char, 64 * 1024> scratch;
  stream_.expires_at(drain_until_);
  stream_.async_read_some(asio::buffer(scratch.data(), std::min(scratch.size(), drain_budget_)),
                          [self = shared_from_this()](beast::error_code ec, size_t bytes) {
                            if (ec) return self->Close();
                            self->drain_budget_ -= std::min(bytes, self->drain_budget_);
                            self->Drain();
                          });
}

void Session::Close() {
  if (closed_) return;
  closed_ = true;
  SetPhase(Phase::kBusy);
  body_memory_.Release();
  beast::error_code ignored;
  stream_.socket().shutdown(asio::ip::tcp::socket::shutdown_send, ignored);
  stream_.socket().close(ignored);
}

}  // namespace reenact::server
