// Tests that need OpenGL (EGL surfaceless, e.g. Mesa llvmpipe): suites start with "Gl" so
// that machines without it can filter them out (--gtest_filter=-Gl*).
#include "viewer-client/render/renderer.h"

#include <cmath>
#include <cstdlib>

#include <gtest/gtest.h>

#include "common/error/check.h"

namespace reenact::viewer {
namespace {

// Viewer camera with a principal point off the pixel grid, to catch half-pixel errors.
PinholeCamera ViewerCamera() { return PinholeCamera{160, 120, 200, 200, 80.3, 60.7, {}}; }

Renderer MakeRenderer() {
  Expected<Renderer> renderer = Renderer::CreateHeadless(160, 120);
  if (!renderer) ADD_FAILURE() << renderer.error().code << ": " << renderer.error().message;
  return std::move(renderer).value();
}

// A flat-coloured cylinder along the optical axis direction (head-on): its near cap at
// depth z0 is a disk of radius fx * radius / z0 pixels around the projection of `a`.
CylinderDraw HeadOn(const Eigen::Vector3d& a, double length, double radius,
                    const Eigen::Vector3f& color) {
  CylinderDraw c;
  c.a = a;
  c.b = a + Eigen::Vector3d(0, 0, length);
  c.radius = radius;
  c.color = color;
  return c;
}

FrameDraw BlackFrame() {
  FrameDraw frame;
  frame.camera = ViewerCamera();
  frame.clear_color = Eigen::Vector3f(0, 0, 1);  // exactly (0, 0, 255)
  return frame;
}

bool IsClear(const RenderedFrame& out, int x, int y) {
  return out.color.at(x, y, 0) == 0 && out.color.at(x, y, 1) == 0 &&
         out.color.at(x, y, 2) == 255 && out.subject_mask.at(x, y) == 0;
}

// A stored crop whose colour encodes its own texel: R = 2 tx, G = 3 ty, B = 77.
StoredTexture PositionCodedCrop(const PinholeCamera& full, int x0, int y0, int w, int h) {
  StoredTexture t;
  t.color = ImageRgb8(w, h, 3);
  t.mask = ImageGray8(w, h, 1, 255);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      t.color.at(x, y, 0) = static_cast<uint8_t>(2 * x);
      t.color.at(x, y, 1) = static_cast<uint8_t>(3 * y);
      t.color.at(x, y, 2) = 77;
    }
  }
  t.camera = full.Cropped(x0, y0, w, h);
  return t;
}

constexpr int kCropX0 = 40, kCropY0 = 20, kCropW = 100, kCropH = 80;
// stored_from_viewer translates by (0.05, -0.025, 0) m; at the cap depth of 1 m this moves
// the stored projection by (+10, -5) pixels.
constexpr int kShiftU = 10, kShiftV = -5;

CylinderDraw TexturedHeadOn(int texture) {
  CylinderDraw c = HeadOn(Eigen::Vector3d(0.02, -0.01, 1.0), 0.5, 0.15, {1, 0, 0});
  TextureCandidate t;
  t.texture = texture;
  t.stored_from_viewer.block<3, 1>(0, 3) = Eigen::Vector3d(0.05, -0.025, 0.0);
  c.candidates.push_back(t);
  return c;
}

// Cap centre (84.3, 58.7), radius 30 px; pixels well inside it.
template <typename F>
void ForEachInsideCap(double margin, F f) {
  const Eigen::Vector2d centre(200 * 0.02 + 80.3, 200 * -0.01 + 60.7);
  for (int y = 0; y < 120; ++y) {
    for (int x = 0; x < 160; ++x) {
      if ((Eigen::Vector2d(x, y) - centre).norm() < 30 - margin) f(x, y);
    }
  }
}

TEST(GlRenderer, TexturedCapReproducesTheStoredCropAtTheMappedPixels) {
  Renderer renderer = MakeRenderer();
  const int index =
      renderer.UploadTexture(PositionCodedCrop(ViewerCamera(), kCropX0, kCropY0, kCropW, kCropH));
  EXPECT_EQ(index, 0);
  EXPECT_EQ(renderer.texture_count(), 1u);
  FrameDraw frame = BlackFrame();
  frame.cylinders.push_back(TexturedHeadOn(index));
  const RenderedFrame out = renderer.Render(frame);
  ASSERT_EQ(out.color.width, 160);
  ASSERT_EQ(out.color.height, 120);
  int checked = 0;
  ForEachInsideCap(3.0, [&](int x, int y) {
    const int tx = x + kShiftU - kCropX0, ty = y + kShiftV - kCropY0;
    // Texel centres are sampled exactly: half a texel off would blend neighbours.
    ASSERT_EQ(out.color.at(x, y, 0), 2 * tx) << x << "," << y;
    ASSERT_EQ(out.color.at(x, y, 1), 3 * ty) << x << "," << y;
    ASSERT_EQ(out.color.at(x, y, 2), 77);
    ASSERT_EQ(out.subject_mask.at(x, y), 255);
    ++checked;
  });
  EXPECT_GT(checked, 2000);
  EXPECT_TRUE(IsClear(out, 2, 2));
  EXPECT_TRUE(IsClear(out, 150, 110));
}

TEST(GlRenderer, MaskedTexelsAreDiscardedAndShowWhatIsBehind) {
  Renderer renderer = MakeRenderer();
  StoredTexture crop = PositionCodedCrop(ViewerCamera(), kCropX0, kCropY0, kCropW, kCropH);
  for (int y = 0; y < kCropH; ++y) {
    for (int x = 0; x < kCropW / 2; ++x) crop.mask.at(x, y) = 0;
  }
  FrameDraw frame = BlackFrame();
  frame.cylinders.push_back(TexturedHeadOn(renderer.UploadTexture(crop)));
  const RenderedFrame alone = renderer.Render(frame);
  // A flat green cylinder behind: visible exactly where the texture was discarded.
  frame.cylinders.push_back(HeadOn(Eigen::Vector3d(0.02, -0.01, 3.0), 0.5, 1.0, {0, 1, 0}));
  const RenderedFrame behind = renderer.Render(frame);
  int discarded = 0, kept = 0;
  ForEachInsideCap(3.0, [&](int x, int y) {
    const int tx = x + kShiftU - kCropX0;
    if (tx < kCropW / 2 - 1) {
      ASSERT_TRUE(IsClear(alone, x, y)) << x << "," << y;
      ASSERT_GT(behind.color.at(x, y, 1), 200);
      ASSERT_EQ(behind.color.at(x, y, 0), 0);
      ASSERT_EQ(behind.subject_mask.at(x, y), 255);
      ++discarded;
    } else if (tx > kCropW / 2) {
      ASSERT_NEAR(alone.color.at(x, y, 0), 2 * tx, 1);
      ASSERT_EQ(alone.subject_mask.at(x, y), 255);
      ASSERT_NEAR(behind.color.at(x, y, 0), 2 * tx, 1);
      ++kept;
    }
  });
  EXPECT_GT(discarded, 500);
  EXPECT_GT(kept, 500);
}

TEST(GlRenderer, UntexturedOrTexturingOffDrawsFlatColour) {
  Renderer renderer = MakeRenderer();
  FrameDraw frame = BlackFrame();
  frame.cylinders.push_back(TexturedHeadOn(
      renderer.UploadTexture(PositionCodedCrop(ViewerCamera(), kCropX0, kCropY0, kCropW, kCropH))));
  frame.textured = false;
  const RenderedFrame out = renderer.Render(frame);
  // The cap faces the camera: Lambert factor near 1, flat red.
  const int x = 84, y = 59;
  EXPECT_GT(out.color.at(x, y, 0), 240);
  EXPECT_EQ(out.color.at(x, y, 1), 0);
  EXPECT_EQ(out.color.at(x, y, 2), 0);
  EXPECT_EQ(out.subject_mask.at(x, y), 255);
}

TEST(GlRenderer, NearerCylinderWinsWhateverTheDrawOrder) {
  Renderer renderer = MakeRenderer();
  const CylinderDraw near = HeadOn(Eigen::Vector3d(0, 0, 1.0), 0.3, 0.1, {0, 1, 0});
  const CylinderDraw far = HeadOn(Eigen::Vector3d(0, 0, 2.0), 0.3, 0.4, {1, 0, 0});
  for (bool near_first : {true, false}) {
    FrameDraw frame = BlackFrame();
    frame.cylinders = near_first ? std::vector<CylinderDraw>{near, far}
                                 : std::vector<CylinderDraw>{far, near};
    const RenderedFrame out = renderer.Render(frame);
    // Principal point (80.3, 60.7): near disk radius 20 px, far disk radius 40 px.
    EXPECT_GT(out.color.at(80, 61, 1), 200) << near_first;
    EXPECT_EQ(out.color.at(80, 61, 0), 0) << near_first;
    EXPECT_GT(out.color.at(80 + 30, 61, 0), 200) << near_first;
    EXPECT_EQ(out.color.at(80 + 30, 61, 1), 0) << near_first;
  }
}

// Tiny head-on cylinders whose caps are disks of radius 0.6 px centred at sub-pixel
// positions within 0.25 px of a pixel centre: only that pixel's centre is covered.
TEST(GlRenderer, ProjectedPointLightsExactlyThePixelItNames) {
  Renderer renderer = MakeRenderer();
  const PinholeCamera cam = ViewerCamera();
  const double depth = 2.0, radius = 0.6 * depth / cam.fx;
  FrameDraw frame = BlackFrame();
  std::vector<Eigen::Vector2d> targets;
  std::srand(3);
  for (int gy = 0; gy < 9; ++gy) {
    for (int gx = 0; gx < 12; ++gx) {
      const double du = (std::rand() / double(RAND_MAX) - 0.5) * 0.5;
      const double dv = (std::rand() / double(RAND_MAX) - 0.5) * 0.5;
      targets.emplace_back(6 + 13 * gx + du, 6 + 13 * gy + dv);
    }
  }
  for (const Eigen::Vector2d& t : targets) {
    const Eigen::Vector3d a = cam.Unproject(t, depth);
    const Eigen::Vector2d projected = *cam.Project(a);
    ASSERT_NEAR((projected - t).norm(), 0, 1e-9);
    frame.cylinders.push_back(HeadOn(a, 0.001, radius, {1, 1, 1}));
  }
  const RenderedFrame out = renderer.Render(frame);
  for (const Eigen::Vector2d& t : targets) {
    const int u = static_cast<int>(std::lround(t.x())), v = static_cast<int>(std::lround(t.y()));
    for (int y = v - 2; y <= v + 2; ++y) {
      for (int x = u - 2; x <= u + 2; ++x) {
        if (!out.subject_mask.Contains(x, y)) continue;
        EXPECT_EQ(out.subject_mask.at(x, y), (x == u && y == v) ? 255 : 0)
            << "target " << t.transpose() << " pixel " << x << "," << y;
      }
    }
  }
}

TEST(GlRenderer, BackgroundImageFillsTheFrameBehindCylinders) {
  Renderer renderer = MakeRenderer();
  ImageRgb8 background(160, 120, 3);
  for (int y = 0; y < 120; ++y) {
    for (int x = 0; x < 160; ++x) {
      background.at(x, y, 0) = static_cast<uint8_t>(x);
      background.at(x, y, 1) = static_cast<uint8_t>(2 * y);
      background.at(x, y, 2) = static_cast<uint8_t>((x + y) % 256);
    }
  }
  FrameDraw frame = BlackFrame();
  frame.background = &background;
  frame.cylinders.push_back(HeadOn(Eigen::Vector3d(0, 0, 1.0), 0.3, 0.1, {0, 1, 0}));
  const RenderedFrame out = renderer.Render(frame);
  const Eigen::Vector2d centre(80.3, 60.7);
  for (int y = 0; y < 120; ++y) {
    for (int x = 0; x < 160; ++x) {
      const double r = (Eigen::Vector2d(x, y) - centre).norm();
      if (r > 21) {
        for (int c = 0; c < 3; ++c) ASSERT_EQ(out.color.at(x, y, c), background.at(x, y, c));
        ASSERT_EQ(out.subject_mask.at(x, y), 0);
      } else if (r < 19) {
        ASSERT_GT(out.color.at(x, y, 1), 200);
        ASSERT_EQ(out.subject_mask.at(x, y), 255);
      }
    }
  }
}

TEST(GlRenderer, FloorCoversTheLowerImageAndLeavesTheSkyClear) {
  Renderer renderer = MakeRenderer();
  FrameDraw frame = BlackFrame();
  FloorGrid floor;  // world = viewer frame; floor 1 m below the camera (y down)
  floor.up_in_world = Eigen::Vector3d(0, -1, 0);
  floor.point_on_floor_in_world = Eigen::Vector3d(0, 1, 4);
  floor.extent_m = 3.5;
  frame.floor = floor;
  const RenderedFrame out = renderer.Render(frame);
  // The floor at depth z is seen at row cy + fy / z: depth 4 m at row 110.7.
  EXPECT_FALSE(IsClear(out, 80, 111));
  EXPECT_EQ(out.subject_mask.at(80, 111), 0);
  EXPECT_TRUE(IsClear(out, 80, 30));   // above the horizon
  EXPECT_TRUE(IsClear(out, 80, 62));   // just below the horizon: beyond the floor's extent
}

TEST(GlRenderer, BonesAreDrawnOnTopButAreNotSubject) {
  Renderer renderer = MakeRenderer();
  FrameDraw frame = BlackFrame();
  frame.cylinders.push_back(HeadOn(Eigen::Vector3d(0, 0, 1.0), 0.3, 0.1, {0, 1, 0}));
  frame.bone_color = Eigen::Vector3f(1, 0, 1);
  // A horizontal bone behind the cylinder, on row v = 60 (y = (60 - cy) z / fy).
  const double z = 3.0, y = (60 - 60.7) * z / 200;
  frame.bones.push_back({Eigen::Vector3d(-1.0, y, z), Eigen::Vector3d(1.0, y, z)});
  const RenderedFrame out = renderer.Render(frame);
  for (int x = 40; x <= 120; ++x) {
    bool found = false;
    for (int row = 59; row <= 61; ++row) {
      found |= out.color.at(x, row, 0) == 255 && out.color.at(x, row, 1) == 0 &&
               out.color.at(x, row, 2) == 255;
    }
    EXPECT_TRUE(found) << x;
  }
  EXPECT_EQ(out.subject_mask.at(80, 60), 255);  // the cylinder under the bone
  EXPECT_EQ(out.subject_mask.at(30, 60), 0);    // bone over empty background
}

TEST(GlRenderer, FollowsTheCameraSize) {
  Renderer renderer = MakeRenderer();
  FrameDraw frame = BlackFrame();
  frame.camera = PinholeCamera{64, 48, 60, 60, 31.5, 23.5, {}};
  const RenderedFrame out = renderer.Render(frame);
  EXPECT_EQ(out.color.width, 64);
  EXPECT_EQ(out.color.height, 48);
  EXPECT_EQ(out.subject_mask.width, 64);
  EXPECT_TRUE(IsClear(out, 63, 47));
}

TEST(GlRenderer, TwoRenderersKeepTheirOwnContexts) {
  Renderer first = MakeRenderer();
  Renderer second = MakeRenderer();
  first.UploadTexture(PositionCodedCrop(ViewerCamera(), 0, 0, 8, 8));
  EXPECT_EQ(first.texture_count(), 1u);
  EXPECT_EQ(second.texture_count(), 0u);
  FrameDraw frame = BlackFrame();
  frame.cylinders.push_back(HeadOn(Eigen::Vector3d(0, 0, 1.0), 0.3, 0.1, {0, 1, 0}));
  EXPECT_EQ(first.Render(frame).subject_mask.at(80, 61), 255);
  EXPECT_EQ(second.Render(frame).subject_mask.at(80, 61), 255);
  Renderer moved = std::move(first);
  EXPECT_EQ(moved.Render(frame).subject_mask.at(80, 61), 255);
}

TEST(GlRenderer, RejectsATextureIndexThatWasNeverUploaded) {
  Renderer renderer = MakeRenderer();
  FrameDraw frame = BlackFrame();
  frame.cylinders.push_back(HeadOn(Eigen::Vector3d(0, 0, 1.0), 0.3, 0.1, {0, 1, 0}));
  frame.cylinders.back().candidates.push_back({0, Eigen::Matrix4d::Identity(), 1.0});
  EXPECT_THROW(renderer.Render(frame), CheckError);
}

TEST(GlRenderer, RejectsAMaskOfAnotherSize) {
  Renderer renderer = MakeRenderer();
  StoredTexture crop = PositionCodedCrop(ViewerCamera(), 0, 0, 8, 8);
  crop.mask = ImageGray8(7, 8, 1, 255);
  EXPECT_THROW(renderer.UploadTexture(crop), CheckError);
  EXPECT_EQ(renderer.texture_count(), 0u);
}

TEST(GlRenderer, RejectsPartLabelsDepthOrNormalsOfAnotherSizeAndNonFiniteNormals) {
  Renderer renderer = MakeRenderer();
  StoredTexture labels = PositionCodedCrop(ViewerCamera(), 0, 0, 8, 8);
  labels.part_labels = ImageLabel8(8, 7, 1, 1);
  EXPECT_THROW(renderer.UploadTexture(labels), CheckError);
  StoredTexture depth = PositionCodedCrop(ViewerCamera(), 0, 0, 8, 8);
  depth.depth_m = Image<float>(8, 8, 2, 1.0f);
  EXPECT_THROW(renderer.UploadTexture(depth), CheckError);
  StoredTexture normals = PositionCodedCrop(ViewerCamera(), 0, 0, 8, 8);
  normals.normals = Image<float>(8, 8, 1, 0.0f);
  EXPECT_THROW(renderer.UploadTexture(normals), CheckError);
  normals.normals = Image<float>(8, 8, 3, 0.0f);
  normals.normals.at(3, 4, 1) = NAN;
  EXPECT_THROW(renderer.UploadTexture(normals), CheckError);
  EXPECT_EQ(renderer.texture_count(), 0u);
}

TEST(GlRenderer, RejectsTooManyCandidatesANegativeWeightOrTolerance) {
  Renderer renderer = MakeRenderer();
  renderer.UploadTexture(PositionCodedCrop(ViewerCamera(), 0, 0, 8, 8));
  FrameDraw frame = BlackFrame();
  frame.cylinders.push_back(HeadOn(Eigen::Vector3d(0, 0, 1.0), 0.3, 0.1, {0, 1, 0}));
  frame.cylinders.back().candidates.assign(kMaxTextureCandidates + 1,
                                           {0, Eigen::Matrix4d::Identity(), 1.0});
  EXPECT_THROW(renderer.Render(frame), CheckError);
  frame.cylinders.back().candidates = {{0, Eigen::Matrix4d::Identity(), -1.0}};
  EXPECT_THROW(renderer.Render(frame), CheckError);
  frame.cylinders.back().candidates = {{0, Eigen::Matrix4d::Identity(), 1.0}};
  frame.depth_tolerance_m = -0.01;
  EXPECT_THROW(renderer.Render(frame), CheckError);
}

TEST(GlRenderer, RejectsABackgroundOfAnotherSize) {
  Renderer renderer = MakeRenderer();
  const ImageRgb8 background(100, 120, 3);
  FrameDraw frame = BlackFrame();
  frame.background = &background;
  EXPECT_THROW(renderer.Render(frame), CheckError);
}

TEST(GlRenderer, RejectsANonPositiveRadius) {
  Renderer renderer = MakeRenderer();
  FrameDraw frame = BlackFrame();
  frame.cylinders.push_back(HeadOn(Eigen::Vector3d(0, 0, 1.0), 0.3, 0.0, {0, 1, 0}));
  EXPECT_THROW(renderer.Render(frame), CheckError);
}

// A shaped cylinder seen end-on (common/model/cylinder_model.h's PartShape): its near cap is
// the ellipse with semi-axes fx W r / z along the width direction and fx D r / z across it.
TEST(GlRenderer, EllipticCylinderEndOnShowsItsEllipticCap) {
  Renderer renderer = MakeRenderer();
  const double r = 0.15, w = 1.4, d = 0.6;
  for (bool width_along_x : {true, false}) {
    FrameDraw frame = BlackFrame();
    CylinderDraw c = HeadOn(Eigen::Vector3d(0.02, -0.01, 1.0), 0.5, r, {0, 1, 0});
    c.shape.width.fill(w);
    c.shape.depth.fill(d);
    c.width_direction = width_along_x ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
    frame.cylinders.push_back(c);
    const RenderedFrame out = renderer.Render(frame);
    const double cu = 200 * 0.02 + 80.3, cv = 200 * -0.01 + 60.7;
    const double half_u = 200 * (width_along_x ? w : d) * r;
    const double half_v = 200 * (width_along_x ? d : w) * r;
    int left = -1, right = -1, top = -1, bottom = -1;
    for (int x = 0; x < 160; ++x) {
      if (!out.subject_mask.at(x, 59)) continue;
      if (left < 0) left = x;
      right = x;
    }
    for (int y = 0; y < 120; ++y) {
      if (!out.subject_mask.at(84, y)) continue;
      if (top < 0) top = y;
      bottom = y;
    }
    EXPECT_NEAR(left, cu - half_u, 1.0);
    EXPECT_NEAR(right, cu + half_u, 1.0);
    EXPECT_NEAR(top, cv - half_v, 1.0);
    EXPECT_NEAR(bottom, cv + half_v, 1.0);
  }
}

// Flat shading uses the shaped surface's normal (common/render/cylinder_mesh.h's rule): on a
// steep cone across the view (radius 0.05 -> 0.25 m over 0.4 m, slope 0.5, axis along x at
// depth 2) the Lambert term at a pixel is 0.35 + 0.65 |n . e| with n the cone's exact normal
// where the pixel's ray meets it, leaning back along the axis by atan(0.5).
TEST(GlRenderer, FlatShadingFollowsTheConesTiltedNormal) {
  Renderer renderer = MakeRenderer();
  const PinholeCamera cam = ViewerCamera();
  const double r = 0.05, d = 2.0, x0 = -0.2, x1 = 0.2;
  FrameDraw frame = BlackFrame();
  CylinderDraw& c = frame.cylinders.emplace_back();
  c.a = Eigen::Vector3d(x0, 0, d);
  c.b = Eigen::Vector3d(x1, 0, d);
  c.radius = r;
  c.color = Eigen::Vector3f(1, 1, 1);
  for (int k = 0; k < kShapeRings; ++k) c.shape.width[k] = c.shape.depth[k] = 1.0 + k;
  const RenderedFrame out = renderer.Render(frame);
  // Radius R(x) = s (x - apex); the ray t (dx, dy, 1) meets the cone where
  // (t dy)^2 + (t - d)^2 = s^2 (t dx - apex)^2 (nearest root).
  const double s = r * 4 / (x1 - x0), apex = x0 - r / s;
  for (int v = 57; v <= 64; ++v)
    for (int u = 70; u <= 95; ++u) {
      const Eigen::Vector3d ray((u - cam.cx) / cam.fx, (v - cam.cy) / cam.fy, 1.0);
      const double qa = ray.y() * ray.y() + 1 - s * s * ray.x() * ray.x();
      const double qb = -2 * d + 2 * s * s * apex * ray.x();
      const double qc = d * d - s * s * apex * apex;
      const double t = (-qb - std::sqrt(qb * qb - 4 * qa * qc)) / (2 * qa);
      const Eigen::Vector3d p = t * ray;
      const Eigen::Vector3d radial = Eigen::Vector3d(0, p.y(), p.z() - d).normalized();
      const Eigen::Vector3d n = (radial - s * Eigen::Vector3d::UnitX()).normalized();
      const double expected = 255 * (0.35 + 0.65 * std::abs(n.dot(-p.normalized())));
      ASSERT_EQ(out.subject_mask.at(u, v), 255) << u << ", " << v;
      EXPECT_NEAR(out.color.at(u, v, 1), expected, 3.0) << u << ", " << v;
    }
}

TEST(GlRenderer, RejectsANonPositiveOrNonFiniteShapeAndWidthDirection) {
  Renderer renderer = MakeRenderer();
  for (double bad : {0.0, -1.0, std::nan("")}) {
    FrameDraw frame = BlackFrame();
    frame.cylinders.push_back(HeadOn(Eigen::Vector3d(0, 0, 1.0), 0.3, 0.1, {0, 1, 0}));
    frame.cylinders.back().shape.depth[2] = bad;
    EXPECT_THROW(renderer.Render(frame), CheckError) << bad;
  }
  FrameDraw frame = BlackFrame();
  frame.cylinders.push_back(HeadOn(Eigen::Vector3d(0, 0, 1.0), 0.3, 0.1, {0, 1, 0}));
  frame.cylinders.back().width_direction = Eigen::Vector3d(std::nan(""), 0, 0);
  EXPECT_THROW(renderer.Render(frame), CheckError);
}

}  // namespace
}  // namespace reenact::viewer

namespace reenact::viewer {
namespace {

// Both headless platforms draw the same picture (Mesa offers both; NVIDIA only devices).
TEST(GlRendererPlatforms, SurfacelessAndDeviceRenderTheSameFrame) {
  FrameDraw frame = BlackFrame();
  frame.cylinders.push_back(HeadOn(Eigen::Vector3d(0, 0, 1.0), 0.3, 0.1, {0, 1, 0}));
  std::vector<RenderedFrame> outs;
  for (EglPlatform platform : {EglPlatform::kSurfaceless, EglPlatform::kDevice}) {
    Expected<Renderer> renderer = Renderer::CreateHeadless(160, 120, platform);
    if (!renderer) GTEST_SKIP() << "platform unavailable: " << renderer.error().message;
    outs.push_back(renderer->Render(frame));
  }
  EXPECT_EQ(outs[0].color.data, outs[1].color.data);
  EXPECT_EQ(outs[0].subject_mask.data, outs[1].subject_mask.data);
  EXPECT_EQ(outs[0].subject_mask.at(80, 61), 255);
}

}  // namespace
}  // namespace reenact::viewer
