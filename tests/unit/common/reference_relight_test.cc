// Relighting in the CPU reference renderer (common/render/texturing.h): every candidate's
// colour times SubjectShade(n, light) / SubjectShade(n, stored_light), n the surface normal,
// against the shading computed from the exact geometry of constructed scenes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "common/error/check.h"
#include "common/render/reference_renderer.h"
#include "common/texture/subject_light.h"

namespace reenact {
namespace {

PinholeCamera Camera() { return PinholeCamera{160, 120, 200, 200, 80.3, 60.7, {}}; }

// A crop of grey `value`, all subject, the whole camera: with an identity stored_from_viewer
// every pixel samples its own texel.
ReferenceCrop GreyCrop(uint8_t value) {
  const PinholeCamera cam = Camera();
  ReferenceCrop crop;
  crop.color = ImageRgb8(cam.width, cam.height, 3, value);
  crop.mask = ImageGray8(cam.width, cam.height, 1, 255);
  crop.camera = cam;
  return crop;
}

ReferencePart PartOn(const Cylinder& cylinder, const ReferenceCrop& crop,
                     const Eigen::Vector3d& stored_light) {
  ReferencePart part;
  part.cylinder = cylinder;
  part.part = BodyPart::kLowerTorso;
  part.candidates.push_back({&crop, 0, Eigen::Matrix4d::Identity(), 1.0, stored_light});
  return part;
}

// A cylinder seen head-on: its near cap (normal (0, 0, -1), towards the viewer) covers a disk
// of 30 px radius around (84.3, 58.7).
const Cylinder kHeadOn{{0.02, -0.01, 1.0}, {0.02, -0.01, 1.5}, 0.15};

double CapValue(const ReferenceRender& r) { return r.color.at(84, 59, 0); }

TEST(ReferenceRelight, CapIsReshadedByTheRatioOfTheTwoShadings) {
  const ReferenceCrop crop = GreyCrop(100);
  const Eigen::Vector3d towards_viewer(0.2, 0.1, -0.8);  // n . L = 0.8
  ReferenceRenderOptions options;
  options.subject_light = towards_viewer;
  const ReferencePart lit_now = PartOn(kHeadOn, crop, Eigen::Vector3d::Zero());
  EXPECT_EQ(CapValue(RenderReference(Camera(), {&lit_now, 1}, options)), 180);  // 100 * 1.8

  const ReferencePart lit_then = PartOn(kHeadOn, crop, Eigen::Vector3d(0.3, 0, -0.5));
  EXPECT_EQ(CapValue(RenderReference(Camera(), {&lit_then, 1}, options)), 120);  // 180 / 1.5

  // A zero light is no relighting, whatever the candidates' stored lights.
  options.subject_light = Eigen::Vector3d::Zero();
  EXPECT_EQ(CapValue(RenderReference(Camera(), {&lit_then, 1}, options)), 100);

  // A light behind the cap (n . L < 0) shades it as ambient only: no change.
  options.subject_light = Eigen::Vector3d(0, 0, 2);
  const ReferencePart unlit = PartOn(kHeadOn, crop, Eigen::Vector3d::Zero());
  EXPECT_EQ(CapValue(RenderReference(Camera(), {&unlit, 1}, options)), 100);
}

TEST(ReferenceRelight, BrightenedColoursSaturateAt255) {
  const ReferenceCrop crop = GreyCrop(200);
  ReferenceRenderOptions options;
  options.subject_light = Eigen::Vector3d(0, 0, -1);
  const ReferencePart part = PartOn(kHeadOn, crop, Eigen::Vector3d::Zero());
  EXPECT_EQ(CapValue(RenderReference(Camera(), {&part, 1}, options)), 255);
}

// A cylinder lying across the view (axis along x, 1 m away), lit from above (-y): every pixel's
// value is 100 (1 + max(0, -n_y)) with n the exact normal where the pixel's ray meets the
// cylinder. The renderer shades with the tessellated mesh's interpolated normals (32 sides):
// within 2 degrees of the exact normal, 100 sin(2 deg) = 3.5 levels, plus rounding.
TEST(ReferenceRelight, SideOfACylinderFollowsTheExactNormals) {
  const ReferenceCrop crop = GreyCrop(100);
  const double yc = 0.0, zc = 1.0, r = 0.15;
  const Cylinder across{{-0.2, yc, zc}, {0.2, yc, zc}, r};
  ReferenceRenderOptions options;
  options.subject_light = Eigen::Vector3d(0, -1, 0);
  const ReferencePart part = PartOn(across, crop, Eigen::Vector3d::Zero());
  const ReferenceRender render = RenderReference(Camera(), {&part, 1}, options);
  const PinholeCamera cam = Camera();
  int checked = 0, lit = 0;
  for (int y = 0; y < cam.height; ++y)
    for (int x = 40; x < 120; ++x) {
      const Eigen::Vector3d d((x - cam.cx) / cam.fx, (y - cam.cy) / cam.fy, 1);
      // |t (dy, dz) - (yc, zc)| = r, nearest root.
      const double a = d.y() * d.y() + d.z() * d.z(), b = -2 * (d.y() * yc + d.z() * zc),
                   c = yc * yc + zc * zc - r * r, disc = b * b - 4 * a * c;
      if (disc < 0 || !render.mask.at(x, y)) continue;
      const double t = (-b - std::sqrt(disc)) / (2 * a);
      const Eigen::Vector3d n(0, (t * d.y() - yc) / r, (t * d.z() - zc) / r);
      if (std::abs(n.dot(d.normalized())) < 0.3) continue;  // the grazing rim: left out
      const double expected = 100 * SubjectShade(n, options.subject_light);
      EXPECT_NEAR(render.color.at(x, y, 0), expected, 4.0) << x << ", " << y;
      ++checked;
      lit += expected > 110;
    }
  EXPECT_GT(checked, 2000);
  EXPECT_GT(lit, 500);  // the upper half is brightened
}

// With the crop's normal map, the stored surface's own normal, carried to the viewer by the
// rotation of stored_from_viewer, replaces the model's: here every texel's normal is
// n_s = (0.6, 0, -0.8) and the map turns the viewer's frame by 90 degrees about the optical
// axis, so the carried normal is R^T n_s = (0, -0.6, -0.8), and a light along -y shades it by
// 1 + 0.6 where the model's cap normal (0, 0, -1) would leave 1.
TEST(ReferenceRelight, TheStoredNormalIsCarriedWithTheTexture) {
  ReferenceCrop crop = GreyCrop(100);
  crop.normals = Image<float>(crop.color.width, crop.color.height, 3, 0.0f);
  for (int y = 0; y < crop.color.height; ++y)
    for (int x = 0; x < crop.color.width; ++x) {
      crop.normals.at(x, y, 0) = 0.6f;
      crop.normals.at(x, y, 2) = -0.8f;
    }
  ReferencePart part = PartOn(kHeadOn, crop, Eigen::Vector3d::Zero());
  Eigen::Matrix4d turn = Eigen::Matrix4d::Identity();
  turn.topLeftCorner<3, 3>() =
      Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  part.candidates[0].stored_from_viewer = turn;
  ReferenceRenderOptions options;
  options.subject_light = Eigen::Vector3d(0, -1, 0);
  EXPECT_EQ(CapValue(RenderReference(Camera(), {&part, 1}, options)), 160);
  // The same light as the stored frame saw it: no change.
  part.candidates[0].stored_light = options.subject_light;
  EXPECT_EQ(CapValue(RenderReference(Camera(), {&part, 1}, options)), 100);

  // Where the map holds no normal (zero), the model's normal is used: the cap's faces the
  // viewer, so this light leaves it unshaded, and a light towards the viewer doubles it.
  std::fill(crop.normals.data.begin(), crop.normals.data.end(), 0.0f);
  part.candidates[0].stored_light = Eigen::Vector3d::Zero();
  EXPECT_EQ(CapValue(RenderReference(Camera(), {&part, 1}, options)), 100);
  options.subject_light = Eigen::Vector3d(0, 0, -1);
  EXPECT_EQ(CapValue(RenderReference(Camera(), {&part, 1}, options)), 200);
}

TEST(ReferenceRelight, NormalMapsOfAnotherSizeOrNotFiniteAreRefused) {
  ReferenceCrop crop = GreyCrop(100);
  crop.normals = Image<float>(crop.color.width, crop.color.height, 1, 0.0f);
  const ReferencePart part = PartOn(kHeadOn, crop, Eigen::Vector3d::Zero());
  EXPECT_THROW(RenderReference(Camera(), {&part, 1}), CheckError);
  crop.normals = Image<float>(crop.color.width, crop.color.height, 3, 0.0f);
  crop.normals.at(5, 5, 2) = INFINITY;
  EXPECT_THROW(RenderReference(Camera(), {&part, 1}), CheckError);
}

TEST(ReferenceRelight, NonFiniteLightsAreRefused) {
  const ReferenceCrop crop = GreyCrop(100);
  ReferenceRenderOptions options;
  options.subject_light = Eigen::Vector3d(NAN, 0, 0);
  const ReferencePart part = PartOn(kHeadOn, crop, Eigen::Vector3d::Zero());
  EXPECT_THROW(RenderReference(Camera(), {&part, 1}, options), CheckError);
  options.subject_light = Eigen::Vector3d::Zero();
  const ReferencePart bad = PartOn(kHeadOn, crop, Eigen::Vector3d(0, INFINITY, 0));
  EXPECT_THROW(RenderReference(Camera(), {&bad, 1}, options), CheckError);
}

}  // namespace
}  // namespace reenact
