#include "proto/clip/byte_io.h"

#include <bit>

namespace reenact::proto::internal {
namespace {

template <typename T>
void Append(std::vector<uint8_t>& out, T v) {
  for (size_t i = 0; i < sizeof(T); ++i) out.push_back(static_cast<uint8_t>(v >> (8 * i)));
}

template <typename T>
T Load(const uint8_t* p) {
  T v = 0;
  for (size_t i = 0; i < sizeof(T); ++i) v |= static_cast<T>(p[i]) << (8 * i);
  return v;
}

}  // namespace

void ByteWriter::U32(uint32_t v) { Append(bytes_, v); }
void ByteWriter::U64(uint64_t v) { Append(bytes_, v); }
void ByteWriter::F64(double v) { Append(bytes_, std::bit_cast<uint64_t>(v)); }
void ByteWriter::Bytes(std::span<const uint8_t> b) { bytes_.insert(bytes_.end(), b.begin(), b.end()); }
void ByteWriter::Text(std::string_view t) { bytes_.insert(bytes_.end(), t.begin(), t.end()); }

bool ByteReader::U32(uint32_t* v) {
  if (remaining() < 4) return false;
  *v = Load<uint32_t>(bytes_.data() + at_);
  at_ += 4;
  return true;
}

bool ByteReader::U64(uint64_t* v) {
  if (remaining() < 8) return false;
  *v = Load<uint64_t>(bytes_.data() + at_);
  at_ += 8;
  return true;
}

bool ByteReader::F64(double* v) {
  uint64_t bits = 0;
  if (!U64(&bits)) return false;
  *v = std::bit_cast<double>(bits);
  return true;
}

bool ByteReader::Take(uint64_t n, std::span<const uint8_t>* out) {
  if (n > remaining()) return false;
  *out = bytes_.subspan(at_, static_cast<size_t>(n));
  at_ += static_cast<size_t>(n);
  return true;
}

}  // namespace reenact::proto::internal
