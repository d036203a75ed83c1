#pragma once
// `reenact-eval slam --tum DIR [--camera fr1|fr2|fr3] [--max-frames N] [--methods LIST]
//                   [--readout-ratio R] [--json FILE]`
// runs every method over the same TUM RGB-D sequence (capture-client/source/tum_source.h;
// raw colour and depth, the camera with its distortion) and compares each trajectory with
// the motion-capture ground truth:
//   - reenact:        our RGB-D SLAM (capture-client/slam/rgbd_slam.h), frame-to-map;
//   - opencv-rgbd:    cv::rgbd::RgbdOdometry, frame to frame, chained;
//   - opencv-fasticp: cv::rgbd::FastICPOdometry, frame to frame, chained.
// The OpenCV odometries take undistorted images: they get colour and depth undistorted with
// the same lookup (opencv_odometry.h); ours undistorts its keypoints instead.
//
// Figures per method (report names of DESIGN.md where they exist):
//   ate_rmse_m     absolute trajectory error: RMSE of the positions after the rigid
//                  (Umeyama) alignment to the ground truth, over frames with a pose and a
//                  ground truth pose (common/align/trajectory_error.h);
//   rpe_m, rpe_deg relative pose error between consecutive such frames: RMSE of the
//                  translation (metres per frame) and rotation (degrees per frame) of
//                  (T_gt(i-1)^-1 T_gt(i))^-1 (T(i-1)^-1 T(i));
//   tracked_rate   frames with a pose / frames;
//   ms_per_frame   median wall time of the method's per-frame work (ours: Track(); OpenCV:
//                  grey conversion, frame preparation and compute), fps = 1000 / that;
//   ours also: keyframes, fallback and relocalised frames, the points of the map a clip
//   would store and its bytes (map_bytes, proto/clip/map_codec.h).

#include <optional>
#include <set>
#include <string>
#include <vector>

#include "capture-client/slam/rolling_shutter.h"
#include "common/cli/command_line.h"
#include "common/error/expected.h"
#include "proto/report/report_table.h"

namespace reenact::eval {

// Rolling-shutter readout ratio used for ours unless --readout-ratio says otherwise: the TUM
// sequences were all recorded with Kinect v1 sensors.
inline constexpr double kKinectReadoutRatio = capture::slam::kKinectV1ReadoutRatio;

struct SlamEvalOptions {
  std::string tum_dir;
  std::optional<std::string> camera;  // "fr1" / "fr2" / "fr3"; default: from the folder name
  int max_frames = -1;                // -1: every frame
  std::vector<std::string> methods = {"reenact", "opencv-rgbd", "opencv-fasticp"};
  double readout_ratio = kKinectReadoutRatio;  // for ours, [0, 1]
};

struct SlamMethodResult {
  std::string method;
  int frames = 0;
  int tracked = 0;        // frames with a pose
  int evaluated = 0;      // frames with a pose and a ground truth pose
  double ate_rmse_m = 0;  // NaN when fewer than 3 frames could be evaluated
  double rpe_m = 0;       // NaN without consecutive evaluated frames
  double rpe_deg = 0;
  double ms_per_frame = 0;  // median
  double ms_p90 = 0;
  // Ours only (0 for the others):
  int keyframes = 0;
  int fallback_frames = 0;
  int relocalised_frames = 0;
  int map_points = 0;       // points of the map stored with a clip
  long long map_bytes = 0;  // their encoded size
};

struct SlamEvalRun {
  std::string sequence;  // the folder name
  std::string camera;    // e.g. "fr1"
  int frames = 0;
  int frames_with_truth = 0;
  std::vector<SlamMethodResult> methods;
};

// The value flags of `slam`.
std::set<std::string> SlamFlags();

// Errors (code "usage"): no --tum, an unknown method or empty list, --max-frames not an
// integer >= 3, --readout-ratio not in [0, 1], a bad --camera; (code "io") an unwritable
// --json file.
struct SlamCommand {
  SlamEvalOptions options;
  std::optional<std::string> json_path;
};
Expected<SlamCommand> ParseSlamCommand(const CommandLine& command_line);

// Runs every method. Errors: those of opening and reading the sequence (not_found, corrupt,
// usage for an undetectable camera); "invalid_argument" when it has no ground truth.
Expected<SlamEvalRun> RunSlamEval(const SlamEvalOptions& options);

proto::Report SlamReport(const SlamEvalRun& run);
std::vector<std::string> SlamRules();

// The whole command: parse, run, print the table and rules (and --json). Exit status.
int RunSlamCommand(const CommandLine& command_line);

}  // namespace reenact::eval
