#pragma once
// Colour-camera intrinsics of the TUM RGB-D benchmark's three Kinects (Sturm et al. 2012,
// "File Formats" / "Intrinsic Camera Calibration of the Kinect" on the benchmark's site),
// 640x480, OpenCV's Brown-Conrady model (k1 k2 p1 p2 k3):
//   fr1: fx 517.3  fy 516.5  cx 318.6  cy 255.3  d  0.2624 -0.9531 -0.0054  0.0026 1.1633
//   fr2: fx 520.9  fy 521.0  cx 325.1  cy 249.7  d  0.2312 -0.7849 -0.0033 -0.0001 0.9172
//   fr3: fx 535.4  fy 539.2  cx 320.1  cy 247.6  d  0 (its images were undistorted already)
// Sequence directories are named after their sensor ("rgbd_dataset_freiburg1_xyz"), which
// DetectTumCamera reads.

#include <optional>
#include <string>
#include <string_view>

#include "common/error/expected.h"
#include "common/geometry/pinhole_camera.h"

namespace reenact::capture {

enum class TumCamera { kFreiburg1, kFreiburg2, kFreiburg3 };

std::string_view TumCameraName(TumCamera camera);  // "fr1", "fr2", "fr3"
PinholeCamera TumColorCamera(TumCamera camera);    // with its distortion

// "fr1" / "freiburg1" (any case) and likewise for 2 and 3; an Error (code "usage") otherwise.
Expected<TumCamera> ParseTumCamera(std::string_view name);

// The camera named in a directory name: it contains "freiburg1" or "fr1" (any case), etc.
// nullopt when it names none or more than one.
std::optional<TumCamera> DetectTumCamera(std::string_view directory_name);

}  // namespace reenact::capture
