#pragma once
// Hole filling of the person mask (person_segmenter.h, step 4). Masks: 255 = person, 0 = not.
// `box`: the mask's bounding box (every set pixel inside it). Callbacks take pixel (x, y);
// depth_m gives metres, 0 without a reading.

#include <functional>

#include "capture-client/segment/pixel_rect.h"
#include "capture-client/segment/segment_options.h"
#include "common/image/image.h"

namespace reenact::capture {

// Depth holes: every run of pixels without a reading along an image row, at most max_run_px
// long and with a reading at both ends, belongs to the surface at its farther end: it joins
// the mask when that end pixel is in the mask. Why the farther end: a structured-light
// sensor's holes at silhouettes are the projector's shadow, which falls on the surface
// behind the occluding edge (a Kinect v1's projector sits beside its camera along the image
// rows); so the shadow of an arm on the torso joins the mask, the shadow beside the body on
// the wall does not, and a hole with the person at both ends (dark hair, a shiny belt) joins.
// Returns pixels added.
int FillDepthHoles(const std::function<double(int, int)>& depth_m, int max_run_px,
                   const PixelRect& box, ImageGray8* mask);

// Enclosed regions: background regions (4-connected) that the mask encloses (that reach
// neither the edge of the box grown by one pixel nor the image border) join the mask when at
// least person_ratio of their pixels have a reading at the person's depth: not farther than
// z_b + step(z_b), z_b the median depth of the mask pixels bordering the region, and not on
// the floor (is_floor(x, y, z)). A view through a gap between limbs (background readings or
// no readings) stays out. Returns pixels added.
int FillEnclosedHoles(const std::function<double(int, int)>& depth_m,
                      const std::function<bool(int, int, double)>& is_floor,
                      const DepthTolerance& step, double person_ratio, const PixelRect& box,
                      ImageGray8* mask);

}  // namespace reenact::capture
