#include "capture-client/synthetic/depth_noise.h"

#include <algorithm>
#include <cmath>

#include "capture-client/synthetic/procedural.h"
#include "common/error/check.h"

namespace reenact::capture {

void DepthNoiseOptions::Check() const {
  REENACT_CHECK(std::isfinite(sigma_scale) && sigma_scale >= 0 && sigma_scale <= 10,
                "sigma_scale must lie in [0, 10]");
}

void ApplyDepthNoise(ImageDepthMm* depth_mm, uint64_t seed, const DepthNoiseOptions& options) {
  REENACT_CHECK(depth_mm != nullptr && depth_mm->channels == 1, "need a one-channel depth image");
  options.Check();
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
