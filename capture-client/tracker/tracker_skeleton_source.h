#pragma once
// The depth tracker as the recorder's skeleton source (record/clip_recorder.h,
// RecordOptions::frame_skeletons): one SkeletonTracker per recording, fed every source
// frame's depth in order, with its timestamp (the tracker's prediction spans a dropped frame's
// gap), the recorder's pose hint (the source's pose, or SLAM's prediction for a sensor without
// poses) and world up when known: the tracker's static scene and floor need them for a moving
// sensor. Counts what happened, for the recording's summary.

#include <array>
#include <memory>
#include <string>

#include "capture-client/record/clip_recorder.h"
#include "capture-client/source/frame_source.h"
#include "capture-client/tracker/skeleton_tracker.h"

namespace reenact::capture {

struct TrackerSourceStats {
  int frames = 0;
  int tracked = 0;             // frames with a skeleton
  int calibration_frame = -1;  // source frame index of the (first) calibration, -1 = none
  bool from_calibration_pose = false;
  // A start without the calibration pose: the body's head (radius) and legs (thigh + shin)
  // against the average proportions of its height, as measured from the silhouette
  // (head_size.h, crotch_height.h) and fitted on the fly; 1 otherwise.
  double head_scale = 1, leg_scale = 1;
  int losses = 0, recoveries = 0;
  // Frames given the sensor's pose (the source's, or SLAM's prediction): only on those does
  // the tracker learn and leave out the static scene beside the subject (static_scene_voxels.h).
  int posed = 0;
  // Frames per detection outcome (Index: DetectStatus).
  std::array<int, 3> detect{};

  // One line for people: what was tracked, or why nothing was (and what to do).
  std::string Describe() const;
};

class TrackerSkeletonSource {
 public:
  // Preconditions as SkeletonTracker's (the source's depth camera and scale).
  TrackerSkeletonSource(const SensorInfo& info, const SkeletonTrackerOptions& options = {});

  // The function for RecordOptions::frame_skeletons; it refers to this object, which must
  // outlive the recording. Errors: a frame whose depth is not the depth camera's size
  // ("corrupt").
  FrameSkeletonSource Function();

  const TrackerSourceStats& stats() const { return stats_; }
  const SkeletonTracker& tracker() const { return *tracker_; }

 private:
  Expected<std::optional<Skeleton>> Track(int64_t index, const SensorFrame& frame,
                                          const FramePoseHint& pose);

  SensorInfo info_;
  std::unique_ptr<SkeletonTracker> tracker_;
  TrackerSourceStats stats_;
};

}  // namespace reenact::capture
