#include "capture-client/slam/slam_result.h"

namespace reenact::capture::slam {

std::string_view SlamStatusName(SlamStatus status) {
  switch (status) {
    case SlamStatus::kInitialised:
      return "initialised";
    case SlamStatus::kTracked:
      return "tracked";
    case SlamStatus::kOdometryFallback:
      return "odometry_fallback";
    case SlamStatus::kRelocalised:
      return "relocalised";
    case SlamStatus::kLost:
      return "lost";
  }
  return "unknown";
}

std::string_view SlamLostReasonName(SlamLostReason reason) {
  switch (reason) {
    case SlamLostReason::kNone:
      return "none";
    case SlamLostReason::kNotInitialised:
      return "not_initialised";
    case SlamLostReason::kTooFewFeatures:
      return "too_few_features";
    case SlamLostReason::kTooFewInliers:
      return "too_few_inliers";
    case SlamLostReason::kNotRelocalised:
      return "not_relocalised";
  }
  return "unknown";
}

}  // namespace reenact::capture::slam
