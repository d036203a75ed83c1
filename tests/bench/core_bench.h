#pragma once
// `reenact-bench core`: the reenactment core's speed against its error, one group of rows
// per part of common/ (each in its own file).

#include "proto/report/report_table.h"

namespace reenact::bench {

struct CoreBenchOptions {
  int repeats = 7;     // samples per measurement (the median is reported), >= 1
  bool quick = false;  // smaller sizes, for a smoke run
};

void AddSelectionRows(proto::Report& report, const CoreBenchOptions& options);  // Eq. 5
void AddMappingRows(proto::Report& report, const CoreBenchOptions& options);    // Eq. 6-16
void AddRenderRows(proto::Report& report, const CoreBenchOptions& options);     // CPU reference
void AddModelRows(proto::Report& report, const CoreBenchOptions& options);      // Eq. 2-4

}  // namespace reenact::bench
