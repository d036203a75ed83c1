#include "tests/bench/core_bench.h"

namespace reenact::bench {

// Model building over a long clip arrives with the core work; no rows until then.
void AddModelRows(proto::Report&, const CoreBenchOptions&) {}

}  // namespace reenact::bench
