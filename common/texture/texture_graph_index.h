#pragma once
// An approximate index for texture selection (thesis Eq. 5) on long clips: a hierarchical
// navigable small-world graph (HNSW: Malkov and Yashunin, IEEE TPAMI 42(4), 2020) over the
// stored frames under the Eq. 5 cost itself (neck_offsets.h), which needs no metric.
//
// Build: frames are inserted in stored order; each gets a level L = floor(-ln(u) / ln(M)) from
// a seeded generator (u uniform in (0, 1]), is linked on layers 0..L to at most M (2M on
// layer 0) neighbours found by a beam search of width build_beam, chosen by the HNSW
// diversity heuristic (a candidate is kept only if it is nearer to the new frame than to
// every neighbour kept so far), and over-full neighbour lists are pruned by the same rule.
// Deterministic for a given input and seed. Costs during build and search use single
// precision in a padded structure-of-arrays layout (192 bytes a frame). Finally every frame
// that the bottom layer cannot reach from the entry point (the pruning can drop a frame's
// last in-link) is linked from the nearest reached frame with a free repair slot.
//
// Query: greedy descent through the upper layers, then a beam search of width `beam` on
// layer 0; the beam's frames are re-scored with the double arithmetic of
// TextureSelectionCost and the top_k of them returned, ranked as RankTextureFrames ranks
// (ascending cost, ties to the lower frame index). Returned costs are exact; the returned
// frames are the true top_k with high probability, not always (reenact-bench core measures
// recall@1 and the cost excess against the scan). With beam >= indexed_count() the search
// visits every frame (after the build, every frame is made reachable from the entry on layer
// 0, and the search starts from the entry too), so the answer equals the scan's.
// For answers that must be exact, use TextureIndex (texture_index.h) or RankTextureFrames.
//
// Frames without a neck (unscorable) and frames flagged unusable are left out at build time.
// Memory: about 192 + 360 + 4 (2M + 3) bytes a frame (single, double, links): 692 with M = 16.

#include <cstdint>
#include <span>
#include <vector>

#include "common/skeleton/skeleton.h"
#include "common/texture/neck_offsets.h"
#include "common/texture/texture_selection.h"

namespace reenact {

struct TextureGraphIndexOptions {
  int max_neighbors = 16;             // M, >= 2: links a frame keeps per upper layer (2M on 0)
  int build_beam = 128;               // beam width while inserting, >= max_neighbors
  double missing_joint_cost_m = 1.0;  // cost of a missing joint while building, >= 0
  uint64_t seed = 1;                  // for the level draws

  void Check() const;
};

struct TextureGraphSearch {
  int beam = 48;  // candidates kept on layer 0 (ef), >= 1; at least top_k are kept

  void Check() const;
};

class TextureGraphIndex {
 public:
  // An empty index (no frame): every query returns nothing.
  TextureGraphIndex() = default;

  // Indexes stored skeletons (each in its own sensor frame); usable (if not empty) has one
  // flag per stored skeleton, as in RankTextureFrames. Cost O(N log N) cost evaluations
  // times about build_beam * M; the index keeps no reference to `stored`.
  explicit TextureGraphIndex(std::span<const Skeleton> stored, std::span<const bool> usable = {},
                             const TextureGraphIndexOptions& options = {});

  // The top_k frames by ascending Eq. 5 cost among those the search reached (see above);
  // empty if no frame can be scored or the viewer lacks a neck. Safe to call from several
  // threads at once.
  std::vector<TextureCandidate> Rank(const Skeleton& viewer_skeleton,
                                     const TextureSelectionOptions& options = {},
                                     const TextureGraphSearch& search = {}) const;

  int stored_count() const { return stored_count_; }
  int indexed_count() const { return static_cast<int>(frame_.size()); }
  int top_level() const { return top_level_; }

 private:
  struct alignas(64) Point {  // single-precision offsets, slot 15 a zero pad
    float x[16], y[16], z[16];
  };
  struct Found {
    float cost;
    int node;
    bool operator<(const Found& o) const {
      return cost < o.cost || (cost == o.cost && node < o.node);
    }
    bool operator>(const Found& o) const { return o < *this; }
  };
  class Visited;

  static Point ToPoint(const double* offsets);
  void Insert(int node, int level, int build_beam, Visited& visited);
  // The beam search of one layer from `entry`: up to `beam` nodes, nearest first.
  std::vector<Found> SearchLayer(const Point& q, uint16_t q_mask, float missing_cost,
                                 std::span<const Found> entries, int layer, int beam,
                                 Visited& visited) const;
  // Links every frame that the bottom layer cannot reach from the entry (the diversity
  // pruning can drop a frame's last in-link) from a reached frame near it.
  void ConnectUnreachable(int build_beam, Visited& visited);
  int Links0Stride() const;
  Found Descend(const Point& q, uint16_t q_mask, float missing_cost, int to_layer) const;
  // The HNSW diversity heuristic over candidates carrying their cost to one base node.
  std::vector<int> SelectNeighbors(std::vector<Found> candidates, int count) const;
  float Cost(int a, int b) const;
  std::span<const int> Links(int node, int layer) const;
  void SetLinks(int node, int layer, std::span<const int> links);

  int stored_count_ = 0;
  int max_neighbors_ = 16;
  float build_missing_cost_ = 1;
  int entry_ = -1;
  int top_level_ = -1;
  std::vector<int> frame_;               // node -> stored frame index
  std::vector<Point> point_;             // node -> single-precision offsets
  std::vector<uint16_t> present_;        // node -> present slots (bit 15, the pad, set)
  std::vector<double> offset_;           // node -> kNeckOffsetDims exact offsets
  std::vector<int> links0_;              // node -> [count, 2M + 2 links] on layer 0
  std::vector<std::vector<int>> upper_;  // node -> per layer >= 1: [count, M links]
};

}  // namespace reenact
