#include "tests/eval/part_provenance.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "common/error/check.h"

namespace reenact::eval {

double WrongShareOfSample(const SourceLabels& source, double u, double v, int expected_label) {
  REENACT_CHECK(source.crop_mask != nullptr && source.labels != nullptr,
                "source labels need a crop mask and a label image");
  const ImageGray8& mask = *source.crop_mask;
  REENACT_CHECK(!mask.empty() && std::isfinite(u) && std::isfinite(v),
                "sample must be finite and the crop not empty");
  const double fu = std::floor(u), fv = std::floor(v);
  const double tu = u - fu, tv = v - fv;
  const int x0 = static_cast<int>(fu), y0 = static_cast<int>(fv);
  double alpha = 0, wrong = 0;
  for (int dy = 0; dy < 2; ++dy) {
    const int y = std::clamp(y0 + dy, 0, mask.height - 1);
    const double wy = dy ? tv : 1 - tv;
    for (int dx = 0; dx < 2; ++dx) {
      const int x = std::clamp(x0 + dx, 0, mask.width - 1);
      const double weight = wy * (dx ? tu : 1 - tu);
      if (weight == 0 || mask.at(x, y) < 128) continue;
      alpha += weight;
      const int sx = x + source.crop_x, sy = y + source.crop_y;
      const int label =
          source.labels->Contains(sx, sy) ? source.labels->at(sx, sy) : kBackgroundLabel;
      if (label != expected_label) wrong += weight;
    }
  }
  return alpha > 0 ? wrong / alpha : 0.0;
}

PartProvenance MeasurePartProvenance(const ReferenceRender& render,
                                     std::span<const BodyPart> cylinder_parts,
                                     const std::function<SourceLabels(int frame)>& source,
                                     const ImageLabel8* seen_labels) {
  REENACT_CHECK(!seen_labels || (seen_labels->width == render.mask.width &&
                                 seen_labels->height == render.mask.height),
                "the seen labels must have the render's size");
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
      const int seen_at_pixel = seen_labels ? seen_labels->at(x, y) : kBackgroundLabel;
      const int seen = seen_at_pixel != kBackgroundLabel ? seen_at_pixel : drawn;
      for (int j = 0; j < render.source_frame.channels; ++j) {
        const int frame = render.source_frame.at(x, y, j);
        if (frame < 0) continue;
        const double share =
            render.source_weight.empty() ? (j == 0 ? 1.0 : 0.0) : render.source_weight.at(x, y, j);
        if (share <= 0) continue;
        const SourceLabels labels = source(frame);
        const double u = render.source_pixel.at(x, y, 2 * j);
        const double v = render.source_pixel.at(x, y, 2 * j + 1);
        const double wrong = WrongShareOfSample(labels, u, v, drawn);
        out.wrong_pixels += share * wrong;
        if (seen_labels)
          out.wrong_seen_pixels +=
              share * (seen == drawn ? wrong : WrongShareOfSample(labels, u, v, seen));
      }
    }
  return out;
}

}  // namespace reenact::eval
