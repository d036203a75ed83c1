#include "tests/eval/slam_eval.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <limits>
#include <numbers>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "capture-client/slam/opencv_odometry.h"
#include "capture-client/slam/rgbd_slam.h"
#include "capture-client/source/tum_source.h"
#include "common/align/trajectory_error.h"
#include "common/estimate/median.h"
#include "common/geometry/rotation.h"
#include "proto/clip/map_codec.h"
#include "tests/eval/quality_cli.h"

namespace reenact::eval {
namespace {

namespace fs = std::filesystem;
using capture::SensorFrame;
using capture::TumSource;
using capture::TumSourceOptions;
using capture::slam::OdometryMethod;
using capture::slam::OpenCvOdometry;
using capture::slam::OpenCvOdometryOptions;
using capture::slam::RgbdSlam;
using capture::slam::SlamOptions;
using capture::slam::SlamStatus;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

const std::vector<std::string>& KnownMethods() {
  static const std::vector<std::string> methods = {"reenact", "opencv-rgbd", "opencv-fasticp"};
  return methods;
}

std::string JoinMethods() {
  std::string out;
  for (const std::string& m : KnownMethods()) out += (out.empty() ? "" : ", ") + m;
  return out;
}

Expected<std::unique_ptr<TumSource>> OpenSequence(const SlamEvalOptions& options) {
  TumSourceOptions o;
  o.undistort = TumSourceOptions::Undistort::kNone;  // each method undistorts as it needs
  if (options.camera) {
    auto camera = capture::ParseTumCamera(*options.camera);
    if (!camera.ok()) return camera.error();
    o.camera = *camera;
  }
  return TumSource::Open(options.tum_dir, o);
}

// A method's poses (world_from_sensor, nullopt when it had none) and per-frame times.
struct Trajectory {
  std::vector<std::optional<Eigen::Isometry3d>> poses;
  std::vector<double> ms;
};

void Score(const Trajectory& t, const std::vector<std::optional<Eigen::Isometry3d>>& truth,
           SlamMethodResult& r) {
  r.frames = static_cast<int>(t.poses.size());
  std::vector<Eigen::Isometry3d> gt, est;
  double rpe_t2 = 0, rpe_r2 = 0;
  int rpe_n = 0;
  std::optional<size_t> previous;
  for (size_t i = 0; i < t.poses.size(); ++i) {
    if (t.poses[i]) ++r.tracked;
    if (!t.poses[i] || i >= truth.size() || !truth[i]) {
      previous.reset();
      continue;
    }
    gt.push_back(*truth[i]);
    est.push_back(*t.poses[i]);
    if (previous) {
      const Eigen::Isometry3d dt = truth[*previous]->inverse() * *truth[i];
      const Eigen::Isometry3d de = t.poses[*previous]->inverse() * *t.poses[i];
      const Eigen::Isometry3d e = dt.inverse() * de;
      rpe_t2 += e.translation().squaredNorm();
      const double deg = RotationAngle(e.linear()) * 180 / std::numbers::pi;
      rpe_r2 += deg * deg;
      ++rpe_n;
    }
    previous = i;
  }
  r.evaluated = static_cast<int>(gt.size());
  r.ate_rmse_m = kNaN;
  if (gt.size() >= 3) {
    const TrajectoryErrorResult ate = AbsoluteTrajectoryError(gt, est);
    if (ate.ok()) r.ate_rmse_m = ate.ate_rmse_m;
  }
  r.rpe_m = rpe_n > 0 ? std::sqrt(rpe_t2 / rpe_n) : kNaN;
  r.rpe_deg = rpe_n > 0 ? std::sqrt(rpe_r2 / rpe_n) : kNaN;
  r.ms_per_frame = t.ms.empty() ? kNaN : UpperMedian(t.ms);
  r.ms_p90 = t.ms.empty() ? kNaN : Percentile(t.ms, 0.9);
}

using Clock = std::chrono::steady_clock;
double MsSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// Calls visit(frame) for the first max_frames frames of a fresh pass over the sequence.
template <typename Visit>
Status ForEachFrame(const SlamEvalOptions& options, Visit visit) {
  auto source = OpenSequence(options);
  if (!source.ok()) return source.error();
  for (int i = 0; options.max_frames < 0 || i < options.max_frames; ++i) {
    auto next = (*source)->Next();
    if (!next.ok()) return next.error();
    if (!next->has_value()) break;
    visit(**next);
  }
  return {};
}

Expected<SlamMethodResult> RunOurs(const SlamEvalOptions& options, const capture::SensorInfo& info,
                                   Trajectory& t) {
  SlamOptions so;
  so.readout_ratio = options.readout_ratio;
  RgbdSlam slam(info.color_camera, info.depth_scale_m, so);
  SlamMethodResult r;
  r.method = "reenact";
  std::optional<Error> failure;
  const Status pass = ForEachFrame(options, [&](const SensorFrame& f) {
    if (failure) return;
    const auto start = Clock::now();
    const auto result = slam.Track(f.timestamp_s, f.color, f.depth);
    const double ms = MsSince(start);
    if (!result.ok()) {
      failure = result.error();
      return;
    }
    t.ms.push_back(ms);
    t.poses.push_back(result->world_from_sensor);
    r.keyframes += result->keyframe;
    r.fallback_frames += result->status == SlamStatus::kOdometryFallback;
    r.relocalised_frames += result->status == SlamStatus::kRelocalised;
  });
  if (!pass.ok()) return pass.error();
  if (failure) return *failure;
  const proto::ClipMap map = slam.ExportClipMap();
  r.map_points = static_cast<int>(map.points.size());
  if (!map.points.empty()) {
    const auto bytes = proto::EncodeMap(map, proto::MapCodecOptions{});
    if (!bytes.ok()) return bytes.error();
    r.map_bytes = static_cast<long long>(bytes->size());
  }
  return r;
}

Expected<SlamMethodResult> RunOpenCv(const SlamEvalOptions& options,
                                     const capture::SensorInfo& info, OdometryMethod method,
                                     Trajectory& t) {
  OpenCvOdometryOptions oo;
  oo.method = method;
  const OpenCvOdometry odometry(info.color_camera, info.depth_scale_m, oo);
  SlamMethodResult r;
  r.method = method == OdometryMethod::kRgbd ? "opencv-rgbd" : "opencv-fasticp";
  cv::Ptr<cv::rgbd::OdometryFrame> previous;
  Eigen::Isometry3d world_from_sensor = Eigen::Isometry3d::Identity();
  const Status pass = ForEachFrame(options, [&](const SensorFrame& f) {
    const auto start = Clock::now();
    const cv::Mat rgb(f.color.height, f.color.width, CV_8UC3,
                      const_cast<uint8_t*>(f.color.data.data()));
    cv::Mat gray;
    cv::cvtColor(rgb, gray, cv::COLOR_RGB2GRAY);
    cv::Ptr<cv::rgbd::OdometryFrame> current = odometry.Prepare(gray, f.depth, nullptr);
    std::optional<Eigen::Isometry3d> pose;
    if (!previous) {
      pose = world_from_sensor;  // the first frame defines the world
    } else if (const auto current_from_previous = odometry.Compute(previous, current)) {
      world_from_sensor = world_from_sensor * current_from_previous->inverse();
      pose = world_from_sensor;
    }
    previous = current;
    t.ms.push_back(MsSince(start));
    t.poses.push_back(pose);
  });
  if (!pass.ok()) return pass.error();
  return r;
}

Expected<std::vector<std::string>> ParseMethods(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream ss(text);
  for (std::string item; std::getline(ss, item, ',');) {
    if (std::find(KnownMethods().begin(), KnownMethods().end(), item) == KnownMethods().end())
      return MakeError("usage",
                       "--methods: unknown method '" + item + "' (known: " + JoinMethods() + ")");
    if (std::find(out.begin(), out.end(), item) == out.end()) out.push_back(item);
  }
  if (out.empty() || text.empty() || text.back() == ',')
    return MakeError("usage", "--methods: give a comma-separated list of " + JoinMethods());
  return out;
}

}  // namespace

std::set<std::string> SlamFlags() {
  return {"tum", "camera", "max-frames", "methods", "readout-ratio", "json"};
}

Expected<SlamCommand> ParseSlamCommand(const CommandLine& cl) {
  SlamCommand c;
  const auto tum = cl.Get("tum");
  if (!tum || tum->empty())
    return MakeError("usage",
                     "slam needs --tum DIR (a TUM RGB-D sequence folder, e.g. "
                     "../shared/data/tum-fr1-rpy-head)");
  c.options.tum_dir = *tum;
  c.options.camera = cl.Get("camera");
  if (c.options.camera && !capture::ParseTumCamera(*c.options.camera).ok())
    return MakeError("usage", "--camera: '" + *c.options.camera + "' is not fr1, fr2 or fr3");
  const auto max_frames = cl.GetInt("max-frames", -1);
  if (!max_frames.ok()) return max_frames.error();
  if (cl.Has("max-frames") && (*max_frames < 3 || *max_frames > 1'000'000))
    return MakeError("usage", "--max-frames: give an integer >= 3 (an ATE needs 3 poses)");
  c.options.max_frames = static_cast<int>(*max_frames);
  if (const auto methods = cl.Get("methods")) {
    auto parsed = ParseMethods(*methods);
    if (!parsed.ok()) return parsed.error();
    c.options.methods = *parsed;
  }
  const auto ratio = cl.GetDouble("readout-ratio", kKinectReadoutRatio);
  if (!ratio.ok()) return ratio.error();
  if (!(*ratio >= 0 && *ratio <= 1))
    return MakeError("usage", "--readout-ratio: give a number in [0, 1] (0: global shutter)");
  c.options.readout_ratio = *ratio;
  c.json_path = cl.Get("json");
  if (c.json_path) {
    if (Status s = CheckWritableFile("json", *c.json_path); !s.ok()) return s.error();
  }
  return c;
}

Expected<SlamEvalRun> RunSlamEval(const SlamEvalOptions& options) {
  auto source = OpenSequence(options);
  if (!source.ok()) return source.error();
  const capture::SensorInfo info = (*source)->info();
  if (!(*source)->has_ground_truth())
    return MakeError("invalid_argument", options.tum_dir +
                                             ": no groundtruth.txt, so there is nothing to "
                                             "compare the trajectories with");
  SlamEvalRun run;
  run.sequence = fs::path(options.tum_dir).lexically_normal().filename().string();
  if (run.sequence.empty())
    run.sequence = fs::path(options.tum_dir).lexically_normal().parent_path().filename().string();
  run.camera = std::string(capture::TumCameraName((*source)->camera()));
  std::vector<std::optional<Eigen::Isometry3d>> truth = (*source)->ground_truth();
  for (const std::string& method : options.methods) {
    Trajectory t;
    Expected<SlamMethodResult> r =
        method == "reenact"
            ? RunOurs(options, info, t)
            : RunOpenCv(options, info,
                        method == "opencv-rgbd" ? OdometryMethod::kRgbd : OdometryMethod::kFastIcp,
                        t);
    if (!r.ok()) return r.error();
    Score(t, truth, *r);
    run.frames = r->frames;
    run.methods.push_back(*r);
  }
  run.frames_with_truth = 0;
  for (int i = 0; i < run.frames && i < static_cast<int>(truth.size()); ++i)
    run.frames_with_truth += truth[i].has_value();
  return run;
}

proto::Report SlamReport(const SlamEvalRun& run) {
  proto::Report report;
  report.command = "slam";
  for (const SlamMethodResult& m : run.methods) {
    proto::ReportRow row;
    row.Add("method", m.method)
        .Add("sequence", run.sequence)
        .Add("n", static_cast<long long>(m.frames))
        .Add("tracked_rate", m.frames > 0 ? static_cast<double>(m.tracked) / m.frames : kNaN)
        .Add("ate_rmse_m", m.ate_rmse_m)
        .Add("rpe_m", m.rpe_m)
        .Add("rpe_deg", m.rpe_deg)
        .Add("ms_per_frame", m.ms_per_frame)
        .Add("ms_p90", m.ms_p90)
        .Add("fps", m.ms_per_frame > 0 ? 1000.0 / m.ms_per_frame : kNaN);
    if (m.method == "reenact") {
      row.Add("keyframes", static_cast<long long>(m.keyframes))
          .Add("fallback_frames", static_cast<long long>(m.fallback_frames))
          .Add("relocalised_frames", static_cast<long long>(m.relocalised_frames))
          .Add("map_points", static_cast<long long>(m.map_points))
          .Add("map_bytes", m.map_bytes);
    }
    report.rows.push_back(std::move(row));
  }
  return report;
}

std::vector<std::string> SlamRules() {
  return {
      "ate_rmse_m: RMSE of positions after rigid Umeyama alignment to the ground truth, over "
      "frames with a pose and a ground-truth pose; rpe_m / rpe_deg: RMSE per consecutive pair",
      "tracked_rate: frames with a pose / frames (a failed OpenCV odometry step, or a lost "
      "frame of ours, has none)",
      "ms_per_frame: median wall time of a method's per-frame work on this machine (image "
      "decoding excluded), fps = 1000 / ms_per_frame",
      "input: raw colour and depth of the sequence; ours undistorts keypoints, the OpenCV "
      "odometries get both images undistorted (depth by nearest neighbour)",
  };
}

int RunSlamCommand(const CommandLine& cl) {
  const auto command = ParseSlamCommand(cl);
  if (!command.ok()) return ReportFailure("reenact-eval", command.error());
  const auto run = RunSlamEval(command->options);
  if (!run.ok()) return ReportFailure("reenact-eval", run.error());
  std::cout << "sequence " << run->sequence << " (" << run->camera << "), " << run->frames
            << " frames, " << run->frames_with_truth << " with ground truth\n";
  const Status printed = SlamReport(*run).Print(command->json_path);
  for (const std::string& rule : SlamRules()) std::cout << rule << "\n";
  if (!printed.ok()) return ReportFailure("reenact-eval", printed.error());
  return 0;
}

}  // namespace reenact::eval
