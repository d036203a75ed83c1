#include "tests/eval/segment_eval.h"

#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "capture-client/segment/mask_overlap.h"
#include "capture-client/segment/person_segmenter.h"
#include "common/estimate/median.h"
#include "synthetic/synthetic_scene.h"
#include "tests/eval/quality_cli.h"

namespace reenact::eval {
namespace {

// CPU time of the calling thread, milliseconds.
double ThreadCpuMs() {
  timespec t{};
  ::clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return t.tv_sec * 1e3 + t.tv_nsec * 1e-6;
}

Expected<SegmentEvalRow> RunScenario(const std::string& name, const SegmentEvalOptions& options) {
  auto scene = capture::SyntheticScene::Create(name, options.seed);
  if (!scene.ok()) return scene.error();
  capture::PersonSegmenter segmenter(scene->sensor_camera(), 0.001, options.segment);
  capture::SyntheticRenderOptions render;
  render.depth_noise = options.depth_noise;

  SegmentEvalRow row;
  row.scenario = name;
  row.depth_noise = options.depth_noise;
  std::vector<double> ious, ms, cpu_ms;
  double precision = 0, recall = 0;
  for (int f = 0; f < scene->frame_count(); f += options.frame_step) {
    const capture::SyntheticView view = scene->RenderSensor(f, render);
    const Eigen::Isometry3d world_from_sensor = scene->world_from_sensor(f);
    const Skeleton skeleton = scene->skeleton_in_world(f).Transformed(world_from_sensor.inverse());
    const double cpu_start = ThreadCpuMs();
    const auto start = std::chrono::steady_clock::now();
    auto result = segmenter.Segment(view.depth, skeleton, {world_from_sensor, scene->world_up()});
    const auto stop = std::chrono::steady_clock::now();
    cpu_ms.push_back(ThreadCpuMs() - cpu_start);
    if (!result.ok()) return result.error();
    ms.push_back(std::chrono::duration<double, std::milli>(stop - start).count());
    const capture::MaskOverlap overlap = capture::CompareMasks(result->mask, view.mask);
    if (ious.empty() || overlap.iou < row.iou_min) row.iou_min = overlap.iou, row.worst_frame = f;
    ious.push_back(overlap.iou);
    precision += overlap.precision;
    recall += overlap.recall;
    row.not_ok_frames += result->status != capture::SegmentStatus::kOk;
    row.floor_fits += result->floor_refitted;
  }
  row.frames = static_cast<int>(ious.size());
  if (row.frames == 0) return row;
  double sum = 0;
  for (double v : ious) sum += v;
  row.iou_mean = sum / row.frames;
  row.precision = precision / row.frames;
  row.recall = recall / row.frames;
  std::vector<double> sorted = ious;
  std::sort(sorted.begin(), sorted.end());
  const size_t rank = static_cast<size_t>(std::ceil(0.1 * row.frames));
  row.iou_p10 = sorted[std::max<size_t>(rank, 1) - 1];
  row.ms_per_frame = ms.empty() ? 0 : Median(ms);
  row.cpu_ms_per_frame = cpu_ms.empty() ? 0 : Median(cpu_ms);
  return row;
}

}  // namespace

Expected<std::vector<SegmentEvalRow>> RunSegmentEval(const SegmentEvalOptions& options) {
  REENACT_CHECK(options.frame_step >= 1, "frame_step must be >= 1");
  options.segment.Check();
  std::vector<SegmentEvalRow> rows;
  for (const std::string& name : options.scenarios) {
    auto row = RunScenario(name, options);
    if (!row.ok()) return row.error();
    rows.push_back(std::move(*row));
  }
  return rows;
}

proto::Report SegmentReport(const std::vector<SegmentEvalRow>& rows) {
  proto::Report report;
  report.command = "segment";
  for (const SegmentEvalRow& r : rows) {
    proto::ReportRow row;
    row.Add("scenario", r.scenario)
        .Add("noise", std::string(r.depth_noise ? "on" : "off"))
        .Add("n", static_cast<long long>(r.frames))
        .Add("iou", r.iou_mean)
        .Add("iou_min", r.iou_min)
        .Add("iou_p10", r.iou_p10)
        .Add("worst_frame", static_cast<long long>(r.worst_frame))
        .Add("precision", r.precision)
        .Add("recall", r.recall)
        .Add("not_ok", static_cast<long long>(r.not_ok_frames))
        .Add("floor_fits", static_cast<long long>(r.floor_fits))
        .Add("ms_per_frame", r.ms_per_frame)
        .Add("cpu_ms_per_frame", r.cpu_ms_per_frame);
    report.rows.push_back(std::move(row));
  }
  return report;
}

std::set<std::string> SegmentFlags() { return {"scenario", "step", "json", "noise"}; }

Expected<SegmentCommand> ParseSegmentCommand(const CommandLine& cl) {
  SegmentCommand command;
  SegmentEvalOptions& o = command.options;
  if (auto text = cl.Get("scenario")) {
    o.scenarios.clear();
    std::stringstream ss(*text);
    for (std::string item; std::getline(ss, item, ',');) o.scenarios.push_back(item);
    if (text->empty() || text->back() == ',') o.scenarios.emplace_back();
    for (const std::string& name : o.scenarios)
      if (name.empty())
        return MakeError("usage", "--scenario: empty name in '" + *text +
                                      "' (give a scenario or a comma-separated list)");
  }
  const auto step = cl.GetInt("step", o.frame_step);
  if (!step.ok()) return step.error();
  if (*step < 1 || *step > 1'000'000)
    return MakeError("usage", "--step must be a whole number >= 1 (every K-th frame), got " +
                                  std::to_string(*step));
  o.frame_step = static_cast<int>(*step);
  if (auto noise = cl.Get("noise")) {
    if (*noise != "on" && *noise != "off")
      return MakeError("usage", "--noise must be on or off, got '" + *noise + "'");
    o.depth_noise = *noise == "on";
  }
  if (auto path = cl.Get("json")) {
    if (Status s = CheckWritableFile("json", *path); !s.ok()) return s.error();
    command.json_path = *path;
  }
  return command;
}

}  // namespace reenact::eval
