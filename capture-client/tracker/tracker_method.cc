#include "capture-client/tracker/tracker_method.h"

#include "capture-client/tracker/front_check_step.h"
#include "capture-client/tracker/travel_heading_step.h"
#include "capture-client/tracker/turned_starts_step.h"
#include "capture-client/tracker/uncross_step.h"
#include "common/error/check.h"

namespace reenact::capture {

void TrackerMethod::Check() const {
  detect.Check();
  calibration.Check();
  head_size.Check();
  fitter.Check();
  start.Check();
  measurement.Check();
  static_scene.Check();
  confidence.Check();
  for (const auto& step : steps) REENACT_CHECK(step != nullptr, "a correction step is missing");
}

TrackerMethod DefaultTrackerMethod(const SkeletonTrackerOptions& options) {
  options.Check();
  TrackerMethod m;
  m.detect.min_depth_m = options.min_depth_m;
  m.detect.max_depth_m = options.max_depth_m;
  m.fitter.fit.iterations = options.iterations;
  m.start.from_silhouette = options.recover_from_silhouette;
  m.static_scene.enabled = options.learn_static_scene;
  m.confidence.min_confidence = options.min_confidence;
  if (options.turn_start_deg > 0)
    m.steps.push_back(std::make_unique<TurnedStartsStep>(
        TurnedStartsOptions{.turn_deg = options.turn_start_deg, .limb_jump = {}}));
  m.steps.push_back(std::make_unique<UncrossStep>(kArms, UncrossOptions{}));
  m.steps.push_back(std::make_unique<UncrossStep>(kLegs, UncrossOptions{}));
  m.steps.push_back(std::make_unique<FrontCheckStep>(FrontCheckOptions{}));
  m.steps.push_back(std::make_unique<TravelHeadingStep>(TravelHeadingOptions{}));
  return m;
}

}  // namespace reenact::capture
