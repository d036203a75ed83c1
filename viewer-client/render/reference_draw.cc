#include "viewer-client/render/reference_draw.h"

namespace reenact::viewer {

ReferenceCrop ReferenceCropOf(const StoredTexture& t) {
  return ReferenceCrop{t.color, t.mask, t.camera, t.part_labels, t.depth_m, t.normals};
}

std::vector<ReferencePart> ReferencePartsOf(
    const FrameDraw& frame, const std::function<ReferenceTexture(int texture)>& texture) {
  std::vector<ReferencePart> parts;
  parts.reserve(frame.cylinders.size());
  for (const CylinderDraw& c : frame.cylinders) {
    ReferencePart part;
    part.cylinder = Cylinder{c.a, c.b, c.radius, c.shape, c.width_direction};
    part.color = c.color;
    part.part = c.part;
    part.texturing = c.texturing;
    if (frame.textured)
      for (const TextureCandidate& t : c.candidates) {
        const ReferenceTexture source = texture(t.texture);
        part.candidates.push_back({source.crop, source.stored_frame, t.stored_from_viewer, t.weight,
                                   t.stored_light, t.fallback});
      }
    parts.push_back(std::move(part));
  }
  return parts;
}

ReferenceRenderOptions ReferenceOptionsOf(const FrameDraw& frame) {
  ReferenceRenderOptions options;
  options.depth_tolerance_m = frame.depth_tolerance_m;
  options.subject_light = frame.subject_light;
  return options;
}

}  // namespace reenact::viewer
