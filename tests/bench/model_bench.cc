#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "common/model/model_building.h"
#include "tests/bench/bench_support.h"
#include "tests/bench/core_bench.h"
#include "tests/unit/common/cylinder_raycast.h"

namespace reenact::bench {
namespace {

// A person 2.5-3.5 m from the sensor, turning (yaw within +-0.8 rad), raising and lowering
// both arms (10 to 90 degrees from hanging) and stepping: frame n of a clip, sensor frame.
Skeleton ClipSkeleton(int n) {
  const double two_pi = 2 * std::numbers::pi;
  const double elevation =
      (10 + 80 * (0.5 - 0.5 * std::cos(two_pi * n / 200))) * std::numbers::pi / 180;
  const double yaw = 0.8 * std::sin(two_pi * n / 150);
  const double step = std::sin(two_pi * n / 40);
  const double distance = 3 + 0.5 * std::sin(two_pi * n / 300);
  const Eigen::Vector3d left_arm(std::sin(elevation), std::cos(elevation), 0);
  const Eigen::Vector3d right_arm(-std::sin(elevation), std::cos(elevation), 0);
  const Eigen::Vector3d l_shoulder(0.2, -0.5, 0), r_shoulder(-0.2, -0.5, 0);
  const Eigen::Vector3d local[kJointCount] = {
      {0, -0.75, 0},
      {0, -0.55, 0},
      {0, -0.3, 0},
      {0, 0, 0},
      l_shoulder,
      l_shoulder + 0.28 * left_arm,
      l_shoulder + 0.55 * left_arm,
      r_shoulder,
      r_shoulder + 0.28 * right_arm,
      r_shoulder + 0.55 * right_arm,
      {0.1, 0.05, 0},
      {0.11, 0.5, 0.1 * step},
      {0.12, 0.95, 0.2 * step},
      {-0.1, 0.05, 0},
      {-0.11, 0.5, -0.1 * step},
      {-0.12, 0.95, -0.2 * step},
  };
  const Eigen::Matrix3d rot = Eigen::AngleAxisd(yaw, -Eigen::Vector3d::UnitY()).toRotationMatrix();
  Skeleton s;
  for (int i = 0; i < kJointCount; ++i)
    s.Set(static_cast<Joint>(i), rot * local[i] + Eigen::Vector3d(0, 0, distance));
  return s;
}

// The true radius ratios: the defaults, each part made 20% thinner or thicker.
RadiusRatios TrueRatios() {
  RadiusRatios r = DefaultRadiusRatios();
  for (int p = 0; p < kBodyPartCount; ++p) r[p] *= (p % 2 ? 0.8 : 1.2);
  return r;
}

// Dilates the mask by `radius` pixels, the new pixels taking a neighbour's depth: a
// segmentation that bleeds into the background.
void Dilate(ModelFrameImages& im, int radius) {
  const ImageGray8 mask = im.mask;
  const ImageDepthMm depth = im.depth;
  int x0 = mask.width, y0 = mask.height, x1 = -1, y1 = -1;
  for (int y = 0; y < mask.height; ++y)
    for (int x = 0; x < mask.width; ++x)
      if (mask.at(x, y)) {
        x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
      }
  for (int y = std::max(0, y0 - radius); y <= std::min(mask.height - 1, y1 + radius); ++y)
    for (int x = std::max(0, x0 - radius); x <= std::min(mask.width - 1, x1 + radius); ++x) {
      if (mask.at(x, y)) continue;
      for (int dy = -radius; dy <= radius && !im.mask.at(x, y); ++dy)
        for (int dx = -radius; dx <= radius; ++dx)
          if (mask.Contains(x + dx, y + dy) && mask.at(x + dx, y + dy)) {
            im.mask.at(x, y) = 255;
            im.depth.at(x, y) = depth.at(x + dx, y + dy);
            break;
          }
    }
}

}  // namespace

// Model building (Eq. 2-4) over a synthetic clip: the true skeletons render exact cylinders
// (ray cast, truth known), the builder sees the skeletons with 2 cm tracker noise. Scenario
// "bad_masks_30pct": each frame's mask bleeds 5 pixels into the background with probability
// 0.3, drawn anew in each of 8 trials; its errors are means (max: the worst) over the trials.
// Timing covers scoring every frame and fitting k frames whose images sit decoded in memory
// (rendered once, before the timed runs), in the first trial.
void AddModelRows(proto::Report& report, const CoreBenchOptions& options) {
  const int frames = options.quick ? 120 : 600;
  const RadiusRatios truth = TrueRatios();
  const PinholeCamera camera = PinholeCamera::KinectLike();
  std::mt19937 rng(11);
  std::normal_distribution<double> noise(0.0, 0.02);
  std::vector<Skeleton> truth_skeletons, tracked;
  for (int n = 0; n < frames; ++n) {
    truth_skeletons.push_back(ClipSkeleton(n));
    Skeleton s = truth_skeletons.back();
    for (int j = 0; j < kJointCount; ++j)
      s.position[j] += Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
    tracked.push_back(s);
  }
  std::map<int, ModelFrameImages> clean;  // rendered frames, shared by every trial
  const auto render = [&](int n) -> const ModelFrameImages& {
    auto it = clean.find(n);
    if (it == clean.end()) {
      ModelFrameImages im{camera, {}, {}};
      testing::RayCastCylinders(PoseCylinders(truth_skeletons[n], truth), camera, im.depth,
                                im.mask);
      it = clean.emplace(n, std::move(im)).first;
    }
    return it->second;
  };

  for (const std::string scenario : {"clean", "bad_masks_30pct"}) {
    const int trials = scenario == "clean" ? 1 : (options.quick ? 3 : 8);
    for (int k : options.quick ? std::vector<int>{1, 3} : std::vector<int>{1, 3, 5, 9}) {
      ModelBuildOptions build;
      build.robust_k = k;
      double ms = 0, err_mean = 0, err_max = 0;
      int fitted_parts = kBodyPartCount;
      for (int trial = 0; trial < trials; ++trial) {
        std::mt19937 draw(100 + trial);
        std::bernoulli_distribution bleeds(scenario == "clean" ? 0.0 : 0.3);
        std::vector<bool> bad(frames);
        for (int n = 0; n < frames; ++n) bad[n] = bleeds(draw);
        std::map<int, ModelFrameImages> corrupted;
        const ModelFrameImagesFn images = [&](int n) -> std::optional<ModelFrameImages> {
          if (!bad[n]) return render(n);
          auto it = corrupted.find(n);
          if (it == corrupted.end()) {
            ModelFrameImages im = render(n);
            Dilate(im, 5);
            it = corrupted.emplace(n, std::move(im)).first;
          }
          return it->second;
        };
        ModelBuildResult result = BuildCylinderModel(tracked, images, build);  // fills caches
        if (trial == 0)
          ms = Median(TimeRepeated(options.repeats, 1000.0,
                                   [&] { result = BuildCylinderModel(tracked, images, build); }));
        fitted_parts = std::min(fitted_parts, result.fitted_count());
        for (int p = 0; p < kBodyPartCount; ++p) {
          const double err = 100 * std::abs(result.radius_ratio[p] - truth[p]) / truth[p];
          err_mean += err / (kBodyPartCount * trials);
          err_max = std::max(err_max, err);
        }
      }
      report.rows.push_back(
          proto::ReportRow{}
              .Add("op", "model_build")
              .Add("scenario", scenario)
              .Add("method", k == 1 ? std::string("single_frame") : "robust_k" + std::to_string(k))
              .Add("n", static_cast<long long>(frames))
              .Add("trials", static_cast<long long>(trials))
              .Add("ms_per_build", ms)
              .Add("fitted_parts", static_cast<long long>(fitted_parts))
              .Add("ratio_err_pct", err_mean)
              .Add("ratio_err_max_pct", err_max));
    }
  }
}

}  // namespace reenact::bench
