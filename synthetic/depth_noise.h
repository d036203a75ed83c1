#pragma once
// A Kinect v1-like depth error model, applied to a rendered depth image in millimetres:
//
// 1. Projector shadow (holes at silhouettes). A Kinect v1 triangulates with an IR projector
//    that sits projector_baseline_m (7.5 cm) beside its IR camera, on the camera's +x side
//    (the image's right; seen from the front of the device the projector is on the viewer's
//    left). A surface point the projector cannot light has no reading. In image space, with
//    the camera at the origin (OpenCV frame: x right, y down, z forward) and the projector
//    at (b, 0, 0), the projector ray to the point seen at pixel column u with depth z_u
//    passes, at depth z, over the pixel column
//      u(z) = u + f b (1/z - 1/z_u)          (f = fx in pixels, same row),
//    i.e. it runs from u towards the projector's side (+u). The point is shadowed when a
//    surface the camera sees at a column v > u on that row lies in front of the ray there:
//      v - u < f b (1/z_v - 1/z_u)   <=>   p(v) < p(u),   p(w) = w - f b / z_w,
//    so only nearer surfaces within the disparity difference f b (1/z_near - 1/z_far) pixels
//    on the projector's side can shadow, and pixel u is shadowed when min over v > u of p(v)
//    is below p(u) by more than shadow_margin_px (a margin against the millimetre steps of
//    the input). Behind a foreground edge at column e (the first foreground pixel) with
//    depths z_near in front of z_far, the background columns (e - D, e) with
//    D = f b (1/z_near - 1/z_far) become holes: a strip about D pixels wide on the side of
//    the foreground away from the projector (its left in the image), none on its right.
//    Pixels without a reading (0) neither block nor change. The test uses the surfaces the
//    camera sees (a surface hidden from the camera casts no shadow here), one row at a time
//    (the baseline is horizontal).
// 2. Axial noise (after Khoshelham and Elberink, 2012): Gaussian, standard deviation growing
//    with the square of the distance,
//      sigma(z) = sigma_scale * 1.425e-3 * z^2   (metres, z in metres),
// 3. then the quantisation of the sensor's disparity: depth is rounded to
//      z_q = c / round(c / z),  c = 1 / 2.85e-3 m^-1 (steps of about 2.85 mm * z^2).
// Pixels with no reading (0) stay 0. Deterministic for a given seed.

#include <cstdint>

#include "common/geometry/pinhole_camera.h"
#include "common/image/image.h"

namespace reenact::capture {

struct DepthNoiseOptions {
  // Multiplier on the Gaussian sigma above, [0, 10]. Default 1 (Kinect-like); 0 keeps only
  // the quantisation.
  double sigma_scale = 1.0;
  // Disparity quantisation on or off. Default on.
  bool quantise = true;
  // Projector shadow holes on or off. Default off: with them on, the person segmenter's
  // test (segment_person_test.cc, noise on) takes background next to the subject's left
  // silhouette for the subject; turn on once segmentation handles them.
  bool shadow_holes = false;
  // Projector to camera distance along the camera's +x axis, metres, in (0, 1]. Default
  // 0.075 (Kinect v1).
  double projector_baseline_m = 0.075;
  // How far (pixels, [0, 10]) a surface must reach past a projector ray to shadow. Default
  // 0.25: 1 mm of depth moves f b / z at most 0.25 px for z >= 0.4 m (f b = 39 px m).
  double shadow_margin_px = 0.25;

  // Throws CheckError when a field is out of range.
  void Check() const;
};

// Sets the readings that the projector cannot light to 0 (step 1 above), in place. The
// image is the depth of `camera` (same size; fx > 0); a depth image in millimetres.
// Throws CheckError on a size mismatch, a non-positive fx or options that fail Check().
void ApplyProjectorShadow(ImageDepthMm* depth_mm, const PinholeCamera& camera,
                          const DepthNoiseOptions& options = {});

// Applies the model in place (shadow holes when options.shadow_holes, then noise and
// quantisation) to a depth image in millimetres seen by `camera`. Throws CheckError as
// ApplyProjectorShadow does.
void ApplyDepthNoise(ImageDepthMm* depth_mm, const PinholeCamera& camera, uint64_t seed,
                     const DepthNoiseOptions& options = {});

}  // namespace reenact::capture
