#pragma once
// Inputs of the SLAM tests: a real TUM RGB-D sequence read through the tum: source (raw
// colour and depth, the camera with its distortion, motion-capture ground truth per frame),
// and the synthetic walk-handheld scenario (a hand-held sensor moving through the textured
// room around a walking person), rendered once per process.

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include "common/geometry/pinhole_camera.h"
#include "common/image/image.h"
#include "synthetic/synthetic_scene.h"

namespace reenact::capture::slam::test_input {

struct Frame {
  double timestamp_s = 0;
  ImageRgb8 color;
  ImageDepthMm depth;
  ImageGray8 mask;  // the subject (synthetic only; empty for TUM)
  std::optional<Eigen::Isometry3d> truth_world_from_sensor;
};

struct Sequence {
  PinholeCamera camera;
  double depth_scale_m = 0.001;
  std::vector<Frame> frames;
};

// ../shared/data/tum-fr1-rpy-head
std::string TumRpyDir();

// The first max_frames frames of a TUM sequence; no frames when the folder is absent.
Sequence LoadTum(const std::string& dir, int max_frames);

// walk-handheld frames 0, step, 2 step, ... (count of them), with Kinect-like depth noise
// (synthetic/depth_noise.h), the subject's mask, and the true sensor poses. Cached.
const Sequence& WalkHandheld(int count, int step);

// The scenario itself (for rendering other views of the same world).
const SyntheticScene& WalkHandheldScene();

}  // namespace reenact::capture::slam::test_input
