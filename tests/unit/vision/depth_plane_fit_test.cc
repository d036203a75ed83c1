#include "vision/features/depth_plane_fit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "common/error/check.h"

namespace reenact::vision {
namespace {

// A plane in inverse depth, w(u, v) = a + b u + c v (metres^-1), which is what any plane in
// space looks like to a pinhole camera.
struct InversePlane {
  double a, b, c;
  double W(double u, double v) const { return a + b * u + c * v; }
  double Z(double u, double v) const { return 1.0 / W(u, v); }
};

// Depth image of the plane at 0.1 mm steps (depth_scale_m = 1e-4), so rounding is far below
// what the tests bound.
constexpr double kFineScale = 1e-4;
ImageDepthMm Render(const InversePlane& plane, int width = 64, int height = 48) {
  ImageDepthMm d(width, height, 1, 0);
  for (int v = 0; v < height; ++v)
    for (int u = 0; u < width; ++u)
      d.at(u, v) = static_cast<uint16_t>(std::lround(plane.Z(u, v) / kFineScale));
  return d;
}

TEST(DepthPlaneFit, ExactSlantedPlaneAtSubPixelPosition) {
  // A floor-like slant: depth changes by about 4% per pixel row around (30, 20).
  const InversePlane plane{0.1, 0.0005, 0.004};
  const ImageDepthMm d = Render(plane);
  for (const auto& [x, y] : {std::pair{30.0, 20.0}, {30.4, 20.3}, {12.6, 30.5}}) {
    const auto z = FitDepthPlane(d, kFineScale, x, y);
    ASSERT_TRUE(z.has_value()) << x << "," << y;
    // Rounding to 0.1 mm is at most 5e-5 m per reading; the fit averages it further.
    EXPECT_NEAR(*z, plane.Z(x, y), 5e-5) << x << "," << y;
  }
}

TEST(DepthPlaneFit, AveragesKinectLikeNoiseDownByTheWindowSize) {
  // A wall about 5 m away with a Kinect v1's errors: Gaussian in inverse depth (sigma 1.425e-3
  // per metre, depth_noise.h) and the disparity rounding (steps of 2.85e-3 per metre), the
  // readings stored in millimetres. The least-squares intercept over n = 81 independent
  // readings has sigma / sqrt(81): 9 times less than one reading. Bound: 4 times.
  const InversePlane plane{0.2, 1e-5, -2e-5};
  std::mt19937_64 rng(3);
  std::normal_distribution<double> noise(0, 1.425e-3);
  constexpr double kStep = 2.85e-3;
  double single = 0, fitted = 0;
  int n = 0;
  for (int trial = 0; trial < 200; ++trial) {
    ImageDepthMm d(32, 32, 1, 0);
    for (int v = 0; v < 32; ++v) {
      for (int u = 0; u < 32; ++u) {
        const double w = std::round((plane.W(u, v) + noise(rng)) / kStep) * kStep;
        d.at(u, v) = static_cast<uint16_t>(std::lround(1000.0 / w));
      }
    }
    const double truth = plane.Z(16, 16);
    const auto z = FitDepthPlane(d, 0.001, 16, 16);
    ASSERT_TRUE(z.has_value());
    single += std::pow(d.at(16, 16) * 0.001 - truth, 2);
    fitted += std::pow(*z - truth, 2);
    ++n;
  }
  const double single_rms = std::sqrt(single / n), fitted_rms = std::sqrt(fitted / n);
  EXPECT_GT(single_rms, 0.03);  // the problem is real: several centimetres at 5 m
  EXPECT_LT(fitted_rms, single_rms / 4) << single_rms << " vs " << fitted_rms;
}

TEST(DepthPlaneFit, IgnoresAnotherSurfaceInTheWindow) {
  // The keypoint lies 3 px from a depth edge: columns u >= x + 3 show a surface at 1 m, the
  // rest a wall at 3 m. 6 of the window's 9 columns are on the wall (support 2/3 >= 0.6).
  const InversePlane wall{1.0 / 3.0, 0, 0};
  ImageDepthMm d = Render(wall);
  for (int v = 0; v < d.height; ++v)
    for (int u = 33; u < d.width; ++u)
      d.at(u, v) = static_cast<uint16_t>(std::lround(1.0 / kFineScale));
  const auto z = FitDepthPlane(d, kFineScale, 30, 20);
  ASSERT_TRUE(z.has_value());
  EXPECT_NEAR(*z, 3.0, 1e-4);
  // At the edge itself neither surface holds 60% of the window: no fit.
  EXPECT_FALSE(FitDepthPlane(d, kFineScale, 33, 20).has_value());
}

TEST(DepthPlaneFit, NoReadingsGiveNoFit) {
  const ImageDepthMm empty(64, 48, 1, 0);
  EXPECT_FALSE(FitDepthPlane(empty, 0.001, 30, 20).has_value());
}

TEST(DepthPlaneFit, ReadingsOnOneLineGiveNoFit) {
  // Only row 20 has readings: the slope across rows is undetermined (collinear samples).
  ImageDepthMm d(64, 48, 1, 0);
  for (int u = 0; u < 64; ++u) d.at(u, 20) = 2000;
  const auto z =
      FitDepthPlane(d, 0.001, 30, 20, {.radius_px = 4, .rel_tolerance = 0.03, .min_support = 0.1});
  EXPECT_FALSE(z.has_value());
}

TEST(DepthPlaneFit, KeypointOutsideOrNotFiniteGivesNoFit) {
  const ImageDepthMm d = Render({0.5, 0, 0});
  EXPECT_FALSE(FitDepthPlane(d, kFineScale, -20, -20).has_value());
  EXPECT_FALSE(
      FitDepthPlane(d, kFineScale, std::numeric_limits<double>::quiet_NaN(), 5).has_value());
  EXPECT_FALSE(
      FitDepthPlane(d, kFineScale, 5, std::numeric_limits<double>::infinity()).has_value());
  // At the image corner a quarter of the window exists: below min_support.
  EXPECT_FALSE(FitDepthPlane(d, kFineScale, 0, 0).has_value());
}

TEST(DepthPlaneFit, RejectsOptionsOutOfRange) {
  const ImageDepthMm d = Render({0.5, 0, 0});
  EXPECT_THROW(FitDepthPlane(d, kFineScale, 5, 5, {.radius_px = 0}), CheckError);
  EXPECT_THROW(FitDepthPlane(d, kFineScale, 5, 5, {.radius_px = 4, .rel_tolerance = 0}),
               CheckError);
  EXPECT_THROW(FitDepthPlane(d, kFineScale, 5, 5,
                             {.radius_px = 4, .rel_tolerance = 0.03, .min_support = 1.5}),
               CheckError);
  EXPECT_THROW(FitDepthPlane(d, 0.0, 5, 5), CheckError);
}

}  // namespace
}  // namespace reenact::vision
