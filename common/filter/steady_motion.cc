#include "common/filter/steady_motion.h"

#include <algorithm>
#include <cmath>

#include "common/error/check.h"

namespace reenact {
namespace {

void CheckTrack(std::span<const Skeleton> skeletons, std::span<const double> times_s,
                std::span<const bool> flagged) {
  REENACT_CHECK(skeletons.size() == times_s.size() && skeletons.size() == flagged.size(),
                "skeletons, times and flags must have one size");
  for (double t : times_s) REENACT_CHECK(std::isfinite(t), "times must be finite");
}

Skeleton Between(const Skeleton& a, const Skeleton& b, double w) {
  Skeleton out;
  for (int j = 0; j < kJointCount; ++j) {
    const bool in_a = a.confidence[j] > 0, in_b = b.confidence[j] > 0;
    if (in_a && in_b) {
      out.position[j] = a.position[j] + w * (b.position[j] - a.position[j]);
      out.confidence[j] = std::min(a.confidence[j], b.confidence[j]);
    } else if (in_a || in_b) {
      out.position[j] = in_a ? a.position[j] : b.position[j];
      out.confidence[j] = in_a ? a.confidence[j] : b.confidence[j];
    }
  }
  return out;
}

// One sample of every joint's filter; a missing joint restarts its filter.
void FilterJoints(std::vector<OneEuroFilter3>& filters, Skeleton& skeleton, double t_s) {
  for (int j = 0; j < kJointCount; ++j) {
    if (skeleton.confidence[j] > 0)
      skeleton.position[j] = filters[j].Filter(skeleton.position[j], t_s);
    else
      filters[j].Reset();
  }
}

}  // namespace

std::vector<Skeleton> InterpolateFlaggedSkeletons(std::span<const Skeleton> skeletons,
                                                  std::span<const double> times_s,
                                                  std::span<const bool> flagged) {
  CheckTrack(skeletons, times_s, flagged);
  std::vector<Skeleton> out(skeletons.begin(), skeletons.end());
  const int count = static_cast<int>(out.size());
  std::vector<int> kept;
  for (int n = 0; n < count; ++n)
    if (!flagged[n]) kept.push_back(n);
  if (kept.empty()) return out;
  for (int n = 0; n < count; ++n) {
    if (!flagged[n]) continue;
    const auto next = std::lower_bound(kept.begin(), kept.end(), n);
    if (next == kept.begin()) {
      out[n] = skeletons[kept.front()];
    } else if (next == kept.end()) {
      out[n] = skeletons[kept.back()];
    } else {
      const int p = *(next - 1), q = *next;
      const double dt = times_s[q] - times_s[p];
      const double w = dt > 0 ? std::clamp((times_s[n] - times_s[p]) / dt, 0.0, 1.0)
                              : static_cast<double>(n - p) / (q - p);
      out[n] = Between(skeletons[p], skeletons[q], w);
    }
  }
  return out;
}

std::vector<Skeleton> SteadySkeletonTrack(std::span<const Skeleton> skeletons,
                                          std::span<const double> times_s,
                                          std::span<const bool> flagged,
                                          const SteadyMotionOptions& options) {
  options.Check();
  CheckTrack(skeletons, times_s, flagged);
  std::vector<Skeleton> out = options.interpolate_flagged
                                  ? InterpolateFlaggedSkeletons(skeletons, times_s, flagged)
                                  : std::vector<Skeleton>(skeletons.begin(), skeletons.end());
  if (!options.filter) return out;
  const int count = static_cast<int>(out.size());
  std::vector<OneEuroFilter3> filters(kJointCount, OneEuroFilter3(options.one_euro));
  for (int n = 0; n < count; ++n) FilterJoints(filters, out[n], times_s[n]);
  if (!options.zero_phase) return out;
  for (OneEuroFilter3& f : filters) f.Reset();
  for (int n = count - 1; n >= 0; --n) FilterJoints(filters, out[n], -times_s[n]);
  return out;
}

}  // namespace reenact
