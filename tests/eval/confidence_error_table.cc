#include "tests/eval/confidence_error_table.h"

#include <algorithm>
#include <cmath>

#include "common/error/check.h"

namespace reenact::eval {

int ConfidenceErrorTable::Bin(double confidence) {
  const double c = confidence >= 0 ? std::min(confidence, 1.0) : 0.0;  // NaN: the lowest
  return std::min(static_cast<int>(c * kConfidenceBinCount), kConfidenceBinCount - 1);
}

std::string_view ConfidenceErrorTable::BinName(int bin) {
  static constexpr std::array<std::string_view, kConfidenceBinCount> kNames = {
      "0-0.25", "0.25-0.5", "0.5-0.75", "0.75-1"};
  REENACT_CHECK(bin >= 0 && bin < kConfidenceBinCount, "confidence bin out of range");
  return kNames[bin];
}

void ConfidenceErrorTable::Add(const Skeleton& estimate, const Skeleton& truth) {
  for (int j = 0; j < kJointCount; ++j) {
    const Joint joint = static_cast<Joint>(j);
    if (!estimate.Has(joint) || !truth.Has(joint)) continue;
    const double e = (estimate[joint] - truth[joint]).norm();
    if (!std::isfinite(e)) continue;
    Sum& s = sums_[Bin(estimate.confidence[j])];
    ++s.n;
    s.gross += e > kGrossErrorM;
    s.error_m += e;
  }
}

std::array<ConfidenceBinStats, kConfidenceBinCount> ConfidenceErrorTable::Stats() const {
  int total = 0;
  for (const Sum& s : sums_) total += s.n;
  std::array<ConfidenceBinStats, kConfidenceBinCount> out;
  for (int b = 0; b < kConfidenceBinCount; ++b) {
    const Sum& s = sums_[b];
    if (s.n == 0) continue;
    out[b].n = s.n;
    out[b].share = static_cast<double>(s.n) / total;
    out[b].mean_cm = 100 * s.error_m / s.n;
    out[b].gross_share = static_cast<double>(s.gross) / s.n;
  }
  return out;
}

}  // namespace reenact::eval
