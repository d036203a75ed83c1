#pragma once
// Validated reading of JSON documents from outside (manifest, frame headers). Internal to
// proto/clip: a JsonField names where it sits ("location.lat_deg") and every accessor throws
// JsonFieldError with a message a person can act on, e.g.
//   "manifest: location.lat_deg = 95 is outside [-90, 90]".
// Parsers catch JsonFieldError at their boundary and return it as an Error; it never
// escapes proto/clip.

#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace reenact::proto::internal {

class JsonFieldError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A closed or open interval for range checks; printed as "[lo, hi]", "(lo, hi]", ...
struct Interval {
  double lo, hi;
  bool lo_open = false;
  bool hi_open = false;
  bool Contains(double v) const;
  std::string ToString() const;
};

// Shortest text that reads back as the same double ("95", "0.001", "1e+300").
std::string FormatNumber(double value);

class JsonField {
 public:
  // prefix: the document's name for messages ("manifest"); path: "" for the root.
  JsonField(const nlohmann::json& value, std::string prefix, std::string path = "");

  const nlohmann::json& json() const { return value_; }
  const std::string& path() const { return path_; }

  // Member of an object; throws "missing field" if absent, or if this is no object.
  JsonField operator[](std::string_view key) const;
  bool Has(std::string_view key) const;
  // Element of an array (index checked).
  JsonField operator[](size_t index) const;

  void ExpectObject() const;
  // Array of exactly `size` elements when size >= 0; returns its size.
  size_t ExpectArray(long size = -1) const;

  double Number() const;                       // finite number
  double NumberIn(const Interval& range) const;  // finite number within range
  int64_t Integer() const;                     // integral JSON number (not 2.0)
  int64_t IntegerIn(int64_t lo, int64_t hi) const;
  std::string String() const;

  // Throws JsonFieldError("<prefix>: <path> <what>").
  [[noreturn]] void Fail(const std::string& what) const;

 private:
  const nlohmann::json& value_;
  std::string prefix_;
  std::string path_;
};

}  // namespace reenact::proto::internal
