#pragma once
// The viewer's camera pose in the clip's world frame (the capture's SLAM map frame), from the
// clip's relocalisation map (proto/clip/map_codec.h: background points with ORB
// descriptors), frame after frame:
//
//  - relocalisation (no pose known, or the track was lost): the frame's ORB features
//    (vision/features/orb_features.h) are matched against every map point by descriptor
//    (Hamming distance <= reloc_max_distance, best < reloc_ratio * the best of another
//    place, map points within 2 cm being one place; OpenCV's brute-force matcher), the pose
//    comes from PnP in RANSAC (vision/pose/pnp_estimator.h; inlier when the reprojection
//    error is <= ransac_max_error_px), is refined on the inliers
//    (vision/pose/pose_refinement.h: Levenberg-Marquardt on the reprojection error with
//    Huber's loss), and is confirmed by guided matching as in tracking. It succeeds with at
//    least reloc_min_inliers inliers;
//  - tracking (the previous frame had a pose): the pose is predicted by constant velocity,
//    viewer_from_world_pred = (T_{k-1} T_{k-2}^-1) T_{k-1} (or T_{k-1} after one posed frame),
//    the map points are projected with the prediction and matched to the keypoints within
//    search_radius_px of their projection (wide_search_radius_px when that finds too few),
//    the pose is refined from the prediction, then matched again within half the search
//    radius at the refined pose and refined once more. It succeeds with at least
//    track_min_inliers inliers; otherwise the same frame is relocalised.
//
// Every processed frame ends in one state: relocalised (found from scratch), tracked (followed
// from the previous frame) or lost (no pose; the next frame relocalises).
//
// Frames: viewer_from_world maps world points (metres) into the viewer camera's frame with
// OpenCV axes (x right, y down, z forward). The camera model is the viewer's calibration
// (distortion allowed: keypoints are undistorted, map points projected through it).

#include <Eigen/Geometry>
#include <cstdint>
#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "common/error/expected.h"
#include "common/geometry/pinhole_camera.h"
#include "common/image/image.h"
#include "proto/clip/map_codec.h"
#include "viewer-client/reloc/pose_smoother.h"
#include "vision/features/feature_matching.h"
#include "vision/features/orb_features.h"
#include "vision/pose/observation_model.h"
#include "vision/pose/pose_refinement.h"

namespace reenact::viewer {

enum class RelocStatus { kRelocalised, kTracked, kLost };

// "relocalised", "tracked", "lost".
std::string_view RelocStatusName(RelocStatus status);

struct RelocaliserOptions {
  // ORB features per frame (the map's are OpenCV ORB with scale 1.2 and 8 levels; keep those).
  // Default 2000 features, sub-pixel keypoints as the map's (capture-client's
  // DefaultMapFeatures); depth fields unused (the viewer has no depth).
  // Why 2000 and not the map's 1000 per view: the error that remains is each map point's own
  // (its keypoint as detected from the capture's or a virtual viewpoint, 0.5-1 px from where
  // the viewer detects the same corner), fixed per point, so it does not average out over
  // frames but only over points; on a far wall it turns into a sideways shift. Twice the
  // features give about twice the matches and halve that error: at 40 degrees around the
  // subject, a fit started at the true pose lands about 1 cm off (median) instead of 2.
  vision::OrbFeatureOptions features{.num_features = 2000, .subpixel = true};
  // A map with fewer points is refused by Create; >= 4 (PnP needs 3 plus one to check).
  // Default 50: with fewer, reloc_min_inliers can rarely be reached.
  int min_map_points = 50;

  // Relocalisation by descriptor: Hamming distance [0, 256], default 64; ratio (0, 1],
  // default 0.8.
  int reloc_max_distance = 64;
  double reloc_ratio = 0.8;
  // PnP RANSAC: inlier threshold in pixels (> 0, default 4), trials [1, 100000] (default
  // 1000, adaptive below that), inliers needed to accept a relocalisation (>= 4, default 30).
  double ransac_max_error_px = 4.0;
  int ransac_max_iterations = 1000;
  int reloc_min_inliers = 30;

  // Tracking by projection: search radius in pixels around the projected map point (> 0,
  // default 10), the wider radius tried when fewer than 2 track_min_inliers matches are
  // found (>= search_radius_px, default 25); Hamming distance [0, 256] (default 80: the
  // position already narrows the candidates); ratio (0, 1] (default 0.9); inliers needed to
  // keep tracking (>= 4, default 25).
  double search_radius_px = 10.0;
  double wide_search_radius_px = 25.0;
  int track_max_distance = 80;
  double track_ratio = 0.9;
  int track_min_inliers = 25;

  // Keypoint noise of the refinement (pixel sigma at level 0 and the pyramid's scale; the
  // depth terms are unused) and its rounds and iterations. Sub-pixel keypoints: 0.5 px. It
  // also sets the inlier test (chi-square 95%: 1.2 px at level 0), and a tighter one keeps
  // the map's few wrong points (on depth edges) out of the fit: within 2 cm / 1 degree on
  // turn-and-kick 0.62 -> 0.73 from 1 px, on walk-handheld 0.79 -> 0.95 (every third frame);
  // on real TUM fr1_rpy all 60 frames stay tracked (median inliers 207 -> 152). At 0.3 px
  // TUM loses 6 of 60.
  vision::ObservationNoise noise{.pixel_sigma_px = 0.5};
  vision::PoseRefinementOptions refinement;
  uint64_t seed = 1;  // RANSAC's random generator
  // The pose reported for tracked frames: smoothed over time (pose_smoother.h), or each
  // frame's own refined pose. The search for the next frame's matches is predicted from the
  // frames' own poses either way (a smoothed prediction lags behind fast turns: on TUM
  // fr1_rpy it cost 5 relocalisations in 60 frames). Default on.
  bool smooth = true;
  PoseSmootherOptions smoothing;

  // Throws CheckError when a field is out of range.
  void Check() const;
};

// CPU time of ProcessFrame's stages, milliseconds (vision::CpuMs: the process's CPU time, so
// the machine's other load does not count; a shared machine's wall times are noisy).
struct RelocStageTimes {
  vision::OrbTimings orb;       // feature extraction, step by step
  double features_ms = 0;       // all of feature extraction (the sum of orb's steps)
  double grid_ms = 0;           // bucketing the keypoints
  double match_ms = 0;          // matching by projection (tracking and confirmation)
  double refine_ms = 0;         // pose refinement (tracking and confirmation)
  double relocalise_ms = 0;     // descriptor search and PnP RANSAC (relocalising frames only)
  double smooth_ms = 0;         // the pose smoother
  double total_ms = 0;          // all of ProcessFrame
  vision::MatchStats matching;  // projection matching's work (all its calls in the frame)
};

struct RelocFrameResult {
  RelocStatus status = RelocStatus::kLost;
  // The pose (set unless lost).
  std::optional<Eigen::Isometry3d> viewer_from_world;
  int features = 0;     // ORB keypoints in the frame
  int matches = 0;      // map point - keypoint matches the pose was estimated from
  int inliers = 0;      // of them, consistent with the pose
  double ms = 0;        // wall time of ProcessFrame, milliseconds
  RelocStageTimes cpu;  // CPU time per stage
  std::string reason;   // why the frame is lost (empty otherwise)
};

class Relocaliser {
 public:
  // Errors ("invalid_argument"): an empty map, a map with fewer than min_map_points points
  // (the message says how many it has and needs), a camera that fails Check(). Throws
  // CheckError for invalid options.
  static Expected<Relocaliser> Create(proto::ClipMap map, const PinholeCamera& camera,
                                      const RelocaliserOptions& options = {});

  // One frame: CV_8UC1 (grey) or CV_8UC3 (BGR, as OpenCV decodes) of the camera's size.
  // Errors ("invalid_argument"): an empty image, another size than the camera's (the message
  // gives both), another pixel type. A frame without features is not an error: it is lost.
  Expected<RelocFrameResult> ProcessFrame(const cv::Mat& image);
  // The same for an RGB frame (common/image/image.h).
  Expected<RelocFrameResult> ProcessFrame(const ImageRgb8& image);

  // Move-only: the match candidates point into the map's descriptors.
  Relocaliser(Relocaliser&&) = default;
  Relocaliser& operator=(Relocaliser&&) = default;
  Relocaliser(const Relocaliser&) = delete;
  Relocaliser& operator=(const Relocaliser&) = delete;

  // Forgets the track: the next frame relocalises from scratch.
  void Reset();

  const PinholeCamera& camera() const { return camera_; }
  size_t map_size() const { return map_.points.size(); }

 private:
  struct Estimate {
    Eigen::Isometry3d viewer_from_world = Eigen::Isometry3d::Identity();
    int matches = 0;
    int inliers = 0;
    Eigen::Matrix<double, 6, 6> information = Eigen::Matrix<double, 6, 6>::Zero();
  };

  Relocaliser(proto::ClipMap map, const PinholeCamera& camera, const RelocaliserOptions& options);
  Estimate Refine(const Eigen::Isometry3d& start, const vision::FrameFeatures& features,
                  const std::vector<vision::FeatureMatch>& matches, RelocStageTimes& cpu) const;
  Estimate TrackFrom(const Eigen::Isometry3d& predicted, const vision::FrameFeatures& features,
                     const vision::KeypointGrid& grid, RelocStageTimes& cpu) const;
  std::optional<Estimate> Relocalise(const vision::FrameFeatures& features,
                                     const vision::KeypointGrid& grid, std::string& reason,
                                     RelocStageTimes& cpu);

  proto::ClipMap map_;
  PinholeCamera camera_;
  RelocaliserOptions options_;
  std::vector<vision::MatchCandidate> candidates_;  // every map point, id = its index
  cv::Mat map_descriptors_;                         // CV_8UC1, one 32-byte row per point
  cv::Ptr<cv::DescriptorMatcher> matcher_;
  std::vector<int> point_group_;  // per map point: the first point of its place
  ImageDepthMm no_depth_;         // zeros: the viewer has no depth
  std::optional<Eigen::Isometry3d> last_, before_last_;  // viewer_from_world of posed frames
  PoseSmoother smoother_;
  uint64_t frames_ = 0;
};

}  // namespace reenact::viewer
