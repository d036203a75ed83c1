#pragma once
// Generic RANSAC (Fischler and Bolles 1981) with an adaptive number of trials and optional
// local optimisation (LO-RANSAC, Chum et al. 2003): used for PnP, 3D-3D alignment
// (common/align/umeyama_estimator.h) and line/plane fits.
//
// Each trial draws kMinSampleSize distinct samples, asks the estimator for the models they
// determine (zero for a degenerate draw, several for minimal solvers like P3P) and counts the
// inliers of each: samples whose residual is <= max_error. The best model has the most
// inliers, ties going to the smaller sum of inlier residuals, then to the earlier one. After
// each improvement the number of trials needed to draw one all-inlier sample with
// probability `confidence` is
//   N = log(1 - confidence) / log(1 - w^m),  w = inlier ratio, m = kMinSampleSize,
// clamped to [min_iterations, max_iterations]. Deterministic for a seed: the generator is
// std::mt19937_64 and indices are drawn by a fixed rule (no distribution objects, whose
// output differs between standard libraries).

#include <algorithm>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <random>
#include <vector>

#include "common/error/check.h"

namespace reenact {

// An estimator: a Sample type (one datum), a Model type (default-constructible, copyable),
// the minimal sample size, a solver and a residual function. Estimate must accept any number >=
// kMinSampleSize of samples (least squares beyond the minimum) when local optimisation is on.
template <typename E>
concept RansacEstimator = requires(const E& e, const std::vector<typename E::Sample>& samples,
                                   const typename E::Model& model) {
  typename E::Sample;
  typename E::Model;
  requires std::default_initializable<typename E::Model>;
  requires std::copy_constructible<typename E::Model>;
  { E::kMinSampleSize } -> std::convertible_to<int>;
  { e.Estimate(samples) } -> std::convertible_to<std::vector<typename E::Model>>;
  { e.Residuals(model, samples) } -> std::convertible_to<std::vector<double>>;
};

struct RansacOptions {
  // A sample is an inlier when its residual is <= max_error (the estimator's residual
  // units, e.g. pixels or metres); > 0 and finite.
  double max_error = 1.0;
  // Probability of drawing at least one all-inlier sample; in (0, 1). Default 0.99.
  double confidence = 0.99;
  // Trials: at least min_iterations, at most max_iterations; 0 <= min <= max, max >= 1.
  int min_iterations = 0;
  int max_iterations = 10000;
  // Seed of the random generator; the same seed and input give the same result.
  uint64_t seed = 0;
  // Rounds of local optimisation after each improvement: re-estimate from all inliers and
  // keep the result while it gains inliers; 0 turns it off. >= 0. Default 0.
  int local_optimization_rounds = 0;
  // Re-estimate the final model from all its inliers (kept only if it does not lose
  // inliers). Default false.
  bool final_refit = false;

  void Check() const {
    REENACT_CHECK(std::isfinite(max_error) && max_error > 0, "max_error must be > 0");
    REENACT_CHECK(confidence > 0 && confidence < 1, "confidence must be in (0, 1)");
    REENACT_CHECK(min_iterations >= 0 && max_iterations >= 1 && min_iterations <= max_iterations,
                  "need 0 <= min_iterations <= max_iterations, max_iterations >= 1");
    REENACT_CHECK(local_optimization_rounds >= 0, "local_optimization_rounds must be >= 0");
  }
};

template <typename Model>
struct RansacResult {
  bool success = false;         // a model with at least kMinSampleSize inliers was found
  Model model{};                // the best model (meaningful when success)
  std::vector<size_t> inliers;  // indices into the data, ascending
  int num_trials = 0;           // samples drawn
  double inlier_ratio = 0;      // inliers / data size
};

// Trials needed (see the header comment), clamped to [min_iterations, max_iterations].
inline int RansacRequiredTrials(double inlier_ratio, int sample_size,
                                const RansacOptions& options) {
  const double all_inliers = std::pow(inlier_ratio, sample_size);
  double n;
  if (!(all_inliers > 0)) {
    n = options.max_iterations;
  } else if (all_inliers >= 1) {
    n = 0;
  } else {
    n = std::ceil(std::log(1 - options.confidence) / std::log1p(-all_inliers));
  }
  if (!(n <= options.max_iterations)) n = options.max_iterations;
  return std::max(options.min_iterations, static_cast<int>(n));
}

namespace ransac_internal {

template <typename Model>
struct Scored {
  Model model;
  std::vector<size_t> inliers;
  double residual_sum = 0;
};

template <RansacEstimator E>
Scored<typename E::Model> Score(const E& estimator, const typename E::Model& model,
                                const std::vector<typename E::Sample>& data, double max_error) {
  Scored<typename E::Model> s{model, {}, 0};
  const std::vector<double> residuals = estimator.Residuals(model, data);
  REENACT_CHECK(residuals.size() == data.size(), "Residuals must return one value per sample");
  for (size_t i = 0; i < residuals.size(); ++i) {
    if (residuals[i] <= max_error) {  // false for NaN
      s.inliers.push_back(i);
      s.residual_sum += residuals[i];
    }
  }
  return s;
}

template <typename Model>
bool Better(const Scored<Model>& a, const std::optional<Scored<Model>>& best) {
  if (!best) return true;
  if (a.inliers.size() != best->inliers.size()) return a.inliers.size() > best->inliers.size();
  return a.residual_sum < best->residual_sum;
}

template <RansacEstimator E>
std::optional<Scored<typename E::Model>> Refit(const E& estimator,
                                               const Scored<typename E::Model>& from,
                                               const std::vector<typename E::Sample>& data,
                                               double max_error) {
  std::vector<typename E::Sample> subset;
  subset.reserve(from.inliers.size());
  for (size_t i : from.inliers) subset.push_back(data[i]);
  std::optional<Scored<typename E::Model>> best;
  for (const auto& model : estimator.Estimate(subset)) {
    auto s = Score(estimator, model, data, max_error);
    if (s.inliers.size() >= from.inliers.size() && Better(s, best)) best = std::move(s);
  }
  return best;
}

}  // namespace ransac_internal

// Runs RANSAC over `data`. Precondition (CHECK): valid options. Fewer samples than
// kMinSampleSize, or no model with that many inliers, gives success = false.
template <RansacEstimator E>
RansacResult<typename E::Model> Ransac(const E& estimator,
                                       const std::vector<typename E::Sample>& data,
                                       const RansacOptions& options) {
  using Model = typename E::Model;
  using ransac_internal::Better;
  using ransac_internal::Scored;
  options.Check();
  constexpr int m = E::kMinSampleSize;
  static_assert(m >= 1, "kMinSampleSize must be >= 1");
  RansacResult<Model> result;
  const size_t n = data.size();
  if (n < static_cast<size_t>(m)) return result;

  std::mt19937_64 rng(options.seed);
  std::optional<Scored<Model>> best;
  int needed = options.max_iterations;
  std::vector<size_t> picked;
  std::vector<typename E::Sample> sample;
  while (result.num_trials < needed) {
    ++result.num_trials;
    picked.clear();
    while (picked.size() < static_cast<size_t>(m)) {  // distinct indices by rejection
      const size_t index = static_cast<size_t>(rng() % n);
      bool seen = false;
      for (size_t p : picked) seen = seen || p == index;
      if (!seen) picked.push_back(index);
    }
    sample.clear();
    for (size_t p : picked) sample.push_back(data[p]);
    bool improved = false;
    for (const Model& model : estimator.Estimate(sample)) {
      auto scored = ransac_internal::Score(estimator, model, data, options.max_error);
      if (Better(scored, best)) {
        best = std::move(scored);
        improved = true;
      }
    }
    if (!improved || best->inliers.size() < static_cast<size_t>(m)) continue;
    for (int round = 0; round < options.local_optimization_rounds; ++round) {
      auto refined = ransac_internal::Refit(estimator, *best, data, options.max_error);
      if (!refined || refined->inliers.size() <= best->inliers.size()) break;
      best = std::move(refined);
    }
    needed = RansacRequiredTrials(static_cast<double>(best->inliers.size()) / n, m, options);
  }
  if (!best || best->inliers.size() < static_cast<size_t>(m)) return result;
  if (options.final_refit) {
    auto refined = ransac_internal::Refit(estimator, *best, data, options.max_error);
    if (refined) best = std::move(refined);
  }
  result.success = true;
  result.model = std::move(best->model);
  result.inliers = std::move(best->inliers);
  result.inlier_ratio = static_cast<double>(result.inliers.size()) / n;
  return result;
}

}  // namespace reenact
