#pragma once
// Shared pieces of the benchmarks: timing, medians, random test data.

#include <chrono>
#include <functional>
#include <random>
#include <vector>

#include "common/skeleton/skeleton.h"

namespace reenact::bench {

using Clock = std::chrono::steady_clock;

// Median of the samples (the upper median for an even count); 0 for none.
double Median(std::vector<double> samples);

// Runs `body` `repeats` times; each sample is its wall time in microseconds divided by
// `per` (the operations one run performs).
std::vector<double> TimeRepeated(int repeats, double per, const std::function<void()>& body);

// A standing person in a sensor frame (y down, z forward) with random yaw, distance
// 2-4 m and 5 cm joint jitter: plausible Eq. 5 query and stored skeletons.
Skeleton RandomSkeleton(std::mt19937& rng);

}  // namespace reenact::bench
