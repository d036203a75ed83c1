#include "tests/bench/server_bench.h"

namespace reenact::bench {

int RunServerBench(const CommandLine&) {
  return ReportFailure("reenact-bench",
                       MakeError("unsupported", "'server' is not in this build yet: it arrives "
                                                "with the server hardening work"));
}

}  // namespace reenact::bench
