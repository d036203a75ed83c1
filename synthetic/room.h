#pragma once
// The synthetic room in the world frame (z up, floor z = 0, metres): a 6 m x 6.5 m room
// (x in [-3, 3], y in [-4, 2.5]) 3 m high, with a ceiling and four textured walls, and four
// furniture boxes (a bookshelf and a cabinet along the back wall, a cardboard box on the
// right, a small table on the left). The subject stands near the origin; the sensor looks
// along +y from y of about -3.
//
// Every surface is a textured rectangle whose albedo is baked once into an RGB texture at
// about 1 cm per texel, and lit by one directional light (Lambert, constant per face).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <vector>

#include "common/image/image.h"
#include "synthetic/room_texture.h"

namespace reenact::capture {

// Direction towards the scene's directional light, world frame, unit length.
Eigen::Vector3d SceneLightDirection();
// Ambient share of the scene's Lambert shading (the rest follows the directional light).
inline constexpr double kSceneAmbient = 0.5;
// Lambert factor ambient + (1 - ambient) * max(0, n . l) for a world normal; ambient in
// [0, 1] (1: lit flat, the factor 1 whatever the normal).
double LambertShade(const Eigen::Vector3d& normal_in_world, double ambient = kSceneAmbient);

struct RoomFace {
  Eigen::Vector3d origin;  // world position of texture coordinate (0, 0), metres
  Eigen::Vector3d u_axis;  // unit, world
  Eigen::Vector3d v_axis;  // unit, world
  double width = 0;        // metres along u_axis
  double height = 0;       // metres along v_axis
  Eigen::Vector3d normal;  // unit, world, facing into the visible side
  RoomMaterial material = RoomMaterial::kPlasterWall;
  double texels_per_metre = 100;
  ImageRgb8 texture;  // width*texels_per_metre x height*texels_per_metre, baked albedo
  double shade = 1;   // LambertShade(normal)
};

struct Box {
  Eigen::Vector3d min, max;  // world, metres
};

struct RoomModel {
  std::vector<RoomFace> faces;
  std::vector<Box> furniture;          // the furniture boxes (for tests and occlusion reasoning)
  Eigen::Vector3d room_min, room_max;  // the room's inner walls, floor and ceiling
};

// Builds the room and bakes its textures (about 0.1-0.2 s).
RoomModel BuildRoom();

// The room, built once per process and shared (thread-safe).
std::shared_ptr<const RoomModel> SharedRoom();

// Baked albedo times shade at texture coordinate (u, v) metres, bilinear, sRGB [0, 255].
Eigen::Vector3f SampleFace(const RoomFace& face, float u, float v);

}  // namespace reenact::capture
