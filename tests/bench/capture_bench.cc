// Rows (each recorded --repeats times, medians over every frame of every run):
//  - synthetic, source poses and masks: what the recorder did before it tracked (encoding
//    and map keyframes only): the baseline;
//  - synthetic as a real sensor (no pose, no mask; skeletons from the scene, as an imported
//    track gives them): segmentation + SLAM + encoding, the real-sensor pipeline;
//  - the same with the sensor moving (walk-handheld);
//  - tum:DIR (real Kinect images) with a skeleton out of range: SLAM on a real room.
// The source's own time (rendering the synthetic scene, decoding TUM's PNGs) is reported
// apart: a live sensor delivers frames without it. pipeline_ms is the median over frames of
// the recorder's own stages, pipeline_mean_ms their mean (keyframes cost more than other
// frames), and fps the sustained rate 1000 / mean; the once-per-clip model building and
// writing are given apart (per_clip_ms).
#include "tests/bench/capture_bench.h"

#include <unistd.h>

#include <filesystem>
#include <functional>
#include <memory>
#include <string>

#include "capture-client/record/clip_recorder.h"
#include "capture-client/source/synthetic_source.h"
#include "proto/report/report_table.h"
#include "tests/bench/bench_support.h"
#include "tests/support/as_real_sensor.h"

namespace reenact::bench {
namespace {

namespace fs = std::filesystem;

struct Case {
  std::string name;
  // Opens the source and fills the options' skeleton lookup when the case needs one; the
  // returned source must outlive the recording.
  std::function<Expected<std::unique_ptr<capture::FrameSource>>(capture::RecordOptions&)> open;
};

Expected<std::unique_ptr<capture::FrameSource>> AsRealSensor(const std::string& scenario,
                                                             capture::RecordOptions& options) {
  auto inner = capture::SyntheticSource::Open(scenario);
  if (!inner.ok()) return inner.error();
  auto source = std::make_unique<test_support::AsRealSensor>(std::move(inner).value(),
                                                             /*keep_skeleton=*/false);
  options.skeletons = [s = source.get()](int64_t index, double) { return s->SkeletonOf(index); };
  return std::unique_ptr<capture::FrameSource>(std::move(source));
}

void Append(std::vector<double>& all, const std::vector<double>& more) {
  all.insert(all.end(), more.begin(), more.end());
}

Status AddCaseRow(proto::Report& report, const Case& c, int frames, int repeats,
                  const fs::path& scratch) {
  std::vector<double> source_ms, segment_ms, slam_ms, encode_ms, map_ms, pipeline_ms, once_ms;
  capture::RecordSummary last;
  for (int r = 0; r < repeats; ++r) {
    capture::RecordOptions options;
    options.max_frames = frames;
    auto source = c.open(options);
    if (!source.ok()) return source.error();
    const fs::path out = scratch / (c.name + "-" + std::to_string(r));
    auto summary = capture::RecordClip(**source, out, options);
    std::error_code ec;
    fs::remove_all(out, ec);
    if (!summary.ok()) return summary.error();
    const capture::RecordStageTimes& t = summary->stage_times;
    Append(source_ms, t.source_ms);
    Append(segment_ms, t.segment_ms);
    Append(slam_ms, t.slam_ms);
    Append(encode_ms, t.encode_ms);
    Append(map_ms, t.map_ms);
    for (size_t k = 0; k < t.slam_ms.size(); ++k)
      pipeline_ms.push_back(t.segment_ms[k] + t.slam_ms[k] + t.encode_ms[k] + t.map_ms[k]);
    once_ms.push_back(t.model_ms + t.write_ms);
    last = std::move(summary).value();
  }
  double mean = 0;
  for (double ms : pipeline_ms) mean += ms / pipeline_ms.size();
  report.rows.push_back(proto::ReportRow{}
                            .Add("case", c.name)
                            .Add("frames", static_cast<long long>(last.frames))
                            .Add("source_ms", Median(source_ms))
                            .Add("segment_ms", Median(segment_ms))
                            .Add("slam_ms", Median(slam_ms))
                            .Add("encode_ms", Median(encode_ms))
                            .Add("map_ms", Median(map_ms))
                            .Add("pipeline_ms", Median(pipeline_ms))
                            .Add("pipeline_mean_ms", mean)
                            .Add("fps", mean > 0 ? 1000 / mean : 0.0)
                            .Add("per_clip_ms", Median(once_ms))
                            .Add("kb_per_frame", last.frame_bytes / 1024.0 / last.frames)
                            .Add("map_points", static_cast<long long>(last.map_points)));
  return {};
}

}  // namespace

int RunCaptureBench(const CommandLine& cl) {
  const auto fail = [](const Error& e) { return ReportFailure("reenact-bench", e); };
  const auto repeats = cl.GetInt("repeats", 3);
  if (!repeats.ok()) return fail(repeats.error());
  const auto frames = cl.GetInt("frames", 90);
  if (!frames.ok()) return fail(frames.error());
  if (*repeats < 1 || *frames < 1)
    return fail(MakeError("usage", "--repeats and --frames must be >= 1"));

  std::vector<Case> cases = {
      {"synthetic-source-poses",
       [](capture::RecordOptions&) { return capture::SyntheticSource::Open("turn-and-kick"); }},
      {"synthetic-as-sensor",
       [](capture::RecordOptions& o) { return AsRealSensor("turn-and-kick", o); }},
      {"handheld-as-sensor",
       [](capture::RecordOptions& o) { return AsRealSensor("walk-handheld", o); }},
  };
  if (const auto tum = cl.Get("tum")) {
    Skeleton far_away;  // beyond the Kinect's range: nobody to segment, SLAM sees everything
    for (int j = 0; j < kJointCount; ++j) far_away.Set(static_cast<Joint>(j), {0.01 * j, 0, 10});
    cases.push_back({"tum", [dir = *tum, far_away](capture::RecordOptions& o) {
                       o.skeletons = [far_away](int64_t, double) { return far_away; };
                       return capture::OpenFrameSource("tum:" + dir + "?undistort=both");
                     }});
  }
  const fs::path scratch =
      fs::temp_directory_path() / ("reenact-bench-capture-" + std::to_string(getpid()));
  proto::Report report{"capture", {}};
  Status status;
  for (const Case& c : cases) {
    status = AddCaseRow(report, c, static_cast<int>(*frames), static_cast<int>(*repeats), scratch);
    if (!status.ok()) break;
  }
  std::error_code ec;
  fs::remove_all(scratch, ec);
  if (!status.ok()) return fail(status.error());
  const Status printed = report.Print(cl.Get("json"));
  return printed.ok() ? 0 : fail(printed.error());
}

}  // namespace reenact::bench
