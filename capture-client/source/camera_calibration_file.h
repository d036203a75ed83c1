#pragma once
// The camera of an RGB-D folder (rgbd_folder_source.h) from a calibration file: OpenCV
// FileStorage YAML (as cv::FileStorage writes it, first line "%YAML:1.0"; a file without that
// line is read as YAML too) or JSON, one top-level map. Two forms of the intrinsics:
//
//   OpenCV's calibration tools:               a plain camera.json (e.g. UTD-MHAD's):
//     image_width: 640                          { "width": 320, "height": 240,
//     image_height: 480                           "fx": 285.63, "fy": 285.63,
//     camera_matrix: !!opencv-matrix              "cx": 160.0, "cy": 120.0,
//       rows: 3                                   "depth_unit_m": 0.001,
//       cols: 3                                   "frames": 48, "fps": 30 }
//       dt: d
//       data: [ fx, 0, cx, 0, fy, cy, 0, 0, 1 ]
//     distortion_coefficients: !!opencv-matrix
//       rows: 1
//       cols: 5
//       dt: d
//       data: [ k1, k2, p1, p2, k3 ]
//
// Keys (a file holds camera_matrix or fx/fy/cx/cy, not both; every other key is optional):
//   camera_matrix            3x3 [fx 0 cx; 0 fy cy; 0 0 1] (no skew), pixels: an
//                            !!opencv-matrix (JSON: {"type_id": "opencv-matrix", "rows": 3,
//                            "cols": 3, "dt": "d", "data": [...]}) or a list of 9 numbers
//   fx, fy, cx, cy           numbers, pixels
//   image_width/image_height or width/height: positive integers (both or neither); without
//                            them the images' size is taken
//   distortion_coefficients  k1 k2 p1 p2 [k3 [k4 k5 k6]]: 4, 5 or 8 numbers, one row or
//                            column (or a list); k4-k6 must be 0 (Brown-Conrady only)
//   depth_unit_m             metres per depth unit, in (0, 1]
//   fps                      frames per second, > 0
//   frames                   the number of frames, integer >= 1
//   mirrored                 0/1 or true/false: the images are mirrored left-right (as the
//                            Kinect SDK delivers them); the intrinsics describe the images as
//                            stored
// Pixel centres at integers (OpenCV's convention). fx and fy must be > 0.
//
// Errors: "not_found" (no such file), "corrupt" (not a YAML or JSON FileStorage file, no
// top-level map, intrinsics missing, a key of the wrong type or outside its range: the message
// names the file and the key), "unsupported" (non-zero k4-k6).

#include <filesystem>
#include <optional>

#include "common/error/expected.h"
#include "common/geometry/pinhole_camera.h"

namespace reenact::capture {

struct CameraCalibrationFile {
  PinholeCamera camera;  // width and height 0 when the file gives no image size
  std::optional<double> depth_unit_m;
  std::optional<double> fps;
  std::optional<int> frames;
  std::optional<bool> mirrored;
};

Expected<CameraCalibrationFile> ReadCameraCalibrationFile(const std::filesystem::path& path);

}  // namespace reenact::capture
