#pragma once
// A Kinect v1-like depth error model (after Khoshelham and Elberink, 2012): axial Gaussian
// noise whose standard deviation grows with the square of the distance,
//   sigma(z) = sigma_scale * 1.425e-3 * z^2   (metres, z in metres),
// followed by the quantisation of the sensor's disparity: depth is rounded to
//   z_q = c / round(c / z),  c = 1 / 2.85e-3 m^-1 (steps of about 2.85 mm * z^2).
// Pixels with no reading (0) stay 0. Deterministic for a given seed.

#include <cstdint>

#include "common/image/image.h"

namespace reenact::capture {

struct DepthNoiseOptions {
  // Multiplier on the Gaussian sigma above, [0, 10]. Default 1 (Kinect-like); 0 keeps only
  // the quantisation.
  double sigma_scale = 1.0;
  // Disparity quantisation on or off. Default on.
  bool quantise = true;

  // Throws CheckError when a field is out of range.
  void Check() const;
};

// Adds noise in place to a depth image in millimetres.
void ApplyDepthNoise(ImageDepthMm* depth_mm, uint64_t seed, const DepthNoiseOptions& options = {});

}  // namespace reenact::capture
