#pragma once
// Connections held per client address, against a per-address cap, so that one address cannot
// take every connection slot of the server. Thread-safe; memory is one entry per address with
// a connection open.

#include <cstddef>
#include <mutex>
#include <string>
#include <unordered_map>

namespace reenact::server {

class AddressLimiter {
 public:
  // per_address: connections one address may hold at once; 0 = no limit.
  explicit AddressLimiter(int per_address) : per_address_(per_address) {}

  // Counts one more connection from `address`; false (nothing counted) when it already
  // holds per_address of them.
  bool Acquire(const std::string& address);
  // Forgets one connection of `address` that Acquire counted.
  void Release(const std::string& address);
  // Connections `address` holds now.
  int Held(const std::string& address) const;

 private:
  const int per_address_;
  mutable std::mutex mutex_;
  std::unordered_map<std::string, int> held_;
};

}  // namespace reenact::server
