// reenact-bench: speed, reported as medians over repetitions, with ratios against a baseline
// measured in the same run.

#include <algorithm>
#include <optional>
#include <string>

#include "common/cli/command_line.h"
#include "proto/report/report_table.h"
#include "tests/bench/capture_bench.h"
#include "tests/bench/core_bench.h"
#include "tests/bench/server_bench.h"
#include "tests/bench/source_bench.h"
#include "tests/bench/viewer_bench.h"

namespace {

using namespace reenact;

constexpr const char* kUsage =
    "usage:\n"
    "  reenact-bench core [--repeats R] [--quick] [--only GROUP] [--json FILE]\n"
    "                     groups: selection, mapping, render, model\n"
    "  reenact-bench server [--quick] [--clips N] [--clients C] [--seconds S]\n"
    "                       [--db DIR|postgresql://URL] [--kills K] [--server PATH]\n"
    "                       [--json FILE]\n"
    "                       with a URL: SQLite and PostgreSQL in one table, then two\n"
    "                       reenact-server processes on it and K random SIGKILLs (50)\n"
    "  reenact-bench server --attacks [--only GROUP] [--clips N] [--clients C] [--seconds S]\n"
    "                       [--json FILE]\n"
    "                       instead, the server under attack: 10^4 clips, S = 8 s per\n"
    "                       measurement, about 3 min; groups: slow-headers, bodies,\n"
    "                       slow-body, heavy, stalled\n"
    "  reenact-bench sources [--oni FILE] [--tum DIR] [--repeats R] [--json FILE]\n"
    "  reenact-bench capture [--frames N] [--repeats R] [--tum DIR] [--json FILE]\n"
    "  reenact-bench viewer [--frames N] [--repeats R] [--texturing NAME] [--json FILE]\n";

int Fail(const Error& e) { return ReportFailure("reenact-bench", e); }

int Core(const CommandLine& cl) {
  const auto repeats = cl.GetInt("repeats", 7);
  if (!repeats.ok()) return Fail(repeats.error());
  if (*repeats < 1) return Fail(MakeError("usage", "--repeats must be >= 1"));
  const bench::CoreBenchOptions options{static_cast<int>(*repeats), cl.Has("quick")};
  proto::Report report{"core", {}};
  // Each group of rows prints as its own table.
  const std::pair<const char*, void (*)(proto::Report&, const bench::CoreBenchOptions&)> groups[] =
      {{"selection", bench::AddSelectionRows},
       {"mapping", bench::AddMappingRows},
       {"render", bench::AddRenderRows},
       {"model", bench::AddModelRows}};
  const std::optional<std::string> only = cl.Get("only");
  if (only && std::none_of(std::begin(groups), std::end(groups),
                           [&](const auto& g) { return *only == g.first; }))
    return Fail(MakeError("usage", "--only: unknown group '" + *only +
                                       "'; groups: selection, mapping, render, model"));
  for (const auto& [table, add] : groups) {
    if (only && *only != table) continue;
    const size_t first = report.rows.size();
    add(report, options);
    for (size_t r = first; r < report.rows.size(); ++r) report.rows[r].table = table;
  }
  const Status printed = report.Print(cl.Get("json"));
  return printed.ok() ? 0 : Fail(printed.error());
}

}  // namespace

int main(int argc, char** argv) {
  // Flags of every command; each command reads its own.
  const CommandLineSpec spec{{"repeats", "only", "json", "clips", "clients", "seconds", "db", "oni",
                              "tum", "frames", "texturing", "kills", "server"},
                             {"quick", "attacks"}};
  return RunTool("reenact-bench", kUsage, spec,
                 {{"core", Core},
                  {"server", bench::RunServerBench},
                  {"sources", bench::RunSourceBench},
                  {"capture", bench::RunCaptureBench},
                  {"viewer", bench::RunViewerBench}},
                 argc, argv);
}
