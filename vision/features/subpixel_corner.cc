#include "vision/features/subpixel_corner.h"

#include <cmath>
#include <limits>

#include "common/error/check.h"

namespace reenact::vision {

void SubpixelCornerOptions::Check() const {
  REENACT_CHECK(max_iterations >= 1 && max_iterations <= 100, "max_iterations in [1, 100]");
  REENACT_CHECK(std::isfinite(epsilon_px) && epsilon_px > 0, "epsilon_px must be > 0");
}

SubpixelCornerRefiner::SubpixelCornerRefiner(const SubpixelCornerOptions& options)
    : options_(options) {
  options_.Check();
}

const std::vector<float>& SubpixelCornerRefiner::Weights(int h) const {
  if (static_cast<int>(weights_.size()) <= h) weights_.resize(h + 1);
  std::vector<float>& w = weights_[h];
  if (w.empty()) {
    const int side = 2 * h + 1;
    std::vector<float> axis(side);
    for (int i = 0; i < side; ++i) {
      const float t = static_cast<float>(i - h) / static_cast<float>(h);
      axis[i] = std::exp(-t * t);
    }
    w.resize(static_cast<size_t>(side) * side);
    for (int i = 0; i < side; ++i)
      for (int j = 0; j < side; ++j) w[static_cast<size_t>(i) * side + j] = axis[i] * axis[j];
  }
  return w;
}

std::optional<Eigen::Vector2f> SubpixelCornerRefiner::Refine(const cv::Mat& gray,
                                                             const Eigen::Vector2f& start,
                                                             int h) const {
  REENACT_CHECK(gray.type() == CV_8UC1, "gray must be CV_8UC1");
  REENACT_CHECK(h >= 1 && h <= 64, "half_window must be in [1, 64]");
  if (!std::isfinite(start.x()) || !std::isfinite(start.y())) return std::nullopt;
  const std::vector<float>& weights = Weights(h);
  const int side = 2 * h + 1, padded = side + 2;
  samples_.resize(static_cast<size_t>(padded) * padded);
  const float eps2 = static_cast<float>(options_.epsilon_px * options_.epsilon_px);
  Eigen::Vector2f q = start;
  for (int iteration = 0; iteration < options_.max_iterations; ++iteration) {
    // Samples at q + (j - h - 1, i - h - 1), j, i in [0, padded), interpolated bilinearly
    // from the four pixels around each: all share the fractional offset of q.
    const float fx = std::floor(q.x()), fy = std::floor(q.y());
    const int x0 = static_cast<int>(fx) - h - 1, y0 = static_cast<int>(fy) - h - 1;
    if (x0 < 0 || y0 < 0 || x0 + padded >= gray.cols || y0 + padded >= gray.rows) {
      return std::nullopt;
    }
    const float ax = q.x() - fx, ay = q.y() - fy;
    const float w00 = (1 - ax) * (1 - ay), w01 = ax * (1 - ay), w10 = (1 - ax) * ay, w11 = ax * ay;
    for (int i = 0; i < padded; ++i) {
      const uint8_t* r0 = gray.ptr<uint8_t>(y0 + i) + x0;
      const uint8_t* r1 = gray.ptr<uint8_t>(y0 + i + 1) + x0;
      float* out = &samples_[static_cast<size_t>(i) * padded];
      for (int j = 0; j < padded; ++j) {
        out[j] = w00 * r0[j] + w01 * r0[j + 1] + w10 * r1[j] + w11 * r1[j + 1];
      }
    }
    double a = 0, b = 0, c = 0, bb1 = 0, bb2 = 0;
    for (int i = 0; i < side; ++i) {
      const float* row = &samples_[static_cast<size_t>(i + 1) * padded + 1];
      const float* wrow = &weights[static_cast<size_t>(i) * side];
      const float py = static_cast<float>(i - h);
      float ra = 0, rb = 0, rc = 0, rb1 = 0, rb2 = 0;
      for (int j = 0; j < side; ++j) {
        const float gx = row[j + 1] - row[j - 1];
        const float gy = row[j + padded] - row[j - padded];
        const float m = wrow[j], px = static_cast<float>(j - h);
        const float gxx = gx * gx * m, gxy = gx * gy * m, gyy = gy * gy * m;
        ra += gxx;
        rb += gxy;
        rc += gyy;
        rb1 += gxx * px + gxy * py;
        rb2 += gxy * px + gyy * py;
      }
      a += ra;
      b += rb;
      c += rc;
      bb1 += rb1;
      bb2 += rb2;
    }
    const double det = a * c - b * b;
    // Singular (flat window or a straight edge): relative to the gradients' own scale.
    if (!(det > 1e-9 * (a * c)) || !(a > 0)) return std::nullopt;
    const Eigen::Vector2f step(static_cast<float>((c * bb1 - b * bb2) / det),
                               static_cast<float>((a * bb2 - b * bb1) / det));
    q += step;
    if (!std::isfinite(q.x()) || !std::isfinite(q.y())) return std::nullopt;
    if (step.squaredNorm() <= eps2) break;
  }
  if (std::abs(q.x() - start.x()) > h || std::abs(q.y() - start.y()) > h) return std::nullopt;
  return q;
}

}  // namespace reenact::vision
