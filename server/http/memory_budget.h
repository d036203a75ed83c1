#pragma once
// The memory that request bodies may hold at once, server-wide. A body is read only once
// its size (Content-Length, or the route's limit for a chunked body) is reserved here; what
// does not fit is refused (503, retry shortly) instead of growing the process. Thread-safe.

#include <atomic>
#include <cstddef>
#include <optional>

namespace reenact::server {

class MemoryBudget;

// Bytes held from a MemoryBudget until destroyed. Move-only.
class MemoryReservation {
 public:
  MemoryReservation() = default;
  MemoryReservation(MemoryReservation&& other) noexcept
      : budget_(other.budget_), bytes_(other.bytes_) {
    other.budget_ = nullptr;
  }
  MemoryReservation& operator=(MemoryReservation&& other) noexcept;
  MemoryReservation(const MemoryReservation&) = delete;
  MemoryReservation& operator=(const MemoryReservation&) = delete;
  ~MemoryReservation() { Release(); }

  size_t bytes() const { return budget_ ? bytes_ : 0; }
  void Release();

 private:
  friend class MemoryBudget;
  MemoryReservation(MemoryBudget* budget, size_t bytes) : budget_(budget), bytes_(bytes) {}
  MemoryBudget* budget_ = nullptr;
  size_t bytes_ = 0;
};

class MemoryBudget {
 public:
  // total_bytes: the most all reservations may hold together; > 0.
  explicit MemoryBudget(size_t total_bytes) : total_(total_bytes) {}

  // Holds `bytes` if they fit beside what is held; nullopt otherwise.
  std::optional<MemoryReservation> TryReserve(size_t bytes);
  size_t held() const { return held_.load(); }
  size_t total() const { return total_; }

 private:
  friend class MemoryReservation;
  const size_t total_;
  std::atomic<size_t> held_{0};
};

}  // namespace reenact::server
