#pragma once
// The GL renderer's draw list for the CPU reference renderer (common/render/reference_renderer.h):
// tests and evaluations that render one frame both ways (agreement, per-pixel provenance)
// convert it here, so a field added to CylinderDraw is carried over in one place.

#include <functional>
#include <vector>

#include "common/render/reference_renderer.h"
#include "viewer-client/render/renderer.h"

namespace reenact::viewer {

// The crop as the reference renderer samples it: colour, mask, camera and visibility maps.
ReferenceCrop ReferenceCropOf(const StoredTexture& texture);

// What stands behind a GL texture index: its reference crop (not null; must outlive the
// render) and the stored frame it came from.
struct ReferenceTexture {
  const ReferenceCrop* crop = nullptr;
  int stored_frame = -1;
};

// One reference part per cylinder, in order: the same axis, radius, shape, width direction,
// flat colour, body part, texturing mode and ranked candidates (texture indices resolved by
// `texture`); no candidates when frame.textured is false (bare cylinders).
std::vector<ReferencePart> ReferencePartsOf(
    const FrameDraw& frame, const std::function<ReferenceTexture(int texture)>& texture);

// The reference options that draw the frame's cylinders as the GL renderer does: its depth
// tolerance and subject light, the rest default.
ReferenceRenderOptions ReferenceOptionsOf(const FrameDraw& frame);

}  // namespace reenact::viewer
