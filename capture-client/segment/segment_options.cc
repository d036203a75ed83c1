#include "capture-client/segment/segment_options.h"

#include <cmath>
#include <string>

#include "common/error/check.h"

namespace reenact::capture {

void DepthTolerance::Check(const char* name) const {
  REENACT_CHECK(std::isfinite(base_m) && std::isfinite(per_z2) && base_m >= 0 && per_z2 >= 0 &&
                    base_m + per_z2 > 0,
                std::string(name) + ": need finite base_m, per_z2 >= 0, not both 0");
}

void PersonSegmentOptions::Check() const {
  REENACT_CHECK(std::isfinite(min_depth_m) && std::isfinite(max_depth_m) && min_depth_m >= 0 &&
                    min_depth_m < max_depth_m,
                "need 0 <= min_depth_m < max_depth_m");
  REENACT_CHECK(floor_max_tilt_deg > 0 && floor_max_tilt_deg < 90,
                "floor_max_tilt_deg must lie in (0, 90)");
  REENACT_CHECK(std::isfinite(floor_search_band_m) && floor_search_band_m > 0,
                "floor_search_band_m must be > 0");
  REENACT_CHECK(std::isfinite(floor_search_radius_m) && floor_search_radius_m > 0,
                "floor_search_radius_m must be > 0");
  REENACT_CHECK(floor_sample_stride_px >= 1, "floor_sample_stride_px must be >= 1");
  floor_fit.Check("floor_fit");
  REENACT_CHECK(floor_min_inliers >= 3, "floor_min_inliers must be >= 3");
  REENACT_CHECK(floor_min_inlier_ratio >= 0 && floor_min_inlier_ratio <= 1,
                "floor_min_inlier_ratio must lie in [0, 1]");
  REENACT_CHECK(floor_keep_ratio > 0 && floor_keep_ratio <= 1,
                "floor_keep_ratio must lie in (0, 1]");
  REENACT_CHECK(floor_max_trials >= 1, "floor_max_trials must be >= 1");
  floor_clearance.Check("floor_clearance");
  REENACT_CHECK(std::isfinite(seed_step_px) && seed_step_px >= 0.5, "seed_step_px must be >= 0.5");
  REENACT_CHECK(std::isfinite(seed_in_front_m) && seed_in_front_m >= 0,
                "seed_in_front_m must be >= 0");
  REENACT_CHECK(std::isfinite(seed_behind_m) && seed_behind_m >= 0, "seed_behind_m must be >= 0");
  depth_step.Check("depth_step");
  REENACT_CHECK(std::isfinite(body_margin_m) && body_margin_m > 0, "body_margin_m must be > 0");
  REENACT_CHECK(max_hole_run_px >= 0, "max_hole_run_px must be >= 0");
  REENACT_CHECK(
      std::isfinite(core_radius_m) && core_radius_m >= 0 && core_radius_m <= body_margin_m,
      "core_radius_m must lie in [0, body_margin_m]");
  REENACT_CHECK(hole_person_ratio > 0 && hole_person_ratio <= 1,
                "hole_person_ratio must lie in (0, 1]");
}

}  // namespace reenact::capture
