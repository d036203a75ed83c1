#pragma once
// Procedural clothing and skin of the synthetic subject, evaluated per pixel from a point
// in its segment's frame (body_model.h: x forward, y to the subject's left, z up in the
// rest pose; origin at the segment's proximal joint). Direction is visible everywhere:
// a face with eyes and mouth on the front of the head and hair behind; a shirt with
// horizontal stripes and a chest emblem on the left breast in front and a diamond check
// with a large number on the back; short sleeves and bare skin arms and hands, a watch on
// the left wrist; jeans with seams, back pockets, a belt with a front buckle and worn
// knees; shoes with white soles, laces and a side stripe.

#include "synthetic/body_model.h"
#include "synthetic/procedural.h"

namespace reenact::capture {

// Albedo (sRGB, [0, 1]) of a segment's surface at point_in_segment.
Color BodyAlbedo(Segment segment, const Eigen::Vector3d& point_in_segment);

}  // namespace reenact::capture
