#pragma once
// Per-part texture selection (issue 9): the stored frame for each body part separately,
// instead of one frame for the whole body (thesis Eq. 5).
//
// What a part looks like from a camera depends only on the direction of the ray from the
// camera to the part, seen in the part's own frame, and on the pose of the part and its
// neighbours (the neighbours fix the turn about the part's axis: which side of a forearm
// faces the camera). Both are captured by the offsets of a few joints J(p) -- the part's two
// joints a, b first, then neighbours -- from the part's axis midpoint m, in the part's look
// frame:
//   d_j = L (s_j - m),  L's rows: x = the axis b - a with its component along m removed,
//                       normalised; z = m / |m|; y = z x x
// (camera frame, OpenCV). L turns with the camera, so turning a camera about its centre
// (which moves the part in the image but shows the same surface) leaves every d_j unchanged.
// Per part the cost of stored frame n is Eq. 5 restricted to J(p):
//   cost_p(n) = sum_{j in J(p)} || d*_j - d_{n,j} ||   (missing_joint_cost_m for a joint
//                                                      absent in either skeleton)
// d* from the viewer skeleton in the viewer frame, d_n from stored frame n in its own sensor
// frame. A frame is a candidate for part p only when it has both joints of p and the
// caller's per-part flag allows it (e.g. the skeleton passed the bone check and the part
// lies inside the stored crop). Degenerate frames: m at the camera centre takes z = +z; an
// axis along the ray (or of zero length) takes x from the camera's x axis (its y axis when x
// is along the ray too).
//
// Blending weights (unstructured lumigraph rendering, Buehler et al. 2001): of the top_k
// candidates by cost c_0 <= ... <= c_{k-1}, with c_k the cost of the next-best frame (the
// first one left out), w_i = 1 - c_i / c_k (clamped to >= 0), then normalised to sum 1. A
// candidate's weight falls to zero continuously as it reaches the rank where it drops out,
// so the blend does not pop when the candidate set changes. With no frame left out (fewer
// than top_k + 1 candidates) c_k is taken as twice the largest cost (plus 1 mm). When every
// weight is zero (all costs tie), the candidates share equally.
//
// Hysteresis: frames chosen for the part at the previous output frame (PartSelectionHistory)
// compete with their cost scaled by (1 - hysteresis), so a new frame takes over only when it
// is better by that fraction; weights use the scaled costs too. Costs and descriptors in
// metres; descriptors are computed once per stored frame at construction.
//
// Fallback candidates (issue 9): where none of the top_k candidates sees a point of the part
// (another part in front of it there, or the depth disagrees), the renderer would take the
// first usable one, whose texel there shows the occluder. Given each stored frame's coverage
// of each part (part_coverage.h: the cells of the part's facing half it sees), up to
// fallback_k more frames are appended greedily: each the frame that covers the most cells
// none of the candidates so far covers (ties to the lower cost, then the lower frame index),
// until no frame adds a cell. They carry weight 0, so the renderer's blend never uses them
// where a ranked candidate is visible (common/render/texturing.h); hysteresis applies to
// their costs as to every frame's, and the history keeps only the top_k.

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "common/skeleton/skeleton.h"
#include "common/texture/part_coverage.h"

namespace reenact {

inline constexpr int kMaxPartJoints = 5;  // |J(p)| for every part, at most

// J(p): the joints whose offsets describe part p, the part's own two joints first.
std::span<const Joint> PartDescriptorJoints(BodyPart part);

struct PartSelectionOptions {
  int top_k = 1;                      // candidates returned per part, [1, 8]
  double missing_joint_cost_m = 1.0;  // >= 0, finite
  double hysteresis = 0.0;            // [0, 1): cost discount of the previous frames
  int fallback_k = 0;                 // fallback candidates appended per part, [0, 8]

  void Check() const;
};

struct PartCandidate {
  int frame = -1;     // stored frame index
  double cost = 0;    // cost_p(n), metres, after the hysteresis discount
  double weight = 1;  // blending weight, the part's weights sum to 1
  bool fallback = false;  // a fallback candidate (weight 0), after the top_k
};

using PartCandidates = std::array<std::vector<PartCandidate>, kBodyPartCount>;

// The frames chosen per part at the previous output frame, in rank order.
struct PartSelectionHistory {
  std::array<std::vector<int>, kBodyPartCount> previous;
  void Clear() {
    for (auto& v : previous) v.clear();
  }
};

// The descriptor of part p in a skeleton (camera frame): offsets d_j in J(p) order and the
// mask of present joints; nullopt when either joint of p is missing.
struct PartDescriptor {
  std::array<Eigen::Vector3d, kMaxPartJoints> offset;
  uint8_t present = 0;
};
std::optional<PartDescriptor> DescribePart(BodyPart part, const Skeleton& skeleton_in_camera);

class PartTextureIndex {
 public:
  PartTextureIndex() = default;  // no frame: every query returns nothing

  // stored: skeletons, each in its own sensor frame. part_allowed (if not empty) has one
  // mask per stored frame, bit Index(p) set where the frame may texture part p (frames
  // with mask 0 are never chosen). coverage (if not empty) has one entry per stored frame;
  // without it no fallback is chosen. O(N) time and memory, about 1 kB per frame.
  explicit PartTextureIndex(std::span<const Skeleton> stored,
                            std::span<const uint16_t> part_allowed = {},
                            std::span<const PartCoverages> coverage = {});

  // cost_p(n) of one stored frame for one part; nullopt when n is not a candidate for p or
  // the viewer skeleton lacks one of p's joints.
  std::optional<double> Cost(BodyPart part, const Skeleton& viewer_skeleton, int n,
                             double missing_joint_cost_m = 1.0) const;

  // The top_k candidates of every part by ascending cost (ties to the lower frame index),
  // with weights as above, then its fallback candidates (weight 0, fallback set). A part
  // the viewer skeleton lacks (either joint missing) or that no frame can texture gets no
  // candidates. history (if not null) gives the previous
  // frames for the hysteresis and receives this call's choice. O(N |J(p)|) per part.
  PartCandidates Select(const Skeleton& viewer_skeleton, const PartSelectionOptions& options,
                        PartSelectionHistory* history = nullptr) const;

  int stored_count() const { return stored_count_; }

 private:
  struct Row {
    int frame = -1;
    PartDescriptor descriptor;
    PartCoverage coverage = 0;
  };
  void AppendFallbacks(int p, int fallback_k, std::span<const PartCandidate> scored,
                       std::vector<PartCandidate>& chosen) const;
  int stored_count_ = 0;
  std::array<std::vector<Row>, kBodyPartCount> rows_;  // per part, candidates only
};

}  // namespace reenact
