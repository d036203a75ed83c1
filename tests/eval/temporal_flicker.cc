#include "tests/eval/temporal_flicker.h"

#include <cstdlib>

#include "common/error/check.h"

namespace reenact::eval {

FlickerMeasure MeasureFlicker(const ImageRgb8& rendered_a, const ImageGray8& rendered_mask_a,
                              const ImageRgb8& rendered_b, const ImageGray8& rendered_mask_b,
                              const ImageRgb8& truth_a, const ImageGray8& truth_mask_a,
                              const ImageRgb8& truth_b, const ImageGray8& truth_mask_b) {
  const int w = truth_mask_a.width, h = truth_mask_a.height;
  for (const ImageGray8* m : {&rendered_mask_a, &rendered_mask_b, &truth_mask_a, &truth_mask_b})
    REENACT_CHECK(m->width == w && m->height == h && m->channels == 1, "masks differ in size");
  for (const ImageRgb8* c : {&rendered_a, &rendered_b, &truth_a, &truth_b})
    REENACT_CHECK(c->width == w && c->height == h && c->channels == 3,
                  "colour images must be RGB of the masks' size");
  double reenacted = 0, truth = 0, error = 0;
  int any_pixels = 0;
  FlickerMeasure out;
  for (size_t i = 0; i < static_cast<size_t>(w) * h; ++i) {
    const bool ra = rendered_mask_a.data[i] > 127, rb = rendered_mask_b.data[i] > 127;
    const bool ta = truth_mask_a.data[i] > 127, tb = truth_mask_b.data[i] > 127;
    if (!(ra || rb || ta || tb)) continue;
    ++any_pixels;
    out.truth_pixels += ta || tb;
    for (size_t c = 0; c < 3; ++c) {
      const int r0 = ra ? rendered_a.data[3 * i + c] : 0, r1 = rb ? rendered_b.data[3 * i + c] : 0;
      const int t0 = ta ? truth_a.data[3 * i + c] : 0, t1 = tb ? truth_b.data[3 * i + c] : 0;
      reenacted += std::abs(r1 - r0);
      truth += std::abs(t1 - t0);
      error += std::abs((r1 - t1) - (r0 - t0));
    }
  }
  const int normaliser = out.truth_pixels ? out.truth_pixels : any_pixels;
  if (normaliser) {
    out.reenacted_change = reenacted / (3.0 * normaliser);
    out.truth_change = truth / (3.0 * normaliser);
    out.error_change = error / (3.0 * normaliser);
  }
  return out;
}

}  // namespace reenact::eval
