#pragma once
// What the renderers need to test a stored frame's visibility (common/render/texturing.h):
// the crop's part-label map (part_label_map.h) and its depth in metres.

#include "common/geometry/pinhole_camera.h"
#include "common/image/image.h"
#include "common/model/cylinder_model.h"
#include "common/skeleton/skeleton.h"

namespace reenact {

struct VisibilityMaps {
  ImageLabel8 part_labels;  // PartLabel or kBackgroundLabel, the crop's size
  Image<float> depth_m;     // metres, 0 = no reading, the crop's size
};

// Depth units times depth_scale_m, as float metres (0 stays 0). Precondition (CHECK):
// depth_scale_m finite and > 0; depth 1 channel (may be empty: empty result).
Image<float> DepthInMetres(const ImageDepthMm& depth, double depth_scale_m);

// Both maps of a stored frame: its skeleton in its sensor frame, the clip's radius ratios (and
// part extensions and shapes: the shape the parts are drawn with, defaults the thesis's
// cylinders), the crop's camera, mask and depth (registered to colour, depth units of
// depth_scale_m).
// Preconditions (CHECK): those of PartLabelMapOfFrame and DepthInMetres; depth empty or of
// the mask's size (empty depth: empty depth_m, the depth test then always passes).
VisibilityMaps MakeVisibilityMaps(const Skeleton& skeleton_in_sensor, const RadiusRatios& ratios,
                                  const PinholeCamera& crop_camera, const ImageGray8& mask,
                                  const ImageDepthMm& depth, double depth_scale_m,
                                  const PartExtensions& extensions = {},
                                  const PartShapes& shapes = {});

}  // namespace reenact
