#pragma once
// The part-label map of a stored frame (issue 9, occlusion-aware texturing): which body part
// of the posed cylinder model (cylinder_model.h) every crop pixel shows, for the visibility
// test of common/render/texturing.h.
//
// Per crop pixel (x, y), with the camera's intrinsics (distortion ignored, as the renderers
// do) and the ray r(t) = t ((x - cx) / fx, (y - cy) / fy, 1), t > 0 (so t is the depth z):
//   - background pixels (mask < 128): kBackgroundLabel;
//   - else the part of the nearest closed cylinder (side and both caps, exact, not
//     tessellated) the ray hits at depth t > 0, ties to the lower part index;
//   - else (a subject pixel no cylinder covers: the cylinders are rough, the silhouette
//     ragged) the part whose projected capsule is nearest in the image: the signed distance
//     |pixel - closest point of the projected axis| - rho, rho the projected radius
//     (fx radius / z) interpolated along the projected axis between its two ends; the axis
//     is first clipped to z >= kLabelMapNearZ (a part wholly behind the camera takes no
//     part), ties to the lower part index;
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
// 1-channel of the camera's size; every posed cylinder finite with radius > 0 (a
// zero-length axis is hit only through its degenerate caps: never, and never nearest).
ImageLabel8 RenderPartLabelMap(const std::array<std::optional<Cylinder>, kBodyPartCount>& cylinders,
                               const PinholeCamera& camera, const ImageGray8& mask);

// The map of a stored frame: PoseCylinders(skeleton_in_sensor, ratios, extensions) rendered
// into the crop camera (PinholeCamera::Cropped of the colour camera) over the crop's mask;
// extensions: the shape the frame is drawn with (all zeros: the thesis's cylinders).
ImageLabel8 PartLabelMapOfFrame(const Skeleton& skeleton_in_sensor, const RadiusRatios& ratios,
                                const PinholeCamera& crop_camera, const ImageGray8& mask,
                                const PartExtensions& extensions = {});

}  // namespace reenact
