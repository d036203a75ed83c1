#pragma once
// Removes lens distortion from the colour images of one camera. The output camera keeps the
// input's size and K (fx, fy, cx, cy) with zero distortion, so a scene point P lands at
// K (X/Z, Y/Z) in the output where it landed at PinholeCamera::Project(P) (with the
// Brown-Conrady model) in the input. The per-pixel lookup, out(u, v) = in(distort(u, v)), is
// built once (OpenCV initUndistortRectifyMap, fixed-point maps) and applied per frame with a
// bilinear remap; output pixels whose source lies outside the input image are 0. Depth
// registered to the distorted colour can follow with UndistortDepth: the same lookup by
// nearest neighbour (depth is never interpolated across edges).

#include <memory>

#include "common/geometry/pinhole_camera.h"
#include "common/image/image.h"

namespace reenact::capture {

class ImageUndistorter {
 public:
  // Precondition (CHECK): camera.Check() passes.
  explicit ImageUndistorter(const PinholeCamera& distorted);
  ~ImageUndistorter();
  ImageUndistorter(ImageUndistorter&&) noexcept;
  ImageUndistorter& operator=(ImageUndistorter&&) noexcept;

  const PinholeCamera& distorted_camera() const { return distorted_; }
  const PinholeCamera& undistorted_camera() const { return undistorted_; }

  // Precondition (CHECK): image of the camera's size, 3 channels.
  ImageRgb8 Undistort(const ImageRgb8& image) const;
  // Precondition (CHECK): image of the camera's size, 1 channel.
  ImageDepthMm UndistortDepth(const ImageDepthMm& depth) const;

 private:
  struct Maps;
  PinholeCamera distorted_, undistorted_;
  std::unique_ptr<Maps> maps_;
};

}  // namespace reenact::capture
