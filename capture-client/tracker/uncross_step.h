#pragma once
// Crossed limbs (limb_swap.h): where the fit's arms (legs) lie crossed, the body is also fitted
// from the limbs swapped and, for the arms where the prediction had them apart, from each arm
// back at its predicted joint angles with the other reaching where it ended (ReturnedLimb: one
// arm took the other's data); the cheapest of these replaces the frame's fit when it costs
// less than (1 - gain) times as much. A subject crossing its arms keeps them crossed: the
// swapped fit then costs more. Not the returned limb for the legs: on CesiumMan's walk the
// returned leg left the hips 18 cm high where the swap alone leaves them 16 cm.

#include "capture-client/tracker/correction_step.h"
#include "capture-client/tracker/limb_swap.h"

namespace reenact::capture {

struct UncrossOptions {
  double gain = 0.05;       // [0, 1)
  bool return_limb = true;  // the returned arm as a start too (arms only)

  void Check() const;
};

class UncrossStep final : public CorrectionStep {
 public:
  UncrossStep(LimbPair pair, const UncrossOptions& options);
  std::string_view name() const override;
  AcceptanceRule rule() const override;
  std::vector<Candidate> Propose(const StepFrame& frame, const BodyFitResult& current) override;

 private:
  LimbPair pair_;
  UncrossOptions options_;
};

}  // namespace reenact::capture
