#include "synthetic/depth_noise.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "common/error/check.h"
#include "synthetic/procedural.h"

namespace reenact::capture {

void DepthNoiseOptions::Check() const {
  REENACT_CHECK(std::isfinite(sigma_scale) && sigma_scale >= 0 && sigma_scale <= 10,
                "sigma_scale must lie in [0, 10]");
  REENACT_CHECK(
      std::isfinite(projector_baseline_m) && projector_baseline_m > 0 && projector_baseline_m <= 1,
      "projector_baseline_m must lie in (0, 1] m");
  REENACT_CHECK(std::isfinite(shadow_margin_px) && shadow_margin_px >= 0 && shadow_margin_px <= 10,
                "shadow_margin_px must lie in [0, 10]");
}

namespace {

void CheckInputs(const ImageDepthMm* depth_mm, const PinholeCamera& camera,
                 const DepthNoiseOptions& options) {
  REENACT_CHECK(depth_mm != nullptr && depth_mm->channels == 1, "need a one-channel depth image");
  REENACT_CHECK(depth_mm->width == camera.width && depth_mm->height == camera.height,
                "the depth image must have the camera's size");
  REENACT_CHECK(std::isfinite(camera.fx) && camera.fx > 0, "the camera needs fx > 0");
  options.Check();
}

}  // namespace

void ApplyProjectorShadow(ImageDepthMm* depth_mm, const PinholeCamera& camera,
                          const DepthNoiseOptions& options) {
  CheckInputs(depth_mm, camera, options);
  const double fb_mm = camera.fx * options.projector_baseline_m * 1000.0;  // px * mm
  std::vector<bool> shadowed(depth_mm->width);
  for (int y = 0; y < depth_mm->height; ++y) {
    // Right to left: min_p is the least p(v) = v - f b / z_v over the readings right of x.
    double min_p = std::numeric_limits<double>::infinity();
    for (int x = depth_mm->width - 1; x >= 0; --x) {
      const uint16_t d = depth_mm->at(x, y);
      shadowed[x] = false;
      if (d == 0) continue;
      const double p = x - fb_mm / d;
      shadowed[x] = min_p < p - options.shadow_margin_px;
      min_p = std::min(min_p, p);
    }
    for (int x = 0; x < depth_mm->width; ++x)
      if (shadowed[x]) depth_mm->at(x, y) = 0;
  }
}

void ApplyDepthNoise(ImageDepthMm* depth_mm, const PinholeCamera& camera, uint64_t seed,
                     const DepthNoiseOptions& options) {
  CheckInputs(depth_mm, camera, options);
  if (options.shadow_holes) ApplyProjectorShadow(depth_mm, camera, options);
  constexpr double kSigmaPerZ2 = 1.425e-3;
  constexpr double kDisparityConstant = 1.0 / 2.85e-3;
  Random rng(Mix64(seed));
  for (uint16_t& d : depth_mm->data) {
    if (d == 0) continue;
    double z = d * 1e-3;
    z += options.sigma_scale * kSigmaPerZ2 * z * z * rng.Normal();
    if (options.quantise && z > 0) z = kDisparityConstant / std::round(kDisparityConstant / z);
    const double mm = std::round(z * 1000.0);
    d = static_cast<uint16_t>(std::clamp(mm, 1.0, 65535.0));
  }
}

}  // namespace reenact::capture
