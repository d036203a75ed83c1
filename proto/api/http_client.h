#pragma once
// A blocking HTTP/1.1 client (Boost.Beast) for the capture and viewer clients. One TCP
// connection per request; every step (resolve + connect, write, read) runs under a deadline.
// No TLS: deployments put reenact-server behind a reverse proxy and clients on a trusted
// network or a local tunnel.

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "common/error/expected.h"
#include "proto/api/http_headers.h"

namespace reenact::proto {

struct HttpClientOptions {
  // Deadline for resolving the host and connecting; > 0. Default 10 s.
  std::chrono::milliseconds connect_timeout{10'000};
  // Deadline for sending the request and reading the whole response; > 0. Default 10 s.
  std::chrono::milliseconds read_timeout{10'000};
  // Largest response body accepted, bytes; > 0. Default 256 MiB.
  size_t max_response_body_bytes = size_t{256} << 20;

  void Check() const;
};

// "http://HOST:PORT" (optionally with a trailing '/'; the port defaults to 80). HOST is a
// name, an IPv4 address or a bracketed IPv6 address.
struct BaseUrl {
  std::string host;
  uint16_t port = 80;
  std::string text;  // normalised "http://host:port"
};
// code "invalid_argument" with a message showing the expected form.
Expected<BaseUrl> ParseBaseUrl(std::string_view url);

struct HttpRequest {
  std::string method = "GET";  // GET, POST, PUT, DELETE, ...
  std::string target = "/";    // path and query, e.g. "/v1/clips?near=1,2"
  HttpHeaders headers;         // extra headers (Host, Content-Length are set for you)
  std::string content_type;    // sent when not empty
  std::string body;
};

struct HttpResponse {
  int status = 0;
  HttpHeaders headers;
  std::string body;

  // The first header with this name (case-insensitive), or nullopt.
  std::optional<std::string> Header(std::string_view name) const;
};

class HttpClient {
 public:
  // An invalid base_url makes every Send fail with the parse error.
  explicit HttpClient(std::string base_url, HttpClientOptions options = {});

  // Sends one request and reads the response, whatever its status. Errors:
  //   "invalid_argument": a malformed base URL;
  //   "unreachable": cannot resolve or connect ("cannot reach server at http://h:p:
  //                  connection refused; is reenact-server running?");
  //   "timeout": a deadline passed; "too_large": the body exceeds the limit;
  //   "network": the connection broke or the response was not HTTP.
  Expected<HttpResponse> Send(const HttpRequest& request) const;

  const std::string& base_url() const { return base_url_text_; }

 private:
  std::string base_url_text_;
  Expected<BaseUrl> base_url_;
  HttpClientOptions options_;
};

}  // namespace reenact::proto
