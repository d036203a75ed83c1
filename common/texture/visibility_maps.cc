#include "common/texture/visibility_maps.h"

#include <cmath>

#include "common/error/check.h"
#include "common/texture/part_label_map.h"

namespace reenact {

Image<float> DepthInMetres(const ImageDepthMm& depth, double depth_scale_m) {
  REENACT_CHECK(std::isfinite(depth_scale_m) && depth_scale_m > 0,
                "depth_scale_m must be finite and positive");
  if (depth.empty()) return {};
  REENACT_CHECK(depth.channels == 1, "depth must be single-channel");
  Image<float> out(depth.width, depth.height, 1, 0.0f);
  for (size_t i = 0; i < depth.data.size(); ++i)
    out.data[i] = static_cast<float>(depth.data[i] * depth_scale_m);
  return out;
}

VisibilityMaps MakeVisibilityMaps(const Skeleton& skeleton_in_sensor, const RadiusRatios& ratios,
                                  const PinholeCamera& crop_camera, const ImageGray8& mask,
                                  const ImageDepthMm& depth, double depth_scale_m,
                                  const PartExtensions& extensions, const PartShapes& shapes) {
  REENACT_CHECK(depth.empty() || (depth.width == mask.width && depth.height == mask.height),
                "depth must be empty or of the mask's size");
  return {PartLabelMapOfFrame(skeleton_in_sensor, ratios, crop_camera, mask, extensions, shapes),
          DepthInMetres(depth, depth_scale_m)};
}

}  // namespace reenact
