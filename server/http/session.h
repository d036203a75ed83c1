#pragma once
// Internal to the HTTP server: one connection (after Boost.Beast's async server example),
// serving requests one after another on its network thread:
//   wait for a request (idle_timeout) -> header (min rate once its first byte is in) ->
//   framing checks -> admission on the handler pool (routes.h, Admit) -> body memory reserved
//   -> body (min rate) -> handler on the pool -> response (min rate; streamed payloads a
//   piece at a time, each piece read on the pool).
// A refused request is answered, a little of its unread body is drained so the client can read
// the answer, and the connection is closed.

#include <atomic>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "server/http/message.h"
#include "server/http/server_core.h"
#include "server/http/transfer_deadline.h"

namespace reenact::server {

class Session : public std::enable_shared_from_this<Session> {
 public:
  // What a connection is doing, as seen from the acceptor (any thread).
  enum class Phase { kIdle, kHeader, kBusy };

  // refusal: answer it at once and close (the server or the address is at its limit);
  // nullopt: serve. `address` was counted in core.addresses when refusal is nullopt.
  Session(boost::asio::ip::tcp::socket&& socket, ServerCore& core, std::string address,
          std::optional<Response> refusal);
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  void Start();
  // Closes the connection now if it is between requests; otherwise after the response.
  void Shutdown();
  // Closes the connection if it is still idle or reading a request header and has no unread
  // bytes waiting (to make room for a new one at the connection limit); false when it is busy
  // or already being evicted. The close happens on the connection's own thread, so the cap
  // may be passed by the few connections whose eviction finds a request waiting.
  bool Evict();

  bool Evictable() const { return phase_ != Phase::kBusy && !evicting_; }
  Phase phase() const { return phase_; }
  // When the current phase began (steady clock ticks).
  int64_t phase_since() const { return phase_since_; }

 private:
  using Parser = boost::beast::http::request_parser<boost::beast::http::string_body>;

  void SetPhase(Phase phase);
  void NextRequest();
  void ReadSome();
  void OnRead(boost::beast::error_code ec, size_t bytes);
  void Parse();
  void OnHeader();
  void OnAdmitted(std::optional<Response> refusal);
  void ReadBody();
  void OnRequest();
  void Refuse(Response response);
  void Reply(Response response);
  void WriteWhole();
  void WriteStreamed();
  void NextPiece();
  void OnPiece(Expected<size_t> bytes);
  void OnWrite(boost::beast::error_code ec);
  void Drain();
  void Close();
  SteadyTime ReadDeadline() const;
  SteadyTime WriteDeadline(uint64_t bytes_after_this_write) const;

  boost::beast::tcp_stream stream_;
  ServerCore& core_;
  const std::string address_;
  const bool counted_;  // holds a slot in core_.served and core_.addresses
  std::optional<Response> initial_refusal_;

  std::atomic<Phase> phase_{Phase::kIdle};
  std::atomic<int64_t> phase_since_{0};
  std::atomic<bool> evicting_{false};
  bool closed_ = false;

  boost::beast::flat_buffer buffer_;
  std::optional<Parser> parser_;
  bool header_seen_ = false;
  SteadyTime request_wait_start_;
  SteadyTime transfer_start_;  // first header byte, body start or response start
  uint64_t transferred_ = 0;   // bytes of the current transfer
  bool reading_body_ = false;
  bool keep_alive_ = true;
  size_t body_limit_ = 0;
  MemoryReservation body_memory_;

  std::string route_;
  int status_ = 0;
  size_t bytes_in_ = 0;
  size_t bytes_out_ = 0;
  SteadyTime started_;
  bool close_after_reply_ = false;
  size_t drain_budget_ = 0;
  SteadyTime drain_until_;

  std::shared_ptr<boost::beast::http::response<boost::beast::http::string_body>> whole_;
  std::shared_ptr<BlobReader> reader_;
  std::shared_ptr<boost::beast::http::response<boost::beast::http::buffer_body>> streamed_;
  std::optional<boost::beast::http::response_serializer<boost::beast::http::buffer_body>>
      serializer_;
  std::vector<char> piece_;
  uint64_t streamed_offset_ = 0;
};

}  // namespace reenact::server
