#include "capture-client/tracker/uncross_step.h"

#include "common/error/check.h"

namespace reenact::capture {

void UncrossOptions::Check() const { REENACT_CHECK(gain >= 0 && gain < 1, "gain in [0, 1)"); }

UncrossStep::UncrossStep(LimbPair pair, const UncrossOptions& options)
    : pair_(pair), options_(options) {
  options.Check();
}

std::string_view UncrossStep::name() const {
  return pair_.left == kArms.left ? "uncross-arms" : "uncross-legs";
}

AcceptanceRule UncrossStep::rule() const {
  AcceptanceRule rule;
  rule.cost_ratio = 1 - options_.gain;
  return rule;
}

std::vector<Candidate> UncrossStep::Propose(const StepFrame& frame, const BodyFitResult& current) {
  const ArticulatedBody& body = frame.fitter.body();
  const JointLimits& limits = frame.fitter.options().limits;
  if (!LimbsCrossed(body, current.posed, pair_)) return {};
  std::vector<ArticulatedPose> starts = {SwappedLimbs(body, current.pose, pair_, limits)};
  if (options_.return_limb && pair_.left == kArms.left &&
      !LimbsCrossed(body, body.Pose(frame.prediction), pair_))
    for (const Limb taker : {pair_.left, pair_.right})
      starts.push_back(ReturnedLimb(body, current.pose, frame.prediction, pair_, taker, limits));
  std::optional<BodyFitResult> best;
  for (const ArticulatedPose& start : starts) {
    BodyFitResult r = frame.fitter.Fit(start, frame.observation);
    if (!best || r.cost < best->cost) best = std::move(r);
  }
  return {{std::move(*best)}};
}

}  // namespace reenact::capture
