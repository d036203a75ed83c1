#include "capture-client/tracker/hanging_arm.h"

#include <numbers>
#include <optional>

#include "common/error/check.h"

namespace reenact::capture {

void HangingArmOptions::Check() const {
  REENACT_CHECK(min_support >= 0 && min_support <= 1, "min_support must be in [0, 1]");
  REENACT_CHECK(swing_rad >= 0 && elbow_rad >= 0 && elbow_rad < std::numbers::pi,
                "need swing_rad >= 0 and elbow_rad in [0, pi)");
  REENACT_CHECK(gain >= 0 && gain < 1, "gain must be in [0, 1)");
  REENACT_CHECK(max_other_move_m > 0, "max_other_move_m must be > 0");
}

std::vector<ArticulatedPose> HangingArmStarts(const ArticulatedPose& pose, Limb arm,
                                              const JointLimits& limits,
                                              const HangingArmOptions& options) {
  options.Check();
  REENACT_CHECK(arm == Limb::kLeftArm || arm == Limb::kRightArm, "an arm, not a leg");
  const int upper = static_cast<int>(LimbUpper(arm)), lower = static_cast<int>(LimbLower(arm));
  std::vector<ArticulatedPose> starts;
  for (const double swing : {-options.swing_rad, 0.0, options.swing_rad}) {
    ArticulatedPose start = pose;
    start.local[upper] = ExpRotation(Eigen::Vector3d(0, swing, 0));
    start.hinge_angle[lower] = options.elbow_rad;
    ArticulatedBody::Clamp(&start, limits);
    starts.push_back(start);
  }
  return starts;
}

BodyFitResult HangUnsupportedArms(const ArticulatedBody& body, BodyFitResult fit,
                                  const BodyObservation& observation,
                                  const BodyFitOptions& fit_options, const JointLimits& limits,
                                  const HangingArmOptions& options) {
  options.Check();
  if (options.min_support <= 0) return fit;
  for (const Limb arm : {Limb::kLeftArm, Limb::kRightArm}) {
    const int upper = static_cast<int>(LimbUpper(arm)), lower = static_cast<int>(LimbLower(arm));
    const double expected = fit.expected_support[upper] + fit.expected_support[lower];
    if (expected <= 0 || fit.support[upper] + fit.support[lower] >= options.min_support * expected)
      continue;
    std::optional<BodyFitResult> best;
    for (const ArticulatedPose& start : HangingArmStarts(fit.pose, arm, limits, options)) {
      BodyFitResult r = FitBody(body, start, observation, fit_options, limits);
      if (!LimbEndsMoved(r.posed, fit.posed, arm, options.max_other_move_m) &&
          (!best || r.cost < best->cost))
        best = std::move(r);
    }
    if (best && CostWithLostPoints(*best, fit_options) <=
                    (1 - options.gain) * CostWithLostPoints(fit, fit_options))
      fit = std::move(*best);
  }
  return fit;
}

}  // namespace reenact::capture
