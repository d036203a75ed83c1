#pragma once
// `reenact-bench server --attacks`: the sharing service's defences under hostile and heavy
// clients. An in-process HttpServer with default ServerOptions (port 0 aside) serves nearby
// queries to normal keep-alive clients while each attack runs on loopback; every figure of
// the normal clients stands beside the same figure measured just before without the attack.

#include <string>

#include "common/error/expected.h"
#include "proto/report/report_table.h"

namespace reenact::bench {

struct AttackBenchOptions {
  std::string db_dir;        // an existing directory for the seeded database (removed after)
  long long clips = 10'000;  // published clips seeded for the nearby queries
  int clients = 4;           // normal client threads
  double seconds = 8;        // each measurement: the baseline, then the same under attack
  // One group of scenarios (kAttackGroups), or all when empty.
  std::string only;
};

// The groups of scenarios, in the order they run.
inline constexpr const char* kAttackGroups[] = {"slow-headers", "bodies", "slow-body", "heavy",
                                                "stalled"};

// One row per scenario in `report` (see server_attack_bench.cc for the columns). code
// "usage" for an unknown group in options.only.
Status RunAttackBench(const AttackBenchOptions& options, proto::Report& report);

}  // namespace reenact::bench
