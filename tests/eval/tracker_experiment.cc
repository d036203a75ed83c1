#include "tests/eval/tracker_experiment.h"

#include <algorithm>
#include <memory>

#include "capture-client/tracker/front_check_step.h"
#include "capture-client/tracker/travel_heading_step.h"
#include "capture-client/tracker/turned_starts_step.h"
#include "capture-client/tracker/uncross_step.h"
#include "common/error/check.h"

namespace reenact::eval {

const std::vector<std::string_view>& TrackerAblations() {
  static const std::vector<std::string_view> names = {
      "turned-starts", "limb-jump",     "uncross-arms",   "uncross-legs", "uncross-return",
      "front-check",   "front-confirm", "travel-heading", "limb-search",  "held-twists",
      "static-scene",  "trunk-breadth", "torso-depth"};
  return names;
}

capture::TrackerMethod ExperimentMethod(const capture::SkeletonTrackerOptions& options,
                                        const std::set<std::string>& without) {
  for (const std::string& name : without)
    REENACT_CHECK(std::count(TrackerAblations().begin(), TrackerAblations().end(), name) == 1,
                  "unknown ablation " + name);
  const auto off = [&](const char* name) { return without.count(name) > 0; };
  capture::TrackerMethod m = capture::DefaultTrackerMethod(options);
  m.steps.clear();
  if (options.turn_start_deg > 0 && !off("turned-starts")) {
    capture::TurnedStartsOptions turned;
    turned.turn_deg = options.turn_start_deg;
    turned.refuse_limb_jumps = !off("limb-jump");
    m.steps.push_back(std::make_unique<capture::TurnedStartsStep>(turned));
  }
  if (!off("uncross-arms"))
    m.steps.push_back(std::make_unique<capture::UncrossStep>(
        capture::kArms, capture::UncrossOptions{.return_limb = !off("uncross-return")}));
  if (!off("uncross-legs"))
    m.steps.push_back(
        std::make_unique<capture::UncrossStep>(capture::kLegs, capture::UncrossOptions{}));
  if (!off("front-check")) {
    capture::FrontCheckOptions front;
    if (off("front-confirm")) front.confirm_frames = 0;
    m.steps.push_back(std::make_unique<capture::FrontCheckStep>(front));
  }
  if (!off("travel-heading"))
    m.steps.push_back(
        std::make_unique<capture::TravelHeadingStep>(capture::TravelHeadingOptions{}));
  if (off("limb-search")) m.fitter.limb_search_trigger = 1;
  if (off("held-twists")) m.fitter.limb_search.held_twists = 0;
  if (off("static-scene")) m.static_scene.enabled = false;
  if (off("trunk-breadth")) m.calibration.fit_trunk_breadth = false;
  if (off("torso-depth")) m.measurement.measure_torso_depth = false;
  return m;
}

std::optional<OracleFit> FitLastFrameFrom(const capture::SkeletonTracker& tracker,
                                          const Skeleton& start_in_sensor) {
  const auto& last = tracker.last_fit();
  if (!tracker.body() || !last) return std::nullopt;
  const capture::ArticulatedBody& body = *tracker.body();
  const capture::BodyFitterOptions& fitter = tracker.method().fitter;
  const capture::ArticulatedPose start = body.PoseFromSkeleton(start_in_sensor);
  OracleFit out;
  out.posed = body.Pose(start).skeleton;
  const capture::BodyFitResult fit =
      capture::FitBody(body, start, last->observation, fitter.fit, fitter.limits);
  out.fitted = fit.posed.skeleton;
  out.fitted_cost = capture::CostWithLostPoints(fit, fitter.fit);
  out.track_cost = capture::CostWithLostPoints(last->fit, fitter.fit);
  return out;
}

}  // namespace reenact::eval
