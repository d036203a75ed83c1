#pragma once
// Content hashes of clip parts (frames, map): SHA-256 as 64 lowercase hexadecimal digits,
// the form the manifest stores in parts[*].sha256.

#include <cstdint>
#include <span>
#include <string>
#include <string_view>

namespace reenact::proto {

// SHA-256 of the bytes, as 64 lowercase hex digits (OpenSSL EVP).
std::string Sha256Hex(std::span<const uint8_t> bytes);
std::string Sha256Hex(std::string_view bytes);

// True if text is exactly 64 lowercase hex digits (the form Sha256Hex returns).
bool IsSha256Hex(std::string_view text);

}  // namespace reenact::proto
