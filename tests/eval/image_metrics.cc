#include "tests/eval/image_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>

#include "common/error/check.h"

namespace reenact::eval {
namespace {

cv::Mat OnBlack(const ImageRgb8& colour, const ImageGray8& mask, const cv::Rect& box) {
  cv::Mat out(box.height, box.width, CV_8UC3, cv::Scalar::all(0));
  for (int y = 0; y < box.height; ++y)
    for (int x = 0; x < box.width; ++x)
      if (mask.at(box.x + x, box.y + y) > 127)
        for (int c = 0; c < 3; ++c) out.at<cv::Vec3b>(y, x)[c] = colour.at(box.x + x, box.y + y, c);
  return out;
}

double Ssim(const cv::Mat& a_rgb, const cv::Mat& b_rgb) {
  cv::Mat a, b;
  cv::cvtColor(a_rgb, a, cv::COLOR_RGB2GRAY);
  cv::cvtColor(b_rgb, b, cv::COLOR_RGB2GRAY);
  a.convertTo(a, CV_64F);
  b.convertTo(b, CV_64F);
  const double c1 = std::pow(0.01 * 255, 2), c2 = std::pow(0.03 * 255, 2);
  auto blur = [](const cv::Mat& m) {
    cv::Mat out;
    cv::GaussianBlur(m, out, cv::Size(11, 11), 1.5, 1.5, cv::BORDER_REFLECT);
    return out;
  };
  const cv::Mat mu_a = blur(a), mu_b = blur(b);
  const cv::Mat mu_a2 = mu_a.mul(mu_a), mu_b2 = mu_b.mul(mu_b), mu_ab = mu_a.mul(mu_b);
  const cv::Mat s_a = blur(a.mul(a)) - mu_a2, s_b = blur(b.mul(b)) - mu_b2,
                s_ab = blur(a.mul(b)) - mu_ab;
  cv::Mat num = (2 * mu_ab + c1).mul(2 * s_ab + c2);
  cv::Mat den = (mu_a2 + mu_b2 + c1).mul(s_a + s_b + c2);
  cv::Mat map;
  cv::divide(num, den, map);
  return cv::mean(map)[0];
}

}  // namespace

PixelBox UnionBox(const ImageGray8& mask_a, const ImageGray8& mask_b) {
  REENACT_CHECK(mask_a.width == mask_b.width && mask_a.height == mask_b.height,
                "masks must share one size");
  int x0 = mask_a.width, y0 = mask_a.height, x1 = -1, y1 = -1;
  for (int y = 0; y < mask_a.height; ++y)
    for (int x = 0; x < mask_a.width; ++x)
      if (mask_a.at(x, y) > 127 || mask_b.at(x, y) > 127)
        x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x), y1 = std::max(y1, y);
  if (x1 < 0) return {};
  return {x0, y0, x1 - x0 + 1, y1 - y0 + 1};
}

SubjectComparison CompareSubject(const ImageRgb8& rendered, const ImageGray8& rendered_mask,
                                 const ImageRgb8& truth, const ImageGray8& truth_mask) {
  REENACT_CHECK(rendered.width == truth.width && rendered.height == truth.height &&
                    rendered_mask.width == truth.width && truth_mask.width == truth.width &&
                    rendered_mask.height == truth.height && truth_mask.height == truth.height,
                "images must share one size");
  SubjectComparison out;
  int inter = 0;
  double abs_sum = 0;
  for (int y = 0; y < truth.height; ++y)
    for (int x = 0; x < truth.width; ++x) {
      const bool r = rendered_mask.at(x, y) > 127, t = truth_mask.at(x, y) > 127;
      if (!(r || t)) continue;
      ++out.union_pixels;
      if (r && t) {
        ++inter;
        for (int c = 0; c < 3; ++c) abs_sum += std::abs(rendered.at(x, y, c) - truth.at(x, y, c));
      }
    }
  if (out.union_pixels == 0) {
    out.iou = 1;
    out.ssim = 1;
    out.psnr_db = std::numeric_limits<double>::infinity();
    return out;
  }
  out.iou = static_cast<double>(inter) / out.union_pixels;
  out.colour_mae = inter ? abs_sum / (3.0 * inter) : 0;
  const PixelBox union_box = UnionBox(rendered_mask, truth_mask);
  const cv::Rect box(union_box.x, union_box.y, union_box.width, union_box.height);
  const cv::Mat a = OnBlack(rendered, rendered_mask, box), b = OnBlack(truth, truth_mask, box);
  cv::Mat diff;
  cv::absdiff(a, b, diff);
  diff.convertTo(diff, CV_64F);
  const cv::Scalar squared = cv::sum(diff.mul(diff));
  const double mean_sq = (squared[0] + squared[1] + squared[2]) / (3.0 * box.area());
  out.psnr_db = mean_sq > 0 ? 10 * std::log10(255.0 * 255.0 / mean_sq)
                            : std::numeric_limits<double>::infinity();
  out.ssim = Ssim(a, b);
  return out;
}

}  // namespace reenact::eval
