#include "proto/api/http_client.h"

#include <boost/asio/connect.hpp>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <cctype>
#include <charconv>

namespace reenact::proto {

namespace {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
using tcp = asio::ip::tcp;

Error BadUrl(std::string_view url, std::string_view why) {
  return MakeError("invalid_argument", "invalid server URL '" + std::string(url) + "': " +
                                           std::string(why) + " (expected http://HOST:PORT)");
}

// One request-response exchange driven by callbacks on a private io_context, so that every
// step can run under a deadline.
class Exchange {
 public:
  Exchange(const BaseUrl& url, const HttpRequest& request, const HttpClientOptions& options)
      : url_(url), options_(options), resolver_(ioc_), stream_(ioc_) {
    request_.method_string(request.method);
    request_.target(request.target);
    request_.version(11);
    request_.set(http::field::host, url.host + ":" + std::to_string(url.port));
    request_.set(http::field::user_agent, "reenact-client/0.1");
    request_.set(http::field::connection, "close");
    for (const auto& [name, value] : request.headers) request_.set(name, value);
    if (!request.content_type.empty())
      request_.set(http::field::content_type, request.content_type);
    request_.body() = request.body;
    request_.prepare_payload();
    parser_.body_limit(options.max_response_body_bytes);
    parser_.header_limit(64 * 1024);
  }

  Expected<HttpResponse> Run() {
    resolver_.async_resolve(url_.host, std::to_string(url_.port),
                            [this](beast::error_code ec, tcp::resolver::results_type results) {
                              OnResolve(ec, std::move(results));
                            });
    deadline_ = std::chrono::steady_clock::now() + options_.connect_timeout;
    ioc_.run_for(options_.connect_timeout + options_.read_timeout + std::chrono::seconds(1));
    if (!done_) return MakeError("timeout", "no answer from " + url_.text + " in time");
    return std::move(result_);
  }

 private:
  void Finish(Expected<HttpResponse> result) {
    result_ = std::move(result);
    done_ = true;
    beast::error_code ignored;
    stream_.socket().shutdown(tcp::socket::shutdown_both, ignored);
    stream_.close();
  }

  void Fail(beast::error_code ec, std::string_view step) {
    if (ec == asio::error::connection_refused) {
      return Finish(
          MakeError("unreachable", "cannot reach server at " + url_.text +
                                       ": connection refused; is reenact-server running?"));
    }
    if (ec == beast::error::timeout || ec == asio::error::operation_aborted) {
      return Finish(MakeError(
          "timeout", "server at " + url_.text + " did not answer within " +
                         std::to_string(step == "connect" ? options_.connect_timeout.count()
                                                          : options_.read_timeout.count()) +
                         " ms (" + std::string(step) + ")"));
    }
    if (ec == http::error::body_limit) {
      return Finish(MakeError("too_large", "response from " + url_.text + " exceeds " +
                                               std::to_string(options_.max_response_body_bytes) +
                                               " bytes"));
    }
    if (step == "resolve" || step == "connect") {
      return Finish(MakeError("unreachable", "cannot reach server at " + url_.text + ": " +
                                                 ec.message() + "; is reenact-server running?"));
    }
    Finish(MakeError("network", "talking to " + url_.text + " failed during " + std::string(step) +
                                    ": " + ec.message()));
  }

  void OnResolve(beast::error_code ec, tcp::resolver::results_type results) {
    if (ec) return Fail(ec, "resolve");
    stream_.expires_at(deadline_);
    stream_.async_connect(results, [this](beast::error_code ec2, const tcp::endpoint&) {
      if (ec2) return Fail(ec2, "connect");
      stream_.expires_after(options_.read_timeout);
      http::async_write(stream_, request_, [this](beast::error_code ec3, size_t) {
        // A server may answer before it has read the whole body (413 for an oversized
        // upload) and close; the answer is still readable, and says more than the write error.
        http::async_read(stream_, buffer_, parser_, [this, ec3](beast::error_code ec4, size_t) {
          if (ec4) return ec3 ? Fail(ec3, "write") : Fail(ec4, "read");
          OnResponse();
        });
      });
    });
  }

  void OnResponse() {
    auto& message = parser_.get();
    HttpResponse response;
    response.status = static_cast<int>(message.result_int());
    for (const auto& field : message) {
      response.headers.emplace_back(std::string(field.name_string()), std::string(field.value()));
    }
    response.body = std::move(message.body());
    Finish(std::move(response));
  }

  BaseUrl url_;
  HttpClientOptions options_;
  asio::io_context ioc_;
  tcp::resolver resolver_;
  beast::tcp_stream stream_;
  beast::flat_buffer buffer_;
  http::request<http::string_body> request_;
  http::response_parser<http::string_body> parser_;
  std::chrono::steady_clock::time_point deadline_;
  bool done_ = false;
  Expected<HttpResponse> result_ = MakeError("network", "no response");
};

}  // namespace

void HttpClientOptions::Check() const {
  REENACT_CHECK(connect_timeout.count() > 0, "connect_timeout must be > 0");
  REENACT_CHECK(read_timeout.count() > 0, "read_timeout must be > 0");
  REENACT_CHECK(max_response_body_bytes > 0, "max_response_body_bytes must be > 0");
}

Expected<BaseUrl> ParseBaseUrl(std::string_view url) {
  constexpr std::string_view kScheme = "http://";
  if (url.size() < kScheme.size() || !EqualsIgnoreCase(url.substr(0, kScheme.size()), kScheme)) {
    if (url.find("://") != std::string_view::npos) return BadUrl(url, "only http:// is supported");
    return BadUrl(url, "missing http://");
  }
  std::string_view rest = url.substr(kScheme.size());
  if (!rest.empty() && rest.back() == '/') rest.remove_suffix(1);
  if (rest.find('/') != std::string_view::npos) return BadUrl(url, "a base URL has no path");
  BaseUrl parsed;
  std::string_view port_text;
  if (!rest.empty() && rest.front() == '[') {
    const size_t close = rest.find(']');
    if (close == std::string_view::npos) return BadUrl(url, "unterminated IPv6 address");
    parsed.host = std::string(rest.substr(1, close - 1));
    std::string_view after = rest.substr(close + 1);
    if (!after.empty()) {
      if (after.front() != ':') return BadUrl(url, "junk after the IPv6 address");
      port_text = after.substr(1);
      if (port_text.empty()) return BadUrl(url, "empty port");
    }
  } else {
    const size_t colon = rest.rfind(':');
    parsed.host = std::string(rest.substr(0, colon));
    if (colon != std::string_view::npos) {
      port_text = rest.substr(colon + 1);
      if (port_text.empty()) return BadUrl(url, "empty port");
    }
  }
  if (parsed.host.empty()) return BadUrl(url, "missing host");
  for (char c : parsed.host) {
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == ':' ||
          c == '_')) {
      return BadUrl(url, "bad character in host");
    }
  }
  if (!port_text.empty()) {
    unsigned port = 0;
    auto [end, ec] = std::from_chars(port_text.data(), port_text.data() + port_text.size(), port);
    if (ec != std::errc() || end != port_text.data() + port_text.size() || port == 0 ||
        port > 65535) {
      return BadUrl(url, "port must be a number in 1..65535");
    }
    parsed.port = static_cast<uint16_t>(port);
  }
  const bool ipv6 = parsed.host.find(':') != std::string::npos;
  parsed.text = "http://" + (ipv6 ? "[" + parsed.host + "]" : parsed.host) + ":" +
                std::to_string(parsed.port);
  return parsed;
}

std::optional<std::string> HttpResponse::Header(std::string_view name) const {
  return FindHeader(headers, name);
}

HttpClient::HttpClient(std::string base_url, HttpClientOptions options)
    : base_url_text_(std::move(base_url)),
      base_url_(ParseBaseUrl(base_url_text_)),
      options_(options) {
  options_.Check();
  if (base_url_) base_url_text_ = base_url_->text;
}

Expected<HttpResponse> HttpClient::Send(const HttpRequest& request) const {
  if (!base_url_) return base_url_.error();
  Exchange exchange(*base_url_, request, options_);
  return exchange.Run();
}

}  // namespace reenact::proto
