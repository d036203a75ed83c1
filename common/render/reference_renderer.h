#pragma once
// CPU reference renderer of the posed, textured cylinder body model: the oracle the GL
// renderer (viewer-client/render/renderer.h) is tested against, and a renderer for
// evaluations that need to know where every pixel came from.
//
// It draws what the GL renderer's cylinder pass draws, rule for rule:
//   - Geometry: every part is the unit cylinder mesh of common/render/cylinder_mesh.h
//     (options.segments sides, the GL renderer's count by default), its vertices placed on
//     the part's shape (ShapedUnitPosition of cylinder.shape) and then by
//     ViewerFromUnitCylinder(cylinder) (axis, radius and width direction); clipped at near_z
//     and far_z (the GL near and far planes by default); a pixel shows the closest kept
//     fragment (depth test strictly closer, like GL_LESS); a discarded fragment writes
//     nothing, so what lies behind it shows through. Parts whose axis is shorter than
//     1e-12 m draw nothing. The viewer camera's distortion is ignored, as on the GPU.
//   - Texture mapping (thesis Eq. 16, p_n = Q Omega p*): the viewer-frame surface point p*
//     under the pixel centre is mapped by a candidate's stored_from_viewer (a 4x4, divided
//     by its w), then projected with the crop camera's intrinsics (distortion ignored):
//     (u, v) = (fx x / z + cx, fy y / z + cy), OpenCV pixel centres at integers.
//   - Sampling: the crop is premultiplied RGBA with the mask as alpha, alpha = 1 where
//     mask >= 128 else 0 (as uploaded to the GPU); sampled bilinearly at (u, v) between
//     the four nearest texel centres, clamped to the edge; the colour is the premultiplied
//     sample divided by its alpha. A candidate is unusable when z <= 0 (behind the stored
//     camera), when (u, v) lies outside [-0.5, width - 0.5] x [-0.5, height - 0.5] (outside
//     the crop), or when the sampled alpha is below 0.5 (off the stored subject).
//   - Candidates, visibility, relighting and the texturing modes: common/render/texturing.h
//     (the normal n of relighting is the interpolated vertex normal below, normalised). A
//     fragment that no candidate colours is discarded.
//   - Untextured parts (no crop) show their flat colour with the GL renderer's two-sided
//     Lambert shading, colour * (0.35 + 0.65 |n . e|), n the interpolated vertex normal
//     (cylinder_mesh.h's rule: ShapedUnitNormal through NormalFromUnitCylinder), normalised,
//     and e the unit direction from the surface point to the viewer.
//   - Colours in [0, 1] are written as round(255 c).
// Exact in double apart from the rasteriser's 1/256-pixel vertex snapping, whereas the GPU
// interpolates in float and filters with 8-bit weights: agreement is approximate along
// silhouette edges and to about one colour level inside.
//
// Frames and units: viewer camera frame (OpenCV: x right, y down, z forward, metres).

#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "common/geometry/pinhole_camera.h"
#include "common/image/image.h"
#include "common/model/cylinder_model.h"
#include "common/render/cylinder_mesh.h"
#include "common/render/texturing.h"
#include "common/skeleton/skeleton.h"
#include "common/texture/subject_light.h"

namespace reenact {

// One stored frame's subject crop (what proto's ClipFrame carries and the GL renderer uploads).
struct ReferenceCrop {
  ImageRgb8 color;       // channels 3, not empty
  ImageGray8 mask;       // channels 1, color's size; >= 128 = subject
  PinholeCamera camera;  // the crop's intrinsics (PinholeCamera::Cropped of the colour
                         // camera); its size is the crop's size
  // Visibility data (texturing.h; common/texture/visibility_maps.h makes both): the posed
  // cylinder model's part labels (PartLabel or kBackgroundLabel) and the stored depth in
  // metres (0 = no reading), each empty or of the crop's size, channels 1. Empty labels:
  // no point of this crop counts as visible; empty depth: test (b) always passes.
  ImageLabel8 part_labels;
  Image<float> depth_m;
  // Relighting (texturing.h): the stored surface's normals (crop camera frame, unit, zero where
  // unknown; DepthNormalMap), empty or of the crop's size, channels 3, finite.
  Image<float> normals;
};

// One texture candidate of a part (texturing.h).
struct ReferenceCandidate {
  // Non-owning, not null, must outlive the Render call.
  const ReferenceCrop* crop = nullptr;
  // The stored frame the texture comes from (reported per pixel in source_frame; any value
  // >= 0 the caller likes, typically the clip frame index).
  int stored_frame = 0;
  // Maps a viewer-frame point on this cylinder into the stored frame's sensor frame (thesis
  // Eq. 16; a similarity from StoredFromViewerMapping); finite.
  Eigen::Matrix4d stored_from_viewer = Eigen::Matrix4d::Identity();
  double weight = 1;  // finite, >= 0; used by kBlendVisible
  // The subject light as this stored frame saw it, viewer frame (relighting, texturing.h);
  // finite.
  Eigen::Vector3d stored_light = Eigen::Vector3d::Zero();
  // A fallback candidate (texturing.h): after every ranked one.
  bool fallback = false;
};

// One body-part cylinder to draw.
struct ReferencePart {
  // Axis a -> b, radius, shape and width direction, viewer frame, metres; finite, radius > 0,
  // shape values > 0.
  Cylinder cylinder;
  // Texture candidates, ranked then fallback ones, at most kMaxTextureCandidates; empty =
  // untextured (flat colour).
  std::vector<ReferenceCandidate> candidates;
  BodyPart part = BodyPart::kHead;  // the body part modelled (visibility test (a))
  TexturingMode texturing = TexturingMode::kFirst;
  Eigen::Vector3f color{0.7f, 0.7f, 0.7f};  // flat colour of an untextured part, [0, 1]
};

struct ReferenceRenderOptions {
  // Sides of each cylinder; >= 3. Default the GL renderer's.
  int segments = kDefaultCylinderSegments;
  // Near and far clipping planes, metres along z; 0 < near_z < far_z. Default the GL
  // renderer's (viewer-client/render/gl_projection.h: 0.05 and 50).
  double near_z = 0.05;
  double far_z = 50.0;
  // Colour of pixels no part covers, RGB in [0, 255]. Default black.
  Eigen::Vector3i clear_color = Eigen::Vector3i::Zero();
  // Visibility test (b) of texturing.h, metres; finite, >= 0.
  double depth_tolerance_m = kDefaultDepthToleranceM;
  // The subject light as the viewer sees it, viewer frame (relighting, texturing.h); finite.
  Eigen::Vector3d subject_light = Eigen::Vector3d::Zero();

  // Throws CheckError when a field is out of range.
  void Check() const;
};

// Per-pixel output. Provenance: the candidates whose colour a pixel shows, in rank order,
// at most kMaxTextureCandidates (channel j = the j-th contributor): one for kFirst and
// kFirstVisible, each visible candidate with a positive weight for kBlendVisible.
struct ReferenceRender {
  ImageRgb8 color;      // viewer camera size, channels 3
  ImageGray8 mask;      // 255 where a part's fragment was kept, else 0
  Image<int32_t> part;  // index into the parts list of the visible part, -1 where none
  // channels kMaxTextureCandidates: stored_frame of each contributor, -1 in unused channels
  // and where none or untextured (so channel 0 is -1 exactly where no stored frame
  // coloured the pixel).
  Image<int32_t> source_frame;
  // channels 2 kMaxTextureCandidates: contributor j's crop pixel (u, v) in channels 2j,
  // 2j + 1, OpenCV pixel centres at integers; (-1, -1) where source_frame is -1.
  Image<float> source_pixel;
  // channels kMaxTextureCandidates: contributor j's share of the colour (its weight
  // renormalised over the contributors; sums to 1 over a textured pixel), 0 where unused.
  Image<float> source_weight;
  Image<double> depth;  // viewer z of the shown surface, metres; +infinity where none
};

// Renders the parts for the viewer camera. Preconditions (CHECK, with a message naming the
// part): camera passes Check(); options pass Check(); every part has a finite axis, a finite
// positive radius, finite shape values > 0, a finite width direction if any, at most
// kMaxTextureCandidates candidates, each with a crop, stored_frame >= 0, a finite
// stored_from_viewer, a finite weight >= 0 and a finite stored_light, and every crop 3-channel
// non-empty colour, a 1-channel mask of the same size, a camera that passes Check() and has the
// crop's size, and part labels and depth each empty or 1-channel of the crop's size. An empty part
// list renders an all-clear image with an empty mask.
ReferenceRender RenderReference(const PinholeCamera& camera, std::span<const ReferencePart> parts,
                                const ReferenceRenderOptions& options = {});

}  // namespace reenact
