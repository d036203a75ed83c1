#include "tests/bench/core_bench.h"

namespace reenact::bench {

// The CPU reference renderer arrives with the core work; no rows until then.
void AddRenderRows(proto::Report&, const CoreBenchOptions&) {}

}  // namespace reenact::bench
