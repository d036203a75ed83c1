#include "capture-client/map/virtual_views.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "capture-client/segment/pixel_rays.h"
#include "common/error/check.h"

namespace reenact::capture {

void VirtualViewOptions::Check() const {
  for (double yaw : yaw_deg) {
    REENACT_CHECK(std::isfinite(yaw) && yaw != 0 && std::abs(yaw) <= 90,
                  "virtual view yaw_deg must be in [-90, 90] and not 0");
  }
  REENACT_CHECK(person_dilation_px >= 0, "person_dilation_px must be >= 0");
  REENACT_CHECK(crack_min_neighbours >= 1 && crack_min_neighbours <= 8,
                "crack_min_neighbours in [1, 8]");
  REENACT_CHECK(hole_margin_px >= 0, "hole_margin_px must be >= 0");
  REENACT_CHECK(keyframe_interval >= 1, "virtual view keyframe_interval must be >= 1");
  REENACT_CHECK(max_keyframes >= 0, "virtual view max_keyframes must be >= 0");
  features.Check();
}

Eigen::Isometry3d TurnAboutVertical(const Eigen::Isometry3d& world_from_sensor,
                                    const Eigen::Vector3d& pivot_in_world,
                                    const Eigen::Vector3d& up_in_world, double yaw_deg) {
  const double norm = up_in_world.norm();
  if (!(norm > 1e-12) || !std::isfinite(norm)) return world_from_sensor;
  const Eigen::AngleAxisd turn(yaw_deg * M_PI / 180.0, up_in_world / norm);
  Eigen::Isometry3d about_pivot = Eigen::Isometry3d::Identity();
  about_pivot.linear() = turn.toRotationMatrix();
  about_pivot.translation() = pivot_in_world - about_pivot.linear() * pivot_in_world;
  return about_pivot * world_from_sensor;
}

namespace {

PinholeCamera Undistorted(PinholeCamera camera) {
  camera.distortion = {};
  return camera;
}

// Fills pixels without depth whose 3x3 neighbourhood has at least min_neighbours readings
// with the median of those readings.
void FillCracks(std::vector<float>& z, int width, int height, int min_neighbours) {
  std::vector<float> out = z;
  float near[8];
  for (int v = 1; v + 1 < height; ++v) {
    for (int u = 1; u + 1 < width; ++u) {
      if (z[v * width + u] > 0) continue;
      int n = 0;
      for (int dv = -1; dv <= 1; ++dv)
        for (int du = -1; du <= 1; ++du) {
          const float value = z[(v + dv) * width + u + du];
          if (value > 0) near[n++] = value;
        }
      if (n < min_neighbours) continue;
      std::nth_element(near, near + n / 2, near + n);
      out[v * width + u] = near[n / 2];
    }
  }
  z.swap(out);
}

Eigen::Vector3f Bilinear(const ImageRgb8& image, double x, double y) {
  const int x0 = static_cast<int>(std::floor(x)), y0 = static_cast<int>(std::floor(y));
  const double ax = x - x0, ay = y - y0;
  Eigen::Vector3f sum = Eigen::Vector3f::Zero();
  for (int j = 0; j <= 1; ++j)
    for (int i = 0; i <= 1; ++i) {
      const int xi = std::clamp(x0 + i, 0, image.width - 1);
      const int yj = std::clamp(y0 + j, 0, image.height - 1);
      const float w = static_cast<float>((i ? ax : 1 - ax) * (j ? ay : 1 - ay));
      for (int c = 0; c < 3; ++c) sum[c] += w * image.at(xi, yj, c);
    }
  return sum;
}

// What every view of one keyframe shares: the input checked, the person mask grown, the
// keyframe camera's pixel rays.
struct KeyframeInputs {
  cv::Mat person;  // CV_8UC1, non-zero = subject (grown); empty = no mask
  PixelRays rays;
};

KeyframeInputs PrepareKeyframe(const ImageRgb8& color, const ImageDepthMm& depth,
                               double depth_scale_m, const ImageGray8& person_mask,
                               const PinholeCamera& camera, const VirtualViewOptions& options) {
  options.Check();
  REENACT_CHECK(color.channels == 3 && color.width == camera.width && color.height == camera.height,
                "colour must be 3 channels of the camera's size");
  REENACT_CHECK(depth.width == camera.width && depth.height == camera.height,
                "depth must be registered to the colour image");
  REENACT_CHECK(std::isfinite(depth_scale_m) && depth_scale_m > 0, "depth_scale_m must be > 0");
  KeyframeInputs inputs{cv::Mat(), PixelRays(camera)};
  if (!person_mask.empty()) {
    REENACT_CHECK(person_mask.width == camera.width && person_mask.height == camera.height,
                  "person mask must have the camera's size");
    inputs.person = cv::Mat(camera.height, camera.width, CV_8UC1,
                            const_cast<uint8_t*>(person_mask.data.data())) > 127;
    if (options.person_dilation_px > 0) {
      const int k = 2 * options.person_dilation_px + 1;
      cv::dilate(inputs.person, inputs.person,
                 cv::getStructuringElement(cv::MORPH_ELLIPSE, {k, k}));
    }
  }
  return inputs;
}

VirtualView Render(const ImageRgb8& color, const ImageDepthMm& depth, double depth_scale_m,
                   const KeyframeInputs& inputs, const PinholeCamera& camera,
                   const Eigen::Isometry3d& world_from_sensor,
                   const Eigen::Isometry3d& world_from_virtual, const VirtualViewOptions& options) {
  const int width = camera.width, height = camera.height;
  const cv::Mat& person = inputs.person;
  VirtualView view;
  view.camera = Undistorted(camera);
  view.world_from_camera = world_from_virtual;
  const Eigen::Isometry3d virtual_from_sensor = world_from_virtual.inverse() * world_from_sensor;
  const Eigen::Matrix3d rotation = virtual_from_sensor.linear();
  const Eigen::Vector3d translation = virtual_from_sensor.translation();

  std::vector<float> z(static_cast<size_t>(width) * height, 0.0f);
  for (int v = 0; v < height; ++v) {
    for (int u = 0; u < width; ++u) {
      const uint16_t raw = depth.at(u, v);
      if (raw == 0 || (!person.empty() && person.at<uint8_t>(v, u))) continue;
      const Eigen::Vector3d p =
          rotation * inputs.rays.Point(u, v, raw * depth_scale_m) + translation;
      if (p.z() <= 0.05) continue;
      const int x = static_cast<int>(std::lround(view.camera.fx * p.x() / p.z() + view.camera.cx));
      const int y = static_cast<int>(std::lround(view.camera.fy * p.y() / p.z() + view.camera.cy));
      if (x < 0 || y < 0 || x >= width || y >= height) continue;
      float& slot = z[static_cast<size_t>(y) * width + x];
      if (slot == 0 || p.z() < slot) slot = static_cast<float>(p.z());
    }
  }
  for (int pass = 0; pass < 2; ++pass) FillCracks(z, width, height, options.crack_min_neighbours);

  view.color = ImageRgb8(width, height, 3, 0);
  view.depth = ImageDepthMm(width, height, 1, 0);
  const Eigen::Isometry3d sensor_from_virtual = virtual_from_sensor.inverse();
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const float zv = z[static_cast<size_t>(y) * width + x];
      if (zv <= 0) continue;
      const Eigen::Vector3d p((x - view.camera.cx) / view.camera.fx * zv,
                              (y - view.camera.cy) / view.camera.fy * zv, zv);
      const auto pixel = camera.Project(sensor_from_virtual * p, 0.05);
      if (!pixel || pixel->x() < -0.5 || pixel->y() < -0.5 || pixel->x() > width - 0.5 ||
          pixel->y() > height - 0.5) {
        continue;
      }
      const Eigen::Vector3f rgb = Bilinear(color, pixel->x(), pixel->y());
      for (int c = 0; c < 3; ++c) {
        view.color.at(x, y, c) = static_cast<uint8_t>(std::clamp(std::lround(rgb[c]), 0L, 255L));
      }
      view.depth.at(x, y) =
          static_cast<uint16_t>(std::min<long>(65535, std::lround(zv / depth_scale_m)));
    }
  }
  return view;
}

}  // namespace

VirtualView RenderVirtualView(const ImageRgb8& color, const ImageDepthMm& depth,
                              double depth_scale_m, const ImageGray8& person_mask,
                              const PinholeCamera& camera,
                              const Eigen::Isometry3d& world_from_sensor,
                              const Eigen::Isometry3d& world_from_virtual,
                              const VirtualViewOptions& options) {
  const KeyframeInputs inputs =
      PrepareKeyframe(color, depth, depth_scale_m, person_mask, camera, options);
  return Render(color, depth, depth_scale_m, inputs, camera, world_from_sensor, world_from_virtual,
                options);
}

std::vector<VirtualMapPoint> VirtualViewFeatures(
    const ImageRgb8& color, const ImageDepthMm& depth, double depth_scale_m,
    const ImageGray8& person_mask, const PinholeCamera& camera,
    const Eigen::Isometry3d& world_from_sensor, const Eigen::Vector3d& pivot_in_world,
    const Eigen::Vector3d& up_in_world, const VirtualViewOptions& options) {
  const KeyframeInputs inputs =
      PrepareKeyframe(color, depth, depth_scale_m, person_mask, camera, options);
  vision::OrbFeatureOptions features = options.features;
  features.mask_dilation_px = options.hole_margin_px;
  std::vector<VirtualMapPoint> points;
  for (double yaw : options.yaw_deg) {
    const Eigen::Isometry3d world_from_virtual =
        TurnAboutVertical(world_from_sensor, pivot_in_world, up_in_world, yaw);
    const VirtualView view = Render(color, depth, depth_scale_m, inputs, camera, world_from_sensor,
                                    world_from_virtual, options);
    ImageGray8 holes(camera.width, camera.height, 1, 0);
    for (int y = 0; y < camera.height; ++y)
      for (int x = 0; x < camera.width; ++x) holes.at(x, y) = view.depth.at(x, y) == 0 ? 255 : 0;
    const cv::Mat rgb(camera.height, camera.width, CV_8UC3,
                      const_cast<uint8_t*>(view.color.data.data()));
    cv::Mat gray;
    cv::cvtColor(rgb, gray, cv::COLOR_RGB2GRAY);
    const vision::FrameFeatures found =
        vision::ExtractOrbFeatures(gray, view.depth, depth_scale_m, &holes, view.camera, features);
    for (size_t i = 0; i < found.size(); ++i) {
      if (found.observations[i].depth_m <= 0) continue;
      VirtualMapPoint point;
      point.position_in_world = world_from_virtual * found.points_in_camera[i];
      std::memcpy(point.descriptor.data(), found.Descriptor(i), 32);
      points.push_back(point);
    }
  }
  return points;
}

std::optional<Eigen::Vector3d> SubjectPivot(const Skeleton& skeleton_in_sensor,
                                            const Eigen::Isometry3d& world_from_sensor) {
  for (Joint j : {Joint::kWaist, Joint::kTorso}) {
    if (skeleton_in_sensor.Has(j)) return world_from_sensor * skeleton_in_sensor[j];
  }
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  int n = 0;
  for (int j = 0; j < kJointCount; ++j) {
    if (skeleton_in_sensor.confidence[j] <= 0) continue;
    sum += skeleton_in_sensor.position[j];
    ++n;
  }
  if (n == 0) return std::nullopt;
  return world_from_sensor * (sum / n);
}

proto::ClipMap AddVirtualViews(proto::ClipMap map,
                               const std::vector<VirtualViewKeyframe>& keyframes,
                               double depth_scale_m, const PinholeCamera& camera,
                               const Eigen::Vector3d& up_in_world,
                               const VirtualViewOptions& options, const BackgroundMapOptions& merge,
                               size_t* points_added) {
  if (points_added != nullptr) *points_added = 0;
  if (keyframes.empty() || options.yaw_deg.empty()) return map;
  BackgroundMapBuilder builder(std::move(map), merge);
  const size_t before = builder.point_count();
  for (const VirtualViewKeyframe& k : keyframes) {
    for (const VirtualMapPoint& p :
         VirtualViewFeatures(k.color, k.depth, depth_scale_m, k.person_mask, camera,
                             k.world_from_sensor, k.pivot_in_world, up_in_world, options)) {
      builder.AddPoint(p.position_in_world, p.descriptor.data());
    }
  }
  if (points_added != nullptr) *points_added = builder.point_count() - before;
  return std::move(builder).Finish();
}

}  // namespace reenact::capture
