#include "common/model/surface_fit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <vector>

#include "common/error/check.h"
#include "common/render/cylinder_mesh.h"
#include "common/render/reference_renderer.h"
#include "tests/unit/common/test_skeletons.h"

namespace reenact {
namespace {

using testing::StandingPerson;

constexpr double kPi = std::numbers::pi;
constexpr BodyPart kPart = BodyPart::kLeftThigh;

// The true surface of the part: its radius, in radii of the plain cylinder, at angle phi
// (from the part's reference direction) and axis fraction t.
using TrueSurface = std::function<double(double phi, double t)>;

// The posed part in a sensor frame, its frame fixed to the body.
Cylinder PosedPart(const Skeleton& skeleton) {
  std::optional<Cylinder> c = PoseCylinder(skeleton, kPart, DefaultRadiusRatios());
  c->width_direction = PartReferenceDirection(skeleton, kPart);
  EXPECT_TRUE(c->width_direction.has_value());
  return *c;
}

struct Frame {
  PinholeCamera camera = PinholeCamera::KinectLike();
  Skeleton skeleton;
  ImageDepthMm depth;
  ImageGray8 mask;
  SurfaceFitFrame View() const { return {&skeleton, &camera, &mask, &depth}; }
};

// Ray casting of the true surface alone, independent of the code under test: each pixel's ray
// is marched in 1 mm steps and the first point inside refined by bisection; depth in mm.
Frame RayCast(const Skeleton& skeleton, const TrueSurface& truth) {
  Frame f;
  f.skeleton = skeleton;
  const PinholeCamera& cam = f.camera;
  f.depth = ImageDepthMm(cam.width, cam.height, 1, 0);
  f.mask = ImageGray8(cam.width, cam.height, 1, 0);
  const Cylinder c = PosedPart(skeleton);
  const Eigen::Matrix4d unit_from_sensor = ViewerFromUnitCylinder(c).inverse();
  const auto inside = [&](const Eigen::Vector3d& x) {
    const Eigen::Vector3d q = (unit_from_sensor * x.homogeneous()).head<3>();
    if (q.z() < 0 || q.z() > 1) return false;
    return q.head<2>().norm() <= truth(std::atan2(q.y(), q.x()), q.z());
  };
  const double reach = 2 * c.radius;
  const double z_near = std::min(c.a.z(), c.b.z()) - reach, z_far = std::max(c.a.z(), c.b.z()) + reach;
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x) {
      const Eigen::Vector3d ray = cam.Unproject(Eigen::Vector2d(x, y), 1.0);
      // Skip rays that pass far from the axis.
      const Eigen::Vector3d mid = 0.5 * (c.a + c.b);
      const Eigen::Vector3d on_ray = ray * mid.z();
      if ((on_ray - mid).head<2>().norm() > 0.5 * c.Length() + reach) continue;
      double prev = z_near;
      for (double z = z_near; z <= z_far; z += 0.001) {
        if (!inside(ray * z)) {
          prev = z;
          continue;
        }
        double lo = prev, hi = z;
        for (int i = 0; i < 30; ++i) {
          const double m = 0.5 * (lo + hi);
          (inside(ray * m) ? hi : lo) = m;
        }
        f.depth.at(x, y) = static_cast<uint16_t>(std::lround(hi * 1000));
        f.mask.at(x, y) = 255;
        break;
      }
    }
  return f;
}

std::vector<Frame> Frames(const std::vector<double>& yaws_deg, const TrueSurface& truth) {
  std::vector<Frame> frames;
  for (double yaw : yaws_deg) frames.push_back(RayCast(StandingPerson(2.0, yaw * kPi / 180, false), truth));
  return frames;
}

SurfaceFitResult Fit(const std::vector<Frame>& frames, const SurfaceFitOptions& options = {}) {
  std::vector<SurfaceFitFrame> views;
  for (const Frame& f : frames) views.push_back(f.View());
  return FitPartSurfaces(views, DefaultRadiusRatios(), {}, {}, options);
}

double NodeAngle(int j, int angles) { return 2 * kPi * j / angles; }
double RingT(int k) { return static_cast<double>(k) / (kShapeRings - 1); }

std::vector<double> AllRound() {
  std::vector<double> yaws;
  for (int i = 0; i < 12; ++i) yaws.push_back(30.0 * i);
  return yaws;
}

// Ring k's nodes against the truth, within tol (in radii): depth steps of 1 mm at 2 m are
// 0.013 radii of this 7.7 cm thigh, and a node is the median over a bin of +-pi / angles
// around it.
void ExpectNodes(const PartSurface& s, const TrueSurface& truth, double tol, int k_lo, int k_hi) {
  for (int k = k_lo; k <= k_hi; ++k)
    for (int j = 0; j < s.angles; ++j)
      EXPECT_NEAR(s.radial[k][j], truth(NodeAngle(j, s.angles), RingT(k)), tol)
          << "ring " << k << " node " << j;
}

// A cone, 1.3 radii at the hip to 0.7 at the knee: no detail around the axis, so the
// coarsest resolution that improves on the rings is chosen, and it follows the taper.
TEST(SurfaceFit, ConeIsFittedAtTheCoarsestResolution) {
  const TrueSurface cone = [](double, double t) { return 1.3 - 0.6 * t; };
  const SurfaceFitResult fit = Fit(Frames(AllRound(), cone));
  const int p = Index(kPart);
  EXPECT_EQ(fit.angles[p], 4);
  ASSERT_TRUE(fit.scored[p]);
  EXPECT_LT(fit.chosen_error_m[p], 0.3 * fit.rings_error_m[p]);
  ExpectNodes(fit.shape[p].surface, cone, 0.04, 1, 3);
  // Parts with no points keep their rings.
  EXPECT_TRUE(fit.shape[Index(BodyPart::kHead)].surface.IsEmpty());
  EXPECT_FALSE(fit.scored[Index(BodyPart::kHead)]);
}

// An ellipse, 1.3 radii along the reference direction and 0.75 across: detail around the axis
// that 4 nodes on its axes cannot follow between them. A node is the median over its bin, and
// the ellipse's radius changes by up to 0.45 radii per radian, so by up to 0.09 over a bin of
// +-pi / 16: the nodes come within 0.07.
TEST(SurfaceFit, EllipseNeedsMoreAngles) {
  const TrueSurface ellipse = [](double phi, double) {
    return 1 / std::hypot(std::cos(phi) / 1.3, std::sin(phi) / 0.75);
  };
  const SurfaceFitResult fit = Fit(Frames(AllRound(), ellipse));
  const int p = Index(kPart);
  EXPECT_GE(fit.angles[p], 8);
  ExpectNodes(fit.shape[p].surface, ellipse, 0.07, 1, 3);
}

// A bulge of 0.35 radii, 25 degrees wide (standard deviation), on one side: more than the 4
// angles are chosen, the node at the bulge (a median over +-22.5 degrees at most) comes within
// 0.1 radii of its peak and the opposite side stays round.
TEST(SurfaceFit, NarrowBulgeIsResolved) {
  const double centre = kPi / 2;
  const TrueSurface bulge = [centre](double phi, double) {
    const double d = std::remainder(phi - centre, 2 * kPi);
    return 1 + 0.35 * std::exp(-0.5 * std::pow(d / (25 * kPi / 180), 2));
  };
  const SurfaceFitResult fit = Fit(Frames(AllRound(), bulge));
  const int p = Index(kPart);
  ASSERT_GE(fit.angles[p], 8);
  const PartSurface& s = fit.shape[p].surface;
  EXPECT_NEAR(s.radial[2][s.angles / 4], 1.35, 0.1);      // the node at pi / 2
  EXPECT_NEAR(s.radial[2][3 * s.angles / 4], 1.0, 0.04);  // the opposite side
}

// Seen from the front only (the person turned by -10 to 10 degrees): where no frame saw the
// part the surface stays at the rings, exactly 1.
TEST(SurfaceFit, UnseenSideStaysAtTheRings) {
  const TrueSurface ellipse = [](double phi, double) {
    return 1 / std::hypot(std::cos(phi) / 1.3, std::sin(phi) / 0.75);
  };
  const std::vector<Frame> frames = Frames({-10, -5, 0, 5, 10}, ellipse);
  const SurfaceFitResult fit = Fit(frames);
  const int p = Index(kPart);
  ASSERT_GT(fit.angles[p], 0);
  const PartSurface& s = fit.shape[p].surface;
  // A node's outward direction at yaw 0; the camera lies towards -z from the part.
  const Skeleton front = StandingPerson(2.0, 0, false);
  const Cylinder c = PosedPart(front);
  const Eigen::Matrix4d sensor_from_unit = ViewerFromUnitCylinder(c);
  int unseen = 0, seen = 0;
  for (int j = 0; j < s.angles; ++j) {
    const double phi = NodeAngle(j, s.angles);
    const Eigen::Vector3d out =
        (sensor_from_unit.topLeftCorner<3, 3>() * Eigen::Vector3d(std::cos(phi), std::sin(phi), 0))
            .normalized();
    const Eigen::Vector3d to_camera = -(0.5 * (c.a + c.b)).normalized();
    const double facing = out.dot(to_camera);
    if (facing < -0.6) {  // more than 127 degrees from the camera at yaw 0, 117 at most
      ++unseen;
      for (int k = 0; k < kShapeRings; ++k) EXPECT_EQ(s.radial[k][j], 1.0) << "node " << j;
    } else if (facing > 0.5) {
      ++seen;
      EXPECT_NEAR(s.radial[2][j], ellipse(phi, 0.5), 0.05) << "node " << j;
    }
  }
  EXPECT_GT(unseen, 0);
  EXPECT_GT(seen, 0);
}

// Holes: the depth of the middle fifth of the thigh missing in every frame (no reading there)
// leaves ring 2 without points; it is filled from rings 1 and 3, which for the cone is exact.
TEST(SurfaceFit, HolesAreFilledFromTheNeighbours) {
  const TrueSurface cone = [](double, double t) { return 1.3 - 0.6 * t; };
  std::vector<Frame> frames = Frames(AllRound(), cone);
  int removed = 0;
  for (Frame& f : frames) {
    const Cylinder c = PosedPart(f.skeleton);
    const Eigen::Matrix4d unit_from_sensor = ViewerFromUnitCylinder(c).inverse();
    for (int y = 0; y < f.depth.height; ++y)
      for (int x = 0; x < f.depth.width; ++x) {
        if (f.depth.at(x, y) == 0) continue;
        const Eigen::Vector3d point = f.camera.Unproject(Eigen::Vector2d(x, y), f.depth.at(x, y) * 1e-3);
        const double t = (unit_from_sensor * point.homogeneous()).z();
        if (std::abs(t - 0.5) < 0.13) {
          f.depth.at(x, y) = 0;
          ++removed;
        }
      }
  }
  ASSERT_GT(removed, 1000);
  const SurfaceFitResult fit = Fit(frames);
  const int p = Index(kPart);
  ASSERT_GT(fit.angles[p], 0);
  for (int j = 0; j < fit.shape[p].surface.angles; ++j)
    EXPECT_NEAR(fit.shape[p].surface.radial[2][j], cone(0, 0.5), 0.04) << "node " << j;
}

// Points that cannot support a node (too few frames) leave the part at its rings; no frame
// and frames without depth fit nothing; bad options and surfaced shapes are refused.
TEST(SurfaceFit, NoDataLeavesTheRings) {
  const TrueSurface cone = [](double, double t) { return 1.3 - 0.6 * t; };
  const SurfaceFitResult none = Fit({});
  for (int p = 0; p < kBodyPartCount; ++p) {
    EXPECT_TRUE(none.shape[p].surface.IsEmpty());
    EXPECT_EQ(none.angles[p], 0);
  }
  std::vector<Frame> frames = Frames({0, 90}, cone);
  for (Frame& f : frames) f.depth = ImageDepthMm();
  const SurfaceFitResult no_depth = Fit(frames);
  EXPECT_EQ(no_depth.points[Index(kPart)], 0);
  EXPECT_TRUE(no_depth.shape[Index(kPart)].surface.IsEmpty());

  SurfaceFitOptions bad;
  bad.angle_choices = {8, 4};
  EXPECT_THROW(bad.Check(), CheckError);
  bad = {};
  bad.min_gain = 1;
  EXPECT_THROW(bad.Check(), CheckError);
  PartShapes surfaced{};
  surfaced[0].surface.angles = 4;
  EXPECT_THROW(FitPartSurfaces({}, DefaultRadiusRatios(), {}, surfaced), CheckError);
}

// The limbs' joint ends are rounded: an elbow bent to 0, 90 and 150 degrees, drawn by the
// reference renderer from the side, leaves no gap at the outside of the bend, where flat ends
// do (the wedge between the two end discs).
TEST(SurfaceFit, BentJointsLeaveNoGap) {
  const SurfaceFitResult fit = Fit({});
  const PartShapes& rounded = fit.shape;
  EXPECT_TRUE(rounded[Index(BodyPart::kLeftUpperArm)].round_end[1]);
  EXPECT_TRUE(rounded[Index(BodyPart::kLeftForearm)].round_end[0]);
  EXPECT_FALSE(rounded[Index(BodyPart::kLeftForearm)].round_end[1]);
  const PinholeCamera camera = PinholeCamera::KinectLike();
  for (double bend_deg : {0.0, 90.0, 150.0}) {
    // Shoulder above the elbow, the forearm turned by the bend in the image plane, 2 m away.
    Skeleton s = StandingPerson(2.0, 0, false);
    const Eigen::Vector3d elbow = s[Joint::kLeftShoulder] + Eigen::Vector3d(0, 0.3, 0);
    const double bend = bend_deg * kPi / 180;
    s.Set(Joint::kLeftElbow, elbow);
    s.Set(Joint::kLeftHand, elbow + 0.27 * Eigen::Vector3d(std::sin(bend), std::cos(bend), 0));
    const Eigen::Vector3d upper_dir(0, 1, 0);
    const Eigen::Vector3d fore_dir(std::sin(bend), std::cos(bend), 0);
    // The outside of the bend: away from both bones, 0.9 of the thinner end's radius out.
    Eigen::Vector3d outside = -(fore_dir - upper_dir);
    if (outside.norm() < 1e-9) outside = Eigen::Vector3d(-1, 0, 0);  // straight: either side
    outside.normalize();
    for (bool round : {true, false}) {
      std::vector<ReferencePart> parts;
      double thinner = 1e9;
      for (BodyPart part : {BodyPart::kLeftUpperArm, BodyPart::kLeftForearm}) {
        PartShapes shapes{};
        if (round) shapes = rounded;
        std::optional<Cylinder> c = PoseCylinder(s, part, DefaultRadiusRatios(), {}, shapes);
        ASSERT_TRUE(c.has_value());
        thinner = std::min(thinner, c->radius);
        parts.push_back({*c, {}, part});
      }
      const ReferenceRender render = RenderReference(camera, parts);
      const auto pixel = camera.Project(elbow + 0.9 * thinner * outside);
      ASSERT_TRUE(pixel.has_value());
      const bool covered =
          render.mask.at(static_cast<int>(std::lround(pixel->x())),
                         static_cast<int>(std::lround(pixel->y()))) == 255;
      if (round || bend_deg == 0) {
        EXPECT_TRUE(covered) << bend_deg << " degrees, rounded " << round;
      } else {
        EXPECT_FALSE(covered) << "flat ends must leave the gap this test looks for, " << bend_deg;
      }
    }
  }
}

}  // namespace
}  // namespace reenact
