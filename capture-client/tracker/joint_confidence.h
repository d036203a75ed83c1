#pragma once
// Per-joint confidence of a fit: each segment's inlier points that no other part explains as
// well (SegmentSupport::exclusive, body_fit.h) over the points its capsules would show if
// unoccluded (BodyFitResult::expected_support), divided by full_support_ratio and clamped to
// [min_confidence, 1]; a joint takes the best of its adjacent segments. An arm lying on the
// trunk or on the other arm is not confirmed by the points it shares with them. A fit that is
// not good has its confidences halved (still at least min_confidence).

#include "capture-client/tracker/articulated_body.h"
#include "capture-client/tracker/body_fit.h"
#include "common/geometry/pinhole_camera.h"
#include "common/skeleton/skeleton.h"

namespace reenact::capture {

struct JointConfidenceOptions {
  double full_support_ratio = 0.5;  // (0, 1]
  double min_confidence = 0.05;     // (0, 1]: tracked joints are never reported missing

  void Check() const;
};

// Joints outside the camera's image (or not in front of it) are not seen: confidence 0
// (missing). A body partly out of view (an upper body close up, a hand raised out of the
// frame) reports what the scene shows instead of inventing the rest.
void MarkJointsOutOfView(const PinholeCamera& camera, Skeleton* skeleton);

// The fit's skeleton with its confidences; inlier_m: what counts as support.
Skeleton WithJointConfidence(const ArticulatedBody& body, const BodyFitResult& fit,
                             const BodyObservation& obs, double inlier_m, bool good,
                             const JointConfidenceOptions& options);

}  // namespace reenact::capture
