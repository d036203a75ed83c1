#include "common/texture/subject_light.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "common/error/check.h"
#include "common/model/cylinder_model.h"
#include "common/texture/visibility_maps.h"
#include "tests/unit/common/cylinder_raycast.h"
#include "tests/unit/common/test_skeletons.h"

namespace reenact {
namespace {

constexpr double kPi = 3.14159265358979323846;
double Deg(double d) { return d * kPi / 180.0; }

// The bin layout and sampling the tests below are written for (coarser than the defaults, so
// each bin holds more samples of the small synthetic frames).
const LightSampleBins kCoarseBins{.axial_bins = 4, .angular_bins = 8};
LightSampleOptions CoarseOptions() { return {.stride = 3, .bins = kCoarseBins}; }
double AngleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b)) * 180.0 / kPi;
}

Eigen::Vector3d RandomUnit(std::mt19937& rng) {
  std::normal_distribution<double> g(0, 1);
  Eigen::Vector3d v(g(rng), g(rng), g(rng));
  while (v.norm() < 1e-6) v = Eigen::Vector3d(g(rng), g(rng), g(rng));
  return v.normalized();
}

// `bins` surface bins of random albedo in [40, 110], each seen `per_bin` times under random
// normals, shaded by `light` (c = a SubjectShade(n, L)) plus uniform value noise in
// [-noise, noise].
std::vector<LightSample> LambertSamples(const Eigen::Vector3d& light, int bins, int per_bin,
                                        double noise, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> albedo(40, 110), jitter(-noise, noise);
  std::vector<LightSample> out;
  for (int b = 0; b < bins; ++b) {
    const double a = albedo(rng);
    for (int i = 0; i < per_bin; ++i) {
      LightSample s;
      s.bin = 3 * b + 7;  // sparse bin ids
      s.normal_in_world = RandomUnit(rng);
      s.value = a * SubjectShade(s.normal_in_world, light) + (noise > 0 ? jitter(rng) : 0.0);
      out.push_back(s);
    }
  }
  return out;
}

void ExpectFinite(const SubjectLightFit& fit) {
  EXPECT_TRUE(fit.light.allFinite());
  EXPECT_TRUE(std::isfinite(fit.gain));
  EXPECT_GE(fit.gain, 0.0);
  EXPECT_LE(fit.gain, 1.0);
}

void ExpectNoLight(const SubjectLightFit& fit) {
  ExpectFinite(fit);
  EXPECT_FALSE(fit.found);
  EXPECT_EQ(fit.light, Eigen::Vector3d::Zero());
  EXPECT_FALSE(fit.reason.empty());
}

// ---------------------------------------------------------------------------------------------
// SubjectShade

TEST(SubjectShade, FlatLightIsOneAwayFromTheLightIsOneAndFacingItIsOnePlusStrength) {
  const Eigen::Vector3d n = Eigen::Vector3d(0.2, -0.4, 0.9).normalized();
  EXPECT_EQ(SubjectShade(n, Eigen::Vector3d::Zero()), 1.0);
  EXPECT_EQ(SubjectShade(n, -1.7 * n), 1.0);
  EXPECT_DOUBLE_EQ(SubjectShade(n, 1.7 * n), 2.7);
  // Half-way (60 degrees): 1 + |L| cos 60.
  const Eigen::Vector3d side = n.cross(Eigen::Vector3d::UnitX()).normalized();
  EXPECT_NEAR(SubjectShade(n, 2.0 * (0.5 * n + std::sqrt(0.75) * side)), 2.0, 1e-12);
}

// ---------------------------------------------------------------------------------------------
// FitSubjectLight

TEST(FitSubjectLight, RecoversAKnownLightFromBinsSeenUnderManyNormals) {
  // A Lambert scene with ambient share 0.5: L = l (1 - k) / k = l, strength 1.
  const Eigen::Vector3d truth = Eigen::Vector3d(0.3, -0.6, 0.75).normalized();
  const SubjectLightFit fit = FitSubjectLight(LambertSamples(truth, 40, 50, 0, 1));
  ASSERT_TRUE(fit.found) << fit.reason;
  EXPECT_TRUE(fit.reason.empty());
  EXPECT_EQ(fit.samples, 2000);
  EXPECT_EQ(fit.bins, 40);
  EXPECT_LT(AngleDeg(fit.light, truth), 2.0);
  EXPECT_NEAR(fit.light.norm(), 1.0, 0.05);
  // Exact data: cost(L_true) = 0, so the refined L leaves almost nothing.
  EXPECT_GT(fit.gain, 0.99);
}

TEST(FitSubjectLight, RecoversTheLightUnderValueNoise) {
  // +-3 grey levels (sigma = sqrt(3)). The scale of L's error: sigma / (albedo sqrt(N var m)),
  // var m = 1/6 - 1/16 for m = max(0, n . l) over uniform normals, about 1.7 / (75 sqrt(2000 *
  // 0.1)) = 0.002, so 2 degrees (0.035 rad) and 5 % are over ten of it. The gain: cost(L_true)
  // is about N sigma^2 = 6000 against cost(0) about N 75^2 var m = 1.2e6, so 1 - 0.005.
  const Eigen::Vector3d truth = Eigen::Vector3d(0.3, -0.6, 0.75).normalized();
  const SubjectLightFit fit = FitSubjectLight(LambertSamples(truth, 40, 50, 3.0, 2));
  ASSERT_TRUE(fit.found) << fit.reason;
  EXPECT_LT(AngleDeg(fit.light, truth), 2.0);
  EXPECT_NEAR(fit.light.norm(), 1.0, 0.05);
  EXPECT_GT(fit.gain, 0.95);
}

TEST(FitSubjectLight, RecoversAWeakLightFromAnotherDirection) {
  const Eigen::Vector3d truth = 0.4 * Eigen::Vector3d(-0.8, 0.1, -0.5).normalized();
  const SubjectLightFit fit = FitSubjectLight(LambertSamples(truth, 40, 50, 0, 3));
  ASSERT_TRUE(fit.found) << fit.reason;
  EXPECT_LT(AngleDeg(fit.light, truth), 2.0);
  EXPECT_NEAR(fit.light.norm(), 0.4, 0.02);
  EXPECT_GT(fit.gain, 0.99);
}

TEST(FitSubjectLight, RecoversTheLightWhenAFifthOfTheSamplesAreOutliers) {
  // Pixels given to the wrong part or bin (the model's labels are rough) carry another
  // patch's colour: here a fifth of the samples get a uniform value in [0, 255], unrelated to
  // their bin. The robust reweighting must keep them from tilting L: with Cauchy weights an
  // outlier 100 levels off weighs about 1 / (1 + (100 / (2.4 * 1.5 * 10))^2) = 0.1 of an
  // inlier (median residual about 10 with the outliers in), so they pull L less than the
  // plain least squares do (measured without the reweighting: 1.2 degrees and strength 0.71 on
  // these data).
  const Eigen::Vector3d truth = Eigen::Vector3d(0.3, -0.6, 0.75).normalized();
  std::vector<LightSample> samples = LambertSamples(truth, 40, 50, 0, 6);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> any(0, 255);
  for (size_t i = 0; i < samples.size(); i += 5) samples[i].value = any(rng);
  const SubjectLightFit fit = FitSubjectLight(samples);
  ASSERT_TRUE(fit.found) << fit.reason;
  EXPECT_LT(AngleDeg(fit.light, truth), 3.0);
  EXPECT_NEAR(fit.light.norm(), 1.0, 0.1);
}

TEST(FitSubjectLight, FlatLightFindsNoLight) {
  // Values = albedo: nothing varies within a bin.
  const SubjectLightFit fit =
      FitSubjectLight(LambertSamples(Eigen::Vector3d::Zero(), 40, 50, 0, 4));
  ExpectNoLight(fit);
  EXPECT_EQ(fit.gain, 0.0);
  EXPECT_EQ(fit.samples, 2000);
  EXPECT_EQ(fit.bins, 40);
}

TEST(FitSubjectLight, FlatLightWithValueNoiseFindsNoLight) {
  // Three parameters fitted to noise explain about 3 / (N - bins) of it, far below min_gain.
  const SubjectLightFit fit =
      FitSubjectLight(LambertSamples(Eigen::Vector3d::Zero(), 40, 50, 3.0, 5));
  ExpectNoLight(fit);
  EXPECT_LT(fit.gain, 0.01);
}

TEST(FitSubjectLight, NoSamplesFindsNoLight) {
  const SubjectLightFit fit = FitSubjectLight({});
  ExpectNoLight(fit);
  EXPECT_EQ(fit.samples, 0);
  EXPECT_EQ(fit.bins, 0);
  EXPECT_EQ(fit.gain, 0.0);
}

TEST(FitSubjectLight, FewerThanMinSamplesFindsNoLight) {
  const Eigen::Vector3d truth = Eigen::Vector3d(0.3, -0.6, 0.75).normalized();
  std::vector<LightSample> samples = LambertSamples(truth, 20, 10, 0, 6);  // exactly 200
  ASSERT_TRUE(FitSubjectLight(samples).found);
  samples.pop_back();
  const SubjectLightFit fit = FitSubjectLight(samples);
  ExpectNoLight(fit);
  EXPECT_EQ(fit.samples, 199);
}

TEST(FitSubjectLight, FewerThanMinBinsFindsNoLight) {
  const Eigen::Vector3d truth = Eigen::Vector3d(0.3, -0.6, 0.75).normalized();
  SubjectLightFitOptions options;
  options.min_bins = 41;
  const SubjectLightFit fit = FitSubjectLight(LambertSamples(truth, 40, 50, 0, 7), options);
  ExpectNoLight(fit);
  EXPECT_EQ(fit.bins, 40);
}

TEST(FitSubjectLight, BinsSeenOnceCarryNoInformation) {
  const Eigen::Vector3d truth = Eigen::Vector3d(0.3, -0.6, 0.75).normalized();
  std::vector<LightSample> samples = LambertSamples(truth, 500, 1, 0, 8);
  const SubjectLightFit fit = FitSubjectLight(samples);
  ExpectNoLight(fit);
  EXPECT_EQ(fit.samples, 500);
  EXPECT_EQ(fit.bins, 0);
}

TEST(FitSubjectLight, BadSamplesAreSkipped) {
  const Eigen::Vector3d truth = Eigen::Vector3d(0.3, -0.6, 0.75).normalized();
  const std::vector<LightSample> clean = LambertSamples(truth, 40, 50, 2.0, 9);
  std::vector<LightSample> dirty = clean;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  // Each would move the fit if used: a wild value in a known bin.
  LightSample bad = clean[0];
  bad.value = nan;
  dirty.insert(dirty.begin() + 5, bad);
  bad = clean[1];
  bad.value = inf;
  dirty.insert(dirty.begin() + 9, bad);
  bad = clean[2];
  bad.value = 250;
  bad.normal_in_world = Eigen::Vector3d(nan, 0, 1);
  dirty.push_back(bad);
  bad.normal_in_world = Eigen::Vector3d(0, 0, 1.01);  // not unit within 1e-3
  dirty.push_back(bad);
  bad.normal_in_world = Eigen::Vector3d(0, 0, 0);
  dirty.push_back(bad);
  bad.normal_in_world = Eigen::Vector3d::UnitX();
  bad.bin = -1;
  dirty.push_back(bad);
  dirty.push_back(bad);  // twice: a negative bin never counts as seen twice either
  const SubjectLightFit fit_clean = FitSubjectLight(clean);
  const SubjectLightFit fit = FitSubjectLight(dirty);
  ExpectFinite(fit);
  ASSERT_TRUE(fit.found);
  EXPECT_EQ(fit.samples, 2000);
  EXPECT_EQ(fit.bins, 40);
  EXPECT_EQ(fit.light, fit_clean.light);
  EXPECT_EQ(fit.gain, fit_clean.gain);
  // A normal within 1e-3 of unit length is used.
  dirty = clean;
  dirty[0].normal_in_world *= 1.0009;
  EXPECT_EQ(FitSubjectLight(dirty).samples, 2000);
}

TEST(FitSubjectLight, AllValuesEqualFindsNoLight) {
  std::vector<LightSample> samples = LambertSamples(Eigen::Vector3d::UnitX(), 40, 50, 0, 10);
  for (LightSample& s : samples) s.value = 100;
  const SubjectLightFit fit = FitSubjectLight(samples);
  ExpectNoLight(fit);
  EXPECT_EQ(fit.gain, 0.0);
}

TEST(FitSubjectLight, OneNormalForEverySampleFindsNoLight) {
  // Seen under one normal only, the shading is one factor per bin, which the bin's albedo
  // absorbs: every L costs the same as L = 0 (value noise keeps cost(0) > 0).
  const Eigen::Vector3d truth = Eigen::Vector3d(0.3, -0.6, 0.75).normalized();
  std::vector<LightSample> samples = LambertSamples(truth, 40, 50, 0, 11);
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> jitter(-3, 3);
  const Eigen::Vector3d n = Eigen::Vector3d(0.1, -0.2, 0.9).normalized();
  for (LightSample& s : samples) {
    s.value =
        s.value / SubjectShade(s.normal_in_world, truth) * SubjectShade(n, truth) + jitter(rng);
    s.normal_in_world = n;
  }
  const SubjectLightFit fit = FitSubjectLight(samples);
  ExpectNoLight(fit);
  EXPECT_LT(fit.gain, 1e-6);
}

TEST(FitSubjectLight, OptionsCheckRefusesEachBadField) {
  EXPECT_NO_THROW(SubjectLightFitOptions{}.Check());
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<SubjectLightFitOptions> bad(12);
  bad[0].directions = 7;
  bad[1].strengths = 0;
  bad[2].max_strength = 0;
  bad[3].max_strength = -1;
  bad[4].max_strength = nan;
  bad[5].max_strength = inf;
  bad[6].min_gain = -0.01;
  bad[7].min_gain = 1;
  bad[8].min_gain = nan;
  bad[9].min_samples = 0;
  bad[10].min_bins = 0;
  bad[11].min_bins = -3;
  const std::vector<LightSample> samples = LambertSamples(Eigen::Vector3d::UnitX(), 20, 20, 0, 13);
  for (size_t i = 0; i < bad.size(); ++i) {
    EXPECT_THROW(bad[i].Check(), CheckError) << i;
    EXPECT_THROW(FitSubjectLight(samples, bad[i]), CheckError) << i;
  }
  SubjectLightFitOptions edge;  // the smallest accepted values
  edge.directions = 8;
  edge.strengths = 1;
  edge.min_gain = 0;
  edge.min_samples = 1;
  edge.min_bins = 1;
  EXPECT_NO_THROW(edge.Check());
}

TEST(FitSubjectLight, TheSmallestSearchStillFindsTheLight) {
  // 8 directions at one strength, L = 0 and the pattern search: the refinement walks the rest.
  const Eigen::Vector3d truth = 1.5 * Eigen::Vector3d(-0.2, 0.7, 0.4).normalized();
  SubjectLightFitOptions options;
  options.directions = 8;
  options.strengths = 1;
  const SubjectLightFit fit = FitSubjectLight(LambertSamples(truth, 40, 50, 0, 14), options);
  ASSERT_TRUE(fit.found) << fit.reason;
  EXPECT_LT(AngleDeg(fit.light, truth), 2.0);
  EXPECT_NEAR(fit.light.norm(), 1.5, 0.075);
}

// ---------------------------------------------------------------------------------------------
// LightSampleBin

// The point at height fraction t and angle theta (radians, from the left direction towards
// axis x left) at distance rho from the part's axis, built from the bin frame's definition.
Eigen::Vector3d PointOnPart(const Skeleton& s, BodyPart part, double t, double theta, double rho) {
  const auto [ja, jb] = PartJoints(part);
  const bool legs = part == BodyPart::kLowerTorso || part == BodyPart::kLeftThigh ||
                    part == BodyPart::kLeftShin || part == BodyPart::kRightThigh ||
                    part == BodyPart::kRightShin;
  const Eigen::Vector3d left = legs ? s[Joint::kLeftHip] - s[Joint::kRightHip]
                                    : s[Joint::kLeftShoulder] - s[Joint::kRightShoulder];
  const Eigen::Vector3d u = (s[jb] - s[ja]).normalized();
  const Eigen::Vector3d r = (left - left.dot(u) * u).normalized();
  return s[ja] + t * (s[jb] - s[ja]) + rho * (std::cos(theta) * r + std::sin(theta) * u.cross(r));
}

TEST(LightSampleBin, PointsAtKnownHeightAndAngleGetTheirBin) {
  const Skeleton s = testing::StandingPerson(2.5, Deg(20), false);
  const LightSampleBins bins = kCoarseBins;
  for (BodyPart part :
       {BodyPart::kHead, BodyPart::kUpperTorso, BodyPart::kLowerTorso, BodyPart::kLeftUpperArm,
        BodyPart::kRightForearm, BodyPart::kLeftThigh, BodyPart::kRightShin}) {
    for (int axial = 0; axial < 4; ++axial)
      for (int angular = 0; angular < 8; ++angular) {
        const double t = (axial + 0.5) / 4, theta = (angular + 0.5) * 2 * kPi / 8;
        const int expected = (Index(part) * 4 + axial) * 8 + angular;
        EXPECT_EQ(LightSampleBin(s, part, PointOnPart(s, part, t, theta, 0.07), bins), expected)
            << PartName(part) << " " << axial << " " << angular;
      }
    // Past the ends: clamped to the first and last ring.
    EXPECT_EQ(LightSampleBin(s, part, PointOnPart(s, part, -0.3, 0.1, 0.05), bins),
              (Index(part) * 4 + 0) * 8 + 0);
    EXPECT_EQ(LightSampleBin(s, part, PointOnPart(s, part, 1.4, 0.1, 0.05), bins),
              (Index(part) * 4 + 3) * 8 + 0);
  }
  // Other bin counts.
  LightSampleBins fine;
  fine.axial_bins = 3;
  fine.angular_bins = 5;
  const BodyPart thigh = BodyPart::kRightThigh;
  EXPECT_EQ(LightSampleBin(s, thigh, PointOnPart(s, thigh, 0.9, Deg(300), 0.05), fine),
            (Index(thigh) * 3 + 2) * 5 + 4);
}

TEST(LightSampleBin, TheFrontOfAStandingPersonIsAtNinetyDegrees) {
  // Facing the camera (yaw 0): the axes point down (+y), the left is +x, so axis x left is
  // -z, towards the camera. A point on the front of the left thigh, a little to the body's
  // left, lies just below 90 degrees (sector 1 of 8); a little to the right, sector 2.
  const Skeleton s = testing::StandingPerson(2.5, 0, false);
  const BodyPart thigh = BodyPart::kLeftThigh;
  const Eigen::Vector3d mid = 0.4 * s[Joint::kLeftHip] + 0.6 * s[Joint::kLeftKnee];
  const int ring = (Index(thigh) * 4 + 2) * 8;  // t = 0.6 is in the third of 4 rings
  EXPECT_EQ(LightSampleBin(s, thigh, mid + Eigen::Vector3d(0.01, 0.001, -0.08), kCoarseBins),
            ring + 1);
  EXPECT_EQ(LightSampleBin(s, thigh, mid + Eigen::Vector3d(-0.01, 0.001, -0.08), kCoarseBins),
            ring + 2);
  // The back (+z, away from the camera) is at 270 degrees: sectors 5 and 6.
  EXPECT_EQ(LightSampleBin(s, thigh, mid + Eigen::Vector3d(-0.01, 0.001, 0.08), kCoarseBins),
            ring + 5);
  EXPECT_EQ(LightSampleBin(s, thigh, mid + Eigen::Vector3d(0.01, 0.001, 0.08), kCoarseBins),
            ring + 6);
}

TEST(LightSampleBin, AMissingJointGivesNoBin) {
  const Skeleton full = testing::StandingPerson(2.5, 0, false);
  const Eigen::Vector3d x = PointOnPart(full, BodyPart::kLeftThigh, 0.5, 1.0, 0.05);
  ASSERT_GE(LightSampleBin(full, BodyPart::kLeftThigh, x, kCoarseBins), 0);
  for (Joint j : {Joint::kLeftHip, Joint::kLeftKnee, Joint::kRightHip}) {
    Skeleton s = full;
    s.confidence[Index(j)] = 0;
    EXPECT_EQ(LightSampleBin(s, BodyPart::kLeftThigh, x, kCoarseBins), -1) << JointName(j);
  }
  // The shoulders carry the arms' left direction.
  Skeleton s = full;
  s.confidence[Index(Joint::kRightShoulder)] = 0;
  EXPECT_EQ(LightSampleBin(s, BodyPart::kLeftForearm,
                           PointOnPart(full, BodyPart::kLeftForearm, 0.5, 1.0, 0.04), kCoarseBins),
            -1);
  // ... but not the legs'.
  EXPECT_GE(LightSampleBin(s, BodyPart::kLeftThigh, x, kCoarseBins), 0);
}

TEST(LightSampleBin, AZeroLengthBoneGivesNoBin) {
  Skeleton s = testing::StandingPerson(2.5, 0, false);
  s.Set(Joint::kLeftKnee, s[Joint::kLeftHip]);
  EXPECT_EQ(LightSampleBin(s, BodyPart::kLeftThigh,
                           s[Joint::kLeftHip] + Eigen::Vector3d(0, 0, -0.05), kCoarseBins),
            -1);
  s.Set(Joint::kLeftKnee, s[Joint::kLeftHip] + Eigen::Vector3d(0, 0.5 * kMinBoneLength, 0));
  EXPECT_EQ(LightSampleBin(s, BodyPart::kLeftThigh,
                           s[Joint::kLeftHip] + Eigen::Vector3d(0, 0, -0.05), kCoarseBins),
            -1);
}

TEST(LightSampleBin, ALeftDirectionAlongTheAxisGivesNoBin) {
  // Arms held out sideways: the upper arm runs within 11 degrees of the shoulder line
  // (sine 0.18 < 0.3).
  const Skeleton out = testing::StandingPerson(2.5, 0, true);
  const Eigen::Vector3d on_arm =
      0.5 * (out[Joint::kLeftShoulder] + out[Joint::kLeftElbow]) + Eigen::Vector3d(0, 0, -0.05);
  EXPECT_EQ(LightSampleBin(out, BodyPart::kLeftUpperArm, on_arm, kCoarseBins), -1);
  LightSampleBins lenient;
  lenient.min_sine = 0.1;
  EXPECT_GE(LightSampleBin(out, BodyPart::kLeftUpperArm, on_arm, lenient), 0);
  // Exactly parallel: no bin even with min_sine 0.
  Skeleton s = testing::StandingPerson(2.5, 0, false);
  const Eigen::Vector3d left = s[Joint::kLeftShoulder] - s[Joint::kRightShoulder];
  s.Set(Joint::kLeftElbow, s[Joint::kLeftShoulder] + 0.7 * left);
  lenient.min_sine = 0;
  EXPECT_EQ(LightSampleBin(s, BodyPart::kLeftUpperArm, on_arm, lenient), -1);
  // Shoulders at one point: no left direction.
  s = testing::StandingPerson(2.5, 0, false);
  s.Set(Joint::kRightShoulder, s[Joint::kLeftShoulder]);
  EXPECT_EQ(LightSampleBin(s, BodyPart::kUpperTorso, s[Joint::kTorso], lenient), -1);
}

TEST(LightSampleBin, ANonFinitePointGivesNoBin) {
  const Skeleton s = testing::StandingPerson(2.5, 0, false);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(LightSampleBin(s, BodyPart::kHead, Eigen::Vector3d(nan, 0, 2), kCoarseBins), -1);
  EXPECT_EQ(
      LightSampleBin(s, BodyPart::kHead,
                     Eigen::Vector3d(0, std::numeric_limits<double>::infinity(), 2), kCoarseBins),
      -1);
}

TEST(LightSampleBin, BinsAreFixedToTheBody) {
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> unit(-1, 1);
  const LightSampleBins bins;
  for (int trial = 0; trial < 20; ++trial) {
    const Skeleton s = testing::StandingPerson(2.5, Deg(18 * trial), trial % 2 == 0);
    const Eigen::Isometry3d b_from_a = Eigen::Translation3d(unit(rng), unit(rng), 3 * unit(rng)) *
                                       Eigen::AngleAxisd(kPi * unit(rng), RandomUnit(rng));
    const Skeleton moved = s.Transformed(b_from_a);
    for (int p = 0; p < kBodyPartCount; ++p) {
      const BodyPart part = static_cast<BodyPart>(p);
      const auto [ja, jb] = PartJoints(part);
      for (int i = 0; i < 20; ++i) {
        const Eigen::Vector3d x =
            s[ja] + (0.5 + 0.7 * unit(rng)) * (s[jb] - s[ja]) + 0.1 * RandomUnit(rng);
        EXPECT_EQ(LightSampleBin(moved, part, b_from_a * x, bins), LightSampleBin(s, part, x, bins))
            << trial << " " << PartName(part);
      }
    }
  }
}

TEST(LightSampleBin, BinsCheckRefusesEachBadField) {
  EXPECT_NO_THROW(LightSampleBins{}.Check());
  std::vector<LightSampleBins> bad(7);
  bad[0].axial_bins = 0;
  bad[1].angular_bins = 0;
  bad[2].min_sine = -0.1;
  bad[3].min_sine = 1;
  bad[4].min_sine = std::numeric_limits<double>::quiet_NaN();
  bad[5].axial_bins = 100000;  // 11 * 1e5 * 8e3 bins do not fit in an int
  bad[5].angular_bins = 8000;
  bad[6].angular_bins = -2;
  const Skeleton s = testing::StandingPerson(2.5, 0, false);
  for (size_t i = 0; i < bad.size(); ++i) {
    EXPECT_THROW(bad[i].Check(), CheckError) << i;
    EXPECT_THROW(LightSampleBin(s, BodyPart::kHead, s[Joint::kHead], bad[i]), CheckError) << i;
  }
}

// ---------------------------------------------------------------------------------------------
// AppendLightSamples

constexpr double kDepthScaleM = 0.001;  // the frames' depth: ImageDepthMm in millimetres

// A stored frame rendered from plain cylinders: depth and mask ray-cast (cylinder_raycast.h,
// millimetres), part labels of the posed model (visibility_maps.h), and per pixel the true
// surface point and outward normal of the labelled part's side where the labelled part's side is
// what the depth shows. Colour: albedo(true bin) * SubjectShade(world_from_sensor * n, light) in
// R, G, B scaled by 1.1, 1.0, 0.9 (grey = their mean); 255 (saturated, skipped) elsewhere.
struct SyntheticFrame {
  Skeleton skeleton;
  PinholeCamera camera = PinholeCamera::KinectLike();
  ImageRgb8 color;
  VisibilityMaps maps;
  Eigen::Matrix3d world_from_sensor = Eigen::Matrix3d::Identity();
  Image<uint8_t> has_truth;
  std::vector<Eigen::Vector3d> true_normal;  // sensor frame, per pixel
  std::vector<double> true_grey;             // albedo * shade before rounding, per pixel

  LightSampleFrame Frame() const {
    LightSampleFrame f;
    f.skeleton_in_sensor = &skeleton;
    f.camera = &camera;
    f.color = &color;
    f.part_labels = &maps.part_labels;
    f.depth_m = &maps.depth_m;
    f.world_from_sensor = world_from_sensor;
    return f;
  }
};

// Albedo in [60, 110) from the bin, scrambled.
double BinAlbedo(int bin) { return 60 + (bin * 37 + 11) % 50; }

SyntheticFrame RenderFrame(const Skeleton& skeleton, const Eigen::Matrix3d& world_from_sensor,
                           const Eigen::Vector3d& light_in_world) {
  SyntheticFrame f;
  f.skeleton = skeleton;
  f.world_from_sensor = world_from_sensor;
  const RadiusRatios ratios = DefaultRadiusRatios();
  const auto cylinders = PoseCylinders(skeleton, ratios);
  ImageDepthMm depth;
  ImageGray8 mask;
  testing::RayCastCylinders(cylinders, f.camera, depth, mask);
  f.maps = MakeVisibilityMaps(skeleton, ratios, f.camera, mask, depth, kDepthScaleM);
  const int w = f.camera.width, h = f.camera.height;
  f.color = ImageRgb8(w, h, 3, 255);
  f.has_truth = Image<uint8_t>(w, h, 1, 0);
  f.true_normal.assign(static_cast<size_t>(w) * h, Eigen::Vector3d::Zero());
  f.true_grey.assign(static_cast<size_t>(w) * h, 0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const int label = f.maps.part_labels.at(x, y);
      if (label == kBackgroundLabel || depth.at(x, y) == 0) continue;
      const BodyPart part = static_cast<BodyPart>(label - 1);
      const Cylinder& c = *cylinders[label - 1];
      // The ray's nearest hit of the part's side (as cylinder_raycast.h solves it).
      const Eigen::Vector3d d = f.camera.Unproject({double(x), double(y)}, 1.0).normalized();
      const Eigen::Vector3d u = (c.b - c.a).normalized();
      const Eigen::Vector3d ap = -c.a - (-c.a).dot(u) * u;
      const Eigen::Vector3d dp = d - d.dot(u) * u;
      const double qa = dp.squaredNorm(), qb = 2 * dp.dot(ap),
                   qc = ap.squaredNorm() - c.radius * c.radius;
      const double disc = qb * qb - 4 * qa * qc;
      if (disc < 0 || qa < 1e-12) continue;
      const double t = (-qb - std::sqrt(disc)) / (2 * qa);
      const Eigen::Vector3d point = t * d;
      const double along = (point - c.a).dot(u);
      if (!(t > 0) || along < 0 || along > c.Length()) continue;
      if (std::abs(point.z() - depth.at(x, y) * kDepthScaleM) > 0.001) continue;  // another surface
      const int bin = LightSampleBin(skeleton, part, point, kCoarseBins);
      if (bin < 0) continue;
      const Eigen::Vector3d n = ((point - c.a) - along * u).normalized();
      const double grey = BinAlbedo(bin) * SubjectShade(world_from_sensor * n, light_in_world);
      const size_t i = static_cast<size_t>(y) * w + x;
      f.has_truth.at(x, y) = 1;
      f.true_normal[i] = n;
      f.true_grey[i] = grey;
      const double scale[3] = {1.1, 1.0, 0.9};
      for (int ch = 0; ch < 3; ++ch)
        f.color.at(x, y, ch) = static_cast<uint8_t>(std::lround(grey * scale[ch]));
    }
  return f;
}

bool SameSample(const LightSample& a, const LightSample& b) {
  return a.bin == b.bin && a.value == b.value && a.normal_in_world == b.normal_in_world;
}

TEST(AppendLightSamples, SamplesCarryTheFramesNormalsColoursAndBins) {
  const Eigen::Matrix3d world_from_sensor =
      Eigen::AngleAxisd(Deg(25), Eigen::Vector3d(1, 2, -0.5).normalized()).toRotationMatrix();
  const Eigen::Vector3d light = 0.8 * Eigen::Vector3d(0.4, -0.7, -0.6).normalized();
  const SyntheticFrame f =
      RenderFrame(testing::StandingPerson(2.5, Deg(30), false), world_from_sensor, light);
  const LightSampleOptions options = CoarseOptions();
  std::vector<LightSample> all;
  AppendLightSamples(f.Frame(), options, &all);
  ASSERT_GT(all.size(), 1500u);

  // Pixel by pixel: labels cleared except the pixel and its four normal neighbours, so the
  // one sample (if any) is known to be this pixel's. Together they must be the whole frame's
  // samples in row-major order.
  const int k = options.normal_step;
  SyntheticFrame g = f;
  g.maps.part_labels = ImageLabel8(f.camera.width, f.camera.height, 1, kBackgroundLabel);
  std::vector<LightSample> stitched;
  std::vector<double> error_deg, error_deg_facing;
  int truth_pixels = 0;
  for (int y = 0; y < f.camera.height; y += options.stride)
    for (int x = 0; x < f.camera.width; x += options.stride) {
      const int label = f.maps.part_labels.at(x, y);
      if (label == kBackgroundLabel) continue;
      const int offsets[5][2] = {{0, 0}, {-k, 0}, {k, 0}, {0, -k}, {0, k}};
      for (const auto& o : offsets)
        if (f.camera.width > x + o[0] && x + o[0] >= 0 && f.camera.height > y + o[1] &&
            y + o[1] >= 0)
          g.maps.part_labels.at(x + o[0], y + o[1]) = f.maps.part_labels.at(x + o[0], y + o[1]);
      std::vector<LightSample> one;
      AppendLightSamples(g.Frame(), options, &one);
      for (const auto& o : offsets)
        if (f.camera.width > x + o[0] && x + o[0] >= 0 && f.camera.height > y + o[1] &&
            y + o[1] >= 0)
          g.maps.part_labels.at(x + o[0], y + o[1]) = kBackgroundLabel;
      ASSERT_LE(one.size(), 1u);
      const size_t i = static_cast<size_t>(y) * f.camera.width + x;
      const bool truth = f.has_truth.at(x, y) != 0;
      truth_pixels += truth;
      // Without truth the pixel is saturated (255) and must be skipped.
      if (!truth) {
        EXPECT_TRUE(one.empty()) << x << ", " << y;
        continue;
      }
      // With truth and all four neighbours on the same part's visible side within the jump
      // limit, a sample must come.
      bool neighbours = true;
      for (int n = 1; n < 5; ++n) {
        const int nx = x + offsets[n][0], ny = y + offsets[n][1];
        neighbours = neighbours && f.camera.width > nx && nx >= 0 && f.camera.height > ny &&
                     ny >= 0 && f.maps.part_labels.at(nx, ny) == label &&
                     f.has_truth.at(nx, ny) != 0 &&
                     std::abs(f.maps.depth_m.at(nx, ny) - f.maps.depth_m.at(x, y)) <=
                         options.max_depth_jump_m * k;
      }
      if (neighbours) {
        EXPECT_EQ(one.size(), 1u) << x << ", " << y;
      }
      if (one.empty()) continue;
      stitched.push_back(one[0]);
      const LightSample& s = one[0];
      // Value: the mean of the stored R, G, B (within rounding of the true grey).
      const double stored = (f.color.at(x, y, 0) + f.color.at(x, y, 1) + f.color.at(x, y, 2)) / 3.0;
      EXPECT_EQ(s.value, stored);
      EXPECT_NEAR(s.value, f.true_grey[i], 0.5);
      // Bin: that of the back-projected point.
      const Eigen::Vector3d point =
          f.camera.Unproject(Eigen::Vector2d(x, y), static_cast<double>(f.maps.depth_m.at(x, y)));
      EXPECT_EQ(s.bin,
                LightSampleBin(f.skeleton, static_cast<BodyPart>(label - 1), point, kCoarseBins));
      // Normal: unit, in the world frame.
      EXPECT_NEAR(s.normal_in_world.norm(), 1.0, 1e-9);
      const Eigen::Vector3d truth_world = world_from_sensor * f.true_normal[i];
      const double e = AngleDeg(s.normal_in_world, truth_world);
      error_deg.push_back(e);
      const Eigen::Vector3d to_camera = -point.normalized();
      if (f.true_normal[i].dot(to_camera) > 0.7) error_deg_facing.push_back(e);
    }
  ASSERT_EQ(stitched.size(), all.size());
  for (size_t i = 0; i < all.size(); ++i) EXPECT_TRUE(SameSample(stitched[i], all[i])) << i;
  EXPECT_GT(static_cast<double>(all.size()), 0.5 * truth_pixels);

  // Normal error. The depth is whole millimetres: at 2.5 m a pixel is 2.5 / 517 = 4.8 mm, the
  // central difference spans 2 normal steps = 19 mm, and the two depths' rounding (each
  // +-0.5 mm) tilts each tangent by at most atan(1 / 19) = 3 degrees, the normal by at most
  // sqrt(2) * 3 = 4.2 degrees. A further error comes from the curvature: pixel steps are not
  // equal steps on the circle; for a surface turned up to 45 degrees from the camera on the
  // thinnest part (forearm radius 47 mm, +-9.7 mm steps) it is below 1 degree. Nearer the
  // silhouette it grows (the steps reach the grazing side: 4.4 degrees at 44 degrees of slant
  // on the forearm, more beyond), so there only the median and the 95th percentile count.
  ASSERT_GT(error_deg_facing.size(), 500u);
  for (size_t i = 0; i < error_deg_facing.size(); ++i) EXPECT_LT(error_deg_facing[i], 5.2) << i;
  std::sort(error_deg.begin(), error_deg.end());
  EXPECT_LT(error_deg[error_deg.size() / 2], 2.0);
  EXPECT_LT(error_deg[error_deg.size() * 95 / 100], 12.0);
}

TEST(AppendLightSamples, TheLightOfATurningSubjectIsRecovered) {
  // 24 stored frames of a person turning through 360 degrees under a fixed light; the camera
  // tilted in the world.
  const Eigen::Matrix3d world_from_sensor =
      Eigen::AngleAxisd(Deg(-15), Eigen::Vector3d::UnitX()).toRotationMatrix();
  const Eigen::Vector3d light = 0.8 * Eigen::Vector3d(0.5, -0.6, -0.4).normalized();
  std::vector<LightSample> samples;
  for (int d = 0; d < 360; d += 15) {
    const SyntheticFrame f =
        RenderFrame(testing::StandingPerson(2.5, Deg(d), false), world_from_sensor, light);
    AppendLightSamples(f.Frame(), CoarseOptions(), &samples);
  }
  const SubjectLightFit fit = FitSubjectLight(samples);
  ASSERT_TRUE(fit.found) << fit.reason;
  // The subject turns about its vertical axis and its parts are vertical cylinders: their
  // normals are horizontal, so they measure the light's horizontal part only. The vertical
  // part shows only on the few surfaces that face up or down (the discs closing each cylinder,
  // the slightly sloped arms) and is weakly determined.
  // Horizontal part: the samples' normals err by about 1 degree in the median and up to about
  // 9 degrees near silhouettes (previous test); an error delta moves a sample's shade by at
  // most |L| sin(delta) = 0.8 sin 9 deg = 0.13 of the ambient, on the few grazing samples
  // only. 2 degrees and 5 % leave room for such a bias on a twentieth of the samples.
  // Vertical part: its sign and size within 0.2 (the discs are a few per cent of the samples).
  // The gain: 8-bit rounding (+-0.5) and a 1-degree normal error (85 * 0.8 * 0.017 = 1.2
  // levels) leave a residual of a few levels^2 per sample against a flat-light cost of about
  // 85^2 * 0.8^2 * var(max(0, n.l)) = 460, so above 0.9.
  const Eigen::Vector3d up = world_from_sensor * Eigen::Vector3d(0, -1, 0);
  const Eigen::Vector3d fit_across = fit.light - fit.light.dot(up) * up;
  const Eigen::Vector3d true_across = light - light.dot(up) * up;
  EXPECT_LT(AngleDeg(fit_across, true_across), 2.0);
  EXPECT_NEAR(fit_across.norm(), true_across.norm(), 0.05 * true_across.norm());
  EXPECT_NEAR(fit.light.dot(up), light.dot(up), 0.2);
  EXPECT_GT(fit.gain, 0.9);
  EXPECT_GT(fit.bins, 200);
}

// DepthNormalMap: every pixel's DepthNormal (the samples' normals, before the rotation to the
// world), zero elsewhere; against the true cylinder normals with the bounds of
// SamplesCarryTheFramesNormalsColoursAndBins (median 2 degrees: whole-millimetre depth).
TEST(DepthNormalMap, HoldsEachPixelsDepthNormalAndZeroWhereThereIsNone) {
  const SyntheticFrame f = RenderFrame(testing::StandingPerson(2.5, Deg(30), false),
                                       Eigen::Matrix3d::Identity(), Eigen::Vector3d::UnitX());
  const Image<float> normals = DepthNormalMap(f.maps.depth_m, f.maps.part_labels, f.camera);
  ASSERT_EQ(normals.channels, 3);
  ASSERT_EQ(normals.width, f.camera.width);
  ASSERT_EQ(normals.height, f.camera.height);
  int with_normal = 0, background = 0;
  std::vector<double> error_deg;
  for (int y = 0; y < f.camera.height; ++y)
    for (int x = 0; x < f.camera.width; ++x) {
      const Eigen::Vector3d n(normals.at(x, y, 0), normals.at(x, y, 1), normals.at(x, y, 2));
      const auto expected = DepthNormal(f.maps.depth_m, f.maps.part_labels, f.camera, x, y, {});
      if (!expected) {
        EXPECT_EQ(n, Eigen::Vector3d::Zero()) << x << ", " << y;
        background += f.maps.part_labels.at(x, y) == kBackgroundLabel;
        continue;
      }
      ++with_normal;
      EXPECT_LT((n - *expected).norm(), 1e-6) << x << ", " << y;
      EXPECT_NEAR(n.norm(), 1.0, 1e-6);
      if (f.has_truth.at(x, y))
        error_deg.push_back(
            AngleDeg(n, f.true_normal[static_cast<size_t>(y) * f.camera.width + x]));
    }
  EXPECT_GT(with_normal, 5000);
  EXPECT_GT(background, 100000);  // the background has none
  ASSERT_GT(error_deg.size(), 5000u);
  std::sort(error_deg.begin(), error_deg.end());
  EXPECT_LT(error_deg[error_deg.size() / 2], 2.0);
}

TEST(DepthNormalMap, RefusesMapsOfAnotherSizeAndBadOptions) {
  const SyntheticFrame f = RenderFrame(testing::StandingPerson(2.5, 0, false),
                                       Eigen::Matrix3d::Identity(), Eigen::Vector3d::UnitX());
  EXPECT_THROW(DepthNormalMap(Image<float>(10, 10, 1, 1.0f), f.maps.part_labels, f.camera),
               CheckError);
  EXPECT_THROW(DepthNormalMap(f.maps.depth_m, ImageLabel8(10, 10, 1, 1), f.camera), CheckError);
  LightSampleOptions bad;
  bad.normal_step = 0;
  EXPECT_THROW(DepthNormalMap(f.maps.depth_m, f.maps.part_labels, f.camera, bad), CheckError);
  // A pixel outside the image has no normal.
  EXPECT_FALSE(DepthNormal(f.maps.depth_m, f.maps.part_labels, f.camera, -1, 5, {}));
}

TEST(AppendLightSamples, AnInvalidFrameIsRefused) {
  const SyntheticFrame f = RenderFrame(testing::StandingPerson(2.5, 0, false),
                                       Eigen::Matrix3d::Identity(), Eigen::Vector3d::UnitX());
  std::vector<LightSample> samples;
  const LightSampleOptions options;
  EXPECT_NO_THROW(AppendLightSamples(f.Frame(), options, &samples));
  EXPECT_THROW(AppendLightSamples(f.Frame(), options, nullptr), CheckError);
  for (int i = 0; i < 5; ++i) {
    LightSampleFrame frame = f.Frame();
    if (i == 0) frame.skeleton_in_sensor = nullptr;
    if (i == 1) frame.camera = nullptr;
    if (i == 2) frame.color = nullptr;
    if (i == 3) frame.part_labels = nullptr;
    if (i == 4) frame.depth_m = nullptr;
    EXPECT_THROW(AppendLightSamples(frame, options, &samples), CheckError) << i;
  }
  const ImageRgb8 grey_color(f.camera.width, f.camera.height, 1, 100);
  const ImageRgb8 small_color(f.camera.width - 1, f.camera.height, 3, 100);
  const ImageLabel8 small_labels(f.camera.width, f.camera.height - 2, 1, 0);
  const ImageLabel8 rgb_labels(f.camera.width, f.camera.height, 3, 0);
  const Image<float> small_depth(f.camera.width / 2, f.camera.height / 2, 1, 0.f);
  LightSampleFrame frame = f.Frame();
  frame.color = &grey_color;
  EXPECT_THROW(AppendLightSamples(frame, options, &samples), CheckError);
  frame = f.Frame();
  frame.color = &small_color;
  EXPECT_THROW(AppendLightSamples(frame, options, &samples), CheckError);
  frame = f.Frame();
  frame.part_labels = &small_labels;
  EXPECT_THROW(AppendLightSamples(frame, options, &samples), CheckError);
  frame = f.Frame();
  frame.part_labels = &rgb_labels;
  EXPECT_THROW(AppendLightSamples(frame, options, &samples), CheckError);
  frame = f.Frame();
  frame.depth_m = &small_depth;
  EXPECT_THROW(AppendLightSamples(frame, options, &samples), CheckError);
  frame = f.Frame();
  frame.world_from_sensor = 1.1 * Eigen::Matrix3d::Identity();
  EXPECT_THROW(AppendLightSamples(frame, options, &samples), CheckError);
  frame.world_from_sensor = -Eigen::Matrix3d::Identity();  // a reflection
  EXPECT_THROW(AppendLightSamples(frame, options, &samples), CheckError);
  PinholeCamera bad_camera = f.camera;
  bad_camera.fx = 0;
  frame = f.Frame();
  frame.camera = &bad_camera;
  EXPECT_THROW(AppendLightSamples(frame, options, &samples), CheckError);
}

TEST(AppendLightSamples, OptionsCheckRefusesEachBadField) {
  EXPECT_NO_THROW(LightSampleOptions{}.Check());
  std::vector<LightSampleOptions> bad(9);
  bad[0].stride = 0;
  bad[1].normal_step = 0;
  bad[2].max_depth_jump_m = 0;
  bad[3].max_depth_jump_m = std::numeric_limits<double>::quiet_NaN();
  bad[4].max_depth_jump_m = std::numeric_limits<double>::infinity();
  bad[5].max_value = 0;
  bad[6].max_value = 256;
  bad[7].bins.axial_bins = 0;
  bad[8].bins.min_sine = 1;
  const SyntheticFrame f = RenderFrame(testing::StandingPerson(2.5, 0, false),
                                       Eigen::Matrix3d::Identity(), Eigen::Vector3d::UnitX());
  std::vector<LightSample> samples;
  for (size_t i = 0; i < bad.size(); ++i) {
    EXPECT_THROW(bad[i].Check(), CheckError) << i;
    EXPECT_THROW(AppendLightSamples(f.Frame(), bad[i], &samples), CheckError) << i;
  }
  EXPECT_TRUE(samples.empty());
}

}  // namespace
}  // namespace reenact
