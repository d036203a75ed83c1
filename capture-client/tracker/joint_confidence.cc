#include "capture-client/tracker/joint_confidence.h"

#include <algorithm>
#include <array>

#include "common/error/check.h"

namespace reenact::capture {
namespace {

using S = BodySegment;

// The segments adjacent to each joint (Index(Joint) order).
const std::array<std::array<S, 2>, kJointCount> kJointSegments = {{
    {S::kHead, S::kHead},
    {S::kHead, S::kChest},
    {S::kChest, S::kLowerSpine},
    {S::kPelvis, S::kLowerSpine},
    {S::kChest, S::kLeftUpperArm},
    {S::kLeftUpperArm, S::kLeftForearm},
    {S::kLeftForearm, S::kLeftForearm},
    {S::kChest, S::kRightUpperArm},
    {S::kRightUpperArm, S::kRightForearm},
    {S::kRightForearm, S::kRightForearm},
    {S::kPelvis, S::kLeftThigh},
    {S::kLeftThigh, S::kLeftShin},
    {S::kLeftShin, S::kLeftShin},
    {S::kPelvis, S::kRightThigh},
    {S::kRightThigh, S::kRightShin},
    {S::kRightShin, S::kRightShin},
}};

}  // namespace

void JointConfidenceOptions::Check() const {
  REENACT_CHECK(full_support_ratio > 0 && full_support_ratio <= 1, "full_support_ratio in (0, 1]");
  REENACT_CHECK(min_confidence > 0 && min_confidence <= 1, "min_confidence in (0, 1]");
}

Skeleton WithJointConfidence(const ArticulatedBody& body, const BodyFitResult& fit,
                             const BodyObservation& obs, double inlier_m, bool good,
                             const JointConfidenceOptions& options) {
  Skeleton s = fit.posed.skeleton;
  const SegmentSupport support = SupportAt(body, fit.posed, obs, inlier_m);
  std::array<double, kBodySegmentCount> seg{};
  for (int k = 0; k < kBodySegmentCount; ++k)
    seg[k] = fit.expected_support[k] > 0
                 ? support.exclusive[k] / (fit.expected_support[k] * options.full_support_ratio)
                 : 0.0;
  for (int j = 0; j < kJointCount; ++j) {
    const double c = std::max(seg[static_cast<int>(kJointSegments[j][0])],
                              seg[static_cast<int>(kJointSegments[j][1])]);
    double conf = std::clamp(c, options.min_confidence, 1.0);
    if (!good) conf = std::max(options.min_confidence, 0.5 * conf);
    s.confidence[j] = conf;
  }
  return s;
}

void MarkJointsOutOfView(const PinholeCamera& camera, Skeleton* skeleton) {
  for (int j = 0; j < kJointCount; ++j) {
    const auto px = camera.Project(skeleton->position[j]);
    if (!px || px->x() < 0 || px->y() < 0 || px->x() > camera.width || px->y() > camera.height)
      skeleton->confidence[j] = 0;
  }
}

}  // namespace reenact::capture
