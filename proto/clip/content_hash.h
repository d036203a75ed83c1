#pragma once
// Content hashes of clip parts (frames, map): SHA-256 as 64 lowercase hexadecimal digits,
// the form the manifest stores in parts[*].sha256.

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>

namespace reenact::proto {

// SHA-256 of the bytes, as 64 lowercase hex digits (OpenSSL EVP).
std::string Sha256Hex(std::span<const uint8_t> bytes);
std::string Sha256Hex(std::string_view bytes);

// SHA-256 of bytes given in pieces: Update(a); Update(b); FinalHex() == Sha256Hex(a + b).
// Its state has a fixed size whatever the input's length. Movable, not copyable.
class Sha256Hasher {
 public:
  Sha256Hasher();
  ~Sha256Hasher();
  Sha256Hasher(Sha256Hasher&&) noexcept;
  Sha256Hasher& operator=(Sha256Hasher&&) noexcept;

  // Appends bytes to the input.
  void Update(std::string_view bytes);
  void Update(std::span<const uint8_t> bytes);
  // The hash of everything given since construction or the last FinalHex, as Sha256Hex
  // writes it; the hasher then starts over with an empty input.
  std::string FinalHex();

 private:
  struct State;  // OpenSSL's digest context
  std::unique_ptr<State> state_;
};

// True if text is exactly 64 lowercase hex digits (the form Sha256Hex returns).
bool IsSha256Hex(std::string_view text);

}  // namespace reenact::proto
