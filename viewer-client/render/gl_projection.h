#pragma once
// OpenGL projection matrix for an OpenCV pinhole camera (distortion ignored).
//
// The matrix takes a point (X, Y, Z, 1) in the OpenCV camera frame (x right, y down,
// z forward, metres) straight to GL clip space, with clip w = Z. It is built so that after
// the viewport transform and the renderer's row flip on read-back (output row
// = height - 1 - GL row), the pixel that a point lights is the pixel PinholeCamera::Project
// names, with OpenCV's pixel centres at integers:
//   GL window x = u + 0.5,           so x_ndc = (2u + 1) / w - 1
//   GL window y = h - (v + 0.5),     so y_ndc = 1 - (2v + 1) / h
//   z_ndc = -1 at Z = near, +1 at Z = far (depth grows with Z: GL_LESS keeps the nearer)
// With u = fx X/Z + cx and v = fy Y/Z + cy:
//   [ 2fx/w    0      (2cx + 1)/w - 1       0           ]
//   [ 0      -2fy/h   1 - (2cy + 1)/h       0           ]
//   [ 0        0      (f + n)/(f - n)   -2 f n/(f - n)  ]
//   [ 0        0           1                0           ]
// The y flip reverses the apparent winding of triangles; the renderer does not cull.

#include <Eigen/Core>

#include "common/geometry/pinhole_camera.h"

namespace reenact::viewer {

inline constexpr double kGlNearM = 0.05;  // near clip plane, metres
inline constexpr double kGlFarM = 50.0;   // far clip plane, metres

// Precondition: camera.Check() passes and 0 < near < far.
Eigen::Matrix4d GlProjectionFromPinhole(const PinholeCamera& camera, double near = kGlNearM,
                                        double far = kGlFarM);

}  // namespace reenact::viewer
