#pragma once
// Expected<T>: a value or an Error that a user can act on. Used for I/O, codec, database and
// network results that cross module boundaries (the third error tier of DESIGN.md).

#include <string>
#include <utility>
#include <variant>

#include "common/error/check.h"

namespace reenact {

struct Error {
  // Stable machine-readable code, e.g. "not_found", "corrupt", "io", "invalid_argument".
  std::string code;
  // One line for a person: what is wrong and what to do.
  std::string message;
};

inline Error MakeError(std::string code, std::string message) {
  return Error{std::move(code), std::move(message)};
}

template <typename T>
class [[nodiscard]] Expected {
 public:
  Expected(T value) : state_(std::move(value)) {}  // NOLINT: implicit by design
  Expected(Error error) : state_(std::move(error)) {}  // NOLINT: implicit by design

  bool ok() const { return state_.index() == 0; }
  explicit operator bool() const { return ok(); }

  const T& value() const& {
    REENACT_CHECK(ok(), "value() of an error: " + std::get<1>(state_).message);
    return std::get<0>(state_);
  }
  T& value() & {
    REENACT_CHECK(ok(), "value() of an error: " + std::get<1>(state_).message);
    return std::get<0>(state_);
  }
  T&& value() && {
    REENACT_CHECK(ok(), "value() of an error: " + std::get<1>(state_).message);
    return std::get<0>(std::move(state_));
  }
  const Error& error() const {
    REENACT_CHECK(!ok(), "error() of a value");
    return std::get<1>(state_);
  }
  const T& operator*() const& { return value(); }
  T& operator*() & { return value(); }
  const T* operator->() const { return &value(); }
  T* operator->() { return &value(); }

 private:
  std::variant<T, Error> state_;
};

// Expected<void>: success or an Error.
template <>
class [[nodiscard]] Expected<void> {
 public:
  Expected() = default;
  Expected(Error error) : error_(std::move(error)), ok_(false) {}  // NOLINT: implicit by design

  bool ok() const { return ok_; }
  explicit operator bool() const { return ok_; }
  const Error& error() const {
    REENACT_CHECK(!ok_, "error() of a success");
    return error_;
  }

 private:
  Error error_;
  bool ok_ = true;
};

using Status = Expected<void>;

}  // namespace reenact
