#include "capture-client/tracker/body_fitter.h"

#include "common/error/check.h"

namespace reenact::capture {

void BodyFitterOptions::Check() const {
  fit.Check();
  limb_search.Check();
  REENACT_CHECK(limb_search_trigger >= 0 && limb_search_trigger <= 1,
                "limb_search_trigger in [0, 1]");
  REENACT_CHECK(limb_search_gain >= 0 && limb_search_gain < 1, "limb_search_gain in [0, 1)");
  REENACT_CHECK(far_start_iterations >= 1, "far_start_iterations must be >= 1");
}

BodyFitter::BodyFitter(const ArticulatedBody& body, const BodyFitterOptions& options)
    : body_(body), options_(options), far_(options.fit) {
  far_.iterations = options.far_start_iterations;
}

BodyFitResult BodyFitter::Fit(const ArticulatedPose& start, const BodyObservation& obs) const {
  return SearchLimbs(FitBody(body_, start, obs, options_.fit, options_.limits), obs);
}

BodyFitResult BodyFitter::FitFromFar(const ArticulatedPose& start,
                                     const BodyObservation& obs) const {
  return SearchLimbs(LocalFitFromFar(start, obs), obs);
}

BodyFitResult BodyFitter::LocalFitFromFar(const ArticulatedPose& start,
                                          const BodyObservation& obs) const {
  return FitBody(body_, start, obs, far_, options_.limits);
}

BodyFitResult BodyFitter::SearchLimbs(BodyFitResult fit, const BodyObservation& obs) const {
  if (fit.outlier_share <= options_.limb_search_trigger) return fit;
  ArticulatedPose pose = fit.pose;
  if (capture::SearchLimbs(body_, obs, options_.fit, options_.limits, options_.limb_search,
                           &pose) == 0)
    return fit;
  BodyFitResult again = FitBody(body_, pose, obs, options_.fit, options_.limits);
  AcceptanceRule rule;
  rule.also_with_lost_points = true;
  rule.lost_points_ratio = 1 - options_.limb_search_gain;
  const GoodFitCriteria unused;
  return Accepts(rule, again, fit, {body_, options_.fit, unused, fit}) ? again : fit;
}

}  // namespace reenact::capture
