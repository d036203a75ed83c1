#pragma once
// A synthetic viewer camera: the [Eval] scenes (synthetic/, the library reenact_synthetic,
// not the capture pipeline) seen by a learner who walks around the spot the
// clip was recorded from, holding the phone, with the true pose of every frame known.
//
//   synthetic:SCENARIO[?frames=N&max_deg=D&subject=0|1&seed=S&body=FILE.glb&body_height=M]
//
// SCENARIO as `reenact-capture record --source synthetic:SCENARIO` takes it (turn-and-kick,
// walk-handheld, bvh:FILE, ...; body/body_height choose the subject the same way). Record the
// clip from the same scenario, so that the viewer stands in the clip's room and world frame.
//
// Trajectory (frames k = 0 .. N-1, N default the scenario's frame count, >= 2): frame k's eye
// is the capture sensor's frame-0 position turned about the vertical through the subject's
// centre (the skeleton's waist at frame 0) by
//     a_k = D sin(2 pi k / (N - 1))        (0 -> +D -> 0 -> -D -> 0 degrees; D default 45)
// at the sensor's distance and height, aimed at the centre, with a walking hand's bob and
// shake (synthetic/handheld_trajectory.h; seed S, default 1). Timestamps are
// k / the scenario's frame rate.
//
// Frame k shows the scene at scenario frame k mod frame_count, rendered with the capture
// sensor's intrinsics (PinholeCamera::KinectLike(): 640x480, no distortion; no calibration file
// is needed or accepted). By default (subject=0) the room alone: the learner visits after the
// performance, and the reenactment is what puts the performer back. subject=1 draws the
// scene's own subject too (the relocaliser then also sees the person occluding the room).
//
// Every CameraFrame carries true_world_from_viewer, so `reenact-viewer play` writes the truth
// beside the relocalised pose (ar_player.h).

#include <Eigen/Geometry>
#include <memory>
#include <string_view>
#include <vector>

#include "synthetic/handheld_trajectory.h"
#include "synthetic/synthetic_scene.h"
#include "viewer-client/camera/camera_source.h"

namespace reenact::viewer {

struct SyntheticViewerPath {
  std::vector<Eigen::Isometry3d> world_from_viewer;  // per frame, OpenCV camera axes
  std::vector<double> angle_deg;                     // a_k, before the hand's shake
};

// The trajectory above for n >= 2 frames and 0 < max_deg <= 90 (CheckError otherwise).
SyntheticViewerPath MakeSyntheticViewerPath(const capture::SyntheticScene& scene, int n,
                                            double max_deg,
                                            const capture::HandheldOptions& hand = {});

struct SyntheticCameraOptions {
  int frames = 0;       // N, >= 2; 0 = the scenario's frame count
  double max_deg = 45;  // D, in (0, 90]
  bool draw_subject = false;
  uint64_t seed = 1;  // the hand's shake

  void Check() const;
};

// Opens the camera for a scene. Throws CheckError when options fail Check().
std::unique_ptr<CameraSource> OpenSyntheticCameraSource(capture::SyntheticScene scene,
                                                        const SyntheticCameraOptions& options);

// From the spec's argument (after "synthetic:"). Errors: "usage" for an empty scenario, an
// unknown option, or a value out of range (the message names the option and its range); those
// of SyntheticScene::Create (an unknown scenario lists the known ones, a body file that cannot
// be used).
Expected<std::unique_ptr<CameraSource>> OpenSyntheticCameraSpec(std::string_view argument);

}  // namespace reenact::viewer
