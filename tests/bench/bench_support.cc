#include "tests/bench/bench_support.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "common/estimate/median.h"

namespace reenact::bench {

double Median(std::vector<double> samples) {
  return samples.empty() ? 0 : UpperMedian(std::move(samples));
}

std::vector<double> TimeRepeated(int repeats, double per, const std::function<void()>& body) {
  std::vector<double> us;
  for (int r = 0; r < repeats; ++r) {
    const auto t0 = Clock::now();
    body();
    us.push_back(std::chrono::duration<double, std::micro>(Clock::now() - t0).count() / per);
  }
  return us;
}

Skeleton RandomSkeleton(std::mt19937& rng) {
  std::uniform_real_distribution<double> yaw(-M_PI, M_PI), jitter(-0.05, 0.05), dist(2.0, 4.0);
  const Eigen::Vector3d base[kJointCount] = {
      {0, -0.75, 0},   {0, -0.55, 0},   {0, -0.3, 0},     {0, 0, 0},        {0.2, -0.5, 0},
      {0.45, -0.3, 0}, {0.6, -0.1, 0},  {-0.2, -0.5, 0},  {-0.45, -0.3, 0}, {-0.6, -0.1, 0},
      {0.1, 0.05, 0},  {0.11, 0.5, 0},  {0.12, 0.95, 0},  {-0.1, 0.05, 0},  {-0.11, 0.5, 0},
      {-0.12, 0.95, 0}};
  const Eigen::Matrix3d r =
      Eigen::AngleAxisd(yaw(rng), Eigen::Vector3d::UnitY()).toRotationMatrix();
  const double z = dist(rng);
  Skeleton s;
  for (int i = 0; i < kJointCount; ++i)
    s.Set(static_cast<Joint>(i), r * (base[i] + Eigen::Vector3d(jitter(rng), jitter(rng), jitter(rng))) +
                                     Eigen::Vector3d(0, 0, z));
  return s;
}

}  // namespace reenact::bench
