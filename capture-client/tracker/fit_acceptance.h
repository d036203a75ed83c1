#pragma once
// When a fit is good, and the one rule under which a candidate fit replaces a frame's current
// fit: shared by the limb search (body_fitter.h) and every correction step (correction_step.h).
//
// Costs are body_fit.h's: BodyFitResult::cost (data + silhouette terms) and CostWithLostPoints
// (the same with each point left beyond outlier_m counted at outlier_m's cost). Points beyond
// outlier_m cost nothing in the fit, so a candidate could cost less by losing a limb's points;
// the second cost keeps such a candidate out where a rule asks for it.

#include <optional>

#include "capture-client/tracker/articulated_body.h"
#include "capture-client/tracker/body_fit.h"
#include "capture-client/tracker/limb_jump.h"

namespace reenact::capture {

// A fit is good when it has points, at least min_inlier_share of them lie within inlier_m of
// the model's surface, and the data cover at least min_coverage of the model's silhouette
// within the image (BodyFitResult::coverage: a model that slid off the person covers little;
// 0.4-0.65 is usual, the body hiding its own parts). Unexplained points alone (an object
// touching the person) do not make a fit bad.
struct GoodFitCriteria {
  double min_inlier_share = 0.5;  // (0, 1]
  double min_coverage = 0.3;      // (0, 1]

  bool Good(const BodyFitResult& fit) const;
  void Check() const;
};

// A candidate replaces the current fit when all of:
//  - it is good, where require_good;
//  - no limb jumped from its data (limb_jump.h) between the step's input fit and the
//    candidate, where refuse_limb_jumps is set: an arm swung behind the head costs nothing in
//    the free-space term, so a start far from the frame's pose could take it there;
//  - and either its CostWithLostPoints is at most lost_points_ratio times the current's
//    (where lost_points_ratio > 0: a clear gain that counts the points each fit leaves), or
//    its cost is below cost_ratio times the current's (below 1: a margin that keeps a limb
//    the data hardly hold from moving for little; above 1: a tolerance for a candidate that
//    another cue prefers) and, where also_with_lost_points, its CostWithLostPoints is below
//    the current's too.
struct AcceptanceRule {
  double cost_ratio = 1;               // > 0
  bool also_with_lost_points = false;  //
  double lost_points_ratio = 0;        // [0, 1]; 0: not used
  bool require_good = false;
  std::optional<LimbJumpOptions> refuse_limb_jumps;

  void Check() const;
};

// What the rule is judged with: the body, the fit options (the costs), the criteria of a good
// fit and the fit the step started from.
struct AcceptanceContext {
  const ArticulatedBody& body;
  const BodyFitOptions& fit;
  const GoodFitCriteria& good;
  const BodyFitResult& input;
};

bool Accepts(const AcceptanceRule& rule, const BodyFitResult& candidate,
             const BodyFitResult& current, const AcceptanceContext& context);

}  // namespace reenact::capture
