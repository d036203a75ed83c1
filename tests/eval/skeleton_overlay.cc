#include "tests/eval/skeleton_overlay.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "common/error/check.h"

namespace reenact::eval {
namespace {

void Draw(const Skeleton& s, const PinholeCamera& camera, int scale, int thickness,
          const cv::Scalar& colour, cv::Mat* picture) {
  const auto pixel = [&](Joint j) -> std::optional<cv::Point> {
    if (!s.Has(j) || !s[j].allFinite()) return std::nullopt;
    const auto p = camera.Project(s[j], 0.05);
    if (!p || !p->allFinite() || p->cwiseAbs().maxCoeff() > 1e5) return std::nullopt;
    return cv::Point(static_cast<int>(std::lround((p->x() + 0.5) * scale - 0.5)),
                     static_cast<int>(std::lround((p->y() + 0.5) * scale - 0.5)));
  };
  std::vector<std::pair<Joint, Joint>> bones = {{Joint::kNeck, Joint::kLeftShoulder},
                                                 {Joint::kNeck, Joint::kRightShoulder},
                                                 {Joint::kWaist, Joint::kLeftHip},
                                                 {Joint::kWaist, Joint::kRightHip}};
  for (int b = 0; b < kBodyPartCount; ++b) bones.push_back(PartJoints(static_cast<BodyPart>(b)));
  for (const auto& [ja, jb] : bones) {
    const auto a = pixel(ja), c = pixel(jb);
    if (a && c) cv::line(*picture, *a, *c, colour, thickness, cv::LINE_AA);
  }
  for (int j = 0; j < kJointCount; ++j)
    if (const auto p = pixel(static_cast<Joint>(j)))
      cv::circle(*picture, *p, thickness + 1, colour, cv::FILLED, cv::LINE_AA);
}

}  // namespace

void SkeletonOverlayOptions::Check() const {
  REENACT_CHECK(scale >= 1 && scale <= 8, "scale must lie in 1-8");
  REENACT_CHECK(thickness >= 1 && thickness <= 8, "thickness must lie in 1-8");
}

ImageRgb8 SkeletonOverlay(const ImageDepthMm& depth, const PinholeCamera& camera,
                          const std::optional<Skeleton>& reference,
                          const std::optional<Skeleton>& estimate,
                          const SkeletonOverlayOptions& options) {
  options.Check();
  REENACT_CHECK(!depth.empty() && depth.channels == 1, "depth must be a 1-channel image");
  REENACT_CHECK(camera.width == depth.width && camera.height == depth.height,
                "the camera's size must be the depth's");
  uint16_t near = UINT16_MAX, far = 0;
  for (uint16_t d : depth.data)
    if (d > 0) near = std::min(near, d), far = std::max(far, d);
  const double range = far > near ? far - near : 1;
  const int scale = options.scale;
  cv::Mat picture(depth.height * scale, depth.width * scale, CV_8UC3);
  for (int y = 0; y < picture.rows; ++y)
    for (int x = 0; x < picture.cols; ++x) {
      const uint16_t d = depth.at(x / scale, y / scale);
      const uint8_t g =
          d == 0 ? 0 : static_cast<uint8_t>(std::lround(255 - 175 * (d - near) / range));
      picture.at<cv::Vec3b>(y, x) = cv::Vec3b(g, g, g);
    }
  if (reference) Draw(*reference, camera, scale, options.thickness, {0, 200, 0}, &picture);
  if (estimate) Draw(*estimate, camera, scale, options.thickness, {230, 30, 30}, &picture);
  ImageRgb8 out(picture.cols, picture.rows, 3);
  std::copy(picture.data, picture.data + out.data.size(), out.data.begin());
  return out;
}

}  // namespace reenact::eval
