#pragma once
// Front from the walking direction (heading.h's TravelDirection): on a good frame, where the
// fitted forward's cosine to the root's direction of travel across the floor is below flip_cos,
// the body is fitted from afar facing the travel (upright on the blob, and the fit's own pose
// turned to it), and the cheaper of the two replaces the frame's fit when it is good and costs
// less than cost_tolerance times as much: front and back fit nearly alike, so the walk decides.
// At most once every cooldown_frames frames. The root's path is kept in the world frame where
// the sensor's pose is given (a moving sensor), else in the sensor's.

#include "capture-client/tracker/correction_step.h"
#include "capture-client/tracker/heading.h"

namespace reenact::capture {

struct TravelHeadingOptions {
  TravelOptions travel;
  double flip_cos = -0.3;       // [-1, 1]
  double cost_tolerance = 1.3;  // >= 1
  int cooldown_frames = 10;     // >= 0

  void Check() const;
};

class TravelHeadingStep final : public CorrectionStep {
 public:
  explicit TravelHeadingStep(const TravelHeadingOptions& options);
  std::string_view name() const override { return "travel-heading"; }
  AcceptanceRule rule() const override;
  std::vector<Candidate> Propose(const StepFrame& frame, const BodyFitResult& current) override;
  void Reset() override;

 private:
  TravelHeadingOptions options_;
  TravelDirection travel_;
  int cooldown_ = 0;
};

}  // namespace reenact::capture
