#pragma once
// Depth images built by ray casting simple geometry, for the tracker's tests: a level sensor
// 1.3 m above a floor, a back wall, and upright cylinders standing on the floor (people of
// known size and place) or held above it (a raised hand). Sensor frame: OpenCV axes, so the
// floor is the plane y = 1.3.

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "common/geometry/pinhole_camera.h"
#include "common/image/image.h"

namespace reenact::capture::tracker_test {

struct Cylinder {
  double x = 0, z = 3;  // axis position, metres
  double radius = 0.18;
  double height = 1.7;  // above the floor
  double bottom = 0;    // its lower end above the floor (0: standing on it)
};

struct RayScene {
  double sensor_height = 1.3;
  bool floor = true;
  double wall_z = 6.0;  // 0 = no wall
  std::vector<Cylinder> people;
};

inline ImageDepthMm RenderDepth(const RayScene& scene, const PinholeCamera& cam) {
  ImageDepthMm depth(cam.width, cam.height, 1, 0);
  for (int v = 0; v < cam.height; ++v)
    for (int u = 0; u < cam.width; ++u) {
      const double dx = (u - cam.cx) / cam.fx, dy = (v - cam.cy) / cam.fy;  // ray (dx, dy, 1)
      double t = std::numeric_limits<double>::infinity();
      if (scene.floor && dy > 1e-9) t = std::min(t, scene.sensor_height / dy);
      if (scene.wall_z > 0) t = std::min(t, scene.wall_z);
      for (const Cylinder& c : scene.people) {
        // (t dx - x)^2 + (t - z)^2 = r^2
        const double a = dx * dx + 1, b = -2 * (dx * c.x + c.z),
                     cc = c.x * c.x + c.z * c.z - c.radius * c.radius;
        const double disc = b * b - 4 * a * cc;
        if (disc < 0) continue;
        const double hit = (-b - std::sqrt(disc)) / (2 * a);
        const double y = hit * dy;  // the floor is at y = sensor_height, the top above it
        if (hit > 0 && y <= scene.sensor_height - c.bottom && y >= scene.sensor_height - c.height)
          t = std::min(t, hit);
      }
      if (std::isfinite(t) && t < 60) depth.at(u, v) = static_cast<uint16_t>(std::lround(t * 1000));
    }
  return depth;
}

}  // namespace reenact::capture::tracker_test
