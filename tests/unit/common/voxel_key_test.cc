#include "common/geometry/voxel_key.h"

#include <gtest/gtest.h>

#include <set>

namespace reenact {
namespace {

TEST(VoxelKey, CellsFloorTowardsMinusInfinity) {
  EXPECT_EQ(VoxelCell({0.015, -0.005, -0.02}, 0.01), Eigen::Vector3i(1, -1, -2));
  EXPECT_EQ(VoxelCell({0, 0, 0}, 0.01), Eigen::Vector3i(0, 0, 0));
}

TEST(VoxelKey, NeighbouringAndDistantCellsHaveDistinctKeys) {
  std::set<int64_t> keys;
  int n = 0;
  for (int x = -2; x <= 2; ++x)
    for (int y = -2; y <= 2; ++y)
      for (int z = -2; z <= 2; ++z, ++n) keys.insert(VoxelKey({x, y, z}));
  for (int big : {(1 << 20) - 1, -(1 << 20)}) {
    keys.insert(VoxelKey({big, 0, 0}));
    keys.insert(VoxelKey({0, big, 0}));
    keys.insert(VoxelKey({0, 0, big}));
    n += 3;
  }
  EXPECT_EQ(static_cast<int>(keys.size()), n);
}

}  // namespace
}  // namespace reenact
