#include <algorithm>
#include <random>

#include "common/texture/texture_selection.h"
#include "tests/bench/bench_support.h"
#include "tests/bench/core_bench.h"

namespace reenact::bench {

// Eq. 5 exact scan over N stored frames; ratio against N = 1000 of the same run.
void AddSelectionRows(proto::Report& report, const CoreBenchOptions& options) {
  std::mt19937 rng(7);
  double baseline_us = 0;
  for (int n : options.quick ? std::vector<int>{1000} : std::vector<int>{1000, 10000, 100000}) {
    std::vector<Skeleton> stored;
    for (int i = 0; i < n; ++i) stored.push_back(RandomSkeleton(rng));
    const int queries = std::max(5, 200000 / n);
    std::vector<Skeleton> viewer;
    for (int i = 0; i < queries; ++i) viewer.push_back(RandomSkeleton(rng));
    const double us = Median(TimeRepeated(options.repeats, queries, [&] {
      for (const Skeleton& v : viewer) RankTextureFrames(v, stored, {.top_k = 4});
    }));
    if (n == 1000) baseline_us = us;
    report.rows.push_back(proto::ReportRow{}
                              .Add("op", "select_eq5_exact")
                              .Add("n", static_cast<long long>(n))
                              .Add("us_per_query", us)
                              .Add("ratio", us / baseline_us)
                              .Add("recall_at_1", 1.0));
  }
}

}  // namespace reenact::bench
