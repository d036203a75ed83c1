#pragma once
// Depth image to 3D points in the camera frame (OpenCV: x right, y down, z forward, metres).
// A depth value d at pixel (x, y) is a point at Z = d * depth_scale_m along the optical axis
// seen through that pixel: PinholeCamera::Unproject, which undistorts (Brown-Conrady) when
// the camera has distortion. Depth 0 is a hole (no reading) and yields no point.
//
// The depth image must be registered to the camera given (same width and height): the
// colour camera when the sensor registers depth to colour, as Kinect and TUM data do.

#include <Eigen/Core>
#include <limits>
#include <optional>
#include <vector>

#include "common/geometry/pinhole_camera.h"
#include "common/image/image.h"

namespace reenact {

struct DepthPointsOptions {
  // Metres per depth unit, > 0 and finite. 0.001 for millimetres; TUM RGB-D uses 0.0002.
  double depth_scale_m = 0.001;
  // Points with Z below min_depth_m or above max_depth_m (metres) are skipped.
  // 0 <= min_depth_m <= max_depth_m; default: keep every reading.
  double min_depth_m = 0;
  double max_depth_m = std::numeric_limits<double>::infinity();
  // Take every stride-th pixel in x and y, starting at (0, 0); >= 1.
  int stride = 1;

  // Throws CheckError when a field is outside its range.
  void Check() const;
};

// Points and the pixel each came from, in row-major pixel order.
struct DepthPoints {
  std::vector<Eigen::Vector3d> points_in_camera;  // metres, camera frame
  std::vector<Eigen::Vector2i> pixels;            // (x, y) of each point
};

// Every pixel with a reading (and, when `mask` is given, a non-zero mask value) as a point.
// Preconditions (CHECK): options valid, camera valid, depth is 1 channel and
// camera-sized, mask (if given) is 1 channel and depth-sized.
DepthPoints DepthToPoints(const ImageDepthMm& depth, const PinholeCamera& camera,
                          const DepthPointsOptions& options = {}, const ImageGray8* mask = nullptr);

// The point seen at one pixel: nullopt for a hole (0), a depth outside the options' range,
// or a pixel outside the image. Same preconditions as DepthToPoints (stride is ignored).
std::optional<Eigen::Vector3d> BackProjectPixel(const ImageDepthMm& depth,
                                                const PinholeCamera& camera, int x, int y,
                                                const DepthPointsOptions& options = {});

}  // namespace reenact
