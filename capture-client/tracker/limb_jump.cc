#include "capture-client/tracker/limb_jump.h"

#include <cmath>

#include "capture-client/tracker/extremity_pose.h"
#include "common/error/check.h"

namespace reenact::capture {
namespace {

// The same limb on the body's other side (Limb's order: left arm, right arm, left leg, right
// leg).
Limb OtherSide(Limb limb) { return static_cast<Limb>(static_cast<int>(limb) ^ 1); }

}  // namespace

void LimbJumpOptions::Check() const {
  REENACT_CHECK(max_move_m > 0 && std::isfinite(max_move_m), "limb jump max_move_m must be > 0");
  REENACT_CHECK(in_view_share >= 0 && in_view_share <= 1 && kept_share >= 0 && kept_share <= 1 &&
                    swap_share >= 0 && swap_share <= 1,
                "limb jump in_view_share, kept_share and swap_share must be in [0, 1]");
}

std::optional<Limb> LimbJumpedFromItsData(const ArticulatedBody& body, const BodyFitResult& own,
                                          const BodyFitResult& other,
                                          const LimbJumpOptions& options) {
  options.Check();
  for (int l = 0; l < kLimbCount; ++l) {
    const Limb limb = static_cast<Limb>(l);
    const int end = static_cast<int>(LimbLower(limb));
    const int seen = own.support[end];
    if (seen == 0 || seen < options.in_view_share * own.expected_support[end]) continue;
    const double move = (LimbEnd(body, other.posed, limb) - LimbEnd(body, own.posed, limb)).norm();
    if (!(move > options.max_move_m) || other.support[end] >= options.kept_share * seen) continue;
    const int opposite = static_cast<int>(LimbLower(OtherSide(limb)));
    const int taken = other.support[opposite] - own.support[opposite];
    if (taken < options.swap_share * (seen - other.support[end])) return limb;
  }
  return std::nullopt;
}

}  // namespace reenact::capture
