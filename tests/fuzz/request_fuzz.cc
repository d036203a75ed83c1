// libFuzzer: arbitrary bytes through the server's request path: Beast's HTTP/1.1 request
// parser (with the server's header limit and per-route body limits), then Handle() on real
// SQLite storage. Nothing may crash, throw, or answer outside the documented statuses.
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "server/auth/token.h"
#include "server/http/routes.h"
#include "server/storage/open_storage.h"

namespace {

namespace http = boost::beast::http;
using namespace reenact::server;

struct World {
  World() {
    std::string pattern = (std::filesystem::temp_directory_path() / "reenact-fuzz-XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr) std::abort();
    auto opened = OpenSqliteStorage(pattern + "/fuzz.db");
    if (!opened) std::abort();
    storage = std::move(*opened);
    token = *AddUserWithToken(*storage.metadata, "fuzz");
  }
  Storage storage;
  Metrics metrics;
  std::string token;
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static World world;
  ServiceContext context{*world.storage.metadata, *world.storage.blobs, world.metrics,
                         ServiceLimits{}};
  http::request_parser<http::string_body> parser;
  parser.header_limit(16 * 1024);
  parser.body_limit(1 << 20);
  parser.eager(true);
  boost::beast::error_code ec;
  parser.put(boost::asio::buffer(data, size), ec);
  if (ec || !parser.is_done()) return 0;
  const auto& message = parser.get();
  Request request;
  request.method = std::string(message.method_string());
  request.target = std::string(message.target());
  for (const auto& field : message) {
    request.headers.emplace_back(std::string(field.name_string()), std::string(field.value()));
  }
  // Half the inputs act as the signed-in user, so the write paths are reached too.
  if (size % 2 == 0) request.headers.emplace_back("Authorization", "Bearer " + world.token);
  request.body = message.body();
  const Response response = Handle(request, context);
  if (response.status < 200 || response.status > 503) std::abort();
  (void)RouteLabel(request.method, request.target);
  (void)BodyLimit(request.method, request.target, context.limits);
  return 0;
}
