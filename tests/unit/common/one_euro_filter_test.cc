#include "common/filter/one_euro_filter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "common/error/check.h"

namespace reenact {
namespace {

double Tau(double cutoff_hz) { return 1.0 / (2.0 * std::numbers::pi * cutoff_hz); }

TEST(OneEuroFilter, AlphaIsTheFirstOrderSmoothingFactor) {
  // alpha = dt / (dt + tau): a 1 Hz cutoff at 30 fps.
  const double dt = 1.0 / 30, tau = Tau(1.0);
  EXPECT_NEAR(OneEuroAlpha(1.0, dt), dt / (dt + tau), 1e-15);
  EXPECT_THROW(OneEuroAlpha(1.0, 0.0), CheckError);
  EXPECT_THROW(OneEuroAlpha(0.0, dt), CheckError);
}

TEST(OneEuroFilter, ConstantSignalPassesUnchanged) {
  OneEuroFilter3 filter({.min_cutoff_hz = 0.5, .beta = 3.0, .derivative_cutoff_hz = 1.0});
  const Eigen::Vector3d x(0.3, -1.2, 2.5);
  for (int n = 0; n < 100; ++n) EXPECT_EQ(filter.Filter(x, n / 30.0), x) << n;
}

TEST(OneEuroFilter, FirstSamplePassesAndZeroIntervalHoldsTheOutput) {
  OneEuroFilter3 filter({.min_cutoff_hz = 1.0, .beta = 0.0, .derivative_cutoff_hz = 1.0});
  EXPECT_EQ(filter.Filter(Eigen::Vector3d(1, 2, 3), 5.0), Eigen::Vector3d(1, 2, 3));
  const Eigen::Vector3d after = filter.Filter(Eigen::Vector3d(2, 2, 3), 5.1);
  // dt = 0 and dt < 0: the sample is ignored, the previous output returned.
  EXPECT_EQ(filter.Filter(Eigen::Vector3d(9, 9, 9), 5.1), after);
  EXPECT_EQ(filter.Filter(Eigen::Vector3d(9, 9, 9), 4.0), after);
  // After Reset the next sample passes unchanged again.
  filter.Reset();
  EXPECT_EQ(filter.Filter(Eigen::Vector3d(7, 8, 9), 6.0), Eigen::Vector3d(7, 8, 9));
}

TEST(OneEuroFilter, RejectsNonFiniteSamplesAndBadOptions) {
  OneEuroFilter3 filter;
  EXPECT_THROW(filter.Filter(Eigen::Vector3d(NAN, 0, 0), 0.0), CheckError);
  EXPECT_THROW(filter.Filter(Eigen::Vector3d::Zero(), INFINITY), CheckError);
  EXPECT_THROW(OneEuroFilter3({.min_cutoff_hz = 0.0}), CheckError);
  EXPECT_THROW(OneEuroFilter3({.min_cutoff_hz = 1.0, .beta = -1.0}), CheckError);
  EXPECT_THROW(OneEuroFilter3({.min_cutoff_hz = 1.0, .beta = 0.0, .derivative_cutoff_hz = 0.0}),
               CheckError);
}

TEST(OneEuroFilter, StepSettlesWithTheTimeConstantOfMinCutoff) {
  // beta = 0: an exponential smoother with tau = 1 / (2 pi f). At 1 kHz (dt << tau) the
  // remaining error after t = tau is e^-1 of the step, after 3 tau e^-3; exactly it is
  // (1 - alpha)^n.
  const double fc = 1.0, dt = 1e-3, tau = Tau(fc);
  OneEuroFilter3 filter({.min_cutoff_hz = fc, .beta = 0.0, .derivative_cutoff_hz = 1.0});
  filter.Filter(Eigen::Vector3d::Zero(), 0.0);
  const double alpha = OneEuroAlpha(fc, dt);
  for (int n = 1; n <= 3000; ++n) {
    const double y = filter.Filter(Eigen::Vector3d(1, 0, 0), n * dt).x();
    EXPECT_NEAR(1.0 - y, std::pow(1.0 - alpha, n), 1e-12) << n;
    const double t = n * dt;
    if (std::abs(t - tau) < dt / 2) {
      EXPECT_NEAR(1.0 - y, std::exp(-1.0), 0.005);
    }
    if (std::abs(t - 3 * tau) < dt / 2) {
      EXPECT_NEAR(1.0 - y, std::exp(-3.0), 0.002);
    }
  }
}

TEST(OneEuroFilter, RampLagsByTheSpeedTimesTheSpeedAdaptedTimeConstant) {
  // A ramp at v m/s: the derivative settles to v, the cutoff to f = min_cutoff + beta v, and
  // the lag of a first-order low-pass behind a ramp to v tau(f).
  const double v = 0.8, dt = 1.0 / 30;
  const OneEuroOptions options{.min_cutoff_hz = 1.0, .beta = 2.0, .derivative_cutoff_hz = 1.0};
  OneEuroFilter3 filter(options);
  double lag = 0;
  for (int n = 0; n < 600; ++n) {
    const double t = n * dt;
    lag = v * t - filter.Filter(Eigen::Vector3d(0, 0, v * t), t).z();
  }
  const double f = options.min_cutoff_hz + options.beta * v;
  EXPECT_NEAR(filter.cutoff_hz(), f, 1e-9);
  EXPECT_NEAR(lag, v * Tau(f), 1e-9);
  // Faster motion raises the cutoff and so lags less than a fixed 1 Hz filter would.
  EXPECT_LT(lag, v * Tau(options.min_cutoff_hz) / 2);
}

TEST(OneEuroFilter, NoiseOnAStaticSignalShrinksByTheCutoffsFactor) {
  // White noise of deviation sigma through y_n = y_{n-1} + alpha (x_n - y_{n-1}) leaves
  // deviation sigma sqrt(alpha / (2 - alpha)).
  const double sigma = 0.01, dt = 1.0 / 30, fc = 1.0;
  OneEuroFilter3 filter({.min_cutoff_hz = fc, .beta = 0.0, .derivative_cutoff_hz = 1.0});
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, sigma);
  const Eigen::Vector3d centre(0.1, 1.0, 3.0);
  double sum_sq = 0;
  int count = 0;
  for (int n = 0; n < 200000; ++n) {
    const Eigen::Vector3d y =
        filter.Filter(centre + Eigen::Vector3d(noise(rng), noise(rng), noise(rng)), n * dt);
    if (n < 300) continue;  // past the start-up
    sum_sq += (y - centre).squaredNorm() / 3;
    ++count;
  }
  const double alpha = OneEuroAlpha(fc, dt);
  EXPECT_NEAR(std::sqrt(sum_sq / count) / sigma, std::sqrt(alpha / (2 - alpha)), 0.01);
}

}  // namespace
}  // namespace reenact
