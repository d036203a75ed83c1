#pragma once
// Records a clip from a frame source into a clip directory (proto/clip/clip_directory.h):
// per frame the subject's crop of colour, depth and person mask with the sensor pose and the
// skeleton in the world frame; the cylinder model (representative frame by Eq. 2-4, radius
// ratios from the depth and mask of the best frames); the relocalisable background map; the
// manifest.
//
// Per source frame, in this order:
//  1. Skeleton in the sensor frame: from options.frame_skeletons when set (a tracker that
//     reads the frame's depth), else options.skeletons (an imported track), else the
//     source's own (moved out of the world by the source's pose).
//  2. Person mask: the source's own, else segmentation from depth and skeleton
//     (segment/person_segmenter.h). A frame with neither has no mask, and SLAM sees all of
//     it, a subject in view included: a track should cover every frame the subject is in.
//  3. Sensor pose: the source's own (synthetic ground truth, a stored clip), or RGB-D SLAM
//     (slam/rgbd_slam.h) on the frame with the person masked out (options.poses).
//  4. Stored when it has both a pose and a skeleton. Frames without a pose (SLAM lost) or
//     without a skeleton still serve SLAM but are not stored; the summary counts them.
// Afterwards: skeletons that fail the consistency check (skeleton_consistency.h) are kept out
// of the model and listed in the manifest's flagged_skeleton_frames, so viewers never texture
// from them. The map is SLAM's export when SLAM gave the poses, else built from keyframes
// with the source's poses (map/background_map_builder.h); then every
// virtual_views.keyframe_interval-th stored frame adds the features of views turned around
// the subject (map/virtual_views.h), so viewers who walk around it still find the map.

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "capture-client/map/background_map_builder.h"
#include "capture-client/map/virtual_views.h"
#include "capture-client/segment/segment_options.h"
#include "capture-client/slam/slam_options.h"
#include "capture-client/source/frame_source.h"
#include "common/error/expected.h"
#include "common/model/model_building.h"
#include "proto/clip/frame_codec.h"

namespace reenact::capture {

enum class PoseSource {
  kAuto,  // the source's poses when its first frame has one, else SLAM
  kSlam,  // SLAM for every frame, even when the source knows poses (evaluation, benchmarks):
          // the map's world frame is then anchored at the first frame's source pose
};

// The skeleton of source frame `index` (0-based, every frame read counts) at timestamp_s, in
// the sensor frame (OpenCV camera axes, metres), or nullopt when there is none.
using SkeletonLookup = std::function<std::optional<Skeleton>(int64_t index, double timestamp_s)>;

// The sensor pose and the world's up (unit) that a frame skeleton source is given with a
// frame, when known: the source's own when the recording takes the source's poses; with SLAM,
// SLAM's prediction for the frame (RgbdSlam::PredictedWorldFromSensor: SLAM tracks a frame
// only after its skeleton, whose person mask it needs; none before SLAM has founded its map
// and while it is lost) and the up known so far (the source's, else the floor's under the
// first posed frame).
struct FramePoseHint {
  std::optional<Eigen::Isometry3d> world_from_sensor;
  std::optional<Eigen::Vector3d> world_up;
};

// The skeleton of a source frame computed from the frame itself (its depth, and the pose hint
// in SLAM's or the source's world), in the sensor frame, or nullopt when there is none.
// Called once per source frame, in order (a tracker keeps state between frames); `frame` is
// valid only during the call. An Error stops the recording.
using FrameSkeletonSource = std::function<Expected<std::optional<Skeleton>>(
    int64_t index, const SensorFrame& frame, const FramePoseHint& pose)>;

struct RecordOptions {
  int max_frames = -1;         // source frames to read, -1 = until the source ends; else >= 1
  int crop_margin_px = 12;     // margin around the person mask's bounding box, >= 0
  int keyframe_interval = 10;  // with source poses: every n-th frame feeds the map, >= 1
  std::string title;           // manifest title (may be set again at publish)
  std::string author;
  proto::FrameCodecOptions codec;
  BackgroundMapOptions map;      // with source poses
  // Map points from virtual views around the subject (map/virtual_views.h), added to the
  // map however it was built; yaw_deg empty = none.
  VirtualViewOptions virtual_views;
  PersonSegmentOptions segment;  // for frames whose source gives no person mask
  PoseSource poses = PoseSource::kAuto;
  // SLAM, when it gives the poses. Its readout_ratio is replaced by the source's
  // SensorInfo::color_readout_ratio, its noise.depth_sigma_1m_m by the source's
  // depth_sigma_1m_m when known, and its initial_world_from_sensor by the first frame's
  // source pose when there is one.
  slam::SlamOptions slam;
  // Skeletons from outside the source; empty = the source's own.
  SkeletonLookup skeletons;
  // Skeletons from the frames themselves (tracker/skeleton_tracker.h); takes precedence over
  // `skeletons`; empty = none.
  FrameSkeletonSource frame_skeletons;
  // Cylinder model (Eq. 2-4): per-part median over the 3 best frames by F(n), which halves
  // the radius error of the thesis's single frame on noisy skeletons (reenact-bench core).
  ModelBuildOptions model{.representative = {}, .fit = {}, .robust_k = 3};

  void Check() const;
};

// Wall time of each stage per stored or skipped source frame, milliseconds, in frame order.
struct RecordStageTimes {
  std::vector<double> source_ms;   // the source's Next(): reading and decoding
  std::vector<double> tracker_ms;  // frame_skeletons (a tracker); 0 without one
  std::vector<double> segment_ms;  // 0 where the source gave the mask
  std::vector<double> slam_ms;     // 0 with source poses
  std::vector<double> encode_ms;   // crop + JPEG/PNG; 0 for frames not stored
  std::vector<double> map_ms;      // keyframes of the background map builder; 0 with SLAM
  double model_ms = 0;             // model building, once
  double write_ms = 0;             // map export, encoding, directory writing, once
};

struct RecordSummary {
  int frames = 0;                   // stored
  int source_frames = 0;            // read from the source
  int frames_without_skeleton = 0;  // not stored: no skeleton (or one without any joint)
  int frames_without_pose = 0;      // not stored: a skeleton, but SLAM had no pose
  uint64_t frame_bytes = 0;         // all encoded frames together
  uint64_t map_bytes = 0;
  size_t map_points = 0;
  size_t virtual_view_points = 0;  // of map_points, from virtual views
  bool slam_poses = false;  // the poses came from SLAM
  int slam_keyframes = 0;
  int slam_fallback_frames = 0;  // tracked by the cv::rgbd odometry fallback
  int slam_relocalised_frames = 0;
  int representative_frame = -1;
  int fitted_parts = 0;            // parts whose radius came from the fit, not the default
  int segmented_frames = 0;        // frames whose person mask came from our segmentation
  int inconsistent_skeletons = 0;  // flagged: kept out of the model and of texturing
  double seconds = 0;              // wall time
  RecordStageTimes stage_times;
};

// A clip stores colour (viewers texture the model and the frames from it): a source without
// colour (SensorInfo.has_color false, e.g. rgbd:DIR without rgb/) is an Error (code
// "unsupported") naming the source kinds that have colour. RecordClip checks it before it
// reads a frame; callers may check it earlier.
Status CheckRecordableSource(const SensorInfo& info);

// Errors: the source has no colour (CheckRecordableSource); the source fails or gives no
// frame; colour, depth and mask sizes disagree; the source's poses stop part-way; no frame
// ends up with both a pose and a skeleton (the message says which was missing and what to
// pass); the directory exists or cannot be written.
// Nothing is left at out_dir on failure.
Expected<RecordSummary> RecordClip(FrameSource& source, const std::filesystem::path& out_dir,
                                   const RecordOptions& options);

}  // namespace reenact::capture
