#include "capture-client/tracker/skeleton_tracker_options.h"

#include <cmath>

#include "common/error/check.h"

namespace reenact::capture {

void SkeletonTrackerOptions::Check() const {
  REENACT_CHECK(min_depth_m >= 0 && min_depth_m < max_depth_m,
                "need 0 <= min_depth_m < max_depth_m");
  REENACT_CHECK(subsample >= 1, "subsample must be >= 1");
  REENACT_CHECK(iterations >= 1 && iterations <= 100, "iterations in [1, 100]");
  REENACT_CHECK(turn_start_deg >= 0 && turn_start_deg < 90, "turn_start_deg must be in [0, 90)");
  REENACT_CHECK(keep_near_model_m > 0, "keep_near_model_m must be > 0");
  REENACT_CHECK(max_gap_ratio >= 1 && std::isfinite(max_gap_ratio), "max_gap_ratio must be >= 1");
  REENACT_CHECK(good_inlier_share > 0 && good_inlier_share <= 1, "good_inlier_share in (0, 1]");
  REENACT_CHECK(min_coverage > 0 && min_coverage <= 1, "min_coverage in (0, 1]");
  REENACT_CHECK(lost_after_frames >= 1, "lost_after_frames must be >= 1");
  REENACT_CHECK(start_without_calibration_after >= -1,
                "start_without_calibration_after must be >= -1");
  REENACT_CHECK(min_confidence > 0 && min_confidence <= 1, "min_confidence in (0, 1]");
}

}  // namespace reenact::capture
