#pragma once
// FrameSource over a TUM RGB-D sequence directory (tum:DIR), for evaluating SLAM against the
// benchmark's motion-capture ground truth and for recording from its frames.
//
// Frames: the colour + depth pairs of associations.txt, else of rgb.txt and depth.txt
// associated by timestamp, at most 0.02 s apart (tum_dataset.h), in colour-time order; a
// frame's timestamp is its colour image's. Depth: the 16-bit PNG value / 5000 is metres, so
// value / 5 rounded is millimetres (0 stays "no reading").
//
// Camera: the sequence's Kinect (tum_camera.h), from `camera=fr1|fr2|fr3` or detected from
// the directory's name ("..._freiburg1_..." or "...fr1..."); neither is an Error asking for
// the option. The colour image is undistorted with that Kinect's Brown-Conrady calibration
// (ImageUndistorter), so SensorInfo's cameras are the undistorted pinhole (same K,
// distortion 0) and SensorInfo.description says so.
// Depth is left as it is (`undistort=color`, the default). TUM's depth was registered by the
// Kinect's OpenNI driver onto the raw, distorted colour image (its pixels correspond 1:1 to
// the distorted colour), and TUM advises against undistorting it: depth is not an image to
// interpolate (bilinear resampling invents depths across object edges), and its registration
// was the driver's, not this calibration's. The cost: once the colour is undistorted, colour
// pixel (u, v) and depth pixel (u, v) are apart by the distortion's displacement at (u, v).
// For fr1 that is 0 at the principal point, 1.2 px at 100 px from it, 5.8 px at 200 px, 7-8
// px at the middles of the image edges and 17-37 px in the corners; over 1 px on 88% of the
// image. fr2 is similar; fr3's images were undistorted at the source (no cost).
// Where that matters, `undistort=both` also remaps depth with the same lookup, by nearest
// neighbour (no invented depths; readings are duplicated or dropped where the map stretches
// or squeezes), which keeps colour and depth registered; `undistort=none` passes both
// through and reports the camera with its distortion.
// Ground truth. groundtruth.txt (optional) is interpolated to every frame's timestamp
// (timed_trajectory.h; frames outside its time span or in a gap over 0.05 s have none) and
// offered through ground_truth(), NOT through SensorFrame::world_from_sensor: that field is
// the pose a capture has tracked, which the recorder stores in the clip and SLAM would take
// as given. Filling it from the motion-capture system would let a TUM recording pass as
// tracked, and an evaluation could not tell whether an estimator read it. SLAM evaluation
// pairs its estimate of frame i with ground_truth()[i] (world = the motion-capture world,
// sensor = the colour camera's optical frame, OpenCV axes).

#include <Eigen/Geometry>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "capture-client/source/frame_checks.h"
#include "capture-client/source/frame_source.h"
#include "capture-client/source/image_undistorter.h"
#include "capture-client/source/tum_camera.h"
#include "capture-client/source/tum_dataset.h"

namespace reenact::capture {

struct TumSourceOptions {
  std::optional<TumCamera> camera;  // nullopt: detected from the directory name
  enum class Undistort { kColor, kBoth, kNone };
  Undistort undistort = Undistort::kColor;  // see "Camera" above
  double max_association_gap_s = 0.02;      // rgb.txt / depth.txt pairing, >= 0
  double max_ground_truth_gap_s = 0.05;     // > 0: 5 samples of the 100 Hz motion capture
  int max_leading_empty_depth_frames = 30;  // frame_checks.h, >= 1

  void Check() const;
};

class TumSource : public FrameSource {
 public:
  // Errors: "not_found" (no such directory, no frame lists, a listed image missing: named
  // with the list that names it), "usage" (no camera given or detectable), and those of
  // ReadTumFrameList and ReadTumTrajectory.
  static Expected<std::unique_ptr<TumSource>> Open(const std::filesystem::path& dir,
                                                   const TumSourceOptions& options);
  // "DIR?camera=fr1&undistort=color|both|none" (tum: spec argument).
  static Expected<std::unique_ptr<TumSource>> OpenSpec(const std::string& argument);

  const SensorInfo& info() const override { return info_; }
  // Errors: "corrupt" (an image that does not decode, depth that is not 16-bit single
  // channel, colour and depth sizes that differ or differ from the camera's), "not_found"
  // (an image deleted since Open), "no_depth" (frame_checks.h).
  Expected<std::optional<SensorFrame>> Next() override;

  const TumFrameList& frames() const { return frames_; }
  TumCamera camera() const { return camera_; }
  bool has_ground_truth() const { return has_ground_truth_; }
  // world_from_sensor of every frame, in the order Next() yields them; all nullopt without
  // groundtruth.txt.
  const std::vector<std::optional<Eigen::Isometry3d>>& ground_truth() const {
    return ground_truth_;
  }
  // The raw samples of groundtruth.txt (empty without it).
  const std::vector<TimedPose>& ground_truth_samples() const { return ground_truth_samples_; }

 private:
  TumSource() = default;
  // Reads groundtruth.txt when there is one and interpolates each frame's pose in it.
  Status LoadGroundTruth();
  // The cameras (undistorted as options_ ask), frame count and rate, and description.
  void DescribeSensor();

  std::filesystem::path dir_;
  TumSourceOptions options_;
  SensorInfo info_;
  TumCamera camera_ = TumCamera::kFreiburg1;
  TumFrameList frames_;
  std::optional<ImageUndistorter> undistorter_;
  bool has_ground_truth_ = false;
  std::vector<TimedPose> ground_truth_samples_;
  std::vector<std::optional<Eigen::Isometry3d>> ground_truth_;
  DepthPresenceGuard depth_guard_;
  size_t next_ = 0;
};

}  // namespace reenact::capture
