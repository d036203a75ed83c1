#pragma once
// Little-endian binary writing and bounds-checked reading for the clip containers (RFRM,
// RMAP). Internal to proto/clip. The reader never reads past its span: every Read* returns
// false (and leaves the output untouched) when too few bytes remain.

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

namespace reenact::proto::internal {

class ByteWriter {
 public:
  void U32(uint32_t v);
  void U64(uint64_t v);
  void F64(double v);
  void Bytes(std::span<const uint8_t> bytes);
  void Text(std::string_view text);

  std::vector<uint8_t>& bytes() { return bytes_; }

 private:
  std::vector<uint8_t> bytes_;
};

class ByteReader {
 public:
  explicit ByteReader(std::span<const uint8_t> bytes) : bytes_(bytes) {}

  size_t remaining() const { return bytes_.size() - at_; }
  size_t offset() const { return at_; }

  bool U32(uint32_t* v);
  bool U64(uint64_t* v);
  bool F64(double* v);
  // A view of the next n bytes.
  bool Take(uint64_t n, std::span<const uint8_t>* out);

 private:
  std::span<const uint8_t> bytes_;
  size_t at_ = 0;
};

}  // namespace reenact::proto::internal
