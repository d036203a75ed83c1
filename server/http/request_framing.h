#pragma once
// Checks of a request's framing (RFC 9112), made on its header before anything else is done
// with it, so that no request is ever read with a length other than the one the client meant
// (request smuggling through a proxy) and every malformed request gets an answer.

#include <optional>

#include "server/http/message.h"

namespace reenact::server {

// The answer for a request whose framing this server refuses, or nullopt when it is fine:
//  505 an HTTP major version other than 1 (a higher 1.x minor is read as 1.1, RFC 9110 2.5);
//  400 Transfer-Encoding beside Content-Length, or on an HTTP/1.0 request, or whose last
//      coding is not chunked (e.g. "xchunked", "chunked, gzip");
//  501 codings before chunked (e.g. "gzip, chunked"): only plain chunked is understood.
// version is major * 10 + minor, as Beast gives it. The caller closes the connection after.
std::optional<Response> FramingRefusal(unsigned version, const HeaderList& headers);

// The answer for a request the HTTP parser could not read: 431 when its header is larger
// than the server accepts, 400 otherwise. `what` says what was wrong (the parser's words).
Response MalformedRequest(bool header_too_large, std::string_view what);

}  // namespace reenact::server
