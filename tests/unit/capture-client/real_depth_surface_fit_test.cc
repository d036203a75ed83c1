// The body surface fit (common/model/surface_fit.h) on real Kinect v1 depth of a real person
// (../shared/data/utd-mhad, 320x240, read through the rgbd: source mirrored to a true camera,
// the background removed by the dataset's authors), posed by the Kinect SDK's skeletons of the
// same frames. The surface is fitted on every other frame; the frames between, which the fit
// never saw, are drawn by the reference renderer with and without it and compared with their
// real depth and silhouette.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "common/model/surface_fit.h"
#include "common/render/reference_renderer.h"
#include "tests/unit/capture-client/utd_mhad_sequence.h"

namespace reenact::capture {
namespace {

struct RealFrame {
  Skeleton skeleton;  // sensor frame
  ImageDepthMm depth;
  ImageGray8 mask;
};

// Every frame of a utd-mhad sequence; empty when the data are absent.
std::vector<RealFrame> ReadSequence(const std::string& sequence, PinholeCamera& camera) {
  auto data = testing::OpenUtdMhadSequence(sequence);
  if (!data) return {};
  auto& source = data->source;
  camera = source->info().depth_camera;
  std::vector<RealFrame> out;
  for (int64_t i = 0;; ++i) {
    auto frame = source->Next();
    if (!frame.ok() || !frame->has_value()) break;
    const auto skeleton = data->reference.ForFrame(i, (**frame).timestamp_s);
    if (!skeleton) continue;
    RealFrame f{*skeleton, (**frame).depth, ImageGray8((**frame).depth.width, (**frame).depth.height, 1, 0)};
    for (size_t k = 0; k < f.depth.data.size(); ++k) f.mask.data[k] = f.depth.data[k] > 0 ? 255 : 0;
    out.push_back(std::move(f));
  }
  return out;
}

// The drawn model against a real frame: silhouette IoU, and the mean |depth difference| over
// the pixels both cover.
struct Agreement {
  double iou = 0;
  double depth_error_m = 0;
};

Agreement Compare(const RealFrame& f, const PinholeCamera& camera, const PartShapes& shapes) {
  std::vector<ReferencePart> parts;
  const auto cylinders = PoseCylinders(f.skeleton, DefaultRadiusRatios(), {}, shapes);
  for (int p = 0; p < kBodyPartCount; ++p)
    if (cylinders[p]) parts.push_back({*cylinders[p], {}, static_cast<BodyPart>(p)});
  const ReferenceRender render = RenderReference(camera, parts);
  int both = 0, either = 0;
  double depth_sum = 0;
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      const bool drawn = render.mask.at(x, y) == 255, real = f.mask.at(x, y) == 255;
      either += drawn || real;
      if (!(drawn && real)) continue;
      ++both;
      depth_sum += std::abs(render.depth.at(x, y) - f.depth.at(x, y) * 1e-3);
    }
  return {either ? static_cast<double>(both) / either : 0, both ? depth_sum / both : 0};
}

// Fitted on the even frames of a real person swiping an arm: on the odd frames, which the fit
// never saw, the drawn body covers the real silhouette better and lies closer to the real depth
// than the rings alone (here the default proportions' cylinders, not fitted to this person).
TEST(RealDepthSurfaceFit, PredictsFramesItNeverSaw) {
  PinholeCamera camera = PinholeCamera::KinectLike();
  const std::vector<RealFrame> frames = ReadSequence("a1_s1_t1", camera);
  if (frames.empty()) GTEST_SKIP() << "../shared/data/utd-mhad is absent";
  ASSERT_GE(frames.size(), 40u);
  std::vector<SurfaceFitFrame> views;
  for (size_t n = 0; n < frames.size(); n += 2)
    views.push_back({&frames[n].skeleton, &camera, &frames[n].mask, &frames[n].depth});
  const SurfaceFitResult fit = FitPartSurfaces(views, DefaultRadiusRatios(), {}, {});
  for (int p = 0; p < kBodyPartCount; ++p) {
    const PartSurface& s = fit.shape[p].surface;
    for (int k = 0; k < kShapeRings; ++k)
      for (int j = 0; j < s.angles; ++j) {
        EXPECT_TRUE(std::isfinite(s.radial[k][j]));
        EXPECT_GE(s.radial[k][j], SurfaceFitOptions{}.min_factor);
        EXPECT_LE(s.radial[k][j], SurfaceFitOptions{}.max_factor);
      }
  }
  double rings_iou = 0, surface_iou = 0, rings_depth = 0, surface_depth = 0;
  int n = 0;
  for (size_t i = 1; i < frames.size(); i += 2, ++n) {
    const Agreement rings = Compare(frames[i], camera, PartShapes{});
    const Agreement surface = Compare(frames[i], camera, fit.shape);
    rings_iou += rings.iou;
    surface_iou += surface.iou;
    rings_depth += rings.depth_error_m;
    surface_depth += surface.depth_error_m;
  }
  rings_iou /= n;
  surface_iou /= n;
  rings_depth /= n;
  surface_depth /= n;
  std::cout << "unseen frames: IoU " << rings_iou << " -> " << surface_iou << ", depth error "
            << 1000 * rings_depth << " -> " << 1000 * surface_depth << " mm\n";
  EXPECT_GT(surface_iou, rings_iou + 0.03);
  EXPECT_LT(surface_depth, rings_depth);
}

}  // namespace
}  // namespace reenact::capture
