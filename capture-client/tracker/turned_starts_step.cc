#include "capture-client/tracker/turned_starts_step.h"

#include <numbers>

#include "capture-client/tracker/heading.h"
#include "common/error/check.h"

namespace reenact::capture {

void TurnedStartsOptions::Check() const {
  REENACT_CHECK(turn_deg > 0 && turn_deg < 90, "turn_deg must be in (0, 90)");
  limb_jump.Check();
}

TurnedStartsStep::TurnedStartsStep(const TurnedStartsOptions& options) : options_(options) {
  options.Check();
}

AcceptanceRule TurnedStartsStep::rule() const {
  AcceptanceRule rule;
  rule.also_with_lost_points = true;
  if (options_.refuse_limb_jumps) rule.refuse_limb_jumps = options_.limb_jump;
  return rule;
}

void TurnedStartsStep::Prepare(const StepFrame& frame) {
  turned_.clear();
  if (!frame.blob.floor_in_sensor) return;
  const Eigen::Vector3d up = frame.blob.floor_in_sensor->normal;
  const double angle = options_.turn_deg * std::numbers::pi / 180;
  for (const double a : {-angle, angle})
    turned_.push_back(std::async(std::launch::async, [&frame, start = frame.prediction, up, a] {
      return frame.fitter.Fit(TurnedBy(start, up, a), frame.observation);
    }));
}

std::vector<Candidate> TurnedStartsStep::Propose(const StepFrame& /*frame*/,
                                                 const BodyFitResult& /*current*/) {
  std::vector<Candidate> out;
  for (std::future<BodyFitResult>& t : turned_) out.push_back({t.get()});
  turned_.clear();
  return out;
}

}  // namespace reenact::capture
