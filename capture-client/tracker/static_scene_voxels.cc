#include "capture-client/tracker/static_scene_voxels.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "common/error/check.h"

namespace reenact::capture {
namespace {

constexpr int kKeyBits = 21;
constexpr int64_t kKeyOffset = int64_t{1} << (kKeyBits - 1);
constexpr int64_t kKeyMax = (int64_t{1} << kKeyBits) - 1;
constexpr double kThickestCapsuleM = 0.3;  // beyond any body capsule's radius

Eigen::Array3i FloorShift(const Eigen::Array3i& i, int bits) {
  return i.unaryExpr([bits](int v) { return v >> bits; });
}

uint64_t BlockKey(const Eigen::Array3i& block) {
  uint64_t key = 0;
  for (int a = 0; a < 3; ++a)
    key = (key << kKeyBits) |
          static_cast<uint64_t>(std::clamp<int64_t>(block[a] + kKeyOffset, 0, kKeyMax));
  return key;
}

}  // namespace

void StaticSceneOptions::Check() const {
  REENACT_CHECK(voxel_m > 0 && std::isfinite(voxel_m), "static scene voxel_m must be > 0");
  REENACT_CHECK(min_frames >= 1 && min_frames <= 255, "static scene min_frames in [1, 255]");
  REENACT_CHECK(body_clearance_m >= 0 && see_through_m > 0 && see_through_margin_m > 0,
                "static scene body_clearance_m must be >= 0, see_through_m and "
                "see_through_margin_m > 0");
  REENACT_CHECK(floor_clearance_m >= 0 && std::isfinite(floor_clearance_m),
                "static scene floor_clearance_m must be >= 0");
  REENACT_CHECK(learn_step >= 1 && max_blocks >= 1,
                "static scene learn_step and max_blocks must be >= 1");
}

StaticSceneVoxels::StaticSceneVoxels(const PinholeCamera& camera, const StaticSceneOptions& options)
    : camera_(camera), options_(options) {
  options_.Check();
}

Eigen::Array3i StaticSceneVoxels::VoxelIndex(const Eigen::Vector3d& p) const {
  constexpr double kLimit = static_cast<double>(kKeyOffset << kBlockBits);
  return (p / options_.voxel_m).array().floor().max(-kLimit).min(kLimit - 1).cast<int>();
}

std::pair<uint64_t, int> StaticSceneVoxels::Slot(const Eigen::Array3i& voxel) {
  const Eigen::Array3i block = FloorShift(voxel, kBlockBits);
  const Eigen::Array3i local = voxel - block * (1 << kBlockBits);
  return {BlockKey(block), local.x() | (local.y() << kBlockBits) | (local.z() << (2 * kBlockBits))};
}

void StaticSceneVoxels::Learn(const PersonBlob& blob, const PixelRays& rays,
                              const Eigen::Isometry3d& world_from_sensor,
                              const ArticulatedBody& body, const PosedBody3& posed) {
  REENACT_CHECK(rays.width() == camera_.width && rays.height() == camera_.height,
                "Learn needs the rays of the map's camera");
  const int g = blob.grid_step_px, gw = blob.depth_m.width, gh = blob.depth_m.height;
  if (gw == 0 || gh == 0 || !world_from_sensor.matrix().allFinite()) return;
  ++frame_;
  const Eigen::Isometry3d sensor_from_world = world_from_sensor.inverse();
  Eigen::AlignedBox3d body_box;
  for (int j = 0; j < kJointCount; ++j) body_box.extend(posed.skeleton[static_cast<Joint>(j)]);

  // Voxels seen through, near the person, are forgotten.
  Eigen::AlignedBox3d near_in_world;
  for (int c = 0; c < 8; ++c)
    near_in_world.extend(world_from_sensor *
                         body_box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c)));
  near_in_world.min().array() -= options_.see_through_margin_m;
  near_in_world.max().array() += options_.see_through_margin_m;
  const Eigen::Array3i lo = VoxelIndex(near_in_world.min()), hi = VoxelIndex(near_in_world.max());
  // Seen through: the readings at the voxel's centre and at its eight corners all lie behind
  // them (a surface that crosses the voxel anywhere covers one of them).
  const auto behind = [&](const Eigen::Vector3d& p_world) {
    const Eigen::Vector3d p = sensor_from_world * p_world;
    const auto px = camera_.Project(p);
    if (!px) return false;
    const int x = static_cast<int>(std::lround(px->x() / g)),
              y = static_cast<int>(std::lround(px->y() / g));
    if (x < 0 || y < 0 || x >= gw || y >= gh) return false;
    const float d = blob.depth_m.at(x, y);
    return d > 0 && d > p.z() + options_.see_through_m;
  };
  const auto seen_through = [&](const Eigen::Array3i& voxel) {
    const Eigen::Vector3d corner = (voxel.cast<double>() * options_.voxel_m).matrix();
    if (!behind(corner + Eigen::Vector3d::Constant(0.5 * options_.voxel_m))) return false;
    for (int c = 0; c < 8; ++c)
      if (!behind(corner + options_.voxel_m * Eigen::Vector3d(c & 1, (c >> 1) & 1, c >> 2)))
        return false;
    return true;
  };
  const Eigen::Array3i block_lo = FloorShift(lo, kBlockBits), block_hi = FloorShift(hi, kBlockBits);
  for (int bz = block_lo.z(); bz <= block_hi.z(); ++bz)
    for (int by = block_lo.y(); by <= block_hi.y(); ++by)
      for (int bx = block_lo.x(); bx <= block_hi.x(); ++bx) {
        const auto it = blocks_.find(BlockKey({bx, by, bz}));
        if (it == blocks_.end()) continue;
        Block& block = it->second;
        for (int v = 0; v < kBlockVoxels; ++v) {
          if (block.count[v] == 0) continue;
          const Eigen::Array3i voxel =
              Eigen::Array3i(bx, by, bz) * (1 << kBlockBits) +
              Eigen::Array3i(v & kBlockMask, (v >> kBlockBits) & kBlockMask, v >> (2 * kBlockBits));
          if ((voxel < lo).any() || (voxel > hi).any()) continue;
          if (seen_through(voxel)) block.count[v] = 0;
        }
      }

  // Readings outside the person's region; those near the fitted body or the floor are left out.
  Eigen::AlignedBox3d near_body = body_box;
  near_body.min().array() -= options_.body_clearance_m + kThickestCapsuleM;
  near_body.max().array() += options_.body_clearance_m + kThickestCapsuleM;
  std::vector<Eigen::Vector3d> readings, near;
  for (int y = 0; y < gh; y += options_.learn_step)
    for (int x = 0; x < gw; x += options_.learn_step) {
      const float z = blob.depth_m.at(x, y);
      if (z <= 0 || blob.mask.at(x, y) != 0) continue;
      const Eigen::Vector3d p = rays.Point(x * g, y * g, z);
      if (blob.floor_in_sensor &&
          blob.floor_in_sensor->SignedDistance(p) < options_.floor_clearance_m)
        continue;
      (near_body.contains(p) ? near : readings).push_back(p);
    }
  const std::vector<int> owner = NearestSegments(body, posed, near, options_.body_clearance_m);
  for (size_t i = 0; i < near.size(); ++i)
    if (owner[i] < 0) readings.push_back(near[i]);

  uint64_t last_key = 0;
  Block* last = nullptr;  // neighbouring readings mostly share a block
  for (const Eigen::Vector3d& p : readings) {
    const auto [key, v] = Slot(VoxelIndex(world_from_sensor * p));
    if (!last || key != last_key) {
      auto it = blocks_.find(key);
      if (it == blocks_.end()) {
        if (blocks_.size() >= options_.max_blocks) continue;
        it = blocks_.emplace(key, Block{}).first;
      }
      last_key = key, last = &it->second;
    }
    Block& block = *last;
    if (block.last_frame[v] == frame_) continue;
    block.last_frame[v] = frame_;
    if (block.count[v] < options_.min_frames) ++block.count[v];
  }
}

bool StaticSceneVoxels::IsStatic(const Eigen::Vector3d& point_in_world) const {
  const auto [key, v] = Slot(VoxelIndex(point_in_world));
  const auto it = blocks_.find(key);
  return it != blocks_.end() && it->second.count[v] >= options_.min_frames;
}

int StaticSceneVoxels::DropStatic(const Eigen::Isometry3d& world_from_sensor,
                                  const std::optional<Plane3>& floor_in_sensor,
                                  BodyObservation* observation) const {
  if (blocks_.empty() || !world_from_sensor.matrix().allFinite()) return 0;
  const size_t before = observation->points.size();
  std::erase_if(observation->points, [&](const Eigen::Vector3d& p) {
    const double height = floor_in_sensor ? floor_in_sensor->SignedDistance(p) : 1e9;
    if (height >= options_.floor_clearance_m) return IsStatic(world_from_sensor * p);
    const double lift = options_.floor_clearance_m - height + 0.5 * options_.voxel_m;
    return IsStatic(world_from_sensor * (p + lift * floor_in_sensor->normal));
  });
  return static_cast<int>(before - observation->points.size());
}

void StaticSceneVoxels::Clear() {
  blocks_.clear();
  frame_ = 0;
}

}  // namespace reenact::capture
