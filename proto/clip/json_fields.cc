#include "proto/clip/json_fields.h"

#include <charconv>
#include <cmath>

namespace reenact::proto::internal {

bool Interval::Contains(double v) const {
  const bool above = lo_open ? v > lo : v >= lo;
  const bool below = hi_open ? v < hi : v <= hi;
  return above && below;
}

std::string Interval::ToString() const {
  return std::string(lo_open ? "(" : "[") + FormatNumber(lo) + ", " + FormatNumber(hi) +
         (hi_open ? ")" : "]");
}

std::string FormatNumber(double value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return std::string(buffer, result.ptr);
}

JsonField::JsonField(const nlohmann::json& value, std::string prefix, std::string path)
    : value_(value), prefix_(std::move(prefix)), path_(std::move(path)) {}

void JsonField::Fail(const std::string& what) const {
  const std::string where = path_.empty() ? "document" : path_;
  throw JsonFieldError(prefix_ + ": " + where + " " + what);
}

void JsonField::ExpectObject() const {
  if (!value_.is_object()) Fail("must be an object");
}

bool JsonField::Has(std::string_view key) const {
  return value_.is_object() && value_.contains(key);
}

JsonField JsonField::operator[](std::string_view key) const {
  ExpectObject();
  const std::string child = path_.empty() ? std::string(key) : path_ + "." + std::string(key);
  const auto it = value_.find(key);
  if (it == value_.end()) throw JsonFieldError(prefix_ + ": missing field " + child);
  return JsonField(*it, prefix_, child);
}

JsonField JsonField::operator[](size_t index) const {
  if (!value_.is_array() || index >= value_.size()) Fail("has no element " + std::to_string(index));
  return JsonField(value_[index], prefix_, path_ + "[" + std::to_string(index) + "]");
}

size_t JsonField::ExpectArray(long size) const {
  if (!value_.is_array()) Fail("must be an array");
  if (size >= 0 && value_.size() != static_cast<size_t>(size))
    Fail("must have " + std::to_string(size) + " elements, not " + std::to_string(value_.size()));
  return value_.size();
}

double JsonField::Number() const {
  if (!value_.is_number()) Fail("must be a number");
  const double v = value_.get<double>();
  if (!std::isfinite(v)) Fail("must be finite");
  return v;
}

double JsonField::NumberIn(const Interval& range) const {
  const double v = Number();
  if (!range.Contains(v)) Fail("= " + FormatNumber(v) + " is outside " + range.ToString());
  return v;
}

int64_t JsonField::Integer() const {
  if (value_.is_number_unsigned()) {
    const uint64_t u = value_.get<uint64_t>();
    if (u > static_cast<uint64_t>(INT64_MAX)) Fail("= " + std::to_string(u) + " is too large");
    return static_cast<int64_t>(u);
  }
  if (!value_.is_number_integer()) Fail("must be an integer");
  return value_.get<int64_t>();
}

int64_t JsonField::IntegerIn(int64_t lo, int64_t hi) const {
  const int64_t v = Integer();
  if (v < lo || v > hi)
    Fail("= " + std::to_string(v) + " is outside [" + std::to_string(lo) + ", " +
         std::to_string(hi) + "]");
  return v;
}

std::string JsonField::String() const {
  if (!value_.is_string()) Fail("must be a string");
  return value_.get<std::string>();
}

}  // namespace reenact::proto::internal
