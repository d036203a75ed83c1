#pragma once
// The depth skeleton tracker's product options (skeleton_tracker.h): what a user or a
// deployment sets. Distances in metres. The method's own parameters (each module's options and
// the correction steps) are in tracker_method.h, built from these.

namespace reenact::capture {

struct SkeletonTrackerOptions {
  // --- Sensor ---
  // Depth readings outside [min_depth_m, max_depth_m] are holes. 0 <= min < max. Defaults
  // 0.4 m and 6 m (a Kinect v1's range).
  double min_depth_m = 0.4;
  double max_depth_m = 6.0;

  // --- Speed against accuracy ---
  // Data points every subsample-th detection grid point in x and y (the grid is every 2nd
  // pixel: subsample 2 takes every 4th pixel). >= 1. Default 2.
  int subsample = 2;
  // Levenberg-Marquardt iterations of a tracked frame's fit. [1, 100]. Default 8.
  int iterations = 8;
  // The turned starts (turned_starts_step.h): every frame also fitted from the prediction
  // turned by -turn_start_deg and +turn_start_deg about up, three fits a frame instead of one
  // (two of them on threads of their own). Degrees, [0, 90); 0 = off. Default 25.
  double turn_start_deg = 25;

  // --- Tracking ---
  // Data points farther than this from the predicted body are not the person's (an object
  // that touches it). > 0, larger than a limb moves in one frame interval; scaled by the
  // prediction's gap ratio where that is above 1. Default 0.4 m.
  double keep_near_model_m = 0.4;
  // Given frame times, the last root displacement is carried on scaled by the time since the
  // last frame over the last interval (gap_ratio.h), at most this: a live sensor drops frames.
  // >= 1. Default 4.
  double max_gap_ratio = 4;
  // Learn the static scene beside the person and leave its points out (static_scene_voxels.h:
  // an object the person walks up to); only on frames whose sensor pose is given. Default on.
  bool learn_static_scene = true;
  // A fit is good when at least good_inlier_share of its points lie within the fit's inlier
  // distance of the model's surface and the data cover at least min_coverage of the model's
  // silhouette within the image (fit_acceptance.h's GoodFitCriteria). (0, 1]. Defaults 0.5
  // and 0.3.
  double good_inlier_share = 0.5;
  double min_coverage = 0.3;
  // This many frames in a row without a good fit lose the track (the frames before it still
  // give a skeleton, its confidences halved). >= 1. Default 3.
  int lost_after_frames = 3;

  // --- Starting ---
  // Frames with a detected person without the calibration pose after which tracking starts
  // with average proportions (measured as the person moves); -1 = wait for the calibration
  // pose. >= -1. Default 15 (half a second at 30 fps).
  int start_without_calibration_after = 15;
  // A lost track is recovered from the silhouette as well as from the calibration pose.
  // Default on.
  bool recover_from_silhouette = true;

  // --- Output ---
  // The least confidence of a tracked joint (joint_confidence.h). (0, 1]. Default 0.05.
  double min_confidence = 0.05;

  // Throws CheckError naming the first field out of range.
  void Check() const;
};

}  // namespace reenact::capture
