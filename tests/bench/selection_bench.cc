#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>

#include "common/texture/texture_graph_index.h"
#include "common/texture/texture_index.h"
#include "common/texture/texture_selection.h"
#include "tests/bench/bench_support.h"
#include "tests/bench/core_bench.h"

namespace reenact::bench {
namespace {

// A kinematic person: body frame at the waist, x to the person's left, y down, z backwards
// (away from a camera it faces). Angles in radians.
struct Pose {
  double lean_forward = 0, lean_side = 0, head_tilt = 0, head_turn = 0;
  double swing[4] = {0, 0, 0, 0};   // l_arm, r_arm, l_leg, r_leg: forward (+) / back
  double spread[4] = {0, 0, 0, 0};  // away from the body
  double bend[4] = {0, 0, 0, 0};    // elbow / knee flexion
};
constexpr int kPoseDof = 16;

double& Dof(Pose& p, int d) {
  double* scalars[4] = {&p.lean_forward, &p.lean_side, &p.head_tilt, &p.head_turn};
  if (d < 4) return *scalars[d];
  if (d < 8) return p.swing[d - 4];
  if (d < 12) return p.spread[d - 8];
  return p.bend[d - 12];
}

// Range of each degree of freedom: (centre, half width).
std::pair<double, double> DofRange(int d) {
  if (d < 4) return {0, d < 2 ? 0.3 : 0.5};
  if (d < 6) return {0.3, 1.4};  // arms swing widely
  if (d < 8) return {0.1, 0.7};  // legs less
  if (d < 10) return {0.6, 0.6};
  if (d < 12) return {0.15, 0.15};
  return {d < 14 ? 0.9 : 0.5, d < 14 ? 0.9 : 0.5};
}

// The skeleton of a pose in a sensor frame: sensor_from_body = yaw about the vertical, pitch
// about x, at `distance` metres along z.
Skeleton PoseSkeleton(const Pose& p, double yaw, double pitch, double distance) {
  using Eigen::AngleAxisd;
  using Eigen::Vector3d;
  const Vector3d down(0, 1, 0);
  Vector3d j[kJointCount];
  const Eigen::Matrix3d upper =
      (AngleAxisd(-p.lean_forward, Vector3d::UnitX()) * AngleAxisd(p.lean_side, Vector3d::UnitZ()))
          .toRotationMatrix();
  j[Index(Joint::kWaist)] = Vector3d::Zero();
  j[Index(Joint::kTorso)] = upper * Vector3d(0, -0.3, 0);
  j[Index(Joint::kNeck)] = upper * Vector3d(0, -0.55, 0);
  j[Index(Joint::kHead)] =
      j[Index(Joint::kNeck)] +
      upper *
          (AngleAxisd(p.head_turn, Vector3d::UnitY()) * AngleAxisd(-p.head_tilt, Vector3d::UnitX()))
              .toRotationMatrix() *
          Vector3d(0, -0.2, 0);
  const Joint limbs[4][3] = {{Joint::kLeftShoulder, Joint::kLeftElbow, Joint::kLeftHand},
                             {Joint::kRightShoulder, Joint::kRightElbow, Joint::kRightHand},
                             {Joint::kLeftHip, Joint::kLeftKnee, Joint::kLeftFoot},
                             {Joint::kRightHip, Joint::kRightKnee, Joint::kRightFoot}};
  for (int l = 0; l < 4; ++l) {
    const bool arm = l < 2;
    const double side = (l % 2 == 0) ? 1 : -1;
    const Vector3d root =
        arm ? Vector3d(upper * Vector3d(0.2 * side, -0.5, 0)) : Vector3d(0.1 * side, 0.05, 0);
    const Eigen::Matrix3d base = arm ? upper : Eigen::Matrix3d::Identity();
    const Eigen::Matrix3d r_upper = base * (AngleAxisd(side * p.spread[l], Vector3d::UnitZ()) *
                                            AngleAxisd(-p.swing[l], Vector3d::UnitX()))
                                               .toRotationMatrix();
    // Elbows flex forward, knees backward.
    const Eigen::Matrix3d r_lower =
        r_upper * AngleAxisd((arm ? -1 : 1) * p.bend[l], Vector3d::UnitX()).toRotationMatrix();
    const double len = arm ? 0.28 : 0.45;
    j[Index(limbs[l][0])] = root;
    j[Index(limbs[l][1])] = root + r_upper * down * len;
    j[Index(limbs[l][2])] = j[Index(limbs[l][1])] + r_lower * down * len;
  }
  const Eigen::Isometry3d sensor_from_body = Eigen::Translation3d(0, 0, distance) *
                                             AngleAxisd(pitch, Vector3d::UnitX()) *
                                             AngleAxisd(yaw, Vector3d::UnitY());
  Skeleton s;
  for (int i = 0; i < kJointCount; ++i) s.Set(static_cast<Joint>(i), sensor_from_body * j[i]);
  return s;
}

// A pose with every degree of freedom uniform in its range.
Pose RandomPose(std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(-1, 1);
  Pose p;
  for (int d = 0; d < kPoseDof; ++d) {
    const auto [centre, half] = DofRange(d);
    Dof(p, d) = centre + half * unit(rng);
  }
  return p;
}

// A clip of n frames as a 30 fps capture gives it: the pose moves by smooth random steps
// (each degree of freedom a damped random walk with velocity, kept in its range), the
// subject turns slowly in front of the sensor, which tilts a little, and the tracker adds
// 1 cm of joint noise.
struct Clip {
  std::vector<Skeleton> stored;  // each in its sensor frame
  std::vector<Pose> poses;       // the pose of each frame, for queries
};

Clip WalkClip(int n, std::mt19937& rng) {
  std::normal_distribution<double> gauss(0, 1);
  Pose p = RandomPose(rng), v;
  double yaw = 0, yaw_rate = 0, pitch = 0.1;
  Clip clip;
  clip.stored.reserve(n);
  clip.poses.reserve(n);
  for (int f = 0; f < n; ++f) {
    for (int d = 0; d < kPoseDof; ++d) {
      const auto [centre, half] = DofRange(d);
      double& x = Dof(p, d);
      double& dx = Dof(v, d);
      dx = 0.9 * dx + 0.01 * half * gauss(rng) - 0.002 * (x - centre);
      x = std::clamp(x + dx, centre - half, centre + half);
    }
    yaw_rate = 0.95 * yaw_rate + 0.004 * gauss(rng);
    yaw += yaw_rate;
    pitch = std::clamp(pitch + 0.002 * gauss(rng), -0.3, 0.4);
    Skeleton s = PoseSkeleton(p, yaw, pitch, 3.0);
    for (auto& j : s.position) j += 0.01 * Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng));
    clip.stored.push_back(s);
    clip.poses.push_back(p);
  }
  return clip;
}

// Independent frames: every pose and viewpoint drawn afresh.
Clip IidClip(int n, std::mt19937& rng) {
  std::uniform_real_distribution<double> yaw(-M_PI, M_PI), pitch(-0.3, 0.4);
  Clip clip;
  clip.stored.reserve(n);
  clip.poses.reserve(n);
  for (int f = 0; f < n; ++f) {
    clip.poses.push_back(RandomPose(rng));
    clip.stored.push_back(PoseSkeleton(clip.poses.back(), yaw(rng), pitch(rng), 3.0));
  }
  return clip;
}

// A viewer's query: the pose of a clip frame seen from anywhere around the subject.
std::vector<Skeleton> Queries(const Clip& clip, int count, std::mt19937& rng) {
  std::uniform_int_distribution<int> frame(0, static_cast<int>(clip.poses.size()) - 1);
  std::uniform_real_distribution<double> yaw(-M_PI, M_PI), pitch(-0.2, 0.5), dist(1.5, 5);
  std::vector<Skeleton> out;
  for (int q = 0; q < count; ++q)
    out.push_back(PoseSkeleton(clip.poses[frame(rng)], yaw(rng), pitch(rng), dist(rng)));
  return out;
}

// Beam widths of the approximate graph index: its speed against its error.
constexpr int kBeams[] = {16, 32, 48, 96};

// How an index's top-1 answers compare with the scan's over the same queries.
struct Agreement {
  double recall_at_1 = 0;    // share of queries where the frame is the scan's
  double excess_median = 0;  // (cost - best cost) / best cost, median over queries
  double excess_max = 0;
};

Agreement Agree(const std::vector<TextureCandidate>& want,
                const std::vector<std::vector<TextureCandidate>>& got) {
  Agreement a;
  std::vector<double> excess;
  for (size_t q = 0; q < want.size(); ++q) {
    const bool hit = !got[q].empty() && got[q][0].frame == want[q].frame;
    a.recall_at_1 += hit;
    const double e =
        got[q].empty() ? 1.0 : (got[q][0].cost - want[q].cost) / std::max(want[q].cost, 1e-12);
    excess.push_back(e);
    a.excess_max = std::max(a.excess_max, e);
  }
  a.recall_at_1 /= std::max<size_t>(1, want.size());
  a.excess_median = Median(excess);
  return a;
}

}  // namespace

// Eq. 5 top-1 over N stored frames, on a smooth clip ("walk") and on independent frames
// ("iid"): the exact scan (the baseline: ratio = time / scan time), the exact tree index
// (same answers; recall_at_1 is 1 unless it is broken) and the approximate graph index at
// several beam widths (its recall_at_1 and cost excess against the scan are its error).
void AddSelectionRows(proto::Report& report, const CoreBenchOptions& options) {
  const std::vector<int> sizes = options.quick ? std::vector<int>{1000, 10000, 100000}
                                               : std::vector<int>{1000, 10000, 100000, 1000000};
  const TextureSelectionOptions select{.top_k = 1};
  for (const char* scenario : {"walk", "iid"}) {
    for (int n : sizes) {
      std::mt19937 rng(7);
      Clip clip = std::string(scenario) == "walk" ? WalkClip(n, rng) : IidClip(n, rng);
      const int scan_queries = std::max(3, 100000 / n);
      const std::vector<Skeleton> queries = Queries(clip, std::max(200, scan_queries), rng);
      const std::span<const Skeleton> scan_set(queries.data(), scan_queries);

      const double scan_us = Median(TimeRepeated(options.repeats, scan_queries, [&] {
        for (const Skeleton& q : scan_set) RankTextureFrames(q, clip.stored, select);
      }));
      // The scan's answers for the agreement checks, outside the timing.
      const std::span<const Skeleton> check_set(queries.data(),
                                                std::min<size_t>(queries.size(), 100));
      std::vector<TextureCandidate> want;
      for (const Skeleton& q : check_set)
        want.push_back(RankTextureFrames(q, clip.stored, select)[0]);
      auto row = [&](const std::string& op, double us, const Agreement& a, double build_ms) {
        report.rows.push_back(proto::ReportRow{}
                                  .Add("op", op)
                                  .Add("scenario", scenario)
                                  .Add("n", static_cast<long long>(n))
                                  .Add("us_per_query", us)
                                  .Add("ratio", us / scan_us)
                                  .Add("recall_at_1", a.recall_at_1)
                                  .Add("cost_excess_median", a.excess_median)
                                  .Add("cost_excess_max", a.excess_max)
                                  .Add("build_ms", build_ms));
      };
      row("select_eq5_scan", scan_us, Agreement{1, 0, 0}, 0);

      std::vector<double> build_ms;
      TextureIndex tree;
      for (int r = 0; r < std::min(options.repeats, 3); ++r) {
        const auto t0 = Clock::now();
        tree = TextureIndex(clip.stored);
        build_ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
      }
      const double tree_us = Median(TimeRepeated(options.repeats, queries.size(), [&] {
        for (const Skeleton& q : queries) tree.Rank(q, select);
      }));
      std::vector<std::vector<TextureCandidate>> got;
      for (const Skeleton& q : check_set) got.push_back(tree.Rank(q, select));
      row("select_eq5_tree", tree_us, Agree(want, got), Median(build_ms));

      // One build: it is the slow part at 10^6.
      const auto t0 = Clock::now();
      const TextureGraphIndex graph(clip.stored);
      const double graph_build_ms =
          std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
      for (int beam : kBeams) {
        const TextureGraphSearch search{.beam = beam};
        const double graph_us = Median(TimeRepeated(options.repeats, queries.size(), [&] {
          for (const Skeleton& q : queries) graph.Rank(q, select, search);
        }));
        got.clear();
        for (const Skeleton& q : check_set) got.push_back(graph.Rank(q, select, search));
        row("select_eq5_graph_beam" + std::to_string(beam), graph_us, Agree(want, got),
            graph_build_ms);
      }
    }
  }
}

}  // namespace reenact::bench
