#include "viewer-client/render/gl_projection.h"

#include "common/error/check.h"

namespace reenact::viewer {

Eigen::Matrix4d GlProjectionFromPinhole(const PinholeCamera& camera, double near, double far) {
  camera.Check();
  REENACT_CHECK(near > 0 && far > near, "clip planes need 0 < near < far");
  const double w = camera.width, h = camera.height;
  Eigen::Matrix4d m = Eigen::Matrix4d::Zero();
  m(0, 0) = 2 * camera.fx / w;
  m(0, 2) = (2 * camera.cx + 1) / w - 1;
  m(1, 1) = -2 * camera.fy / h;
  m(1, 2) = 1 - (2 * camera.cy + 1) / h;
  m(2, 2) = (far + near) / (far - near);
  m(2, 3) = -2 * far * near / (far - near);
  m(3, 2) = 1;
  return m;
}

}  // namespace reenact::viewer
