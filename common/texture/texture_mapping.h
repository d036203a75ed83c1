#pragma once
// Texture mapping (thesis Eq. 6-16), implemented by intent: a point p* on the viewer-frame
// cylinder of a part maps to the point p_n on the stored frame's cylinder of the same part
// with the same height fraction along the axis and the same angle around the axis measured
// from the side that faces the camera.
//
// Each cylinder gets an orthonormal frame (u, f, u x f): u the unit axis a -> b (Eq. 6-7),
// f the facing direction (Eq. 12, 14): the unit vector orthogonal to the axis that points
// from the axis towards the camera centre (the frame's origin). Eq. 12 takes the ray through
// joint a; we take it through the axis midpoint, which is where the cylinder's visible side
// is centred. The map is the similarity
//   p_n = a_n + s R (p* - a*),  R = [u_n f_n u_n x f_n] [u* f* u* x f*]^T,  s = |v_n| / |v*|
// R is the composition of Theta (Eq. 8, axis onto axis) and Q (Eq. 15, the turn about the
// stored axis that brings the viewer's facing side onto the stored facing side); building it
// from the two frames avoids Rodrigues' degenerate parallel and anti-parallel cases. The
// scale goes from the viewer's cylinder to the stored one (Eq. 9 read so that the mapped
// cylinder lands on the stored cylinder, whose radius is |v_n| times the same ratio).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>

namespace reenact {

// Facing direction of the axis a -> b seen from the origin; nullopt if |b - a| is below
// 1e-9 m. If the origin lies on the axis line, a fixed direction orthogonal to the axis.
std::optional<Eigen::Vector3d> FacingDirection(const Eigen::Vector3d& a, const Eigen::Vector3d& b);

// stored_from_viewer (a 4x4 similarity) for one part: viewer-frame axis (a*, b*), stored
// sensor-frame axis (a_n, b_n). nullopt if either axis is degenerate.
std::optional<Eigen::Matrix4d> StoredFromViewerMapping(const Eigen::Vector3d& a_viewer,
                                                       const Eigen::Vector3d& b_viewer,
                                                       const Eigen::Vector3d& a_stored,
                                                       const Eigen::Vector3d& b_stored);

}  // namespace reenact
