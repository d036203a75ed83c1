#pragma once
// The tessellated unit cylinder that every renderer of the cylinder body model draws, so that
// the GL renderer (viewer-client/render/renderer.h), the CPU reference renderer
// (common/render/reference_renderer.h) and the part-label map of a shaped part
// (common/texture/part_label_map.h) rasterise the very same triangles.
//
// The unit cylinder has radius 1 and runs along +z from z = 0 to z = 1 in its own frame. It
// is closed: a side of kShapeRings rings (cylinder_model.h) at z_k = k / (kShapeRings - 1),
// each of `segments` vertices at angles 2 pi i / segments, joined by kShapeRings - 1 bands of
// `segments` quads (two triangles each), and two caps, each a pole and kCapRings rings of
// `segments` vertices at radii CapRingRadius(m), m = 1 .. kCapRings (the last the rim, radius
// 1), a fan from the pole and kCapRings - 1 bands. Side vertices carry radial normals
// (x, y, 0), cap vertices the cap normal (0, 0, -1) at z = 0 and (0, 0, +1) at z = 1, so
// sides and caps do not share vertices. Every triangle is wound counter-clockwise seen from
// outside, in a right-handed frame. Every side vertex lies exactly on a ring: z == z_k in float.
//
// Vertex order: side vertex i of ring k is k * segments + i; then the z = 0 cap's pole and
// its rings (ring m's vertex i at pole + 1 + (m - 1) segments + i), then the z = 1 cap's.
// Sizes: (kShapeRings + 2 kCapRings) segments + 2 vertices, 2 (kShapeRings - 1) segments
// side triangles and (2 kCapRings - 1) segments per cap.
// Triangle order: band k (between rings k and k + 1), quad i (between angles i and i + 1) is
// triangles 2 (k segments + i) and 2 (k segments + i) + 1, for k in [0, kShapeRings - 1);
// then the z = 0 cap's triangles, then the z = 1 cap's.
//
// Shaped drawing (a PartShape, cylinder_model.h): a vertex (x, y, z) on ring k is placed at
// the shaped unit point s (width[k] x, depth[k] y, z) before ViewerFromUnitCylinder, s the
// surface factor at the vertex (PartSurface::FactorAt(k, atan2(y, x)); 1 without a surface or
// at a cap's centre); so ring k is an ellipse with semi-axes width[k] and depth[k] (times the
// radius) along the frame's x and y axes, scaled by the height map around it, each band is
// linear in z between two rings, and each cap's rim follows its end ring. A cap vertex at
// radius rho from the axis moves outwards along the axis by cap_depth[cap] sqrt(1 - rho^2)
// (PartShape::cap_depth; a half ellipsoid over the end ring, a rounded end; 0: the flat cap).
// A plain cylinder (all ones, no surface, flat caps) draws the unit mesh unchanged.
//
// Normals (the rule both renderers use for the untextured Lambert shading):
//   - cap vertices: the cap normal (0, 0, -+1) on a flat cap; on a rounded one the normal of
//     the half ellipsoid, (x / (S W), y / (S D), -+sqrt(1 - rho^2) / cap_depth) at the mesh
//     vertex (x, y) (S the surface factor, W and D the end ring's);
//   - side vertex at angle (c, s) = (cos, sin) on ring k: the normal of the smooth surface
//     (W(z) c, D(z) s, z) whose ring slopes are W'_k, D'_k (RingSlope: central differences,
//     one-sided at the end rings), i.e. n = (D_k c, W_k s, -(W_k D'_k s^2 + D_k W'_k c^2))
//     in the unit frame (W = width, D = depth); (c, s, 0) for a plain cylinder;
//   - with a surface, the normal of P(phi, z) = (S W c, S D s, z), S the surface factor:
//     P_phi x P_z with P_phi = (S' W c - S W s, S' D s + S D c, 0) and
//     P_z = ((S W)'_k c, (S D)'_k s, 1), S' the central difference of FactorAt over half a
//     node spacing (pi / angles) to either side, (S W)'_k and (S D)'_k RingSlope of the ring
//     values at the vertex's angle (which reduces to the rule above where S is 1);
//   - into the viewer frame with NormalFromUnitCylinder (the inverse transpose of the linear
//     part of viewer_from_cylinder), and interpolated over triangles unnormalised like every
//     attribute; the shading normalises the interpolated normal.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "common/model/cylinder_model.h"

namespace reenact {

// Segments the renderers use for every body part.
inline constexpr int kDefaultCylinderSegments = 32;

// Rings of each cap (see above), and the radius of ring m in [0, kCapRings]: 0 at the pole,
// sin(pi m / (2 kCapRings)) (even steps of latitude on a rounded end), exactly 1 at the rim.
inline constexpr int kCapRings = 4;
double CapRingRadius(int m);

struct CylinderMesh {
  std::vector<Eigen::Vector3f> positions;  // cylinder frame, unit radius and length
  std::vector<Eigen::Vector3f> normals;    // unit, one per position
  std::vector<uint32_t> indices;           // triangle list, three per triangle
};

// Builds the closed unit cylinder with `segments` sides and kShapeRings rings. Precondition
// (CHECK): segments >= 3.
CylinderMesh MakeUnitCylinderMesh(int segments);

// The ring a unit mesh vertex lies on: round(z (kShapeRings - 1)) clamped to
// [0, kShapeRings - 1].
int RingOfUnitVertex(double z);

// Slope dv/dz of a ring profile at ring k, z_k = k / (kShapeRings - 1): the central difference
// (v[k + 1] - v[k - 1]) / (z_{k+1} - z_{k-1}) inside, one-sided at k = 0 and the last ring.
// Precondition (CHECK): 0 <= k < kShapeRings.
double RingSlope(const std::array<double, kShapeRings>& values, int k);

// The surface factor s at a unit mesh vertex (see above).
double SurfaceFactorOfUnitVertex(const PartShape& shape, const Eigen::Vector3d& unit_position);

// A unit mesh vertex (on ring RingOfUnitVertex(z)) placed on the shaped unit surface:
// (s width[k] x, s depth[k] y, z), z moved by the rounded end's depth for a cap vertex (one
// whose mesh normal has a non-zero z; the default, zero, is a side vertex's).
Eigen::Vector3d ShapedUnitPosition(const PartShape& shape, const Eigen::Vector3d& unit_position,
                                   const Eigen::Vector3d& unit_normal = Eigen::Vector3d::Zero());

// The unit-frame normal (not unit length) of the shaped surface at a unit mesh vertex with
// its mesh normal: the rule of the header comment. A normal with a non-zero z is a cap's.
Eigen::Vector3d ShapedUnitNormal(const PartShape& shape, const Eigen::Vector3d& unit_position,
                                 const Eigen::Vector3d& unit_normal);

// viewer_from_cylinder: the affine map (bottom row 0 0 0 1) that places the (shaped) unit
// cylinder on the axis a -> b with the given radius: cylinder z = 0 at a, z = 1 at b, and the
// cylinder's x, y axes scaled by radius onto an orthonormal pair perpendicular to the axis,
//   z_hat = (b - a) / |b - a|, y_hat = z_hat x x_hat,
//   x_hat = normalise(w - (w . z_hat) z_hat) for a width direction w (the shape's width runs
//           along it, its depth along z_hat x w), if given and that has norm >= 1e-9 |w|;
//   x_hat = normalise(z_hat x h) otherwise (the helper rule), with h = unit x unless
//           |z_hat.x| >= 0.9, then unit y.
// The choice of x_hat fixes where the tessellation's vertices lie around the axis, so every
// renderer must use this. Precondition: a, b (and w) finite and |b - a| > 0 (a zero-length
// axis yields non-finite entries).
Eigen::Matrix4d ViewerFromUnitCylinder(
    const Eigen::Vector3d& a, const Eigen::Vector3d& b, double radius,
    const std::optional<Eigen::Vector3d>& width_direction = std::nullopt);

// The same placement for a Cylinder: its axis, radius and width direction.
Eigen::Matrix4d ViewerFromUnitCylinder(const Cylinder& cylinder);

// The inverse transpose of viewer_from_cylinder's linear part (columns x_hat / radius,
// y_hat / radius, z_hat / |b - a|): maps unit-frame normals to viewer-frame normals.
// Precondition: viewer_from_cylinder from ViewerFromUnitCylinder with radius > 0.
Eigen::Matrix3d NormalFromUnitCylinder(const Eigen::Matrix4d& viewer_from_cylinder);

}  // namespace reenact
