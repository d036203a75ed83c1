#include "common/texture/texture_selection.h"

#include <algorithm>
#include <cmath>

#include "common/error/check.h"

namespace reenact {

void TextureSelectionOptions::Check() const {
  REENACT_CHECK(top_k >= 1, "top_k must be >= 1");
  REENACT_CHECK(std::isfinite(missing_joint_cost_m) && missing_joint_cost_m >= 0,
                "missing_joint_cost_m must be finite and >= 0");
}

std::optional<double> TextureSelectionCost(const Skeleton& viewer, const Skeleton& stored,
                                           double missing_joint_cost_m) {
  if (!viewer.Has(Joint::kNeck) || !stored.Has(Joint::kNeck)) return std::nullopt;
  const Eigen::Vector3d& vn = viewer[Joint::kNeck];
  const Eigen::Vector3d& sn = stored[Joint::kNeck];
  double cost = 0;
  for (int i = 0; i < kJointCount; ++i) {
    if (viewer.confidence[i] > 0 && stored.confidence[i] > 0)
      cost += ((viewer.position[i] - vn) - (stored.position[i] - sn)).norm();
    else
      cost += missing_joint_cost_m;
  }
  return cost;
}

std::vector<TextureCandidate> RankTextureFrames(const Skeleton& viewer_skeleton,
                                                std::span<const Skeleton> stored,
                                                const TextureSelectionOptions& options,
                                                std::span<const bool> usable) {
  options.Check();
  REENACT_CHECK(usable.empty() || usable.size() == stored.size(),
                "usable must be empty or one flag per stored skeleton");
  std::vector<TextureCandidate> all;
  all.reserve(stored.size());
  for (size_t n = 0; n < stored.size(); ++n) {
    if (!usable.empty() && !usable[n]) continue;
    if (auto cost = TextureSelectionCost(viewer_skeleton, stored[n], options.missing_joint_cost_m))
      all.push_back({static_cast<int>(n), *cost});
  }
  const size_t k = std::min(all.size(), static_cast<size_t>(options.top_k));
  auto less = [](const TextureCandidate& x, const TextureCandidate& y) {
    return x.cost < y.cost || (x.cost == y.cost && x.frame < y.frame);
  };
  std::partial_sort(all.begin(), all.begin() + k, all.end(), less);
  all.resize(k);
  return all;
}

}  // namespace reenact
