#pragma once
// Clips of skeletons for the texture-selection tests, each skeleton in its sensor frame
// (x right, y down, z forward), metres, and the comparison of two rankings.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <vector>

#include "common/skeleton/skeleton.h"
#include "common/texture/texture_selection.h"
#include "tests/unit/common/test_skeletons.h"

namespace reenact::testing {

// A continuous motion: the person turns and moves their joints by small random steps, as a
// clip does from one frame to the next. missing_rate: chance that a joint is missing.
inline std::vector<Skeleton> SmoothClip(int n, std::mt19937& rng, double missing_rate = 0) {
  std::normal_distribution<double> step(0, 0.01), turn(0, 0.03);
  std::uniform_real_distribution<double> unit(0, 1);
  std::vector<Skeleton> clip;
  Eigen::Vector3d drift[kJointCount];
  for (auto& d : drift) d.setZero();
  double yaw = 0;
  for (int f = 0; f < n; ++f) {
    yaw += turn(rng);
    Skeleton s = StandingPerson(3.0 + 0.5 * std::sin(f * 0.01), yaw, f % 200 < 100);
    for (int i = 0; i < kJointCount; ++i) {
      drift[i] += Eigen::Vector3d(step(rng), step(rng), step(rng));
      drift[i] *= 0.98;  // stays near the pose
      s.position[i] += drift[i];
      if (i != Index(Joint::kNeck) && unit(rng) < missing_rate) s.confidence[i] = 0;
    }
    clip.push_back(s);
  }
  return clip;
}

// Independent draws: no continuity at all.
inline std::vector<Skeleton> RandomClip(int n, std::mt19937& rng) {
  std::uniform_real_distribution<double> yaw(-M_PI, M_PI), jitter(-0.1, 0.1);
  std::vector<Skeleton> clip;
  for (int f = 0; f < n; ++f) {
    Skeleton s = StandingPerson(3.0, yaw(rng), f % 2 == 0);
    for (auto& p : s.position) p += Eigen::Vector3d(jitter(rng), jitter(rng), jitter(rng));
    clip.push_back(s);
  }
  return clip;
}

// A viewer skeleton: a clip pose seen from another viewpoint.
inline Skeleton Query(const std::vector<Skeleton>& clip, std::mt19937& rng) {
  std::uniform_int_distribution<int> pick(0, static_cast<int>(clip.size()) - 1);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI);
  const Eigen::Isometry3d viewer_from_sensor =
      Eigen::Translation3d(0.3, -0.2, 1.0) *
      Eigen::AngleAxisd(angle(rng), Eigen::Vector3d::UnitY()) *
      Eigen::AngleAxisd(0.2 * angle(rng), Eigen::Vector3d::UnitX());
  return clip[pick(rng)].Transformed(viewer_from_sensor);
}

// The same frames with the same costs, bit for bit, in the same order.
inline void ExpectSameRanking(const std::vector<TextureCandidate>& got,
                              const std::vector<TextureCandidate>& want) {
  ASSERT_EQ(got.size(), want.size());
  for (size_t r = 0; r < want.size(); ++r) {
    EXPECT_EQ(got[r].frame, want[r].frame) << "rank " << r;
    EXPECT_EQ(got[r].cost, want[r].cost) << "rank " << r;  // bit for bit
  }
}

}  // namespace reenact::testing
