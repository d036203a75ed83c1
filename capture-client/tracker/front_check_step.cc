#include "capture-client/tracker/front_check_step.h"

#include "capture-client/tracker/heading.h"
#include "capture-client/tracker/limb_swap.h"
#include "common/error/check.h"

namespace reenact::capture {

void FrontCheckOptions::Check() const {
  REENACT_CHECK(frames >= 1 && every >= 1 && gain >= 0 && gain < 1 && turn_away_gain >= gain &&
                    turn_away_gain < 1 && confirm_frames >= 0,
                "front check: frames and every must be >= 1, gain in [0, 1), turn_away_gain in "
                "[gain, 1), confirm_frames >= 0");
}

FrontCheckStep::FrontCheckStep(const FrontCheckOptions& options) : options_(options) {
  options.Check();
}

AcceptanceRule FrontCheckStep::rule() const {
  AcceptanceRule rule;
  rule.cost_ratio = 1 - options_.gain;
  rule.require_good = true;
  return rule;
}

void FrontCheckStep::OnTrackStart(TrackStart start) {
  rival_.reset();
  frames_since_start_ = start == TrackStart::kSilhouette ? 0 : -1;
}

void FrontCheckStep::Reset() {
  rival_.reset();
  frames_since_start_ = -1;
}

std::vector<Candidate> FrontCheckStep::Propose(const StepFrame& frame,
                                               const BodyFitResult& current) {
  if (frames_since_start_ < 0) return {};
  const int k = ++frames_since_start_;
  if (rival_) return FollowRival(frame, current);
  if (k > options_.frames) {
    frames_since_start_ = -1;
    return {};
  }
  if (k % options_.every != 0 || !frame.blob.floor_in_sensor || !frame.good.Good(current))
    return {};
  const ArticulatedPose start =
      TurnedAround(frame.fitter.body(), current.pose, frame.blob.floor_in_sensor->normal,
                   frame.fitter.options().limits);
  BodyFitResult around = frame.fitter.Fit(start, frame.observation);
  if (options_.confirm_frames == 0) return {{std::move(around)}};
  if (Accepts(rule(), around, current, frame.Context(current))) rival_ = Rival{around.pose};
  return {};
}

std::vector<Candidate> FrontCheckStep::FollowRival(const StepFrame& frame,
                                                   const BodyFitResult& current) {
  Rival& rival = *rival_;
  BodyFitResult r = frame.fit_as_track(frame.Predicted(rival.pose));
  if (!frame.good.Good(r)) {
    rival_.reset();
    return {};
  }
  rival.pose = r.pose;
  rival.rival_cost += r.cost;
  rival.track_cost += current.cost;
  // Turning a body that faces the sensor away from it takes the larger gain.
  const Eigen::Vector3d up =
      frame.blob.floor_in_sensor ? frame.blob.floor_in_sensor->normal : Eigen::Vector3d::Zero();
  const Eigen::Vector3d sensor = Eigen::Vector3d::Zero();
  const bool turns_away =
      FacesAwayFrom(r.pose, up, sensor) && !FacesAwayFrom(current.pose, up, sensor);
  const double keep = 1 - (turns_away ? options_.turn_away_gain : options_.gain);
  const bool confirmed = rival.rival_cost <= keep * rival.track_cost;
  const bool vetoed = rival.track_cost <= (1 - options_.gain) * rival.rival_cost;
  if (!confirmed && !vetoed && ++rival.frames < options_.confirm_frames) return {};
  rival_.reset();
  if (vetoed || (!confirmed && turns_away)) return {};
  return {{std::move(r), /*judged=*/true}};
}

}  // namespace reenact::capture
