#pragma once
// One fit of the tracker's body to a frame: the local fit (body_fit.h) from a start pose, then,
// where the fit left points unexplained, the limb search (limb_search.h) and a second fit from
// the re-posed limbs, kept under the shared rule (fit_acceptance.h): when its cost with the
// lost points counted is at most (1 - limb_search_gain) times the first fit's, or when it costs
// less on both costs. On its cost alone, a fit that reached a rising hand's points would lose
// to one that left them (points beyond outlier_m cost nothing); the gain keeps a limb the data
// do not hold (hidden behind the body) from moving for a few stray points.

#include "capture-client/tracker/articulated_body.h"
#include "capture-client/tracker/body_fit.h"
#include "capture-client/tracker/fit_acceptance.h"
#include "capture-client/tracker/limb_search.h"

namespace reenact::capture {

struct BodyFitterOptions {
  BodyFitOptions fit;  // fit.iterations: a tracked frame's fit from its prediction
  JointLimits limits;
  LimbSearchOptions limb_search;
  // The limb search runs when more than limb_search_trigger of the points lie beyond outlier_m
  // of the fitted model ([0, 1]; 1 = never); its fit is kept as above ([0, 1)).
  double limb_search_trigger = 0.005;
  double limb_search_gain = 0.1;
  // Iterations of a fit from a start far from the frame's pose (a start, a recovery, the body
  // turned to face its walking direction), >= 1.
  int far_start_iterations = 12;

  void Check() const;
};

// Fits one body; holds references (the body and options must outlive it). Thread-safe: const.
class BodyFitter {
 public:
  BodyFitter(const ArticulatedBody& body, const BodyFitterOptions& options);

  // The local fit and the limb search from `start` (options.fit's iterations).
  BodyFitResult Fit(const ArticulatedPose& start, const BodyObservation& obs) const;
  // The same with far_start_iterations.
  BodyFitResult FitFromFar(const ArticulatedPose& start, const BodyObservation& obs) const;
  // The local fit alone, far_start_iterations.
  BodyFitResult LocalFitFromFar(const ArticulatedPose& start, const BodyObservation& obs) const;

  const ArticulatedBody& body() const { return body_; }
  const BodyFitterOptions& options() const { return options_; }

 private:
  BodyFitResult SearchLimbs(BodyFitResult fit, const BodyObservation& obs) const;

  const ArticulatedBody& body_;
  const BodyFitterOptions& options_;
  BodyFitOptions far_;  // options.fit with far_start_iterations
};

}  // namespace reenact::capture
