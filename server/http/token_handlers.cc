#include "server/auth/token.h"
#include "server/http/handlers.h"

namespace reenact::server::handlers {

Response RevokeOwnToken(const Request& request, ServiceContext& context) {
  auto user = RequireUser(request, context);
  if (auto* response = std::get_if<Response>(&user)) return std::move(*response);
  const auto token = ParseBearer(request.Header("Authorization").value_or(""));
  REENACT_CHECK(token.has_value(), "RequireUser accepted a request without a bearer token");
  auto revoked = context.metadata.RevokeToken(HashToken(*token));
  if (!revoked) return StorageFailure(revoked.error());
  Response done;
  done.status = 204;
  done.content_type.clear();
  return done;
}

}  // namespace reenact::server::handlers
