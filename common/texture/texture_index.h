#pragma once
// A sublinear, exact index for texture selection (thesis Eq. 5) over long clips.
//
// Eq. 5 ranks stored frames n by
//   cost(n) = sum_i c_i(n),  c_i(n) = || q_i - o_{n,i} ||  if joint i is present in both,
//                                     missing_joint_cost_m  otherwise,
// with q_i = s*_{k,i} - s*_{k,neck} (the viewer skeleton, neck-relative, viewer frame) and
// o_{n,i} = s_{n,i} - s_{n,neck} (stored frame n, neck-relative, its own sensor frame): an
// L2,1 distance on the 45-dim vector of the 15 non-neck offsets.
//
// The index is a binary tree over the frames (each node split in halves by the two far
// frames a and b of the node under the L2,1 cost: the half nearer to a, the half nearer to
// b). Each node keeps, per joint i, the 3D axis-aligned box of its frames' offsets o_i (over
// frames that have the joint), their mean c_i and largest distance r_i from it, whether any
// frame lacks the joint, and R = max over its frames of sum_i |o_i - c_i|. For a query, every
// frame below a node costs at least
//   LB = sum_i lb_i,  d_i = max(dist(q_i, box_i), |q_i - c_i| - r_i),
//        lb_i = d_i (all frames have joint i), min(d_i, m) (some frames lack it),
//               m (no frame has it, or the query lacks it)
// because each term of the sum is bounded separately; this holds with missing joints, where
// the cost is not a metric (a missing joint costs m even against itself). When no frame of
// the node lacks a joint the cost is a metric (L2,1) over the query's joints, and the
// triangle inequality adds LB >= sum_i |q_i - c_i| - R + m * (joints the query lacks). Best-first
// search visits nodes in ascending LB and stops when LB exceeds the k-th best cost so far; leaf
// costs are computed with the same arithmetic, in the same joint order, as TextureSelectionCost, so
// the result equals RankTextureFrames bit for bit: same frames, same costs, ties broken by the
// lower frame index. Pruning keeps a margin of 1e-9 relative (far above the rounding of a 16-term
// sum) so rounding never drops a frame.
//
// Frames without a neck (unscorable) and frames flagged unusable are left out at build time.
// For an approximate answer in far less time on long clips, see texture_graph_index.h.
// missing_joint_cost_m and top_k are per query, as in RankTextureFrames.
// Memory: 362 bytes per indexed frame plus about 1.3 kB per tree node (2 N / leaf_size of
// them), about 440 bytes per frame with the default leaf size.

#include <cstdint>
#include <span>
#include <vector>

#include "common/skeleton/skeleton.h"
#include "common/texture/neck_offsets.h"
#include "common/texture/texture_selection.h"

namespace reenact {

// What one query did: a measure of pruning (a scan evaluates every indexed frame).
struct TextureIndexStats {
  int64_t frames_evaluated = 0;  // frames whose cost was computed (some only partly)
  int64_t nodes_visited = 0;     // tree nodes taken from the search queue
};

struct TextureIndexOptions {
  int leaf_size = 32;  // frames per leaf at most, >= 1; smaller prunes finer, costs more nodes

  void Check() const;
};

class TextureIndex {
 public:
  // An empty index (no frame): every query returns nothing.
  TextureIndex() = default;

  // Indexes stored skeletons (each in its own sensor frame). usable (if not empty) has one
  // flag per stored skeleton and marks those that may be chosen, as in RankTextureFrames.
  // Cost O(N log N); the index copies what it needs and does not refer to `stored` later.
  explicit TextureIndex(std::span<const Skeleton> stored, std::span<const bool> usable = {},
                        const TextureIndexOptions& options = {});

  // Exactly RankTextureFrames(viewer_skeleton, stored, options, usable) for the stored
  // skeletons and usable flags given at build time: the top_k frames by ascending Eq. 5 cost,
  // ties to the lower frame index; empty if no frame can be scored or the viewer lacks a neck.
  // stats (if not null) receives what the query did. Safe to call from several threads at once.
  std::vector<TextureCandidate> Rank(const Skeleton& viewer_skeleton,
                                     const TextureSelectionOptions& options = {},
                                     TextureIndexStats* stats = nullptr) const;

  int stored_count() const { return stored_count_; }  // skeletons given at build time
  int indexed_count() const { return static_cast<int>(frame_.size()); }  // scorable and usable
  int node_count() const { return static_cast<int>(nodes_.size()); }

 private:
  static constexpr int kOffsets = kNeckOffsetSlots;
  static constexpr int kDims = kNeckOffsetDims;

  struct Node {
    int begin = 0, end = 0;       // range in tree order
    int left = -1, right = -1;    // children, -1 for a leaf
    uint16_t present_mask = 0;    // bit j: some frame has offset joint j
    uint16_t missing_mask = 0;    // bit j: some frame lacks offset joint j
    double lo[kDims], hi[kDims];  // per-joint boxes of the present offsets
    double centre[kDims];         // per-joint mean of the present offsets
    double radius[kOffsets];      // per joint: max distance of a present offset to centre
    double ball_radius;           // max over frames of sum_j |o_j - centre_j| (present j)
  };

  int Build(int begin, int end, int leaf_size);
  // Fills a node's masks, boxes, centre and radii from the frames in [begin, end).
  void FitNode(Node& node, int begin, int end) const;
  // Reorders [begin, end) by the two far frames a and b (a farthest from `centre`, b farthest
  // from a): [begin, mid) the half nearer to a, [mid, end) the half nearer to b, which follows
  // the data's shape. False, leaving the order, when all frames are identical.
  bool SplitAt(int begin, int mid, int end, const double* centre);
  // Puts the frames, offsets and masks of tree positions order[r] at begin + r.
  void Permute(int begin, const std::vector<int>& order);
  static double LowerBound(const Node& node, const double* query, uint16_t query_mask,
                           double missing_cost);

  int stored_count_ = 0;
  std::vector<int> frame_;         // tree order -> stored frame index
  std::vector<double> offset_;     // tree order, kDims per frame: o_{n,i}, 0 when missing
  std::vector<uint16_t> present_;  // tree order, bit j: offset joint j present
  std::vector<Node> nodes_;        // nodes_[0] is the root when not empty
};

}  // namespace reenact
