#pragma once
// Which of a body part's surface a stored frame can texture (issue 9, the fallback of
// occlusion-aware texturing): a coarse grid over the part's facing half, one bit per cell,
// set where the stored frame sees that surface point unoccluded by the rules of
// common/render/texturing.h.
//
// The texture mapping (texture_mapping.h) carries a viewer-frame surface point at height
// fraction t along the axis and angle theta around it, measured from the side facing the
// viewer, onto the stored cylinder's point at the same (theta, t) measured from the side
// facing the stored camera. So what a viewer sees of a part, its facing half theta in
// (-90, 90) degrees, lands on the stored facing half whatever the two poses, and a stored
// frame textures a cell of that half only where the stored frame sees it. The grid:
//   cell (i, j), i in [0, kCoverageAngles), j in [0, kCoverageHeights): bit i kCoverageHeights
//   + j, centred at theta_i = -90 + (i + 0.5) 180 / kCoverageAngles degrees and
//   t_j = (j + 0.5) / kCoverageHeights of the drawn axis (a -> b, past the end joint where
//   extended).
// The cell's point on the stored (shaped) surface, in the stored sensor frame:
//   P = a + t (b - a) + rho d,  d = cos(theta) f + sin(theta) (u x f),
// u the unit axis, f = FacingDirection(a, b), rho the distance from the axis to the shaped
// surface along d: the ellipse of semi-axes W(t) radius and D(t) radius along the cylinder's
// x_hat and y_hat (cylinder_mesh.h ViewerFromUnitCylinder), W and D linear in t between the
// rings, rho = radius / sqrt((d.x_hat / W)^2 + (d.y_hat / D)^2).
// The cell is covered when P, projected with the crop camera (distortion ignored, as the
// renderers do) to (u, v), lies in front of the camera and inside the crop, and at the nearest
// pixel the mask is >= 128, the part-label map holds PartLabel(part) and the stored depth is 0
// or within depth_tolerance_m of P's depth: the visibility of a fragment whose mapped point
// is P.

#include <array>
#include <cstdint>
#include <optional>

#include "common/geometry/pinhole_camera.h"
#include "common/image/image.h"
#include "common/model/cylinder_model.h"

namespace reenact {

inline constexpr int kCoverageAngles = 12;
inline constexpr int kCoverageHeights = 5;

// Bits of the cells, as above; every cell set is kFullCoverage.
using PartCoverage = uint64_t;
inline constexpr PartCoverage kFullCoverage =
    (PartCoverage{1} << (kCoverageAngles * kCoverageHeights)) - 1;

// Indexed by Index(BodyPart); a part that is not posed covers nothing.
using PartCoverages = std::array<PartCoverage, kBodyPartCount>;

// The coverage of every posed part of one stored frame. cylinders: PoseCylinders of the frame's
// skeleton in its sensor frame, with the shape its label map was drawn with; part_labels and
// depth_m: its visibility maps (visibility_maps.h; depth may be empty: the depth test
// passes). Preconditions (CHECK): camera passes Check(); mask and part_labels 1-channel of the
// camera's size; depth_m empty or 1-channel of that size; depth_tolerance_m finite and >= 0.
PartCoverages CoverageOfFrame(const std::array<std::optional<Cylinder>, kBodyPartCount>& cylinders,
                              const PinholeCamera& camera, const ImageGray8& mask,
                              const ImageLabel8& part_labels, const Image<float>& depth_m,
                              double depth_tolerance_m);

// The number of cells set.
int CoveredCells(PartCoverage coverage);

}  // namespace reenact
