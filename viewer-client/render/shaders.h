#pragma once
// GLSL 330 core sources of the renderer's programs. All positions are in the viewer camera
// frame (OpenCV: x right, y down, z forward, metres); u_projection is
// GlProjectionFromPinhole of the viewer camera.

namespace reenact::viewer::shaders {

// Cylinder: a_position/a_normal of the unit cylinder (cylinder_mesh.h), placed by
// u_viewer_from_cylinder. Textured mode (u_textured != 0), per fragment at viewer-frame
// point p: p_s = u_stored_from_viewer p; u = fx x/z + cx, v = fy y/z + cy with
// u_intrinsics = (fx, fy, cx, cy); texture coordinate ((u + 0.5)/w, (v + 0.5)/h); discard
// if p_s.z <= 0, outside the crop, or the sampled mask (alpha) < 0.5; else the bilinear
// colour of the premultiplied RGBA texture divided by its alpha (so background texels do
// not bleed into the subject). Flat mode: Lambert shading of u_color under a headlight.
// Writes alpha 1: the renderer's subject mask.
extern const char* const kCylinderVertex;
extern const char* const kCylinderFragment;

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
