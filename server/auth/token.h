#pragma once
// Bearer tokens. A token is 32 random bytes (256 bits, OpenSSL RAND_bytes) written as 64
// lowercase hex digits and prefixed "rnk_". The server stores only the token's SHA-256
// (hex); it looks a token up by that hash (timing of the lookup reveals nothing about the
// token itself) and confirms the match with a constant-time comparison.

#include <optional>
#include <string>
#include <string_view>

#include "common/error/expected.h"
#include "server/storage/metadata_store.h"

namespace reenact::server {

// A fresh token; code "crypto" if the system's random source fails.
Expected<std::string> GenerateToken();

// Hex SHA-256 of the token's text: what the database stores.
std::string HashToken(std::string_view token);

// Equality of two strings whose time depends only on their lengths (CRYPTO_memcmp).
bool ConstantTimeEquals(std::string_view a, std::string_view b);

// The token of an "Authorization: Bearer <token>" header value, or nullopt if the header is
// not a well-formed bearer credential.
std::optional<std::string> ParseBearer(std::string_view authorization);

// The user a token belongs to: nullopt for an unknown token; storage errors as errors.
Expected<std::optional<UserRecord>> Authenticate(MetadataStore& store, std::string_view token);

// Creates user `name` with a new token; returns the token (shown to the person once).
// code "invalid_argument" for an empty or over-long name (> 64 bytes, or control characters),
// "conflict" when the name is taken.
Expected<std::string> AddUserWithToken(MetadataStore& store, const std::string& name);

// Issues another token for an existing user (e.g. after revoking a leaked one); returns it.
// code "not_found" when there is no such user.
Expected<std::string> AddTokenForUser(MetadataStore& store, const std::string& name);

}  // namespace reenact::server
