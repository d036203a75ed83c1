#include "tests/eval/side_by_side.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <opencv2/imgproc.hpp>

#include "common/error/check.h"
#include "tests/eval/image_metrics.h"

namespace reenact::eval {

void SideBySideOptions::Check() const {
  REENACT_CHECK(margin_px >= 0 && gap_px >= 0, "margin and gap must be >= 0");
  REENACT_CHECK(error_full_scale > 0 && error_full_scale <= 255,
                "error_full_scale must lie in (0, 255]");
}

ImageRgb8 SideBySide(const ImageRgb8& truth, const ImageGray8& truth_mask,
                     const ImageRgb8& rendered, const ImageGray8& rendered_mask,
                     const SideBySideOptions& options) {
  options.Check();
  const int w = truth.width, h = truth.height;
  REENACT_CHECK(!truth.empty() && truth.channels == 3 && rendered.channels == 3 &&
                    truth_mask.channels == 1 && rendered_mask.channels == 1,
                "side by side needs RGB images and single-channel masks");
  REENACT_CHECK(rendered.width == w && rendered.height == h && truth_mask.width == w &&
                    truth_mask.height == h && rendered_mask.width == w && rendered_mask.height == h,
                "side by side needs images of one size");
  PixelBox box = UnionBox(truth_mask, rendered_mask);
  if (box.empty()) box = {0, 0, w, h};
  const int x0 = std::max(0, box.x - options.margin_px);
  const int y0 = std::max(0, box.y - options.margin_px);
  const int x1 = std::min(w, box.x + box.width + options.margin_px);
  const int y1 = std::min(h, box.y + box.height + options.margin_px);
  const int bw = x1 - x0, bh = y1 - y0;

  // Error map 0..255 on the fixed scale, then coloured by inferno.
  cv::Mat error(bh, bw, CV_8UC1);
  for (int y = 0; y < bh; ++y)
    for (int x = 0; x < bw; ++x) {
      const bool t = truth_mask.at(x0 + x, y0 + y) > 127;
      const bool r = rendered_mask.at(x0 + x, y0 + y) > 127;
      int sum = 0;
      for (int c = 0; c < 3; ++c)
        sum += std::abs((t ? truth.at(x0 + x, y0 + y, c) : 0) -
                        (r ? rendered.at(x0 + x, y0 + y, c) : 0));
      const double scaled = sum / 3.0 / options.error_full_scale * 255.0;
      error.at<uint8_t>(y, x) = static_cast<uint8_t>(std::lround(std::min(255.0, scaled)));
    }
  cv::Mat heat_bgr;
  cv::applyColorMap(error, heat_bgr, cv::COLORMAP_INFERNO);

  ImageRgb8 out(3 * bw + 2 * options.gap_px, bh, 3, 128);
  const int rendered_x = bw + options.gap_px, error_x = 2 * (bw + options.gap_px);
  for (int y = 0; y < bh; ++y)
    for (int x = 0; x < bw; ++x) {
      const bool t = truth_mask.at(x0 + x, y0 + y) > 127;
      const bool r = rendered_mask.at(x0 + x, y0 + y) > 127;
      const cv::Vec3b heat = heat_bgr.at<cv::Vec3b>(y, x);
      for (int c = 0; c < 3; ++c) {
        out.at(x, y, c) = t ? truth.at(x0 + x, y0 + y, c) : 0;
        out.at(rendered_x + x, y, c) = r ? rendered.at(x0 + x, y0 + y, c) : 0;
        out.at(error_x + x, y, c) = heat[2 - c];
      }
    }
  return out;
}

}  // namespace reenact::eval
