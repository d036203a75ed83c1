#pragma once
// An imported skeleton track: one 16-joint skeleton per recorded frame, in the SENSOR frame
// (OpenCV camera axes: x right, y down, z forward, metres; the frame of the depth camera that
// recorded the stream, so world = world_from_sensor * skeleton_in_sensor). Tracks come from
// our JSON (skeleton_track_json.h) or from Kinect v1 text files (kinect_v1_skeleton.h).
//
// Keying. A track is keyed either by timestamp or by frame index, never a mix:
// - every frame has timestamp_s (finite, strictly increasing): keyed by timestamp; frame
//   indices, where present, are kept for information (strictly increasing too);
// - no frame has timestamp_s: every frame needs frame_index (strictly increasing; gaps are
//   fine, e.g. UTKinect tracks only some of its image numbers).
//
// Lookup rule, ForFrame(index, t) for a captured frame with index `index` (0 = first frame
// the source yields) and timestamp `t` (seconds, the source's clock):
// - keyed by timestamp: the track frame nearest to t + timestamp_offset_s, if it lies within
//   timestamp_tolerance_s of it (|t_track - (t + offset)| <= tolerance); of two equally near
//   frames the earlier one; `index` is ignored;
// - keyed by frame index: the track frame whose frame_index equals index + frame_index_offset
//   (UTKinect numbers frames by its image files, so a capture that starts at image N needs
//   frame_index_offset = N); `t` is ignored.
// nullopt where no frame matches (before or after the track, in a gap, beyond the
// tolerance) or t is not finite: such a frame simply has no skeleton (it still serves SLAM).

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common/error/expected.h"
#include "common/skeleton/skeleton.h"

namespace reenact::capture {

struct SkeletonTrackFrame {
  std::optional<int64_t> frame_index;  // >= 0
  std::optional<double> timestamp_s;   // seconds, finite
  Skeleton skeleton_in_sensor;         // metres, sensor frame; confidence 0 = missing joint
};

struct SkeletonTrackLookupOptions {
  // Largest accepted |t_track - (t + timestamp_offset_s)|, seconds; finite, >= 0. Default:
  // half a frame at 30 Hz.
  double timestamp_tolerance_s = 0.5 / 30.0;
  // Added to the capture timestamp before the lookup (track clock = capture clock + offset),
  // seconds; finite.
  double timestamp_offset_s = 0;
  // Added to the capture frame index before the lookup (track index = index + offset).
  int64_t frame_index_offset = 0;

  // Throws CheckError on a non-finite or negative tolerance or a non-finite time offset.
  void Check() const;
};

class SkeletonTrack {
 public:
  // Validates the frames (see the keying rules above; joint positions finite, confidences in
  // [0, 1]; at least one frame). Errors (code "corrupt") name the frame (0-based position in
  // `frames`) and the field, e.g. "skeleton track X: frame 3: timestamp_s 0.1 is not after
  // the previous frame's 0.2". description: one line for people, e.g. the file and format.
  static Expected<SkeletonTrack> Create(std::vector<SkeletonTrackFrame> frames,
                                        std::string description,
                                        const SkeletonTrackLookupOptions& options = {});

  // The skeleton for a captured frame (see the lookup rule above), in the sensor frame.
  std::optional<Skeleton> ForFrame(int64_t index, double timestamp_s) const;

  bool keyed_by_timestamp() const { return keyed_by_timestamp_; }
  size_t size() const { return frames_.size(); }
  const std::vector<SkeletonTrackFrame>& frames() const { return frames_; }
  const std::string& description() const { return description_; }

  const SkeletonTrackLookupOptions& lookup_options() const { return options_; }
  void set_lookup_options(const SkeletonTrackLookupOptions& options);  // Check()s them

 private:
  SkeletonTrack() = default;

  std::vector<SkeletonTrackFrame> frames_;
  std::string description_;
  SkeletonTrackLookupOptions options_;
  bool keyed_by_timestamp_ = false;
};

}  // namespace reenact::capture
