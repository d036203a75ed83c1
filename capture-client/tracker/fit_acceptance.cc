#include "capture-client/tracker/fit_acceptance.h"

#include <cmath>

#include "common/error/check.h"

namespace reenact::capture {

bool GoodFitCriteria::Good(const BodyFitResult& fit) const {
  return fit.points > 0 && fit.inlier_share >= min_inlier_share && fit.coverage >= min_coverage;
}

void GoodFitCriteria::Check() const {
  REENACT_CHECK(min_inlier_share > 0 && min_inlier_share <= 1, "min_inlier_share in (0, 1]");
  REENACT_CHECK(min_coverage > 0 && min_coverage <= 1, "min_coverage in (0, 1]");
}

void AcceptanceRule::Check() const {
  REENACT_CHECK(cost_ratio > 0 && std::isfinite(cost_ratio), "cost_ratio must be > 0");
  REENACT_CHECK(lost_points_ratio >= 0 && lost_points_ratio <= 1, "lost_points_ratio in [0, 1]");
  if (refuse_limb_jumps) refuse_limb_jumps->Check();
}

bool Accepts(const AcceptanceRule& rule, const BodyFitResult& candidate,
             const BodyFitResult& current, const AcceptanceContext& context) {
  if (rule.require_good && !context.good.Good(candidate)) return false;
  if (rule.refuse_limb_jumps &&
      LimbJumpedFromItsData(context.body, context.input, candidate, *rule.refuse_limb_jumps))
    return false;
  const auto lost = [&](const BodyFitResult& f) { return CostWithLostPoints(f, context.fit); };
  if (rule.lost_points_ratio > 0 && lost(candidate) <= rule.lost_points_ratio * lost(current))
    return true;
  return candidate.cost < rule.cost_ratio * current.cost &&
         (!rule.also_with_lost_points || lost(candidate) < lost(current));
}

}  // namespace reenact::capture
