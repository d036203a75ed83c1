#include "capture-client/tracker/travel_heading_step.h"

#include "capture-client/tracker/body_start.h"
#include "common/error/check.h"

namespace reenact::capture {

void TravelHeadingOptions::Check() const {
  travel.Check();
  REENACT_CHECK(flip_cos >= -1 && flip_cos <= 1, "flip_cos in [-1, 1]");
  REENACT_CHECK(cost_tolerance >= 1, "cost_tolerance must be >= 1");
  REENACT_CHECK(cooldown_frames >= 0, "cooldown_frames must be >= 0");
}

TravelHeadingStep::TravelHeadingStep(const TravelHeadingOptions& options)
    : options_(options), travel_(options.travel) {
  options.Check();
}

AcceptanceRule TravelHeadingStep::rule() const {
  AcceptanceRule rule;
  rule.cost_ratio = options_.cost_tolerance;
  rule.require_good = true;
  return rule;
}

void TravelHeadingStep::Reset() {
  travel_.Clear();
  cooldown_ = 0;
}

std::vector<Candidate> TravelHeadingStep::Propose(const StepFrame& frame,
                                                  const BodyFitResult& current) {
  if (!frame.good.Good(current) || !frame.blob.floor_in_sensor) return {};
  const Eigen::Vector3d up = frame.blob.floor_in_sensor->normal;
  const std::optional<Eigen::Isometry3d>& world_from_sensor = frame.world_from_sensor;
  Eigen::Matrix3d world_from_sensor_r = Eigen::Matrix3d::Identity();
  if (world_from_sensor) world_from_sensor_r = world_from_sensor->linear();
  travel_.Add(world_from_sensor
                  ? Eigen::Vector3d(*world_from_sensor * current.pose.root_translation)
                  : current.pose.root_translation);
  if (cooldown_ > 0) {
    --cooldown_;
    return {};
  }
  const auto travel_world = travel_.Direction(world_from_sensor_r * up);
  if (!travel_world) return {};
  const Eigen::Vector3d travel = world_from_sensor_r.transpose() * *travel_world;
  const auto forward = HorizontalForward(current.pose, up);
  if (!forward || forward->dot(travel) >= options_.flip_cos) return {};
  cooldown_ = options_.cooldown_frames;
  bool unused = false;
  std::optional<BodyFitResult> best =
      BestUprightFit(frame.fitter, frame.blob, frame.observation, {travel}, nullptr, 0, 0, &unused);
  BodyFitResult turned =
      frame.fitter.FitFromFar(TurnedTo(current.pose, up, travel), frame.observation);
  if (!best || turned.cost < best->cost) best = std::move(turned);
  return {{std::move(*best)}};
}

}  // namespace reenact::capture
