#include <random>

#include "common/texture/texture_mapping.h"
#include "tests/bench/bench_support.h"
#include "tests/bench/core_bench.h"

namespace reenact::bench {

// Eq. 6-16: the 11 per-part similarities of one output frame.
void AddMappingRows(proto::Report& report, const CoreBenchOptions& options) {
  std::mt19937 rng(11);
  std::vector<Skeleton> a, b;
  for (int i = 0; i < 1000; ++i) {
    a.push_back(RandomSkeleton(rng));
    b.push_back(RandomSkeleton(rng));
  }
  const double us = Median(TimeRepeated(options.repeats, a.size(), [&] {
    for (size_t i = 0; i < a.size(); ++i)
      for (int p = 0; p < kBodyPartCount; ++p) {
        const auto [ja, jb] = PartJoints(static_cast<BodyPart>(p));
        StoredFromViewerMapping(a[i][ja], a[i][jb], b[i][ja], b[i][jb]);
      }
  }));
  report.rows.push_back(proto::ReportRow{}
                            .Add("op", "mapping_eq16_11_parts")
                            .Add("n", static_cast<long long>(a.size()))
                            .Add("us_per_query", us));
}

}  // namespace reenact::bench
