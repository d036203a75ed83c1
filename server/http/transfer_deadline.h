#pragma once
// The deadline of the next read or write of a transfer that must keep a minimum average rate:
// a transfer that began at `start` must have moved `bytes_per_s * (t - start - grace)` bytes
// by time t, and may never run past `start + cap`. So a slow sender (or reader) is cut off
// within seconds of falling behind, while a fast one is never hurried.

#include <chrono>
#include <cstdint>

namespace reenact::server {

struct MinRate {
  // Required average bytes per second after the grace; >= 0, 0 = no rate rule (cap only).
  double bytes_per_s = 0.0;
  // Time before the rate applies (a round trip, a slow start); >= 0.
  std::chrono::milliseconds grace{0};
};

using SteadyTime = std::chrono::steady_clock::time_point;

// The time by which more than `done` bytes must have moved: start + grace + done / rate,
// and never later than start + cap (cap > 0).
SteadyTime TransferDeadline(SteadyTime start, uint64_t done, const MinRate& rate,
                            std::chrono::milliseconds cap);

}  // namespace reenact::server
