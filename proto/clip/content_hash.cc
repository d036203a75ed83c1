#include "proto/clip/content_hash.h"

#include <openssl/evp.h>

#include "common/error/check.h"

namespace reenact::proto {

namespace {

std::string HexDigest(const unsigned char* digest, unsigned int length) {
  REENACT_CHECK(length == 32, "a SHA-256 digest has 32 bytes");
  static constexpr char kHex[] = "0123456789abcdef";
  std::string hex(64, '0');
  for (unsigned int i = 0; i < length; ++i) {
    hex[2 * i] = kHex[digest[i] >> 4];
    hex[2 * i + 1] = kHex[digest[i] & 0xF];
  }
  return hex;
}

}  // namespace

std::string Sha256Hex(std::span<const uint8_t> bytes) {
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int digest_length = 0;
  const int ok =
      EVP_Digest(bytes.data(), bytes.size(), digest, &digest_length, EVP_sha256(), nullptr);
  REENACT_CHECK(ok == 1, "EVP_Digest(SHA-256) failed");
  return HexDigest(digest, digest_length);
}

std::string Sha256Hex(std::string_view bytes) {
  return Sha256Hex(std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(bytes.data()),
                                            bytes.size()));
}

struct Sha256Hasher::State {
  State() : context(EVP_MD_CTX_new()) {
    REENACT_CHECK(context != nullptr, "EVP_MD_CTX_new failed");
    Start();
  }
  ~State() { EVP_MD_CTX_free(context); }
  State(const State&) = delete;
  State& operator=(const State&) = delete;

  void Start() {
    REENACT_CHECK(EVP_DigestInit_ex(context, EVP_sha256(), nullptr) == 1,
                  "EVP_DigestInit_ex(SHA-256) failed");
  }

  EVP_MD_CTX* context;
};

Sha256Hasher::Sha256Hasher() : state_(std::make_unique<State>()) {}
Sha256Hasher::~Sha256Hasher() = default;
Sha256Hasher::Sha256Hasher(Sha256Hasher&&) noexcept = default;
Sha256Hasher& Sha256Hasher::operator=(Sha256Hasher&&) noexcept = default;

void Sha256Hasher::Update(std::string_view bytes) {
  REENACT_CHECK(state_ != nullptr, "Update of a moved-from Sha256Hasher");
  REENACT_CHECK(EVP_DigestUpdate(state_->context, bytes.data(), bytes.size()) == 1,
                "EVP_DigestUpdate(SHA-256) failed");
}

void Sha256Hasher::Update(std::span<const uint8_t> bytes) {
  Update(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

std::string Sha256Hasher::FinalHex() {
  REENACT_CHECK(state_ != nullptr, "FinalHex of a moved-from Sha256Hasher");
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int digest_length = 0;
  REENACT_CHECK(EVP_DigestFinal_ex(state_->context, digest, &digest_length) == 1,
                "EVP_DigestFinal_ex(SHA-256) failed");
  state_->Start();
  return HexDigest(digest, digest_length);
}

bool IsSha256Hex(std::string_view text) {
  if (text.size() != 64) return false;
  for (char c : text)
    if (!((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'))) return false;
  return true;
}

}  // namespace reenact::proto
