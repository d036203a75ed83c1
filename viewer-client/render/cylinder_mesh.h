#pragma once
// CPU mesh of the unit cylinder the renderer instances for every body part.
//
// The cylinder has radius 1 and runs along +z from z = 0 to z = 1 in its own frame. It is
// closed: a side made of `segments` flat quads (two triangles each) and two capping fans.
// Side vertices carry radial normals (x, y, 0), cap vertices the cap normal (0, 0, -1) at
// z = 0 and (0, 0, +1) at z = 1, so sides and caps do not share vertices. Every triangle is
// wound counter-clockwise seen from outside, in a right-handed frame.

#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace reenact::viewer {

struct CylinderMesh {
  std::vector<Eigen::Vector3f> positions;  // cylinder frame, unit radius and length
  std::vector<Eigen::Vector3f> normals;    // unit, one per position
  std::vector<uint32_t> indices;           // triangle list, three per triangle
};

// Builds the closed unit cylinder with `segments` sides. Precondition: segments >= 3.
// Sizes: 4 * segments + 2 vertices, 4 * segments triangles.
CylinderMesh MakeUnitCylinderMesh(int segments);

}  // namespace reenact::viewer
