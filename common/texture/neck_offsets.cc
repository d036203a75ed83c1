#include "common/texture/neck_offsets.h"

#include "common/error/check.h"

namespace reenact {

uint16_t WriteNeckOffsets(const Skeleton& s, double* out) {
  REENACT_CHECK(s.Has(Joint::kNeck), "WriteNeckOffsets needs a skeleton with a neck");
  uint16_t mask = 0;
  for (int j = 0; j < kNeckOffsetSlots; ++j) {
    const int i = JointOfNeckOffsetSlot(j);
    const bool has = s.confidence[i] > 0;
    const Eigen::Vector3d o =
        has ? Eigen::Vector3d(s.position[i] - s[Joint::kNeck]) : Eigen::Vector3d::Zero();
    if (has) mask |= static_cast<uint16_t>(1u << j);
    out[3 * j] = o.x();
    out[3 * j + 1] = o.y();
    out[3 * j + 2] = o.z();
  }
  return mask;
}

double NeckOffsetCost(const double* q, uint16_t q_present, const double* o, uint16_t o_present,
                      double missing_cost, double limit) {
  const uint16_t both = q_present & o_present;
  double cost = 0;
  for (int j = 0; j < kNeckOffsetSlots && cost <= limit; ++j) {
    if (both & (1u << j))
      cost += (Eigen::Map<const Eigen::Vector3d>(&q[3 * j]) -
               Eigen::Map<const Eigen::Vector3d>(&o[3 * j]))
                  .norm();
    else
      cost += missing_cost;
  }
  return cost;
}

NeckOffsetTable MakeNeckOffsetTable(std::span<const Skeleton> stored,
                                    std::span<const bool> usable) {
  REENACT_CHECK(usable.empty() || usable.size() == stored.size(),
                "usable must be empty or one flag per stored skeleton");
  REENACT_CHECK(stored.size() < static_cast<size_t>(std::numeric_limits<int>::max()),
                "too many stored skeletons");
  NeckOffsetTable table;
  for (size_t n = 0; n < stored.size(); ++n) {
    if ((!usable.empty() && !usable[n]) || !stored[n].Has(Joint::kNeck)) continue;
    table.frame.push_back(static_cast<int>(n));
    table.offset.resize(table.offset.size() + kNeckOffsetDims);
    table.present.push_back(
        WriteNeckOffsets(stored[n], &table.offset[table.offset.size() - kNeckOffsetDims]));
  }
  return table;
}

}  // namespace reenact
