#include "synthetic/room.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace reenact::capture {
namespace {

using Eigen::Vector3d;

// Adds the faces of an axis-aligned box; inward faces for the room's shell, outward faces
// for furniture. `materials` per face in the order -x, +x, -y, +y, -z, +z (outward normal
// directions); a face whose material entry is absent (nullptr) is skipped.
void AddBox(const Vector3d& lo, const Vector3d& hi, bool inward,
            const std::array<const RoomMaterial*, 6>& materials, RoomModel* room) {
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      const RoomMaterial* material = materials[axis * 2 + side];
      if (material == nullptr) continue;
      Vector3d n = Vector3d::Zero();
      n[axis] = side == 0 ? -1 : 1;
      const double plane = side == 0 ? lo[axis] : hi[axis];
      if (inward) n = -n;
      RoomFace f;
      f.normal = n;
      f.material = *material;
      if (axis == 2) {
        f.u_axis = Vector3d::UnitX();
        f.v_axis = n.z() > 0 ? Vector3d::UnitY() : Vector3d(-Vector3d::UnitY());
      } else {
        f.v_axis = Vector3d::UnitZ();
        f.u_axis = Vector3d::UnitZ().cross(n);
      }
      // Origin: the box corner on this plane with the smallest u and v.
      Vector3d origin;
      for (int k = 0; k < 3; ++k) {
        const double along_u = f.u_axis[k], along_v = f.v_axis[k];
        const double d = along_u != 0 ? along_u : along_v;
        origin[k] = d > 0 ? lo[k] : (d < 0 ? hi[k] : plane);
      }
      origin[axis] = plane;
      f.origin = origin;
      f.width = std::abs((hi - lo).dot(f.u_axis));
      f.height = std::abs((hi - lo).dot(f.v_axis));
      f.shade = LambertShade(n);
      if (f.material == RoomMaterial::kCeiling) f.texels_per_metre = 40;
      room->faces.push_back(f);
    }
}

void Bake(RoomFace* f) {
  const int w = std::max(2, static_cast<int>(std::ceil(f->width * f->texels_per_metre)));
  const int h = std::max(2, static_cast<int>(std::ceil(f->height * f->texels_per_metre)));
  f->texture = ImageRgb8(w, h, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double u = (x + 0.5) / f->texels_per_metre, v = (y + 0.5) / f->texels_per_metre;
      const Color c = RoomAlbedo(f->material, u, v, f->width, f->height);
      for (int k = 0; k < 3; ++k)
        f->texture.at(x, y, k) = static_cast<uint8_t>(std::clamp(c[k] * 255.0 + 0.5, 0.0, 255.0));
    }
}

}  // namespace

Eigen::Vector3d SceneLightDirection() { return Vector3d(0.3, -0.6, 0.75).normalized(); }

double LambertShade(const Vector3d& n, double ambient) {
  return ambient + (1 - ambient) * std::max(0.0, n.dot(SceneLightDirection()));
}

RoomModel BuildRoom() {
  RoomModel room;
  room.room_min = Vector3d(-3.0, -4.0, 0.0);
  room.room_max = Vector3d(3.0, 2.5, 3.0);
  using M = RoomMaterial;
  static constexpr M kFloor = M::kFloorPlanks, kCeiling = M::kCeiling, kBrick = M::kBrickWall,
                     kPaper = M::kWallpaper, kPlaster = M::kPlasterWall, kPainted = M::kPaintedWall,
                     kWood = M::kWood, kShelf = M::kBookshelf, kCabinet = M::kCabinet,
                     kCardboard = M::kCardboard, kCloth = M::kTablecloth;
  // Shell, seen from inside: -x wall bricks, +x wallpaper, -y (behind the sensor) painted,
  // +y (behind the subject) plaster.
  AddBox(room.room_min, room.room_max, true,
         {&kBrick, &kPaper, &kPainted, &kPlaster, &kFloor, &kCeiling}, &room);
  room.furniture = {
      {Vector3d(-2.2, 2.1, 0.0), Vector3d(-1.2, 2.5, 1.9)},     // bookshelf
      {Vector3d(0.9, 2.05, 0.0), Vector3d(2.3, 2.5, 0.8)},      // cabinet
      {Vector3d(2.0, -0.6, 0.0), Vector3d(2.6, 0.2, 0.6)},      // cardboard box
      {Vector3d(-2.6, -1.0, 0.0), Vector3d(-1.9, -0.2, 0.75)},  // table
  };
  AddBox(room.furniture[0].min, room.furniture[0].max, false,
         {&kWood, &kWood, &kShelf, nullptr, nullptr, &kWood}, &room);
  AddBox(room.furniture[1].min, room.furniture[1].max, false,
         {&kWood, &kWood, &kCabinet, nullptr, nullptr, &kWood}, &room);
  AddBox(room.furniture[2].min, room.furniture[2].max, false,
         {&kCardboard, &kCardboard, &kCardboard, &kCardboard, nullptr, &kCardboard}, &room);
  AddBox(room.furniture[3].min, room.furniture[3].max, false,
         {&kWood, &kWood, &kWood, &kWood, nullptr, &kCloth}, &room);
  for (RoomFace& f : room.faces) Bake(&f);
  return room;
}

std::shared_ptr<const RoomModel> SharedRoom() {
  static const std::shared_ptr<const RoomModel> room =
      std::make_shared<const RoomModel>(BuildRoom());
  return room;
}

Eigen::Vector3f SampleFace(const RoomFace& f, float u, float v) {
  const ImageRgb8& t = f.texture;
  const float x = std::clamp(u * static_cast<float>(f.texels_per_metre) - 0.5f, 0.0f,
                             static_cast<float>(t.width - 1));
  const float y = std::clamp(v * static_cast<float>(f.texels_per_metre) - 0.5f, 0.0f,
                             static_cast<float>(t.height - 1));
  const int x0 = std::min(static_cast<int>(x), t.width - 2);
  const int y0 = std::min(static_cast<int>(y), t.height - 2);
  const float ax = x - x0, ay = y - y0;
  const uint8_t* p00 = &t.at(x0, y0);
  const uint8_t* p10 = p00 + 3;
  const uint8_t* p01 = &t.at(x0, y0 + 1);
  const uint8_t* p11 = p01 + 3;
  Eigen::Vector3f out;
  for (int k = 0; k < 3; ++k) {
    const float top = p00[k] + ax * (p10[k] - p00[k]);
    const float bottom = p01[k] + ax * (p11[k] - p01[k]);
    out[k] = top + ay * (bottom - top);
  }
  return out * static_cast<float>(f.shade);
}

}  // namespace reenact::capture
