// Per source: the median wall time of Next() over every frame of the stream, over --repeats
// passes (each pass opens the source afresh; opening is reported separately), on 640x480.
#include "tests/bench/source_bench.h"

#include <optional>
#include <string>

#include "capture-client/source/frame_source.h"
#include "proto/report/report_table.h"
#include "tests/bench/bench_support.h"

namespace reenact::bench {
namespace {

double Ms(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

Status AddSourceRow(proto::Report& report, const std::string& spec, int repeats) {
  std::vector<double> open_ms, frame_ms;
  int frames = 0;
  std::string description;
  for (int r = 0; r < repeats; ++r) {
    const auto t0 = Clock::now();
    auto source = capture::OpenFrameSource(spec);
    const auto t1 = Clock::now();
    if (!source.ok()) return source.error();
    open_ms.push_back(Ms(t0, t1));
    description = (*source)->info().description;
    frames = 0;
    while (true) {
      const auto a = Clock::now();
      auto next = (*source)->Next();
      const auto b = Clock::now();
      if (!next.ok()) return next.error();
      if (!next->has_value()) break;
      frame_ms.push_back(Ms(a, b));
      ++frames;
    }
  }
  report.rows.push_back(proto::ReportRow{}
                            .Add("source", spec.substr(0, spec.find(':')))
                            .Add("frames", static_cast<long long>(frames))
                            .Add("open_ms", Median(open_ms))
                            .Add("ms_per_frame", Median(frame_ms))
                            .Add("description", description));
  return {};
}

}  // namespace

int RunSourceBench(const CommandLine& cl) {
  const auto repeats = cl.GetInt("repeats", 5);
  if (!repeats.ok()) return ReportFailure("reenact-bench", repeats.error());
  if (*repeats < 1)
    return ReportFailure("reenact-bench", MakeError("usage", "--repeats must be >= 1"));
  const std::optional<std::string> oni = cl.Get("oni"), tum = cl.Get("tum");
  if (!oni && !tum)
    return ReportFailure("reenact-bench",
                         MakeError("usage",
                                   "sources needs --oni FILE and/or --tum DIR, e.g. "
                                   "--oni ../shared/data/oni/kinect-room-12f.oni "
                                   "--tum ../shared/data/tum-fr1-rpy-head"));
  proto::Report report{"sources", {}};
  if (oni)
    if (Status s = AddSourceRow(report, "oni:" + *oni, static_cast<int>(*repeats)); !s.ok())
      return ReportFailure("reenact-bench", s.error());
  if (tum)
    if (Status s = AddSourceRow(report, "tum:" + *tum, static_cast<int>(*repeats)); !s.ok())
      return ReportFailure("reenact-bench", s.error());
  const Status printed = report.Print(cl.Get("json"));
  return printed.ok() ? 0 : ReportFailure("reenact-bench", printed.error());
}

}  // namespace reenact::bench
