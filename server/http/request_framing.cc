#include "server/http/request_framing.h"

#include <string>
#include <vector>

namespace reenact::server {

namespace {

std::string_view Trim(std::string_view text) {
  while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) text.remove_prefix(1);
  while (!text.empty() && (text.back() == ' ' || text.back() == '\t')) text.remove_suffix(1);
  return text;
}

// Every coding named by every Transfer-Encoding line, in order.
std::vector<std::string> TransferCodings(const HeaderList& headers) {
  std::vector<std::string> codings;
  for (const auto& [name, value] : headers) {
    if (!EqualsIgnoreCase(name, "Transfer-Encoding")) continue;
    std::string_view rest = value;
    while (true) {
      const size_t comma = rest.find(',');
      codings.emplace_back(Trim(rest.substr(0, comma)));
      if (comma == std::string_view::npos) break;
      rest.remove_prefix(comma + 1);
    }
  }
  return codings;
}

bool HasHeader(const HeaderList& headers, std::string_view wanted) {
  for (const auto& [name, value] : headers) {
    if (EqualsIgnoreCase(name, wanted)) return true;
  }
  return false;
}

}  // namespace

std::optional<Response> FramingRefusal(unsigned version, const HeaderList& headers) {
  if (version / 10 != 1) {
    return ErrorResponse(505, "http_version_not_supported",
                         "this server speaks HTTP/1.1; got HTTP/" +
                             std::to_string(version / 10) + "." + std::to_string(version % 10));
  }
  const std::vector<std::string> codings = TransferCodings(headers);
  if (codings.empty()) return std::nullopt;
  if (HasHeader(headers, "Content-Length")) {
    return ErrorResponse(400, "bad_request",
                         "a request must not carry both Transfer-Encoding and Content-Length");
  }
  if (version == 10) {
    return ErrorResponse(400, "bad_request", "Transfer-Encoding is not allowed in HTTP/1.0");
  }
  if (!EqualsIgnoreCase(codings.back(), "chunked")) {
    return ErrorResponse(400, "bad_request",
                         "Transfer-Encoding must end with 'chunked' (the body's length is "
                         "otherwise unknown); send exactly 'Transfer-Encoding: chunked' or a "
                         "Content-Length");
  }
  if (codings.size() > 1) {
    return ErrorResponse(501, "not_implemented",
                         "only 'Transfer-Encoding: chunked' is understood; send the body "
                         "without other codings");
  }
  return std::nullopt;
}

Response MalformedRequest(bool header_too_large, std::string_view what) {
  if (header_too_large) {
    return ErrorResponse(431, "header_too_large",
                         "the request header is larger than this server accepts (16 KiB); "
                         "send fewer or shorter header fields");
  }
  return ErrorResponse(400, "bad_request",
                       "malformed HTTP request (" + std::string(what) + "); see RFC 9112");
}

}  // namespace reenact::server
