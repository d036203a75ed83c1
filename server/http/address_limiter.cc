#include "server/http/address_limiter.h"

namespace reenact::server {

bool AddressLimiter::Acquire(const std::string& address) {
  std::lock_guard lock(mutex_);
  int& held = held_[address];
  if (per_address_ > 0 && held >= per_address_) {
    if (held == 0) held_.erase(address);
    return false;
  }
  ++held;
  return true;
}

void AddressLimiter::Release(const std::string& address) {
  std::lock_guard lock(mutex_);
  auto it = held_.find(address);
  if (it == held_.end()) return;
  if (--it->second <= 0) held_.erase(it);
}

int AddressLimiter::Held(const std::string& address) const {
  std::lock_guard lock(mutex_);
  auto it = held_.find(address);
  return it == held_.end() ? 0 : it->second;
}

}  // namespace reenact::server
