#include "common/render/reference_renderer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "common/error/check.h"

namespace reenact {
namespace {

// Viewer camera with a principal point off the pixel grid, to catch half-pixel errors.
PinholeCamera ViewerCamera() { return PinholeCamera{160, 120, 200, 200, 80.3, 60.7, {}}; }

// A stored crop of the viewer camera whose colour encodes its own texel: R = 2 tx,
// G = 3 ty, B = 77 (affine in the texel, so a bilinear sample is the same affine function).
constexpr int kCropX0 = 40, kCropY0 = 20, kCropW = 100, kCropH = 80;
ReferenceCrop PositionCodedCrop() {
  ReferenceCrop crop;
  crop.color = ImageRgb8(kCropW, kCropH, 3);
  crop.mask = ImageGray8(kCropW, kCropH, 1, 255);
  for (int y = 0; y < kCropH; ++y) {
    for (int x = 0; x < kCropW; ++x) {
      crop.color.at(x, y, 0) = static_cast<uint8_t>(2 * x);
      crop.color.at(x, y, 1) = static_cast<uint8_t>(3 * y);
      crop.color.at(x, y, 2) = 77;
    }
  }
  crop.camera = ViewerCamera().Cropped(kCropX0, kCropY0, kCropW, kCropH);
  return crop;
}

// A cylinder along the optical axis seen head-on: its near cap at depth z0 is a disk of
// radius fx * radius / z0 pixels around the projection of a.
ReferencePart HeadOn(const Eigen::Vector3d& a, double length, double radius) {
  ReferencePart part;
  part.cylinder = Cylinder{a, a + Eigen::Vector3d(0, 0, length), radius};
  return part;
}

// stored_from_viewer translating by (tx, ty, 0) m: at the cap depth of 1 m this moves the
// stored projection by (200 tx, 200 ty) pixels.
ReferencePart TexturedHeadOn(const ReferenceCrop* crop, int frame, double tx, double ty) {
  ReferencePart part = HeadOn(Eigen::Vector3d(0.02, -0.01, 1.0), 0.5, 0.15);
  ReferenceCandidate candidate{crop, frame, Eigen::Matrix4d::Identity(), 1.0};
  candidate.stored_from_viewer.block<3, 1>(0, 3) = Eigen::Vector3d(tx, ty, 0.0);
  part.candidates.push_back(candidate);
  return part;
}

// The cap of TexturedHeadOn: centre (84.3, 58.7), radius 30 px.
const Eigen::Vector2d kCapCentre(200 * 0.02 + 80.3, 200 * -0.01 + 60.7);
constexpr double kCapRadiusPx = 30;

template <typename F>
void ForEachPixel(F f) {
  for (int y = 0; y < 120; ++y)
    for (int x = 0; x < 160; ++x) f(x, y, (Eigen::Vector2d(x, y) - kCapCentre).norm());
}

bool IsEmpty(const ReferenceRender& r, int x, int y) {
  return r.mask.at(x, y) == 0 && r.part.at(x, y) == -1 && r.source_frame.at(x, y) == -1 &&
         r.source_pixel.at(x, y, 0) == -1.0f && r.source_pixel.at(x, y, 1) == -1.0f &&
         std::isinf(r.depth.at(x, y));
}

int MaskCount(const ReferenceRender& r) {
  int n = 0;
  for (uint8_t m : r.mask.data) n += m == 255;
  return n;
}

TEST(ReferenceRenderer, HeadOnCapReproducesTheStoredCropAndNamesTheSourcePixels) {
  const ReferenceCrop crop = PositionCodedCrop();
  const std::vector<ReferencePart> parts = {TexturedHeadOn(&crop, 7, 0.05, -0.025)};
  ReferenceRenderOptions options;
  options.clear_color = Eigen::Vector3i(0, 0, 255);
  const ReferenceRender r = RenderReference(ViewerCamera(), parts, options);
  ASSERT_EQ(r.color.width, 160);
  ASSERT_EQ(r.color.height, 120);
  int inside = 0;
  ForEachPixel([&](int x, int y, double d) {
    if (d < kCapRadiusPx - 2) {
      // Shift (+10, -5) px, then into crop coordinates: texel centres sampled exactly.
      const int tx = x + 10 - kCropX0, ty = y - 5 - kCropY0;
      ASSERT_EQ(r.color.at(x, y, 0), 2 * tx) << x << "," << y;
      ASSERT_EQ(r.color.at(x, y, 1), 3 * ty) << x << "," << y;
      ASSERT_EQ(r.color.at(x, y, 2), 77);
      ASSERT_EQ(r.mask.at(x, y), 255);
      ASSERT_EQ(r.part.at(x, y), 0);
      ASSERT_EQ(r.source_frame.at(x, y), 7);
      ASSERT_NEAR(r.source_pixel.at(x, y, 0), tx, 1e-4);
      ASSERT_NEAR(r.source_pixel.at(x, y, 1), ty, 1e-4);
      ASSERT_NEAR(r.depth.at(x, y), 1.0, 1e-9);  // the near cap's plane
      ++inside;
    } else if (d > kCapRadiusPx + 2) {
      ASSERT_TRUE(IsEmpty(r, x, y)) << x << "," << y;
      ASSERT_EQ(r.color.at(x, y, 2), 255);
    }
  });
  EXPECT_GT(inside, 2400);  // about pi 28^2 = 2463
}

TEST(ReferenceRenderer, SamplesBilinearlyBetweenTexelCentres) {
  const ReferenceCrop crop = PositionCodedCrop();
  // Shift by (10.5, -4.75) px: the affine colour code gives R = 2 (tx + 0.5) and
  // G = 3 (ty + 0.25) exactly (up to rounding of 0.75 for G).
  const std::vector<ReferencePart> parts = {TexturedHeadOn(&crop, 0, 0.0525, -0.02375)};
  const ReferenceRender r = RenderReference(ViewerCamera(), parts);
  int checked = 0;
  ForEachPixel([&](int x, int y, double d) {
    if (d >= kCapRadiusPx - 2) return;
    const double u = x + 10.5 - kCropX0, v = y - 4.75 - kCropY0;
    ASSERT_EQ(r.color.at(x, y, 0), std::lround(2 * u));
    ASSERT_EQ(r.color.at(x, y, 1), std::lround(3 * v));
    ASSERT_NEAR(r.source_pixel.at(x, y, 0), u, 1e-4);
    ASSERT_NEAR(r.source_pixel.at(x, y, 1), v, 1e-4);
    ++checked;
  });
  EXPECT_GT(checked, 2400);
}

TEST(ReferenceRenderer, MaskedTexelsAreDiscardedAndShowWhatIsBehind) {
  ReferenceCrop crop = PositionCodedCrop();
  for (int y = 0; y < kCropH; ++y)
    for (int x = 0; x < kCropW / 2; ++x) crop.mask.at(x, y) = 0;
  std::vector<ReferencePart> parts = {TexturedHeadOn(&crop, 3, 0.05, -0.025)};
  const ReferenceRender alone = RenderReference(ViewerCamera(), parts);
  // An untextured green cylinder behind, near cap at z = 3 facing the viewer (normal -z):
  // two-sided Lambert gives 255 (0.35 + 0.65 cos angle between the ray and the axis).
  ReferencePart back = HeadOn(Eigen::Vector3d(0.02, -0.01, 3.0), 0.5, 1.0);
  back.color = Eigen::Vector3f(0, 1, 0);
  parts.push_back(back);
  const ReferenceRender behind = RenderReference(ViewerCamera(), parts);
  const PinholeCamera cam = ViewerCamera();
  int discarded = 0, kept = 0;
  ForEachPixel([&](int x, int y, double d) {
    if (d >= kCapRadiusPx - 2) return;
    const int tx = x + 10 - kCropX0;
    if (tx < kCropW / 2 - 1) {
      ASSERT_TRUE(IsEmpty(alone, x, y)) << x << "," << y;
      const Eigen::Vector3d ray((x - cam.cx) / cam.fx, (y - cam.cy) / cam.fy, 1.0);
      const double cos_angle = 1.0 / ray.norm();
      ASSERT_NEAR(behind.color.at(x, y, 1), 255 * (0.35 + 0.65 * cos_angle), 0.6);
      ASSERT_EQ(behind.color.at(x, y, 0), 0);
      ASSERT_EQ(behind.mask.at(x, y), 255);
      ASSERT_EQ(behind.part.at(x, y), 1);
      ASSERT_EQ(behind.source_frame.at(x, y), -1);  // untextured: no source
      ASSERT_EQ(behind.source_pixel.at(x, y, 0), -1.0f);
      ASSERT_NEAR(behind.depth.at(x, y), 3.0, 1e-9);
      ++discarded;
    } else if (tx > kCropW / 2) {
      ASSERT_EQ(alone.color.at(x, y, 0), 2 * tx);
      ASSERT_EQ(behind.color.at(x, y, 0), 2 * tx);
      ASSERT_EQ(behind.part.at(x, y), 0);
      ASSERT_EQ(behind.source_frame.at(x, y), 3);
      ++kept;
    }
  });
  EXPECT_GT(discarded, 800);
  EXPECT_GT(kept, 800);
}

TEST(ReferenceRenderer, SamplesOutsideTheCropAreDiscarded) {
  const ReferenceCrop crop = PositionCodedCrop();
  // Shift (-40, 0) px at the cap: viewer pixel x maps to crop u = x - 80, inside the crop for
  // u >= -0.5. Where the cap is discarded the cylinder's inside shows through (discarded
  // fragments write no depth), but never a sample from outside the crop.
  const std::vector<ReferencePart> parts = {TexturedHeadOn(&crop, 0, -0.2, 0.0)};
  const ReferenceRender r = RenderReference(ViewerCamera(), parts);
  int inside = 0, outside = 0;
  ForEachPixel([&](int x, int y, double d) {
    if (r.mask.at(x, y)) {
      ASSERT_GE(r.source_pixel.at(x, y, 0), -0.5f);
      ASSERT_LE(r.source_pixel.at(x, y, 0), kCropW - 0.5f);
    }
    if (d >= kCapRadiusPx - 2) return;
    const int u = x - 40 - kCropX0;
    if (u < 0) {
      ASSERT_GT(r.depth.at(x, y), 1.0 + 1e-6) << x << "," << y;  // not the cap
      ++outside;
    } else {
      ASSERT_NEAR(r.depth.at(x, y), 1.0, 1e-9);
      ASSERT_EQ(r.color.at(x, y, 0), 2 * u);
      ++inside;
    }
  });
  EXPECT_GT(inside, 800);
  EXPECT_GT(outside, 800);
}

TEST(ReferenceRenderer, NearerPartWinsWhateverTheDrawOrder) {
  ReferenceCrop red = PositionCodedCrop(), blue = PositionCodedCrop();
  for (int i = 0; i < kCropW * kCropH; ++i) {
    red.color.data[3 * i] = 200;
    blue.color.data[3 * i] = 10;
  }
  const PinholeCamera cam = ViewerCamera();
  // A small near cylinder in front of a large far one, both head-on, identity mapping.
  ReferencePart near = HeadOn(Eigen::Vector3d(0.02, -0.01, 1.0), 0.3, 0.1);
  near.candidates.push_back({&red, 1, Eigen::Matrix4d::Identity(), 1.0});
  ReferencePart far = HeadOn(Eigen::Vector3d(0.04, -0.02, 2.0), 0.3, 0.4);  // same centre
  far.candidates.push_back({&blue, 2, Eigen::Matrix4d::Identity(), 1.0});
  const std::vector<ReferencePart> near_first = {near, far}, far_first = {far, near};
  const ReferenceRender a = RenderReference(cam, near_first);
  const ReferenceRender b = RenderReference(cam, far_first);
  EXPECT_EQ(a.color.data, b.color.data);
  EXPECT_EQ(a.mask.data, b.mask.data);
  EXPECT_EQ(a.source_frame.data, b.source_frame.data);
  // Near cap: radius 20 px; the far cap around it: radius 40 px.
  ForEachPixel([&](int x, int y, double d) {
    if (d < 18) {
      ASSERT_EQ(a.source_frame.at(x, y), 1);
      ASSERT_EQ(a.color.at(x, y, 0), 200);
      ASSERT_NEAR(a.depth.at(x, y), 1.0, 1e-9);
    } else if (d > 22 && d < 38) {
      ASSERT_EQ(a.source_frame.at(x, y), 2);
      ASSERT_EQ(a.color.at(x, y, 0), 10);
      ASSERT_NEAR(a.depth.at(x, y), 2.0, 1e-9);
    }
  });
}

TEST(ReferenceRenderer, PartsBehindTheViewerDrawNothingAndCrossingPartsAreClipped) {
  const ReferenceCrop crop = PositionCodedCrop();
  ReferencePart behind = HeadOn(Eigen::Vector3d(0, 0, -2.0), 1.0, 0.3);
  behind.candidates.push_back({&crop, 0, Eigen::Matrix4d::Identity(), 1.0});
  const std::vector<ReferencePart> only_behind = {behind};
  EXPECT_EQ(MaskCount(RenderReference(ViewerCamera(), only_behind)), 0);

  // An untextured cylinder from z = -1 to z = 3 off the optical axis: only z >= near_z draws.
  ReferencePart crossing;
  crossing.cylinder = Cylinder{Eigen::Vector3d(0.3, 0, -1), Eigen::Vector3d(0.3, 0, 3), 0.1};
  const std::vector<ReferencePart> only_crossing = {crossing};
  ReferenceRenderOptions options;
  const ReferenceRender r = RenderReference(ViewerCamera(), only_crossing, options);
  EXPECT_GT(MaskCount(r), 100);
  for (size_t i = 0; i < r.depth.data.size(); ++i) {
    if (r.mask.data[i]) {
      EXPECT_GE(r.depth.data[i], options.near_z - 1e-9);
      EXPECT_LE(r.depth.data[i], 3.0 + 1e-9);
    }
  }
}

TEST(ReferenceRenderer, SurfaceBehindTheStoredCameraIsDiscarded) {
  const ReferenceCrop crop = PositionCodedCrop();
  ReferencePart part = TexturedHeadOn(&crop, 0, 0, 0);
  // Turn half way about y: the stored points land at z < 0.
  part.candidates[0].stored_from_viewer.topLeftCorner<3, 3>() =
      Eigen::AngleAxisd(std::numbers::pi, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const std::vector<ReferencePart> parts = {part};
  EXPECT_EQ(MaskCount(RenderReference(ViewerCamera(), parts)), 0);
}

// A cylinder across the view (axis along x at depth 2): in a column through its middle the
// covered rows are those between the extreme projections of its 32-gon cross-section,
// whose vertices lie at angles 2 pi i / 32 from the side facing away from the viewer
// (ViewerFromUnitCylinder's x axis is +z for an axis along x, its y axis -y).
TEST(ReferenceRenderer, SideViewSilhouetteFollowsTheTessellatedCrossSection) {
  const PinholeCamera cam = ViewerCamera();
  const double r = 0.1, d = 2.0;
  ReferencePart part;
  part.cylinder = Cylinder{Eigen::Vector3d(-0.3, 0, d), Eigen::Vector3d(0.3, 0, d), r};
  const std::vector<ReferencePart> parts = {part};
  const ReferenceRender out = RenderReference(cam, parts);
  double v_min = 1e9, v_max = -1e9;
  for (int i = 0; i < kDefaultCylinderSegments; ++i) {
    const double angle = 2 * std::numbers::pi * i / kDefaultCylinderSegments;
    const double y = -r * std::sin(angle), z = d + r * std::cos(angle);
    v_min = std::min(v_min, cam.fy * y / z + cam.cy);
    v_max = std::max(v_max, cam.fy * y / z + cam.cy);
  }
  for (int x : {70, 80, 90}) {
    int top = -1, bottom = -1;
    for (int y = 0; y < cam.height; ++y) {
      if (out.mask.at(x, y)) {
        if (top < 0) top = y;
        bottom = y;
      }
    }
    EXPECT_EQ(top, static_cast<int>(std::ceil(v_min))) << x;
    EXPECT_EQ(bottom, static_cast<int>(std::floor(v_max))) << x;
  }
  // Left and right ends: the caps' near edges at z = d - r, x = -+0.3.
  const int row = 61;
  int left = -1, right = -1;
  for (int x = 0; x < cam.width; ++x) {
    if (out.mask.at(x, row)) {
      if (left < 0) left = x;
      right = x;
    }
  }
  EXPECT_NEAR(left, cam.cx - cam.fx * 0.3 / (d - r), 1.0);
  EXPECT_NEAR(right, cam.cx + cam.fx * 0.3 / (d - r), 1.0);
}

TEST(ReferenceRenderer, EmptyListGivesAnEmptyMaskInTheClearColour) {
  ReferenceRenderOptions options;
  options.clear_color = Eigen::Vector3i(1, 2, 3);
  const ReferenceRender r = RenderReference(ViewerCamera(), {}, options);
  EXPECT_EQ(MaskCount(r), 0);
  for (int y = 0; y < 120; ++y)
    for (int x = 0; x < 160; ++x) {
      ASSERT_TRUE(IsEmpty(r, x, y));
      ASSERT_EQ(r.color.at(x, y, 0), 1);
      ASSERT_EQ(r.color.at(x, y, 1), 2);
      ASSERT_EQ(r.color.at(x, y, 2), 3);
    }
}

TEST(ReferenceRenderer, ZeroLengthAxisDrawsNothing) {
  ReferencePart part = HeadOn(Eigen::Vector3d(0, 0, 1), 0.0, 0.1);
  const std::vector<ReferencePart> parts = {part};
  EXPECT_EQ(MaskCount(RenderReference(ViewerCamera(), parts)), 0);
}

TEST(ReferenceRenderer, RejectsANonPositiveRadius) {
  const std::vector<ReferencePart> parts = {HeadOn(Eigen::Vector3d(0, 0, 1), 0.5, 0.0)};
  EXPECT_THROW(RenderReference(ViewerCamera(), parts), CheckError);
}

TEST(ReferenceRenderer, RejectsANonFiniteAxis) {
  const std::vector<ReferencePart> parts = {
      HeadOn(Eigen::Vector3d(0, std::numeric_limits<double>::quiet_NaN(), 1), 0.5, 0.1)};
  EXPECT_THROW(RenderReference(ViewerCamera(), parts), CheckError);
}

TEST(ReferenceRenderer, RejectsAStoredFrameWithoutACrop) {
  ReferencePart part = HeadOn(Eigen::Vector3d(0, 0, 1), 0.5, 0.1);
  part.candidates.push_back({nullptr, 4, Eigen::Matrix4d::Identity(), 1.0});
  const std::vector<ReferencePart> parts = {part};
  EXPECT_THROW(RenderReference(ViewerCamera(), parts), CheckError);
}

TEST(ReferenceRenderer, RejectsAMaskOfAnotherSize) {
  ReferenceCrop crop = PositionCodedCrop();
  crop.mask = ImageGray8(kCropW - 1, kCropH, 1, 255);
  const std::vector<ReferencePart> parts = {TexturedHeadOn(&crop, 0, 0, 0)};
  EXPECT_THROW(RenderReference(ViewerCamera(), parts), CheckError);
}

TEST(ReferenceRenderer, RejectsACropCameraOfAnotherSize) {
  ReferenceCrop crop = PositionCodedCrop();
  crop.camera.width += 1;
  const std::vector<ReferencePart> parts = {TexturedHeadOn(&crop, 0, 0, 0)};
  EXPECT_THROW(RenderReference(ViewerCamera(), parts), CheckError);
}

TEST(ReferenceRenderer, RejectsBadOptionsAndCameras) {
  ReferenceRenderOptions options;
  options.segments = 2;
  EXPECT_THROW(RenderReference(ViewerCamera(), {}, options), CheckError);
  PinholeCamera cam = ViewerCamera();
  cam.fx = 0;
  EXPECT_THROW(RenderReference(cam, {}), CheckError);
}

}  // namespace
}  // namespace reenact
