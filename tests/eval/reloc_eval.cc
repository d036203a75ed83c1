#include "tests/eval/reloc_eval.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <numbers>
#include <opencv2/imgproc.hpp>

#include "capture-client/record/clip_recorder.h"
#include "capture-client/source/synthetic_source.h"
#include "common/error/check.h"
#include "proto/clip/clip_directory.h"
#include "synthetic/synthetic_scene.h"
#include "tests/eval/quality_cli.h"
#include "viewer-client/camera/synthetic_camera_source.h"

namespace reenact::eval {
namespace {

namespace fs = std::filesystem;

double Quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const double pos = q * (v.size() - 1);
  const size_t lo = static_cast<size_t>(std::floor(pos));
  const size_t hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (pos - lo) * (v[hi] - v[lo]);
}

// Records the scenario into a temporary clip directory and reads its map back.
Expected<proto::ClipMap> RecordMap(const RelocEvalOptions& o,
                                   const capture::SyntheticBodySpec& body) {
  auto source = capture::SyntheticSource::Open(o.scenario, 1, body);
  if (!source.ok()) return source.error();
  const fs::path dir =
      fs::temp_directory_path() / ("reenact-eval-reloc-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  capture::RecordOptions record;
  record.max_frames = o.record_frames;
  auto recorded = capture::RecordClip(**source, dir / "clip", record);
  Expected<proto::ClipMap> map = recorded.ok() ? [&]() -> Expected<proto::ClipMap> {
    auto clip = proto::ReadClipDirectory(dir / "clip");
    if (!clip.ok()) return clip.error();
    return clip->ReadMap();
  }()
      : Expected<proto::ClipMap>(recorded.error());
  std::error_code ec;
  fs::remove_all(dir, ec);
  return map;
}

cv::Mat Gray(const ImageRgb8& color) {
  const cv::Mat rgb(color.height, color.width, CV_8UC3, const_cast<uint8_t*>(color.data.data()));
  cv::Mat gray;
  cv::cvtColor(rgb, gray, cv::COLOR_RGB2GRAY);
  return gray;
}

struct FrameOutcome {
  double angle_deg = 0;
  bool posed = false;
  double err_cm = 0, err_deg = 0;
  double ms = 0;
  viewer::RelocStageTimes cpu;
};

std::vector<RelocEvalRow> Rows(const std::string& method, const std::vector<FrameOutcome>& out,
                               double max_deg) {
  struct Band {
    std::string name;
    double lo, hi;
  };
  std::vector<Band> bands;
  for (double lo = 0; lo < max_deg - 1e-9; lo += 15) {
    const double hi = std::min(lo + 15, max_deg);
    char name[32];
    std::snprintf(name, sizeof name, "%g-%g", lo, hi);
    bands.push_back({name, lo, hi});
  }
  bands.push_back({"all", 0, max_deg});
  std::vector<RelocEvalRow> rows;
  for (size_t b = 0; b < bands.size(); ++b) {
    const bool all = b + 1 == bands.size(), last = b + 2 == bands.size();
    RelocEvalRow row;
    row.method = method;
    row.band = bands[b].name;
    std::vector<double> cm, deg, ms, cpu, orb, subpixel, match, refine, reloc, smooth, comparisons;
    int within = 0, posed = 0;
    for (const FrameOutcome& f : out) {
      const double a = std::abs(f.angle_deg);
      const bool in = all || (a >= bands[b].lo && (a < bands[b].hi || (last && a <= bands[b].hi)));
      if (!in) continue;
      ++row.frames;
      ms.push_back(f.ms);
      cpu.push_back(f.cpu.total_ms);
      orb.push_back(f.cpu.orb.detect_ms);
      subpixel.push_back(f.cpu.orb.subpixel_ms);
      match.push_back(f.cpu.match_ms);
      refine.push_back(f.cpu.refine_ms);
      reloc.push_back(f.cpu.relocalise_ms);
      smooth.push_back(f.cpu.smooth_ms);
      comparisons.push_back(static_cast<double>(f.cpu.matching.comparisons));
      if (!f.posed) continue;
      ++posed;
      cm.push_back(f.err_cm);
      deg.push_back(f.err_deg);
      within += f.err_cm <= 2 && f.err_deg <= 1;
    }
    if (row.frames == 0) continue;
    row.within_2cm_1deg = static_cast<double>(within) / row.frames;
    row.tracked_rate = static_cast<double>(posed) / row.frames;
    row.median_err_cm = Quantile(cm, 0.5);
    row.median_err_deg = Quantile(deg, 0.5);
    row.ms_per_frame = Quantile(ms, 0.5);
    row.p99_ms = Quantile(ms, 0.99);
    row.cpu_ms = Quantile(cpu, 0.5);
    row.orb_ms = Quantile(orb, 0.5);
    row.subpixel_ms = Quantile(subpixel, 0.5);
    row.match_ms = Quantile(match, 0.5);
    row.refine_ms = Quantile(refine, 0.5);
    row.reloc_ms = Quantile(reloc, 0.5);
    row.smooth_ms = Quantile(smooth, 0.5);
    row.comparisons = Quantile(comparisons, 0.5);
    rows.push_back(row);
  }
  return rows;
}

}  // namespace

void RelocEvalOptions::Check() const {
  REENACT_CHECK(!scenario.empty(), "scenario must not be empty");
  REENACT_CHECK(viewer_frames == 0 || viewer_frames >= 2, "viewer_frames must be 0 or >= 2");
  REENACT_CHECK(std::isfinite(max_deg) && max_deg > 0 && max_deg <= 90, "max_deg in (0, 90]");
  REENACT_CHECK(record_frames == -1 || record_frames >= 1, "record_frames must be -1 or >= 1");
  REENACT_CHECK(run_track || run_reloc, "at least one method must run");
  relocaliser.Check();
}

Expected<RelocEvalRun> RunRelocEval(const RelocEvalOptions& options) {
  options.Check();
  const capture::SyntheticBodySpec body{.gltf_path = options.body};
  auto scene = capture::SyntheticScene::Create(options.scenario, 1, body);
  if (!scene.ok()) return scene.error();
  auto map = RecordMap(options, body);
  if (!map.ok()) return map.error();
  RelocEvalRun run;
  run.map_points = map->points.size();
  const PinholeCamera camera = scene->sensor_camera();
  // One relocaliser follows the sequence, the other starts from scratch on every frame.
  auto tracker = viewer::Relocaliser::Create(*map, camera, options.relocaliser);
  if (!tracker.ok()) return tracker.error();
  auto fresh_start = viewer::Relocaliser::Create(*map, camera, options.relocaliser);
  if (!fresh_start.ok()) return fresh_start.error();

  const int n = options.viewer_frames > 0 ? options.viewer_frames : scene->frame_count();
  const viewer::SyntheticViewerPath trajectory =
      viewer::MakeSyntheticViewerPath(*scene, n, options.max_deg);
  std::vector<FrameOutcome> tracked, fresh;
  for (int k = 0; k < n; ++k) {
    const Eigen::Isometry3d& truth = trajectory.world_from_viewer[k];
    const cv::Mat gray = Gray(scene->Render(k % scene->frame_count(), camera, truth).color);
    fresh_start->Reset();
    for (viewer::Relocaliser* r : {&*tracker, &*fresh_start}) {
      if (!(r == &*tracker ? options.run_track : options.run_reloc)) continue;
      const auto result = r->ProcessFrame(gray);
      if (!result.ok()) return result.error();
      FrameOutcome f;
      f.angle_deg = trajectory.angle_deg[k];
      f.ms = result->ms;
      f.cpu = result->cpu;
      if (result->viewer_from_world) {
        const Eigen::Isometry3d estimate = result->viewer_from_world->inverse();
        f.posed = true;
        f.err_cm = 100 * (estimate.translation() - truth.translation()).norm();
        f.err_deg = Eigen::AngleAxisd(truth.linear().transpose() * estimate.linear()).angle() *
                    180 / std::numbers::pi;
      }
      (r == &*tracker ? tracked : fresh).push_back(f);
    }
  }
  if (options.run_track) {
    const auto rows = Rows("track", tracked, options.max_deg);
    run.rows.insert(run.rows.end(), rows.begin(), rows.end());
  }
  if (options.run_reloc) {
    const auto rows = Rows("reloc", fresh, options.max_deg);
    run.rows.insert(run.rows.end(), rows.begin(), rows.end());
  }
  return run;
}

proto::Report RelocReport(const RelocEvalRun& run) {
  proto::Report report;
  report.command = "reloc";
  for (const RelocEvalRow& r : run.rows) {
    proto::ReportRow row;
    row.Add("method", r.method)
        .Add("band", r.band)
        .Add("n", static_cast<long long>(r.frames))
        .Add("within_2cm_1deg", r.within_2cm_1deg)
        .Add("tracked_rate", r.tracked_rate)
        .Add("median_err_cm", r.median_err_cm)
        .Add("median_err_deg", r.median_err_deg)
        .Add("ms_per_frame", r.ms_per_frame)
        .Add("p99_ms", r.p99_ms)
        .Add("cpu_ms", r.cpu_ms)
        .Add("orb_ms", r.orb_ms)
        .Add("subpixel_ms", r.subpixel_ms)
        .Add("match_ms", r.match_ms)
        .Add("refine_ms", r.refine_ms)
        .Add("reloc_ms", r.reloc_ms)
        .Add("smooth_ms", r.smooth_ms)
        .Add("comparisons", r.comparisons);
    report.rows.push_back(std::move(row));
  }
  return report;
}

std::set<std::string> RelocFlags() {
  return {"scenario", "body", "frames", "max-deg", "record-frames", "features", "methods", "json"};
}

Expected<RelocCommand> ParseRelocCommand(const CommandLine& cl) {
  RelocCommand command;
  RelocEvalOptions& o = command.options;
  if (auto s = cl.Get("scenario")) {
    if (s->empty()) return MakeError("usage", "--scenario: give a scenario name");
    o.scenario = *s;
  }
  o.body = cl.GetOr("body", "");
  if (o.body == "procedural") o.body.clear();
  const auto frames = cl.GetInt("frames", 0);
  if (!frames.ok()) return frames.error();
  if (cl.Get("frames") && (*frames < 2 || *frames > 1'000'000))
    return MakeError("usage",
                     "--frames must be a whole number >= 2, got " + std::to_string(*frames));
  o.viewer_frames = static_cast<int>(*frames);
  const auto max_deg = cl.GetDouble("max-deg", o.max_deg);
  if (!max_deg.ok()) return max_deg.error();
  if (!(*max_deg > 0 && *max_deg <= 90))
    return MakeError("usage", "--max-deg must be a number in (0, 90] (degrees)");
  o.max_deg = *max_deg;
  const auto record = cl.GetInt("record-frames", -1);
  if (!record.ok()) return record.error();
  if (cl.Get("record-frames") && (*record < 1 || *record > 1'000'000))
    return MakeError("usage",
                     "--record-frames must be a whole number >= 1, got " + std::to_string(*record));
  o.record_frames = static_cast<int>(*record);
  const auto features = cl.GetInt("features", o.relocaliser.features.num_features);
  if (!features.ok()) return features.error();
  if (*features < 100 || *features > 100'000)
    return MakeError("usage", "--features must be a whole number in [100, 100000], got " +
                                  std::to_string(*features));
  o.relocaliser.features.num_features = static_cast<int>(*features);
  if (auto m = cl.Get("methods")) {
    if (*m != "track" && *m != "reloc" && *m != "both")
      return MakeError("usage", "--methods must be track, reloc or both, got '" + *m + "'");
    o.run_track = *m != "reloc";
    o.run_reloc = *m != "track";
  }
  if (auto path = cl.Get("json")) {
    if (Status s = CheckWritableFile("json", *path); !s.ok()) return s.error();
    command.json_path = *path;
  }
  return command;
}

int RunRelocCommand(const CommandLine& cl) {
  const auto command = ParseRelocCommand(cl);
  if (!command.ok()) return ReportFailure("reenact-eval", command.error());
  const auto run = RunRelocEval(command->options);
  if (!run.ok()) return ReportFailure("reenact-eval", run.error());
  std::cout << "scenario " << command->options.scenario << ", map of " << run->map_points
            << " points, " << command->options.relocaliser.features.num_features
            << " features per viewer frame; a frame counts when within 2 cm and 1 degree of the "
               "truth (lost frames count as outside)\n";
  const Status printed = RelocReport(*run).Print(command->json_path);
  if (!printed.ok()) return ReportFailure("reenact-eval", printed.error());
  return 0;
}

}  // namespace reenact::eval
