// reenact-bench: speed, reported as medians over repetitions, with ratios against a baseline
// measured in the same run. `core` today; capture, server and viewer arrive with their work.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <random>

#include "common/cli/command_line.h"
#include "common/texture/texture_mapping.h"
#include "common/texture/texture_selection.h"
#include "proto/report/report_table.h"

namespace {

using namespace reenact;
using Clock = std::chrono::steady_clock;

constexpr const char* kUsage =
    "usage:\n"
    "  reenact-bench core [--repeats R] [--json FILE]\n"
    "  reenact-bench capture|server|viewer ...   (not in this build yet)\n";

int Fail(const Error& e) { return ReportFailure("reenact-bench", e); }

double Median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

// A random plausible skeleton: a standing person with joint jitter, yaw and distance.
Skeleton RandomSkeleton(std::mt19937& rng) {
  std::uniform_real_distribution<double> yaw(-M_PI, M_PI), jitter(-0.05, 0.05), dist(2.0, 4.0);
  const Eigen::Vector3d base[kJointCount] = {
      {0, -0.75, 0},    {0, -0.55, 0},   {0, -0.3, 0},    {0, 0, 0},
      {0.2, -0.5, 0},   {0.45, -0.3, 0}, {0.6, -0.1, 0},  {-0.2, -0.5, 0},
      {-0.45, -0.3, 0}, {-0.6, -0.1, 0}, {0.1, 0.05, 0},  {0.11, 0.5, 0},
      {0.12, 0.95, 0},  {-0.1, 0.05, 0}, {-0.11, 0.5, 0}, {-0.12, 0.95, 0}};
  const Eigen::Matrix3d r =
      Eigen::AngleAxisd(yaw(rng), Eigen::Vector3d::UnitY()).toRotationMatrix();
  const double z = dist(rng);
  Skeleton s;
  for (int i = 0; i < kJointCount; ++i)
    s.Set(static_cast<Joint>(i),
          r * (base[i] + Eigen::Vector3d(jitter(rng), jitter(rng), jitter(rng))) +
              Eigen::Vector3d(0, 0, z));
  return s;
}

int Core(const CommandLine& cl) {
  const auto repeats = cl.GetInt("repeats", 7);
  if (!repeats.ok()) return Fail(repeats.error());
  if (*repeats < 1) return Fail(MakeError("usage", "--repeats must be >= 1"));
  std::mt19937 rng(7);
  proto::Report report{"core", {}};

  // Eq. 5 exact selection over N stored frames; baseline: N = 1000.
  double baseline_us = 0;
  for (int n : {1000, 10000, 100000}) {
    std::vector<Skeleton> stored;
    for (int i = 0; i < n; ++i) stored.push_back(RandomSkeleton(rng));
    const int queries = std::max(5, 200000 / n);
    std::vector<Skeleton> viewer;
    for (int i = 0; i < queries; ++i) viewer.push_back(RandomSkeleton(rng));
    std::vector<double> us;
    int sink = 0;
    for (long long r = 0; r < *repeats; ++r) {
      const auto t0 = Clock::now();
      for (const Skeleton& v : viewer) sink += RankTextureFrames(v, stored, {.top_k = 4})[0].frame;
      us.push_back(std::chrono::duration<double, std::micro>(Clock::now() - t0).count() / queries);
    }
    const double median = Median(us);
    if (n == 1000) baseline_us = median;
    report.rows.push_back(proto::ReportRow{}
                              .Add("op", "select_eq5_exact")
                              .Add("n", static_cast<long long>(n))
                              .Add("us_per_query", median)
                              .Add("ratio_vs_n1000", median / baseline_us)
                              .Add("recall_at_1", 1.0)
                              .Add("checksum", static_cast<long long>(sink % 1000)));
  }

  // Eq. 6-16 mapping for the 11 parts of one output frame.
  {
    std::vector<Skeleton> a, b;
    for (int i = 0; i < 1000; ++i)
      a.push_back(RandomSkeleton(rng)), b.push_back(RandomSkeleton(rng));
    std::vector<double> us;
    double sink = 0;
    for (long long r = 0; r < *repeats; ++r) {
      const auto t0 = Clock::now();
      for (size_t i = 0; i < a.size(); ++i)
        for (int p = 0; p < kBodyPartCount; ++p) {
          const auto [ja, jb] = PartJoints(static_cast<BodyPart>(p));
          if (auto m = StoredFromViewerMapping(a[i][ja], a[i][jb], b[i][ja], b[i][jb]))
            sink += (*m)(0, 3);
        }
      us.push_back(std::chrono::duration<double, std::micro>(Clock::now() - t0).count() / a.size());
    }
    report.rows.push_back(proto::ReportRow{}
                              .Add("op", "mapping_eq16_11_parts")
                              .Add("n", static_cast<long long>(a.size()))
                              .Add("us_per_query", Median(us))
                              .Add("checksum", static_cast<long long>(std::abs(sink)) % 1000));
  }
  std::cout << report.FormatTable();
  if (auto json = cl.Get("json"))
    if (Status s = report.WriteJson(*json); !s.ok()) return Fail(s.error());
  return 0;
}

int NotYet(const CommandLine& cl) {
  return Fail(MakeError(
      "unsupported",
      "'" + cl.positionals()[0] +
          "' is not in this build yet: it arrives with the capture, server and viewer work"));
}

}  // namespace

int main(int argc, char** argv) {
  const CommandLineSpec spec{{"repeats", "json"}, {}};
  return RunTool("reenact-bench", kUsage, spec,
                 {{"core", Core}, {"capture", NotYet}, {"server", NotYet}, {"viewer", NotYet}},
                 argc, argv);
}
