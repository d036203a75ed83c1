#pragma once
// Records a clip from a frame source into a clip directory (proto/clip/clip_directory.h):
// per frame the subject's crop of colour, depth and person mask with the sensor pose and the
// skeleton in the world frame; the cylinder model (representative frame by Eq. 2-4, radius
// ratios from the depth and mask of the best frames); the background map from keyframes;
// the manifest.

#include <filesystem>
#include <string>

#include "capture-client/map/background_map_builder.h"
#include "capture-client/segment/segment_options.h"
#include "capture-client/source/frame_source.h"
#include "common/model/model_building.h"
#include "common/error/expected.h"
#include "proto/clip/frame_codec.h"

namespace reenact::capture {

struct RecordOptions {
  int max_frames = -1;         // frames to record, -1 = until the source ends; else >= 1
  int crop_margin_px = 12;     // margin around the person mask's bounding box, >= 0
  int keyframe_interval = 10;  // every n-th frame feeds the map, >= 1
  std::string title;           // manifest title (may be set again at publish)
  std::string author;
  proto::FrameCodecOptions codec;
  BackgroundMapOptions map;
  PersonSegmentOptions segment;  // for frames whose source gives no person mask
  // Cylinder model (Eq. 2-4): per-part median over the 3 best frames by F(n), which halves
  // the radius error of the thesis's single frame on noisy skeletons (reenact-bench core).
  ModelBuildOptions model{.representative = {}, .fit = {}, .robust_k = 3};

  void Check() const;
};

struct RecordSummary {
  int frames = 0;
  uint64_t frame_bytes = 0;       // all encoded frames together
  uint64_t map_bytes = 0;
  size_t map_points = 0;
  int representative_frame = -1;
  int fitted_parts = 0;           // parts whose radius came from the fit, not the default
  int segmented_frames = 0;       // frames whose person mask came from our segmentation
  int inconsistent_skeletons = 0; // frames kept out of the model (skeleton consistency check)
  double seconds = 0;             // wall time
};

// A frame without a person mask is segmented from its depth and skeleton
// (capture-client/segment/person_segmenter.h). Skeletons that fail the consistency check
// (skeleton_consistency.h) are recorded but kept out of the cylinder model.
// Errors: the source fails, gives no frame, or lacks what this build needs per frame (sensor
// pose and skeleton: SLAM and tracking of real sensors arrive later);
// the directory cannot be written. Nothing is left at out_dir on failure.
Expected<RecordSummary> RecordClip(FrameSource& source, const std::filesystem::path& out_dir,
                                   const RecordOptions& options);

}  // namespace reenact::capture
