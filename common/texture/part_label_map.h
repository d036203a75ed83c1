#pragma once
// The part-label map of a stored frame (issue 9, occlusion-aware texturing): which body part
// of the posed cylinder model (cylinder_model.h) every crop pixel shows, for the visibility
// test of common/render/texturing.h.
//
// Per crop pixel (x, y), with the camera's intrinsics (distortion ignored, as the renderers
// do) and the ray r(t) = t ((x - cx) / fx, (y - cy) / fy, 1), t > 0 (so t is the depth z):
//   - background pixels (mask < 128): kBackgroundLabel;
//   - else the part whose surface the ray hits nearest, ties to the lower part index. A part
//     whose shape IsCylinder() (the thesis's) is the exact closed cylinder (side and both caps,
//     not tessellated; hit at any t > 0). A shaped part (radius rings, elliptic cross-section:
//     cylinder_model.h) is the tessellated shaped mesh the renderers draw
//     (common/render/cylinder_mesh.h, kDefaultCylinderSegments, ShapedUnitPosition placed by
//     ViewerFromUnitCylinder(cylinder)), rasterised with common/render/rasterizer.h (pixel
//     centres, top-left rule, clipped at z >= kLabelMapNearZ);
//   - else (a subject pixel no part covers: the model is rough, the silhouette ragged) the
//     part whose projected capsule is nearest in the image: the signed distance
//     |pixel - closest point of the projected axis| - rho, rho the projected radius
//     (fx radius / z) interpolated along the projected axis between its two ends; the axis
//     is first clipped to z >= kLabelMapNearZ (a part wholly behind the camera takes no
//     part), ties to the lower part index. For a shaped part rho is further scaled by the
//     largest semi-axis ratio max(width[k], depth[k]) of the rings, interpolated linearly in
//     the axis parameter t of the 3D axis point that projects to the closest point;
//   - kBackgroundLabel if no part is posed (no skeleton) or every part lies behind.
// Labels are PartLabel(part) (skeleton.h: part index + 1). Frames: the camera (sensor)
// frame of the stored frame, OpenCV, metres.

#include <array>
#include <optional>

#include "common/geometry/pinhole_camera.h"
#include "common/image/image.h"
#include "common/model/cylinder_model.h"
#include "common/skeleton/skeleton.h"

namespace reenact {

// Nearest depth, metres, of an axis end used for the projected-capsule fallback.
inline constexpr double kLabelMapNearZ = 1e-3;

// Cylinders indexed by Index(BodyPart) (PoseCylinders' output), in the camera's frame;
// unposed parts are nullopt. Preconditions (CHECK): camera passes Check(); mask is
// 1-channel of the camera's size; every posed cylinder finite with radius > 0, shape values
// finite and > 0 and a finite width direction if any (a zero-length axis is never hit, and
// never nearest).
ImageLabel8 RenderPartLabelMap(const std::array<std::optional<Cylinder>, kBodyPartCount>& cylinders,
                               const PinholeCamera& camera, const ImageGray8& mask);

// The map of a stored frame: PoseCylinders(skeleton_in_sensor, ratios, extensions, shapes)
// rendered into the crop camera (PinholeCamera::Cropped of the colour camera) over the crop's
// mask; extensions and shapes: the shape the frame is drawn with (defaults: the thesis's
// cylinders).
ImageLabel8 PartLabelMapOfFrame(const Skeleton& skeleton_in_sensor, const RadiusRatios& ratios,
                                const PinholeCamera& crop_camera, const ImageGray8& mask,
                                const PartExtensions& extensions = {},
                                const PartShapes& shapes = {});

}  // namespace reenact
