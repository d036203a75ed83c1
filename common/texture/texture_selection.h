#pragma once
// Texture selection (thesis Eq. 5): the stored frame whose skeleton, as its own sensor saw it,
// best matches the skeleton as the viewer sees it, both made neck-relative:
//   cost(n) = sum_i || (s*_{k,i} - s*_{k,neck}) - (s_{n,i} - s_{n,neck}) ||
//   n_bar = argmin_n cost(n)
// s*_k = M* S'_k is the output frame's skeleton in the viewer camera frame; s_n = M_n S'_n is
// stored frame n's skeleton in its own sensor frame. The cost mixes pose and viewpoint.
// Joints missing in either skeleton add missing_joint_cost_m instead of a distance, so frames
// with partial skeletons compare fairly; a frame without a neck cannot be scored.

#include <span>
#include <vector>

#include "common/skeleton/skeleton.h"

namespace reenact {

struct TextureSelectionOptions {
  int top_k = 1;                      // how many ranked candidates to return, >= 1
  double missing_joint_cost_m = 1.0;  // cost of a joint absent in either skeleton, >= 0

  void Check() const;
};

struct TextureCandidate {
  int frame = -1;   // index into the stored skeletons
  double cost = 0;  // Eq. 5, metres
};

// Eq. 5 for one pair of skeletons; nullopt if either has no neck.
std::optional<double> TextureSelectionCost(const Skeleton& viewer_skeleton,
                                           const Skeleton& stored_skeleton,
                                           double missing_joint_cost_m = 1.0);

// The top_k stored frames by ascending cost, ties broken by the lower frame index. usable (if
// not empty) marks frames that may be chosen (e.g. skeletons that passed the bone check).
// Empty when no frame can be scored.
std::vector<TextureCandidate> RankTextureFrames(const Skeleton& viewer_skeleton,
                                                std::span<const Skeleton> stored_skeletons,
                                                const TextureSelectionOptions& options = {},
                                                std::span<const bool> usable = {});

}  // namespace reenact
