#pragma once
// GLSL 330 core sources of the renderer's programs. All positions are in the viewer camera
// frame (OpenCV: x right, y down, z forward, metres); u_projection is
// GlProjectionFromPinhole of the viewer camera.

#include <string>

namespace reenact::viewer::shaders {

// Cylinder: a_position/a_normal of the unit cylinder (common/render/cylinder_mesh.h) with `rings`
// (kShapeRings) rings; the vertex program applies the part's shape and normal rules of
// cylinder_mesh.h (ShapedUnitPosition, ShapedUnitNormal): ring k = round(z (rings - 1)), the
// rings' widths and depths u_ring_width, u_ring_depth, the surface's nodes u_surface (ring k's
// node j at k max_angles + j, u_surface_angles of them, 0 for none; PartSurface::FactorAt) and
// the rounded ends' depths u_cap_depth; placed by u_viewer_from_cylinder, normals into the
// viewer frame by u_normal_from_cylinder (NormalFromUnitCylinder).
// The fragment program is built per variant by CylinderFragment: `candidates`
// (1..kMaxTextureCandidates) texture candidates, `visibility` off for TexturingMode::kFirst (one candidate, no visibility texture) and
// on for the visible modes (u_mode 1 kFirstVisible, 2 kBlendVisible), so that the thesis path pays
// nothing for the others (llvmpipe runs both sides of a branch). The rules are those of
// common/render/texturing.h; candidate i is given by u_stored_from_viewer[i], u_intrinsics[i] =
// (fx, fy, cx, cy), u_texture_size[i] = (w, h), u_weight[i], its premultiplied RGBA crop
// u_texture<i> (bilinear) and its visibility texture u_visibility<i> (RGBA32F: part label or -1,
// depth in metres, stored normal; texelFetch at the nearest texel). Per fragment at viewer-frame
// point p: p_s = u_stored_from_viewer[i] p; u = fx x/z + cx, v = fy y/z + cy; texture coordinate
// ((u + 0.5)/w, (v + 0.5)/h); unusable if p_s.z <= 0, outside the crop, or the sampled mask
// (alpha) < 0.5; else the colour is the sample divided by its alpha (so background texels do not
// bleed into the subject); visible if usable, the label equals u_part_label and the depth is 0 or
// within u_depth_tolerance of p_s.z. Candidates [0, u_ranked) are ranked, the rest fallbacks.
// The visible modes sample candidates in rank order and skip one that can no longer change the
// colour (a fallback wherever a ranked one is visible). No candidate colours it: discard. Flat mode
// (u_textured == 0): Lambert shading of u_color under a headlight. Writes alpha 1: the renderer's
// subject mask.
std::string CylinderVertex(int rings, int max_angles);
std::string CylinderFragment(int candidates, bool visibility);

// Floor: a quad with a_position (viewer frame) and a_plane (metres along two in-plane axes
// from the floor point); grid lines every u_spacing metres, anti-aliased with fwidth,
// fading out towards u_extent.
extern const char* const kFloorVertex;
extern const char* const kFloorFragment;

// Background: a full-screen triangle (no vertex buffer) showing u_image with texelFetch,
// output row r = GL row (u_height - 1 - r).
extern const char* const kBackgroundVertex;
extern const char* const kBackgroundFragment;

// Lines and points of the skeleton overlay in u_color; points are u_point_size pixels.
extern const char* const kOverlayVertex;
extern const char* const kOverlayFragment;

}  // namespace reenact::viewer::shaders
