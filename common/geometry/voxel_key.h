#pragma once
// Cells of a uniform voxel grid, for hashing points by position (merging map points, grouping
// nearby ones): the cell of a point is floor(p / size) per axis, and a cell's key packs its
// three coordinates into 21 bits each (two's complement), so cells within 2^20 of the
// origin on every axis have distinct keys: +-10 km at 1 cm cells.

#include <Eigen/Core>
#include <cstdint>

namespace reenact {

// Precondition: size > 0 and p / size within the int range (not checked).
inline Eigen::Vector3i VoxelCell(const Eigen::Vector3d& p, double size) {
  return (p / size).array().floor().cast<int>();
}

inline int64_t VoxelKey(const Eigen::Vector3i& cell) {
  constexpr int64_t kMask = (int64_t{1} << 21) - 1;
  return (static_cast<int64_t>(cell.x()) & kMask) |
         ((static_cast<int64_t>(cell.y()) & kMask) << 21) |
         ((static_cast<int64_t>(cell.z()) & kMask) << 42);
}

}  // namespace reenact
