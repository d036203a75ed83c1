#pragma once
// Turned starts: every tracked frame the body is also fitted from the prediction turned about
// the floor's up by -turn_deg and +turn_deg, and each turned fit replaces the frame's when it
// costs less on both costs (fit_acceptance.h) and, with refuse_limb_jumps, no limb jumped from
// its data in the prediction's own fit (limb_jump.h). The fit from the prediction alone falls
// behind a fast turn where the body's surface shows the turn little (a rounded trunk, the arms
// close to it): on the skinned CesiumMan's turn-and-kick it lagged up to 60 degrees, while a
// fit started from the truth cost 20-60 % less. The two turned fits run on threads of their own
// while the tracker fits the prediction.

#include <future>
#include <optional>
#include <vector>

#include "capture-client/tracker/correction_step.h"
#include "capture-client/tracker/limb_jump.h"

namespace reenact::capture {

struct TurnedStartsOptions {
  double turn_deg = 25;  // degrees, (0, 90)
  bool refuse_limb_jumps = true;
  LimbJumpOptions limb_jump;

  void Check() const;
};

class TurnedStartsStep final : public CorrectionStep {
 public:
  explicit TurnedStartsStep(const TurnedStartsOptions& options);
  std::string_view name() const override { return "turned-starts"; }
  AcceptanceRule rule() const override;
  void Prepare(const StepFrame& frame) override;
  std::vector<Candidate> Propose(const StepFrame& frame, const BodyFitResult& current) override;

 private:
  TurnedStartsOptions options_;
  std::vector<std::future<BodyFitResult>> turned_;
};

}  // namespace reenact::capture
