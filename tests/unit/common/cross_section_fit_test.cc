#include "common/model/cross_section_fit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "common/error/check.h"
#include "tests/unit/common/cylinder_raycast.h"
#include "tests/unit/common/shaped_cylinder_raycast.h"
#include "tests/unit/common/test_part_shapes.h"
#include "tests/unit/common/test_skeletons.h"

namespace reenact {
namespace {

using testing::Cone;
using testing::LinearRings;
using testing::RayCastCylinders;
using testing::RayCastShapedCylinders;
using testing::StandingPerson;
using testing::Uniform;

constexpr double kDeg = std::numbers::pi / 180;

// Limbs tapered (0.8 .. 1.3 and reversed), both torso parts elliptic (1.3 x 0.7).
PartShapes TruthShapes() {
  PartShapes shapes{};
  shapes[Index(BodyPart::kLeftThigh)] = Cone(1.3, 0.8);
  shapes[Index(BodyPart::kRightThigh)] = Cone(1.2, 0.9);
  shapes[Index(BodyPart::kLeftUpperArm)] = Cone(1.3, 0.8);
  shapes[Index(BodyPart::kRightForearm)] = Cone(0.8, 1.3);
  shapes[Index(BodyPart::kLeftShin)] = Cone(1.1, 0.8);
  shapes[Index(BodyPart::kUpperTorso)] = Uniform(1.3, 0.7);
  shapes[Index(BodyPart::kLowerTorso)] = Uniform(1.3, 0.7);
  return shapes;
}

struct Scene {
  PinholeCamera camera = PinholeCamera::KinectLike();
  Skeleton skeleton;
  ImageDepthMm depth;
  ImageGray8 mask;
  CrossSectionFitFrame Frame() const { return {&skeleton, &camera, &mask, &depth}; }
};

Scene MakeScene(const Skeleton& skeleton, const PartShapes& truth,
                const PartExtensions& extensions = {},
                const PinholeCamera& camera = PinholeCamera::KinectLike()) {
  Scene s;
  s.camera = camera;
  s.skeleton = skeleton;
  RayCastShapedCylinders(PoseCylinders(skeleton, DefaultRadiusRatios(), extensions, truth),
                         s.camera, s.depth, s.mask);
  return s;
}

// A skeleton moved sideways by dx metres (off the optical axis: perspective).
Skeleton Shifted(Skeleton s, double dx) {
  for (auto& p : s.position) p.x() += dx;
  return s;
}

// Pixels per metre across a part at its mid-point (f / z).
double PixelsPerMetre(const Skeleton& s, BodyPart part) {
  const auto [ja, jb] = PartJoints(part);
  return PinholeCamera::KinectLike().fx / (0.5 * (s[ja] + s[jb])).z();
}

// A ring ratio's error bound from a half-width error of `pixels`: ratio = half-width / r.
double RatioBound(const Skeleton& s, BodyPart part, double pixels) {
  const auto [ja, jb] = PartJoints(part);
  const double r = (s[ja] - s[jb]).norm() * DefaultRadiusRatios()[Index(part)];
  return pixels / (r * PixelsPerMetre(s, part));
}

// The edges are each found to within half a pixel (a line's outermost pixel centre lies
// within one pixel inside the true edge, +0.5 centres it; the median over the slice's lines
// and the mean of two edges average the rest), so a ring's half-width is within 0.5 pixel.
constexpr double kEdgePx = 0.5;
constexpr double kInset = CrossSectionFitOptions{}.end_inset;

double TruthAt(const std::array<double, kShapeRings>& rings, double t) {
  const double x = t * (kShapeRings - 1);
  const int k = std::min(kShapeRings - 2, static_cast<int>(x));
  return rings[k] + (x - k) * (rings[k + 1] - rings[k]);
}

// By default the end rings take the value measured at the inset (0.15, 0.85), the rest the
// value at the ring.
void ExpectRings(const PartShape& fitted, const PartShape& truth, const Skeleton& s,
                 BodyPart part) {
  const double bound = RatioBound(s, part, kEdgePx);
  for (int k = 0; k < kShapeRings; ++k) {
    const double t = k == 0 ? kInset : k == kShapeRings - 1 ? 1 - kInset : double(k) / 4;
    EXPECT_NEAR(fitted.width[k], TruthAt(truth.width, t), bound) << PartName(part) << " ring " << k;
    EXPECT_NEAR(fitted.depth[k], TruthAt(truth.depth, t), bound) << PartName(part) << " ring " << k;
  }
}

// Every ring measured in one frame holds the half-pixel bound; at least min_rings are.
void ExpectMeasuredRings(const CrossSectionMeasurements& measured, const PartShape& truth,
                         const Skeleton& s, BodyPart part, int min_rings) {
  int rings = 0;
  for (int k = 0; k < kShapeRings; ++k) {
    const auto& ring = measured[Index(part)][k];
    if (!ring) continue;
    ++rings;
    EXPECT_NEAR(ring->half_width, TruthAt(truth.width, ring->t), RatioBound(s, part, kEdgePx))
        << PartName(part) << " ring " << k;
  }
  EXPECT_GE(rings, min_rings) << PartName(part);
}

TEST(ShapedRayCast, AgreesWithThePlainRayCasterOnPlainCylinders) {
  const PinholeCamera cam = PinholeCamera::KinectLike();
  const auto cylinders = PoseCylinders(StandingPerson(2.5, 0.4, true), DefaultRadiusRatios());
  ImageDepthMm depth_a, depth_b;
  ImageGray8 mask_a, mask_b;
  RayCastCylinders(cylinders, cam, depth_a, mask_a);
  RayCastShapedCylinders(cylinders, cam, depth_b, mask_b);
  // The shaped caster closes the ends (caps), the plain one casts the sides alone: they differ
  // only where a cap shows, a few pixels at each end of a part seen obliquely (2% of the
  // silhouette here), and elsewhere agree to the millimetre of depth rounding.
  int differ = 0, subject = 0, both = 0, depth_differ = 0;
  for (size_t i = 0; i < mask_a.data.size(); ++i) {
    differ += mask_a.data[i] != mask_b.data[i];
    subject += mask_a.data[i] != 0;
    if (mask_a.data[i] && mask_b.data[i]) {
      ++both;
      depth_differ += std::abs(depth_a.data[i] - depth_b.data[i]) > 1;
    }
  }
  EXPECT_GT(subject, 20000);
  EXPECT_LT(differ, subject / 50);
  EXPECT_LT(depth_differ, both / 50);
}

TEST(CrossSectionFit, RecoversTaperedLimbsFromOneFrame) {
  const Skeleton person = StandingPerson(2.5, 0.0, /*arms_out=*/true);
  const Scene scene = MakeScene(person, TruthShapes());
  const CrossSectionFitFrame frame = scene.Frame();
  const auto fit = FitCrossSections({&frame, 1}, DefaultRadiusRatios(), {});
  for (BodyPart part : {BodyPart::kLeftThigh, BodyPart::kRightThigh, BodyPart::kLeftUpperArm,
                        BodyPart::kRightForearm, BodyPart::kLeftShin, BodyPart::kRightShin,
                        BodyPart::kLeftForearm, BodyPart::kRightUpperArm}) {
    ASSERT_TRUE(fit.fitted[Index(part)]) << PartName(part);
    EXPECT_EQ(fit.frames_measured[Index(part)], 1);
    EXPECT_FALSE(fit.elliptic[Index(part)]);
    EXPECT_TRUE(fit.shape[Index(part)].IsCircular()) << PartName(part);
    ExpectRings(fit.shape[Index(part)], TruthShapes()[Index(part)], person, part);
  }
}

TEST(CrossSectionFit, PerspectiveOffTheOpticalAxis) {
  // The subject 0.6 m to the right at 2.2 m, turned 17 degrees: the left leg is seen 18
  // degrees off the optical axis, where f / z alone would misjudge its half-width by 5%
  // (1 / cos 18 deg), ten times the half-pixel bound. Every ring that is measured (the thigh's
  // top meets the other thigh in this view) holds that bound.
  const Skeleton person = Shifted(StandingPerson(2.2, 0.3, true), 0.6);
  const Scene scene = MakeScene(person, TruthShapes());
  const auto measured = MeasureCrossSections(scene.Frame(), DefaultRadiusRatios(), {});
  for (BodyPart part : {BodyPart::kLeftThigh, BodyPart::kRightForearm, BodyPart::kLeftShin,
                        BodyPart::kLeftUpperArm})
    ExpectMeasuredRings(measured, TruthShapes()[Index(part)], person, part, 3);
}

TEST(CrossSectionFit, RingsSitOnTheExtendedAxis) {
  PartExtensions extensions{};
  extensions[Index(BodyPart::kLeftShin)] = 0.25;
  extensions[Index(BodyPart::kRightForearm)] = 0.2;
  const Skeleton person = StandingPerson(2.5, 0.0, true);
  const Scene scene = MakeScene(person, TruthShapes(), extensions);
  const CrossSectionFitFrame frame = scene.Frame();
  const auto fit = FitCrossSections({&frame, 1}, DefaultRadiusRatios(), extensions);
  for (BodyPart part : {BodyPart::kLeftShin, BodyPart::kRightForearm}) {
    ASSERT_TRUE(fit.fitted[Index(part)]) << PartName(part);
    ExpectRings(fit.shape[Index(part)], TruthShapes()[Index(part)], person, part);
  }
}

// Headings of the subject (turning about the vertical), as a sensor walking around.
std::vector<Scene> Headings(const std::vector<double>& degrees, const PartShapes& truth) {
  std::vector<Scene> scenes;
  for (size_t i = 0; i < degrees.size(); ++i)
    scenes.push_back(MakeScene(Shifted(StandingPerson(2.5, degrees[i] * kDeg, true),
                                       0.3 * std::sin(static_cast<double>(i))),
                               truth));
  return scenes;
}

std::vector<CrossSectionFitFrame> Frames(const std::vector<Scene>& scenes) {
  std::vector<CrossSectionFitFrame> frames;
  for (const Scene& s : scenes) frames.push_back(s.Frame());
  return frames;
}

// The torso's width W and depth D are separated from views at 12 headings; the upper torso
// narrows from 1.35 to 0.95 (shoulders to waist) at a constant depth 0.7. Each frame's
// q^2 = W^2 c + D^2 (1 - c) carries the half-pixel edge error at the torso's scale (upper torso
// r = 0.1375 m, 29 pixels at 2.5 m: 1.7% of q, 3.4% of q^2); the Theil-Sen line's slope over
// pairs with c differing by >= 0.25 amplifies that at most fourfold, so W and D are held to
// 0.1 (8% of W, 14% of D). The upper torso's ring 0 lies at the shoulders, where the arms
// (held out) join the silhouette in every oblique view: measured only from the front and
// back, it cannot separate W and D, so it takes D from the part's other rings and W from its
// own frames. Those see it within 8 degrees of frontal (c >= 0.99), where a D error of 0.1
// moves W by less than 0.002: W is held to the half-pixel bound (0.017) plus that, 0.02,
// which copying W from ring 1 (0.04 narrower) would miss.
TEST(CrossSectionFit, EllipticTorsoFromSeveralHeadings) {
  PartShapes truth = TruthShapes();
  truth[Index(BodyPart::kUpperTorso)].width = LinearRings(1.35, 0.95);
  const std::vector<Scene> scenes =
      Headings({0, 30, 60, 90, 120, 150, 180, 210, 240, 270, 300, 330}, truth);
  const auto frames = Frames(scenes);
  const auto measured = MeasureCrossSections(frames[1], DefaultRadiusRatios(), {});
  EXPECT_FALSE(measured[Index(BodyPart::kUpperTorso)][0]);  // 30 degrees: beside the arm
  const auto fit = FitCrossSections(frames, DefaultRadiusRatios(), {});
  for (BodyPart part : {BodyPart::kUpperTorso, BodyPart::kLowerTorso}) {
    ASSERT_TRUE(fit.fitted[Index(part)]) << PartName(part);
    EXPECT_TRUE(fit.elliptic[Index(part)]) << PartName(part);
    EXPECT_GE(fit.frames_measured[Index(part)], 10) << PartName(part);
    for (int k = 0; k < kShapeRings; ++k) {
      const double t = k == 0 ? kInset : k == kShapeRings - 1 ? 1 - kInset : double(k) / 4;
      EXPECT_NEAR(fit.shape[Index(part)].width[k], TruthAt(truth[Index(part)].width, t), 0.1)
          << PartName(part) << " " << k;
      EXPECT_NEAR(fit.shape[Index(part)].depth[k], 0.7, 0.1) << PartName(part) << " " << k;
    }
  }
  for (const Scene& scene : scenes) {
    const auto ring = MeasureCrossSections(scene.Frame(), DefaultRadiusRatios(),
                                           {})[Index(BodyPart::kUpperTorso)][0];
    if (ring) {
      EXPECT_GE(0.5 * ((*ring->width_weight)[0] + (*ring->width_weight)[1]), 0.99);
    }
  }
  EXPECT_NEAR(fit.shape[Index(BodyPart::kUpperTorso)].width[0],
              TruthAt(truth[Index(BodyPart::kUpperTorso)].width, kInset), 0.02);
}

TEST(CrossSectionFit, AllFramesFrontalFallBackToCircular) {
  // Seen only from the front (within 20 degrees), D cannot be told from W: the rings are
  // circular with the width the frames show, W (within the bound above).
  const std::vector<Scene> scenes = Headings({0, 10, -10, 20, 180}, TruthShapes());
  const auto frames = Frames(scenes);
  const auto fit = FitCrossSections(frames, DefaultRadiusRatios(), {});
  for (BodyPart part : {BodyPart::kUpperTorso, BodyPart::kLowerTorso}) {
    ASSERT_TRUE(fit.fitted[Index(part)]) << PartName(part);
    EXPECT_FALSE(fit.elliptic[Index(part)]);
    EXPECT_TRUE(fit.shape[Index(part)].IsCircular());
    for (int k = 1; k < kShapeRings - 1; ++k)
      EXPECT_NEAR(fit.shape[Index(part)].width[k], 1.3, 0.1) << PartName(part) << " " << k;
  }
}

TEST(CrossSectionFit, OneSideViewIsNotEnoughToSeparate) {
  const std::vector<Scene> scenes = Headings({0, 10, 90}, TruthShapes());
  const auto frames = Frames(scenes);
  const auto fit = FitCrossSections(frames, DefaultRadiusRatios(), {});
  EXPECT_FALSE(fit.elliptic[Index(BodyPart::kUpperTorso)]);
  EXPECT_TRUE(fit.shape[Index(BodyPart::kUpperTorso)].IsCircular());
  // With one frame each way required, the same frames separate W and D.
  const auto loose =
      FitCrossSections(frames, DefaultRadiusRatios(), {}, {.min_frames_each_way = 1});
  EXPECT_TRUE(loose.elliptic[Index(BodyPart::kUpperTorso)]);
}

TEST(CrossSectionFit, MedianOverFramesOutvotesAWrongFrame) {
  // Frames of the truth and one of parts twice as thick (a bad segmentation): the limb's
  // median over three views keeps the truth; so does the torso's Theil-Sen fit (its slope is
  // the median of pairs, its intercept the median of frames), within the bounds above.
  const Skeleton person = StandingPerson(2.5, 0.0, true);
  PartShapes fat = TruthShapes();
  fat[Index(BodyPart::kLeftThigh)] = Cone(2.0, 2.0);
  fat[Index(BodyPart::kLowerTorso)] = Uniform(2.0, 2.0);
  std::vector<Scene> scenes = Headings({0, 30, 60, 90, 120, 150, 180, 270}, TruthShapes());
  scenes.push_back(MakeScene(person, fat));
  std::vector<Scene> limb_scenes;
  limb_scenes.push_back(MakeScene(person, TruthShapes()));
  limb_scenes.push_back(MakeScene(StandingPerson(2.5, 0.1, true), TruthShapes()));
  limb_scenes.push_back(MakeScene(person, fat));
  const auto fit = FitCrossSections(Frames(scenes), DefaultRadiusRatios(), {});
  for (int k = 0; k < kShapeRings; ++k) {
    EXPECT_NEAR(fit.shape[Index(BodyPart::kLowerTorso)].width[k], 1.3, 0.1) << k;
    EXPECT_NEAR(fit.shape[Index(BodyPart::kLowerTorso)].depth[k], 0.7, 0.1) << k;
  }
  const auto limb_fit = FitCrossSections(Frames(limb_scenes), DefaultRadiusRatios(), {});
  ExpectRings(limb_fit.shape[Index(BodyPart::kLeftThigh)],
              TruthShapes()[Index(BodyPart::kLeftThigh)], person, BodyPart::kLeftThigh);
}

TEST(CrossSectionFit, RingNoFrameMeasuresIsInterpolated) {
  // The mask loses the left thigh's middle (t 0.4 .. 0.6): ring 2 is measured by no frame and
  // takes the mean of rings 1 and 3, which for the linear truth is the truth itself.
  const Skeleton person = StandingPerson(2.5, 0.0, true);
  Scene scene = MakeScene(person, TruthShapes());
  const Eigen::Vector2d hip = *scene.camera.Project(person[Joint::kLeftHip]);
  const Eigen::Vector2d knee = *scene.camera.Project(person[Joint::kLeftKnee]);
  const Eigen::Vector2d dir = (knee - hip).normalized();
  const double length = (knee - hip).norm();
  for (int y = 0; y < scene.mask.height; ++y)
    for (int x = 0; x < scene.mask.width; ++x) {
      const Eigen::Vector2d rel = Eigen::Vector2d(x, y) - hip;
      const double t = rel.dot(dir) / length;
      const double across = std::abs(rel.x() * dir.y() - rel.y() * dir.x());
      if (t > 0.4 && t < 0.6 && across < 25) scene.mask.at(x, y) = 0;
    }
  const CrossSectionFitFrame frame = scene.Frame();
  const auto measured = MeasureCrossSections(frame, DefaultRadiusRatios(), {});
  EXPECT_FALSE(measured[Index(BodyPart::kLeftThigh)][2]);
  EXPECT_TRUE(measured[Index(BodyPart::kLeftThigh)][1]);
  EXPECT_TRUE(measured[Index(BodyPart::kLeftThigh)][3]);
  const auto fit = FitCrossSections({&frame, 1}, DefaultRadiusRatios(), {});
  ExpectRings(fit.shape[Index(BodyPart::kLeftThigh)], TruthShapes()[Index(BodyPart::kLeftThigh)],
              person, BodyPart::kLeftThigh);
}

TEST(CrossSectionFit, ExtrapolatedEndRingsReachTheEnds) {
  // The end ring's value that reproduces the inset measurement under the drawn surface's
  // linear interpolation: v_0 = v_1 + (m - v_1) / 0.4 at the inset 0.15. Its error is
  // 0.5 px / 0.4 from the inset ring and 0.5 px (1 / 0.4 - 1) from ring 1: 2 pixels.
  const Skeleton person = StandingPerson(2.5, 0.0, true);
  const Scene scene = MakeScene(person, TruthShapes());
  const CrossSectionFitFrame frame = scene.Frame();
  const auto fit =
      FitCrossSections({&frame, 1}, DefaultRadiusRatios(), {}, {.extrapolate_end_rings = true});
  for (BodyPart part : {BodyPart::kLeftThigh, BodyPart::kRightForearm, BodyPart::kLeftUpperArm}) {
    const PartShape& fitted = fit.shape[Index(part)];
    const PartShape truth = TruthShapes()[Index(part)];
    const double bound = RatioBound(person, part, 2.0);
    EXPECT_NEAR(fitted.width[0], truth.width[0], bound) << PartName(part);
    EXPECT_NEAR(fitted.width[kShapeRings - 1], truth.width[kShapeRings - 1], bound)
        << PartName(part);
    for (int k = 1; k < kShapeRings - 1; ++k)
      EXPECT_NEAR(fitted.width[k], truth.width[k], RatioBound(person, part, kEdgePx))
          << PartName(part);
  }
}

TEST(CrossSectionFit, RatiosAreClamped) {
  const Skeleton person = StandingPerson(2.5, 0.0, true);
  PartShapes truth{};
  truth[Index(BodyPart::kLeftForearm)] = Cone(1.8, 1.8);
  truth[Index(BodyPart::kRightForearm)] = Cone(0.6, 0.6);
  const Scene scene = MakeScene(person, truth);
  const CrossSectionFitFrame frame = scene.Frame();
  const auto fit = FitCrossSections({&frame, 1}, DefaultRadiusRatios(), {},
                                    {.min_ratio = 0.8, .max_ratio = 1.5});
  for (int k = 0; k < kShapeRings; ++k) {
    EXPECT_DOUBLE_EQ(fit.shape[Index(BodyPart::kLeftForearm)].width[k], 1.5);
    EXPECT_DOUBLE_EQ(fit.shape[Index(BodyPart::kRightForearm)].width[k], 0.8);
  }
}

TEST(CrossSectionFit, ATouchingNeighbourIsNotTheSilhouette) {
  // Arms hanging against the torso: where an arm touches it, the torso's outermost pixels
  // border the arm's, not the background, so those lines measure nothing; what is measured
  // must not take the arm for torso (the fit stays within the bound of the free case or the
  // ring is not measured).
  const Skeleton person = StandingPerson(2.5, 0.0, /*arms_out=*/false);
  PartShapes truth{};
  truth[Index(BodyPart::kUpperTorso)] = Uniform(1.3, 0.7);
  const Scene scene = MakeScene(person, truth);
  const CrossSectionFitFrame frame = scene.Frame();
  const auto measured = MeasureCrossSections(frame, DefaultRadiusRatios(), {});
  for (int k = 0; k < kShapeRings; ++k) {
    const auto& ring = measured[Index(BodyPart::kUpperTorso)][k];
    if (ring) {
      EXPECT_NEAR(ring->half_width, 1.3, RatioBound(person, BodyPart::kUpperTorso, kEdgePx)) << k;
    }
  }
  // Above the arms (ring 0, at the neck) the torso is free; at its middle the arms touch it.
  EXPECT_TRUE(measured[Index(BodyPart::kUpperTorso)][0]);
  EXPECT_FALSE(measured[Index(BodyPart::kUpperTorso)][2]);
}

TEST(CrossSectionFit, AForearmInFrontOfTheTorsoKeepsItsPixelsByDepth) {
  // The right forearm folded across the belly, 0.3 m in front of the torso's axis and 0.1 m
  // in front of its surface. By the image alone its pixels near the torso's axis would go to
  // the torso; by depth they lie on the forearm's surface. Its edges border the torso, which
  // lies behind them, so they count; the elbow's ring meets the upper arm, which is not
  // behind it, and is not measured.
  Skeleton person = StandingPerson(2.5, 0.0, true);
  person.Set(Joint::kRightElbow, Eigen::Vector3d(-0.3, -0.15, 2.2));
  person.Set(Joint::kRightHand, Eigen::Vector3d(0.1, -0.1, 2.15));
  PartShapes truth{};
  truth[Index(BodyPart::kRightForearm)] = Cone(1.3, 0.8);
  const Scene scene = MakeScene(person, truth);
  const auto measured = MeasureCrossSections(scene.Frame(), DefaultRadiusRatios(), {});
  ExpectMeasuredRings(measured, truth[Index(BodyPart::kRightForearm)], person,
                      BodyPart::kRightForearm, 4);
}

TEST(CrossSectionFit, ClippedAtTheImageBorderMeasuresNothingThere) {
  // A crop whose right border runs along the subject's left thigh: its silhouette is cut, so
  // it must not be measured (a narrower width would be wrong); the right thigh still is.
  const Skeleton person = StandingPerson(2.5, 0.0, true);
  const PinholeCamera full = PinholeCamera::KinectLike();
  const int border = static_cast<int>(std::lround(full.Project(person[Joint::kLeftKnee])->x()));
  const PinholeCamera crop = full.Cropped(0, 0, border, full.height);
  const Scene scene = MakeScene(person, TruthShapes(), {}, crop);
  const CrossSectionFitFrame frame = scene.Frame();
  const auto measured = MeasureCrossSections(frame, DefaultRadiusRatios(), {});
  for (int k = 0; k < kShapeRings; ++k) EXPECT_FALSE(measured[Index(BodyPart::kLeftThigh)][k]);
  const auto fit = FitCrossSections({&frame, 1}, DefaultRadiusRatios(), {});
  EXPECT_FALSE(fit.fitted[Index(BodyPart::kLeftThigh)]);
  EXPECT_TRUE(fit.shape[Index(BodyPart::kLeftThigh)].IsCylinder());
  ExpectRings(fit.shape[Index(BodyPart::kRightThigh)], TruthShapes()[Index(BodyPart::kRightThigh)],
              person, BodyPart::kRightThigh);
}

TEST(CrossSectionFit, WithoutDepthTheSilhouetteAloneServes) {
  const Skeleton person = StandingPerson(2.5, 0.0, true);
  Scene scene = MakeScene(person, TruthShapes());
  scene.depth = ImageDepthMm();
  const CrossSectionFitFrame frame = scene.Frame();
  const auto fit = FitCrossSections({&frame, 1}, DefaultRadiusRatios(), {});
  for (BodyPart part : {BodyPart::kLeftThigh, BodyPart::kRightForearm}) {
    ASSERT_TRUE(fit.fitted[Index(part)]);
    ExpectRings(fit.shape[Index(part)], TruthShapes()[Index(part)], person, part);
  }
}

TEST(CrossSectionFit, NoFramesFitsNothing) {
  const auto fit = FitCrossSections({}, DefaultRadiusRatios(), {});
  for (int p = 0; p < kBodyPartCount; ++p) {
    EXPECT_FALSE(fit.fitted[p]);
    EXPECT_EQ(fit.frames_measured[p], 0);
    EXPECT_TRUE(fit.shape[p].IsCylinder());
  }
}

TEST(CrossSectionFit, EmptyMaskFitsNothing) {
  Scene scene = MakeScene(StandingPerson(2.5, 0.0, true), TruthShapes());
  scene.mask = ImageGray8(scene.camera.width, scene.camera.height, 1, 0);
  const CrossSectionFitFrame frame = scene.Frame();
  const auto fit = FitCrossSections({&frame, 1}, DefaultRadiusRatios(), {});
  for (int p = 0; p < kBodyPartCount; ++p) {
    EXPECT_FALSE(fit.fitted[p]);
    EXPECT_TRUE(fit.shape[p].IsCylinder());
  }
}

TEST(CrossSectionFit, MissingJointLeavesItsPartsPlain) {
  const Skeleton person = StandingPerson(2.5, 0.0, true);
  const Scene scene = MakeScene(person, TruthShapes());
  Skeleton tracked = person;
  tracked.confidence[Index(Joint::kLeftElbow)] = 0;
  const CrossSectionFitFrame frame{&tracked, &scene.camera, &scene.mask, &scene.depth};
  const auto fit = FitCrossSections({&frame, 1}, DefaultRadiusRatios(), {});
  for (BodyPart part : {BodyPart::kLeftUpperArm, BodyPart::kLeftForearm}) {
    EXPECT_FALSE(fit.fitted[Index(part)]);
    EXPECT_TRUE(fit.shape[Index(part)].IsCylinder());
  }
  EXPECT_TRUE(fit.fitted[Index(BodyPart::kRightForearm)]);
  EXPECT_TRUE(fit.fitted[Index(BodyPart::kLeftThigh)]);
}

TEST(CrossSectionFit, ZeroLengthBoneAndJointBehindTheCameraMeasureNothing) {
  const Scene scene = MakeScene(StandingPerson(2.5, 0.0, true), TruthShapes());
  Skeleton tracked = scene.skeleton;
  tracked.Set(Joint::kLeftHand, tracked[Joint::kLeftElbow]);
  tracked.Set(Joint::kRightFoot, Eigen::Vector3d(-0.1, 0.9, -0.5));
  const CrossSectionFitFrame frame{&tracked, &scene.camera, &scene.mask, &scene.depth};
  const auto measured = MeasureCrossSections(frame, DefaultRadiusRatios(), {});
  for (int k = 0; k < kShapeRings; ++k) {
    EXPECT_FALSE(measured[Index(BodyPart::kLeftForearm)][k]);
    EXPECT_FALSE(measured[Index(BodyPart::kRightShin)][k]);
  }
  EXPECT_TRUE(measured[Index(BodyPart::kLeftShin)][2]);
  // The whole subject behind the camera: nothing at all.
  const Skeleton behind = StandingPerson(-2.5, 0.0, true);
  const CrossSectionFitFrame back{&behind, &scene.camera, &scene.mask, &scene.depth};
  const auto fit = FitCrossSections({&back, 1}, DefaultRadiusRatios(), {});
  for (int p = 0; p < kBodyPartCount; ++p) EXPECT_FALSE(fit.fitted[p]);
}

TEST(CrossSectionFit, AxisPointingAtTheCameraMeasuresNothing) {
  Skeleton person = StandingPerson(2.5, 0.0, true);
  const Eigen::Vector3d elbow = person[Joint::kLeftElbow];
  person.Set(Joint::kLeftHand, elbow - 0.3 * elbow.normalized());
  const Scene scene = MakeScene(person, TruthShapes());
  const auto measured = MeasureCrossSections(scene.Frame(), DefaultRadiusRatios(), {});
  for (int k = 0; k < kShapeRings; ++k) EXPECT_FALSE(measured[Index(BodyPart::kLeftForearm)][k]);
}

TEST(CrossSectionFit, RejectsBadOptionsAndMismatchedImages) {
  const Scene scene = MakeScene(StandingPerson(2.5, 0.0, true), TruthShapes());
  const CrossSectionFitFrame frame = scene.Frame();
  for (const CrossSectionFitOptions& bad :
       {CrossSectionFitOptions{.end_inset = 0}, CrossSectionFitOptions{.end_inset = 0.3},
        CrossSectionFitOptions{.half_slice = 0.2}, CrossSectionFitOptions{.min_lines = 0},
        CrossSectionFitOptions{.min_ratio = 1.2}, CrossSectionFitOptions{.max_ratio = 0.9},
        CrossSectionFitOptions{.elliptic_split = 1}, CrossSectionFitOptions{.min_pair_spread = 0},
        CrossSectionFitOptions{.depth_scale_m = std::nan("")}})
    EXPECT_THROW(FitCrossSections({&frame, 1}, DefaultRadiusRatios(), {}, bad), CheckError);
  const ImageGray8 small(10, 10, 1, 255);
  CrossSectionFitFrame wrong = frame;
  wrong.mask = &small;
  EXPECT_THROW(MeasureCrossSections(wrong, DefaultRadiusRatios(), {}), CheckError);
  wrong = frame;
  wrong.depth = nullptr;
  EXPECT_THROW(MeasureCrossSections(wrong, DefaultRadiusRatios(), {}), CheckError);
  PartExtensions negative{};
  negative[0] = -1;
  EXPECT_THROW(MeasureCrossSections(frame, DefaultRadiusRatios(), negative), CheckError);
}

TEST(CrossSectionError, TheTruthFitsTheSilhouettesBetterThanThePlainCylinder) {
  const std::vector<Scene> scenes = Headings({0, 45, 90, 180}, TruthShapes());
  const auto frames = Frames(scenes);
  const auto truth = MeasureCrossSectionError(frames, DefaultRadiusRatios(), {}, TruthShapes());
  const auto plain = MeasureCrossSectionError(frames, DefaultRadiusRatios(), {}, PartShapes{});
  ASSERT_GT(truth.samples_all, 100);
  EXPECT_EQ(truth.samples_all, plain.samples_all);
  // The truth misses by the edges' half-pixel at most (4.8 mm at 2.5 m); the plain cylinder
  // by the taper and the torso's ellipse (0.2-0.3 of the radius, centimetres).
  EXPECT_LT(truth.mean_abs_m_all, 0.5 * 2.5 / 525);
  EXPECT_GT(plain.mean_abs_m_all, 3 * truth.mean_abs_m_all);
  EXPECT_LT(truth.mean_abs_m[Index(BodyPart::kUpperTorso)], 0.5 * 2.5 / 525);
  EXPECT_GT(plain.mean_abs_m[Index(BodyPart::kUpperTorso)], 0.01);
  // The fit reproduces the silhouettes as well as the truth does.
  const auto fit = FitCrossSections(frames, DefaultRadiusRatios(), {});
  const auto fitted = MeasureCrossSectionError(frames, DefaultRadiusRatios(), {}, fit.shape);
  EXPECT_LT(fitted.mean_abs_m_all, 0.5 * 2.5 / 525);
}

}  // namespace
}  // namespace reenact
