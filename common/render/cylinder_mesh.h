#pragma once
// The tessellated unit cylinder that every renderer of the cylinder body model draws, so that
// the GL renderer (viewer-client/render/renderer.h) and the CPU reference renderer
// (common/render/reference_renderer.h) rasterise the very same triangles.
//
// The cylinder has radius 1 and runs along +z from z = 0 to z = 1 in its own frame. It is
// closed: a side made of `segments` flat quads (two triangles each) and two capping fans.
// Side vertices carry radial normals (x, y, 0), cap vertices the cap normal (0, 0, -1) at
// z = 0 and (0, 0, +1) at z = 1, so sides and caps do not share vertices. Every triangle is
// wound counter-clockwise seen from outside, in a right-handed frame.
//
// Triangle order: triangles [0, 2 * segments) are the side (quad i is triangles 2i, 2i + 1,
// between ring angles 2 pi i / segments and 2 pi (i + 1) / segments), then segments
// triangles of the z = 0 cap, then segments triangles of the z = 1 cap.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

namespace reenact {

// Segments the renderers use for every body part.
inline constexpr int kDefaultCylinderSegments = 32;

struct CylinderMesh {
  std::vector<Eigen::Vector3f> positions;  // cylinder frame, unit radius and length
  std::vector<Eigen::Vector3f> normals;    // unit, one per position
  std::vector<uint32_t> indices;           // triangle list, three per triangle
};

// Builds the closed unit cylinder with `segments` sides. Precondition (CHECK): segments >= 3.
// Sizes: 4 * segments + 2 vertices, 4 * segments triangles.
CylinderMesh MakeUnitCylinderMesh(int segments);

// viewer_from_cylinder: the affine map (bottom row 0 0 0 1) that places the unit cylinder on
// the axis a -> b with the given radius: cylinder z = 0 at a, z = 1 at b, and the cylinder's
// x, y axes scaled by radius onto an orthonormal pair perpendicular to the axis,
//   z_hat = (b - a) / |b - a|, x_hat = normalise(z_hat x h), y_hat = z_hat x x_hat,
// with helper h = unit x unless |z_hat.x| >= 0.9, then unit y. The choice of x_hat fixes
// where the tessellation's vertices lie around the axis, so both renderers must use this.
// Precondition: a, b finite and |b - a| > 0 (a zero-length axis yields non-finite entries).
Eigen::Matrix4d ViewerFromUnitCylinder(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                       double radius);

}  // namespace reenact
