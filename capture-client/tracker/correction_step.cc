#include "capture-client/tracker/correction_step.h"

namespace reenact::capture {

ArticulatedPose StepFrame::Predicted(ArticulatedPose pose) const {
  pose.root_translation += root_step;
  return pose;
}

AcceptanceContext StepFrame::Context(const BodyFitResult& input) const {
  return {fitter.body(), fitter.options().fit, good, input};
}

BodyFitResult FitAsTrack(const CorrectionSteps& steps, size_t end, const StepFrame& frame) {
  for (size_t k = 0; k < end; ++k) steps[k]->Prepare(frame);
  BodyFitResult fit = frame.fitter.Fit(frame.prediction, frame.observation);
  for (size_t k = 0; k < end; ++k) {
    StepFrame at_step = frame;
    at_step.fit_as_track = [&steps, k, &frame](const ArticulatedPose& start) {
      StepFrame from = frame;
      from.prediction = start;
      return FitAsTrack(steps, k, from);
    };
    const BodyFitResult input = fit;
    const AcceptanceRule rule = steps[k]->rule();
    for (Candidate& c : steps[k]->Propose(at_step, input))
      if (c.judged || Accepts(rule, c.fit, fit, at_step.Context(input))) fit = std::move(c.fit);
  }
  return fit;
}

}  // namespace reenact::capture
