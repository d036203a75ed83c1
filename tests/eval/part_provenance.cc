#include "tests/eval/part_provenance.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <string>

#include "common/error/check.h"

namespace reenact::eval {
namespace {

// The alpha-1 texels of a bilinear sample at crop pixel (u, v): their source labels and
// bilinear weights.
struct SampledTexels {
  int count = 0;
  std::array<int, 4> label{};
  std::array<double, 4> weight{};
  double alpha = 0;  // sum of the weights
};

SampledTexels SampleTexels(const SourceLabels& source, double u, double v) {
  REENACT_CHECK(source.crop_mask != nullptr && source.labels != nullptr,
                "source labels need a crop mask and a label image");
  const ImageGray8& mask = *source.crop_mask;
  REENACT_CHECK(!mask.empty() && std::isfinite(u) && std::isfinite(v),
                "sample must be finite and the crop not empty");
  const double fu = std::floor(u), fv = std::floor(v);
  const double tu = u - fu, tv = v - fv;
  const int x0 = static_cast<int>(fu), y0 = static_cast<int>(fv);
  SampledTexels out;
  for (int dy = 0; dy < 2; ++dy) {
    const int y = std::clamp(y0 + dy, 0, mask.height - 1);
    const double wy = dy ? tv : 1 - tv;
    for (int dx = 0; dx < 2; ++dx) {
      const int x = std::clamp(x0 + dx, 0, mask.width - 1);
      const double weight = wy * (dx ? tu : 1 - tu);
      if (weight == 0 || mask.at(x, y) < 128) continue;
      const int sx = x + source.crop_x, sy = y + source.crop_y;
      out.label[out.count] =
          source.labels->Contains(sx, sy) ? source.labels->at(sx, sy) : kBackgroundLabel;
      out.weight[out.count++] = weight;
      out.alpha += weight;
    }
  }
  return out;
}

// Euclidean distance in pixels from every pixel to the nearest pixel labelled `label`,
// computed on first use per label; +infinity everywhere when no pixel has it.
class LabelDistances {
 public:
  explicit LabelDistances(const ImageLabel8& labels) : labels_(labels) {}

  float At(int label, int x, int y) {
    auto it = distances_.find(label);
    if (it == distances_.end()) it = distances_.emplace(label, Compute(label)).first;
    return it->second.at<float>(y, x);
  }

 private:
  cv::Mat Compute(int label) const {
    cv::Mat others(labels_.height, labels_.width, CV_8U);
    for (int y = 0; y < labels_.height; ++y)
      for (int x = 0; x < labels_.width; ++x)
        others.at<uint8_t>(y, x) = labels_.at(x, y) == label ? 0 : 255;
    if (cv::countNonZero(others) == others.rows * others.cols)
      return cv::Mat(others.size(), CV_32F, cv::Scalar(std::numeric_limits<float>::infinity()));
    cv::Mat distance;
    cv::distanceTransform(others, distance, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
    return distance;
  }

  const ImageLabel8& labels_;
  std::map<int, cv::Mat> distances_;
};

}  // namespace

double WrongShareOfSample(const SourceLabels& source, double u, double v, int expected_label) {
  const SampledTexels texels = SampleTexels(source, u, v);
  double wrong = 0;
  for (int i = 0; i < texels.count; ++i)
    if (texels.label[i] != expected_label) wrong += texels.weight[i];
  return texels.alpha > 0 ? wrong / texels.alpha : 0.0;
}

PartProvenance MeasurePartProvenance(const ReferenceRender& render,
                                     std::span<const BodyPart> cylinder_parts,
                                     const std::function<SourceLabels(int frame)>& source,
                                     const SeenParts* seen) {
  if (seen) {
    REENACT_CHECK(seen->labels && seen->labels->width == render.mask.width &&
                      seen->labels->height == render.mask.height,
                  "the seen labels must have the render's size");
    REENACT_CHECK(std::isfinite(seen->focal_px) && seen->focal_px > 0 &&
                      std::isfinite(seen->border_m) && seen->border_m >= 0,
                  "the doubled-limb rate needs a positive focal length and a border >= 0");
  }
  std::optional<LabelDistances> distances;
  if (seen) distances.emplace(*seen->labels);
  PartProvenance out;
  for (int y = 0; y < render.mask.height; ++y)
    for (int x = 0; x < render.mask.width; ++x) {
      if (render.mask.at(x, y) == 0) continue;
      ++out.subject_pixels;
      if (render.source_frame.at(x, y, 0) < 0) continue;
      ++out.textured_pixels;
      const int part = render.part.at(x, y);
      REENACT_CHECK(part >= 0 && static_cast<size_t>(part) < cylinder_parts.size(),
                    "render part index " + std::to_string(part) + " has no body part");
      const int drawn = PartLabel(cylinder_parts[part]);
      const int seen_at_pixel = seen ? seen->labels->at(x, y) : kBackgroundLabel;
      const int seen_part = seen_at_pixel != kBackgroundLabel ? seen_at_pixel : drawn;
      const double border_px = seen ? seen->focal_px * seen->border_m / render.depth.at(x, y) : 0;
      for (int j = 0; j < render.source_frame.channels; ++j) {
        const int frame = render.source_frame.at(x, y, j);
        if (frame < 0) continue;
        const double share =
            render.source_weight.empty() ? (j == 0 ? 1.0 : 0.0) : render.source_weight.at(x, y, j);
        if (share <= 0) continue;
        const SampledTexels texels =
            SampleTexels(source(frame), render.source_pixel.at(x, y, 2 * j),
                         render.source_pixel.at(x, y, 2 * j + 1));
        if (texels.alpha <= 0) continue;
        double wrong = 0, wrong_seen = 0, doubled = 0;
        for (int i = 0; i < texels.count; ++i) {
          const int label = texels.label[i];
          const double w = texels.weight[i];
          if (label != drawn) wrong += w;
          if (!seen || label == seen_part) continue;
          wrong_seen += w;
          if (label != kBackgroundLabel && distances->At(label, x, y) > border_px) doubled += w;
        }
        out.wrong_pixels += share * wrong / texels.alpha;
        const double seen_share = share * wrong_seen / texels.alpha;
        out.wrong_seen_pixels += seen_share;
        if (seen_at_pixel == drawn) out.wrong_texture_pixels += seen_share;
        out.doubled_limb_pixels += share * doubled / texels.alpha;
      }
    }
  return out;
}

}  // namespace reenact::eval
