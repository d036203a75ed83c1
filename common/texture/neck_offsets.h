#pragma once
// The vector that texture selection (thesis Eq. 5) compares: a skeleton's 15 non-neck joints
// as offsets from its neck, o_i = s_i - s_neck, flattened to kNeckOffsetDims doubles in
// "slot" order (slot j holds joint j before the neck and joint j + 1 after it, i.e. the
// joint order of TextureSelectionCost's sum, where the neck itself adds an exact 0), with a
// mask of the slots whose joint is present. The indexes over long clips store frames in this
// form and score them with NeckOffsetCost, which repeats TextureSelectionCost's arithmetic
// operation for operation, so that their costs equal the scan's bit for bit.

#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "common/skeleton/skeleton.h"

namespace reenact {

inline constexpr int kNeckOffsetSlots = kJointCount - 1;
inline constexpr int kNeckOffsetDims = 3 * kNeckOffsetSlots;

// The joint stored in slot j (0 <= j < kNeckOffsetSlots).
constexpr int JointOfNeckOffsetSlot(int j) { return j < Index(Joint::kNeck) ? j : j + 1; }

// Writes the skeleton's offsets to out[0, kNeckOffsetDims) (zero for missing joints) and
// returns the mask of present slots (bit j). Precondition: the skeleton has a neck.
uint16_t WriteNeckOffsets(const Skeleton& skeleton, double* out);

// Eq. 5 between two offset vectors: sum over slots of |q_j - o_j| where both are present,
// missing_cost otherwise. Stops adding once the sum exceeds `limit` and returns that partial
// sum (then only "above limit" is meaningful).
double NeckOffsetCost(const double* q, uint16_t q_present, const double* o, uint16_t o_present,
                      double missing_cost, double limit = std::numeric_limits<double>::infinity());

// The stored frames an index holds, in stored order: those flagged usable (all when usable is
// empty) that have a neck (the others cannot be scored), as rows of neck offsets.
struct NeckOffsetTable {
  std::vector<int> frame;         // row -> stored frame index
  std::vector<double> offset;     // kNeckOffsetDims per row
  std::vector<uint16_t> present;  // row -> mask of present slots
};

// Throws CheckError unless usable is empty or has one flag per stored skeleton, or when there
// are INT_MAX skeletons or more.
NeckOffsetTable MakeNeckOffsetTable(std::span<const Skeleton> stored, std::span<const bool> usable);

}  // namespace reenact
