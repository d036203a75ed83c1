#include "server/http/transfer_deadline.h"

#include <algorithm>

namespace reenact::server {

SteadyTime TransferDeadline(SteadyTime start, uint64_t done, const MinRate& rate,
                            std::chrono::milliseconds cap) {
  const SteadyTime latest = start + cap;
  if (rate.bytes_per_s <= 0) return latest;
  const double allowed_s = static_cast<double>(done) / rate.bytes_per_s;
  const double cap_s = std::chrono::duration<double>(cap).count();
  if (allowed_s >= cap_s) return latest;
  const auto allowed = std::chrono::duration_cast<SteadyTime::duration>(
      std::chrono::duration<double>(allowed_s));
  return std::min(latest, start + rate.grace + allowed);
}

}  // namespace reenact::server
