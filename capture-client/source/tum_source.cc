#include "capture-client/source/tum_source.h"

#include <cmath>
#include <future>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "capture-client/slam/rolling_shutter.h"
#include "capture-client/source/source_argument.h"

namespace reenact::capture {
namespace {

namespace fs = std::filesystem;

std::string DirectoryName(const fs::path& dir) {
  fs::path p = dir;
  if (!p.has_filename()) p = p.parent_path();  // "DIR/"
  std::error_code ec;
  const fs::path canonical = fs::weakly_canonical(p, ec);
  return (ec ? p : canonical).filename().string();
}

// Every listed image must exist before the first frame is read: a partial download fails
// here, not minutes into a run.
Status CheckListedImagesExist(const fs::path& dir, const TumFrameList& list) {
  std::error_code ec;
  size_t missing = 0;
  std::string first_missing;
  for (const TumFramePair& f : list.frames)
    for (const std::string* file : {&f.color_file, &f.depth_file})
      if (!fs::is_regular_file(dir / *file, ec) && missing++ == 0) first_missing = *file;
  if (missing > 0)
    return MakeError("not_found", "tum:" + dir.string() + ": " + first_missing + ", listed in " +
                                      list.listed_in + ", does not exist (" +
                                      std::to_string(missing) +
                                      " listed image(s) missing); the sequence is incomplete: "
                                      "unpack it again");
  return {};
}

std::string CameraNote(const PinholeCamera& raw, bool undistorted,
                       TumSourceOptions::Undistort undistort) {
  if (raw.distortion.IsZero()) return "images undistorted at the source";
  if (!undistorted) return "images not undistorted (camera with distortion)";
  if (undistort == TumSourceOptions::Undistort::kBoth)
    return "colour and depth undistorted (undistorted camera)";
  return "colour undistorted (undistorted camera), depth as recorded";
}

}  // namespace

void TumSourceOptions::Check() const {
  REENACT_CHECK(std::isfinite(max_association_gap_s) && max_association_gap_s >= 0,
                "max_association_gap_s must be finite and >= 0");
  REENACT_CHECK(std::isfinite(max_ground_truth_gap_s) && max_ground_truth_gap_s > 0,
                "max_ground_truth_gap_s must be finite and > 0");
  REENACT_CHECK(max_leading_empty_depth_frames >= 1, "max_leading_empty_depth_frames >= 1");
}

Expected<std::unique_ptr<TumSource>> TumSource::Open(const fs::path& dir,
                                                     const TumSourceOptions& options) {
  options.Check();
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    return MakeError("not_found", "tum:" + dir.string() +
                                      ": no such directory; tum:DIR needs an unpacked TUM "
                                      "RGB-D sequence (rgbd_dataset_freiburg*_*)");
  std::unique_ptr<TumSource> source(new TumSource());
  source->dir_ = dir;
  source->options_ = options;
  if (options.camera) {
    source->camera_ = *options.camera;
  } else if (auto detected = DetectTumCamera(DirectoryName(dir))) {
    source->camera_ = *detected;
  } else {
    return MakeError("usage", "tum:" + dir.string() +
                                  ": cannot tell which TUM Kinect "
                                  "recorded it from the directory name '" +
                                  DirectoryName(dir) +
                                  "' (no single freiburg1/2/3 or fr1/2/3 in it); name it, e.g. "
                                  "tum:DIR?camera=fr1");
  }

  auto list = ReadTumFrameList(dir, options.max_association_gap_s);
  if (!list.ok()) return list.error();
  source->frames_ = std::move(list).value();
  if (Status exist = CheckListedImagesExist(dir, source->frames_); !exist.ok())
    return exist.error();
  if (Status loaded = source->LoadGroundTruth(); !loaded.ok()) return loaded.error();
  source->DescribeSensor();
  source->depth_guard_ = DepthPresenceGuard(options.max_leading_empty_depth_frames);
  return source;
}

Status TumSource::LoadGroundTruth() {
  std::error_code ec;
  const fs::path gt = dir_ / "groundtruth.txt";
  if (fs::is_regular_file(gt, ec)) {
    auto samples = ReadTumTrajectory(gt);
    if (!samples.ok()) return samples.error();
    ground_truth_samples_ = std::move(samples).value();
    has_ground_truth_ = true;
  }
  for (const TumFramePair& f : frames_.frames)
    ground_truth_.push_back(has_ground_truth_
                                ? InterpolatePose(ground_truth_samples_, f.color_time_s,
                                                  options_.max_ground_truth_gap_s)
                                : std::nullopt);
  return {};
}

void TumSource::DescribeSensor() {
  const PinholeCamera raw = TumColorCamera(camera_);
  SensorInfo& info = info_;
  if (options_.undistort == TumSourceOptions::Undistort::kNone || raw.distortion.IsZero()) {
    info.color_camera = raw;
  } else {
    undistorter_.emplace(raw);
    info.color_camera = undistorter_->undistorted_camera();
  }
  info.depth_camera = info.color_camera;
  info.depth_scale_m = 0.001;
  const auto& frames = frames_.frames;
  info.frame_count = static_cast<int>(frames.size());
  const double span = frames.back().color_time_s - frames.front().color_time_s;
  info.frame_rate_hz = frames.size() >= 2 && span > 0 ? (frames.size() - 1) / span : 30;
  info.color_readout_ratio = slam::kKinectV1ReadoutRatio;  // every TUM RGB-D camera is one
  const std::string camera_note = CameraNote(raw, undistorter_.has_value(), options_.undistort);
  info.description = "tum:" + dir_.string() + " (" + std::string(TumCameraName(camera_)) + ", " +
                     std::to_string(frames.size()) + " frames from " + frames_.listed_in + ", " +
                     camera_note + ", " + (has_ground_truth_ ? "with" : "without") +
                     " ground truth)";
}

Expected<std::unique_ptr<TumSource>> TumSource::OpenSpec(const std::string& argument) {
  auto arg = ParseSourceArgument("tum", argument, {"camera", "undistort"});
  if (!arg.ok()) return arg.error();
  if (arg->path.empty())
    return MakeError("usage",
                     "--source tum:DIR needs a sequence directory, e.g. "
                     "tum:rgbd_dataset_freiburg1_xyz");
  TumSourceOptions options;
  if (auto it = arg->options.find("camera"); it != arg->options.end()) {
    auto camera = ParseTumCamera(it->second);
    if (!camera.ok()) return camera.error();
    options.camera = *camera;
  }
  if (auto it = arg->options.find("undistort"); it != arg->options.end()) {
    const std::string& v = it->second;
    if (v == "color" || v == "colour" || v == "1")
      options.undistort = TumSourceOptions::Undistort::kColor;
    else if (v == "both")
      options.undistort = TumSourceOptions::Undistort::kBoth;
    else if (v == "none" || v == "0")
      options.undistort = TumSourceOptions::Undistort::kNone;
    else
      return MakeError("usage", "tum: undistort=" + v + " must be color, both or none");
  }
  return Open(arg->path, options);
}

Expected<std::optional<SensorFrame>> TumSource::Next() {
  if (next_ >= frames_.frames.size()) {
    if (Status s = depth_guard_.AtEnd(info_.description); !s.ok()) return s.error();
    return std::optional<SensorFrame>();
  }
  const size_t index = next_;
  const TumFramePair& pair = frames_.frames[index];
  const std::string where = "tum:" + dir_.string() + " frame " + std::to_string(index);
  const fs::path color_path = dir_ / pair.color_file, depth_path = dir_ / pair.depth_file;

  for (const auto* p : {&color_path, &depth_path}) {
    std::error_code ec;
    if (!fs::is_regular_file(*p, ec))
      return MakeError("not_found", where + ": " + p->string() + " no longer exists");
  }
  // PNG decoding is nearly all of a frame's time: the two images decode concurrently.
  auto depth_read = std::async(std::launch::async, [&depth_path] {
    return cv::imread(depth_path.string(), cv::IMREAD_UNCHANGED);
  });
  const cv::Mat bgr = cv::imread(color_path.string(), cv::IMREAD_COLOR);
  const cv::Mat raw_depth = depth_read.get();
  if (bgr.empty())
    return MakeError("corrupt", where + ": " + color_path.string() +
                                    " is not a readable image; the sequence is damaged");
  if (raw_depth.empty())
    return MakeError("corrupt", where + ": " + depth_path.string() +
                                    " is not a readable image; the sequence is damaged");
  if (raw_depth.type() != CV_16UC1)
    return MakeError("corrupt", where + ": " + depth_path.string() +
                                    " is not a 16-bit single-channel PNG (TUM depth: value / "
                                    "5000 = metres)");

  SensorFrame frame;
  frame.timestamp_s = pair.color_time_s;
  frame.color = ImageRgb8(bgr.cols, bgr.rows, 3);
  cv::cvtColor(bgr, cv::Mat(bgr.rows, bgr.cols, CV_8UC3, frame.color.data.data()),
               cv::COLOR_BGR2RGB);
  frame.depth = ImageDepthMm(raw_depth.cols, raw_depth.rows, 1);
  for (int y = 0; y < raw_depth.rows; ++y) {
    const uint16_t* in = raw_depth.ptr<uint16_t>(y);
    uint16_t* out = &frame.depth.at(0, y);
    for (int x = 0; x < raw_depth.cols; ++x)
      out[x] = static_cast<uint16_t>((static_cast<uint32_t>(in[x]) + 2) / 5);  // /5000 m -> mm
  }
  if (Status s = CheckRegisteredPair(frame.color, frame.depth, info_.color_camera, where); !s.ok())
    return s.error();
  if (undistorter_) {
    frame.color = undistorter_->Undistort(frame.color);
    if (options_.undistort == TumSourceOptions::Undistort::kBoth)
      frame.depth = undistorter_->UndistortDepth(frame.depth);
  }
  if (Status s = depth_guard_.Observe(frame.depth, info_.description); !s.ok()) return s.error();
  ++next_;
  return std::optional<SensorFrame>(std::move(frame));
}

}  // namespace reenact::capture
