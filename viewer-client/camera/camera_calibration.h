#pragma once
// Intrinsics of a viewer camera from a calibration file: OpenCV FileStorage, YAML (.yaml,
// .yml) or JSON (.json), as OpenCV's own calibration tools write it:
//
//   %YAML:1.0
//   image_width: 640
//   image_height: 480
//   camera_matrix: !!opencv-matrix          # K = [fx 0 cx; 0 fy cy; 0 0 1], pixels
//     rows: 3
//     cols: 3
//     dt: d
//     data: [ 517.3, 0., 318.6, 0., 516.5, 255.3, 0., 0., 1. ]
//   distortion_coefficients: !!opencv-matrix  # k1 k2 p1 p2 [k3 [k4 k5 k6]]
//     rows: 1
//     cols: 5
//     dt: d
//     data: [ 0.2624, -0.9531, -0.0054, 0.0026, 1.1633 ]
//
// Pixel centres at integers (OpenCV's convention). distortion_coefficients may be absent
// (no distortion), or hold 4, 5 or 8 values in one row or column; the rational terms k4-k6
// of an 8-value model must be 0 (the project's camera model is Brown-Conrady with k1 k2 p1 p2
// k3). docs/calibration/ has the TUM RGB-D Kinects' files.

#include <filesystem>

#include "common/error/expected.h"
#include "common/geometry/pinhole_camera.h"

namespace reenact::viewer {

// Errors: "not_found" (no such file), "corrupt" (not parseable as YAML/JSON FileStorage, a
// missing or malformed field: each message names the field and what it must be),
// "unsupported" (non-zero k4-k6).
Expected<PinholeCamera> LoadCameraCalibration(const std::filesystem::path& path);

}  // namespace reenact::viewer
