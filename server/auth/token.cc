#include "server/auth/token.h"

#include <openssl/crypto.h>
#include <openssl/rand.h>

#include <array>
#include <cctype>

#include "proto/clip/content_hash.h"

namespace reenact::server {

namespace {

constexpr std::string_view kTokenPrefix = "rnk_";
constexpr size_t kTokenRandomBytes = 32;

}  // namespace

Expected<std::string> GenerateToken() {
  std::array<unsigned char, kTokenRandomBytes> bytes{};
  if (RAND_bytes(bytes.data(), static_cast<int>(bytes.size())) != 1) {
    return MakeError("crypto", "the system random generator failed; cannot create a token");
  }
  static constexpr char kHex[] = "0123456789abcdef";
  std::string token(kTokenPrefix);
  for (unsigned char b : bytes) {
    token.push_back(kHex[b >> 4]);
    token.push_back(kHex[b & 15]);
  }
  return token;
}

std::string HashToken(std::string_view token) { return proto::Sha256Hex(token); }

bool ConstantTimeEquals(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  return CRYPTO_memcmp(a.data(), b.data(), a.size()) == 0;
}

std::optional<std::string> ParseBearer(std::string_view authorization) {
  constexpr std::string_view kScheme = "bearer ";
  if (authorization.size() <= kScheme.size()) return std::nullopt;
  for (size_t i = 0; i < kScheme.size(); ++i) {
    if (std::tolower(static_cast<unsigned char>(authorization[i])) != kScheme[i]) {
      return std::nullopt;
    }
  }
  std::string_view token = authorization.substr(kScheme.size());
  while (!token.empty() && token.front() == ' ') token.remove_prefix(1);
  while (!token.empty() && token.back() == ' ') token.remove_suffix(1);
  if (token.empty() || token.size() > 512) return std::nullopt;
  for (char c : token) {
    if (c <= ' ' || c > '~') return std::nullopt;
  }
  return std::string(token);
}

Expected<std::optional<UserRecord>> Authenticate(MetadataStore& store, std::string_view token) {
  const std::string hash = HashToken(token);
  auto owner = store.FindUserByTokenHash(hash);
  if (!owner) return owner.error();
  if (!*owner || !ConstantTimeEquals(hash, (*owner)->stored_sha256)) {
    return std::optional<UserRecord>();
  }
  return std::optional<UserRecord>((*owner)->user);
}

Expected<std::string> AddUserWithToken(MetadataStore& store, const std::string& name) {
  if (name.empty() || name.size() > 64) {
    return MakeError("invalid_argument", "user name must be 1 to 64 bytes long");
  }
  for (char c : name) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
      return MakeError("invalid_argument", "user name must not contain control characters");
    }
  }
  auto token = GenerateToken();
  if (!token) return token.error();
  auto user = store.AddUser(name, HashToken(*token));
  if (!user) return user.error();
  return *token;
}

Expected<std::string> AddTokenForUser(MetadataStore& store, const std::string& name) {
  auto token = GenerateToken();
  if (!token) return token.error();
  auto user = store.AddToken(name, HashToken(*token));
  if (!user) return user.error();
  return *token;
}

}  // namespace reenact::server
