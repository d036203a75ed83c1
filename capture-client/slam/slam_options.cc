#include "capture-client/slam/slam_options.h"

#include <cmath>

#include "common/error/check.h"
#include "common/geometry/rotation.h"

namespace reenact::capture::slam {

void SlamOptions::Check() const {
  features.Check();
  noise.Check();
  pose_refinement.Check();
  bundle_adjustment.Check();
  map_export.Check();
  odometry.Check();
  REENACT_CHECK(readout_ratio >= 0 && readout_ratio <= 1, "readout_ratio must be in [0, 1]");
  REENACT_CHECK(min_initial_points >= 3, "min_initial_points must be >= 3");
  REENACT_CHECK(initial_world_from_sensor.matrix().allFinite() &&
                    OrthonormalityError(initial_world_from_sensor.linear()) < 1e-9 &&
                    initial_world_from_sensor.linear().determinant() > 0,
                "initial_world_from_sensor must be a rigid transform");
  REENACT_CHECK(std::isfinite(search_radius_px) && search_radius_px > 0,
                "search_radius_px must be > 0");
  REENACT_CHECK(std::isfinite(wide_search_radius_px) && wide_search_radius_px > 0,
                "wide_search_radius_px must be > 0");
  REENACT_CHECK(max_descriptor_distance >= 0 && max_descriptor_distance <= 256,
                "max_descriptor_distance in [0, 256]");
  REENACT_CHECK(match_ratio > 0 && match_ratio <= 1, "match_ratio in (0, 1]");
  REENACT_CHECK(std::isfinite(ransac_max_error_px) && ransac_max_error_px > 0,
                "ransac_max_error_px must be > 0");
  REENACT_CHECK(ransac_max_iterations >= 1, "ransac_max_iterations must be >= 1");
  REENACT_CHECK(min_tracking_inliers >= 3, "min_tracking_inliers must be >= 3");
  REENACT_CHECK(local_keyframes >= 1, "local_keyframes must be >= 1");
  REENACT_CHECK(relocalisation_min_inliers >= 3, "relocalisation_min_inliers must be >= 3");
  REENACT_CHECK(relocalisation_ransac_iterations >= 1,
                "relocalisation_ransac_iterations must be >= 1");
  REENACT_CHECK(max_frames_between_keyframes >= 1, "max_frames_between_keyframes must be >= 1");
  REENACT_CHECK(keyframe_min_tracked_ratio >= 0 && keyframe_min_tracked_ratio <= 1,
                "keyframe_min_tracked_ratio in [0, 1]");
  REENACT_CHECK(std::isfinite(keyframe_translation_m) && keyframe_translation_m > 0,
                "keyframe_translation_m must be > 0");
  REENACT_CHECK(std::isfinite(keyframe_rotation_deg) && keyframe_rotation_deg > 0,
                "keyframe_rotation_deg must be > 0");
  REENACT_CHECK(max_new_points_per_keyframe >= 0, "max_new_points_per_keyframe must be >= 0");
  REENACT_CHECK(bundle_window_keyframes >= 1, "bundle_window_keyframes must be >= 1");
  REENACT_CHECK(cull_after_keyframes >= 1, "cull_after_keyframes must be >= 1");
  REENACT_CHECK(cull_min_found_ratio >= 0 && cull_min_found_ratio <= 1,
                "cull_min_found_ratio in [0, 1]");
}

}  // namespace reenact::capture::slam
