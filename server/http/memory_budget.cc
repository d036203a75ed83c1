#include "server/http/memory_budget.h"

namespace reenact::server {

MemoryReservation& MemoryReservation::operator=(MemoryReservation&& other) noexcept {
  if (this != &other) {
    Release();
    budget_ = other.budget_;
    bytes_ = other.bytes_;
    other.budget_ = nullptr;
  }
  return *this;
}

void MemoryReservation::Release() {
  if (budget_) budget_->held_ -= bytes_;
  budget_ = nullptr;
}

std::optional<MemoryReservation> MemoryBudget::TryReserve(size_t bytes) {
  size_t held = held_.load();
  do {
    if (bytes > total_ || held > total_ - bytes) return std::nullopt;
  } while (!held_.compare_exchange_weak(held, held + bytes));
  return MemoryReservation(this, bytes);
}

}  // namespace reenact::server
