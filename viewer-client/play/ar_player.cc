#include "viewer-client/play/ar_player.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "common/error/check.h"
#include "common/estimate/median.h"
#include "viewer-client/output/contact_sheet.h"
#include "viewer-client/output/mp4_writer.h"
#include "viewer-client/output/png_writer.h"
#include "viewer-client/output/render_json.h"
#include "viewer-client/play/ar_pipeline.h"

namespace reenact::viewer {
namespace {

std::string SizeText(int w, int h) { return std::to_string(w) + "x" + std::to_string(h); }

cv::Mat Wrap(ImageRgb8& image) {
  return cv::Mat(image.height, image.width, CV_8UC3, image.data.data());
}

using Clock = std::chrono::steady_clock;

double MsSince(Clock::time_point t) {
  return 1e3 * std::chrono::duration<double>(Clock::now() - t).count();
}

// The camera image as an ideal pinhole (same K) image.
ImageRgb8 Undistorted(const ImageRgb8& image, const PinholeCamera& camera) {
  if (camera.distortion.IsZero()) return image;
  const cv::Matx33d k(camera.fx, 0, camera.cx, 0, camera.fy, camera.cy, 0, 0, 1);
  const Distortion& d = camera.distortion;
  const cv::Vec<double, 5> coefficients(d.k1, d.k2, d.p1, d.p2, d.k3);
  ImageRgb8 out(image.width, image.height, 3);
  const cv::Mat in(image.height, image.width, CV_8UC3, const_cast<uint8_t*>(image.data.data()));
  cv::Mat dst = Wrap(out);
  cv::undistort(in, dst, k, coefficients, k);
  return out;
}

}  // namespace

std::string_view ClipClockName(ClipClock clock) {
  return clock == ClipClock::kCameraTime ? "time" : "frames";
}

void ArFrameOptions::Check() const { relocaliser.Check(); }

void ArPlayOptions::Check() const {
  REENACT_CHECK(!out_dir.empty(), "out_dir must be set");
  REENACT_CHECK(max_frames == -1 || max_frames >= 1, "max_frames must be -1 or >= 1");
  REENACT_CHECK(contact_sheet_columns >= 1, "contact_sheet_columns must be >= 1");
  REENACT_CHECK(contact_sheet_thumb_width >= 16, "contact_sheet_thumb_width must be >= 16");
  frame.Check();
}

ArCompositor::ArCompositor(const Reenactment& reenactment, Relocaliser relocaliser,
                           const PinholeCamera& camera, Renderer& renderer,
                           const ArFrameOptions& options)
    : reenactment_(reenactment),
      relocaliser_(std::move(relocaliser)),
      camera_(camera),
      render_camera_(camera),
      renderer_(renderer),
      options_(options),
      textures_(renderer, reenactment) {
  render_camera_.distortion = Distortion{};
}

Expected<ArCompositor> ArCompositor::Create(const Reenactment& reenactment, proto::ClipMap map,
                                            const PinholeCamera& camera, Renderer& renderer,
                                            const ArFrameOptions& options) {
  options.Check();
  try {
    camera.Check();
  } catch (const CheckError& e) {
    return MakeError("invalid_argument", std::string("viewer camera: ") + e.what());
  }
  if (renderer.width() != camera.width || renderer.height() != camera.height)
    return MakeError("invalid_argument",
                     "renderer is " + SizeText(renderer.width(), renderer.height()) +
                         ", the camera " + SizeText(camera.width, camera.height));
  if (reenactment.frame_count() < 1)
    return MakeError("invalid_argument", "the clip has no frames to reenact");
  const size_t points = map.points.size();
  if (points < static_cast<size_t>(std::max(4, options.relocaliser.min_map_points)))
    return MakeError("map_too_small",
                     "the clip's map has " + std::to_string(points) +
                         " points, relocalisation needs at least " +
                         std::to_string(std::max(4, options.relocaliser.min_map_points)) +
                         ": this clip cannot be placed in AR (was the background textured and "
                         "in view while recording?); use --camera orbit to watch it");
  auto relocaliser = Relocaliser::Create(std::move(map), camera, options.relocaliser);
  if (!relocaliser.ok()) return relocaliser.error();
  return ArCompositor(reenactment, std::move(relocaliser).value(), camera, renderer, options);
}

void ArCompositor::SetPresentation(bool textured, bool draw_skeleton) {
  options_.textured = textured;
  options_.draw_skeleton = draw_skeleton;
}

Expected<ArFrame> ArCompositor::Process(const CameraFrame& frame, std::optional<int> clip_frame) {
  auto located = Locate(frame);
  if (!located.ok()) return located.error();
  return Compose(std::move(located).value(), clip_frame);
}

Expected<ArLocatedFrame> ArCompositor::Locate(CameraFrame frame) {
  const ImageRgb8& image = frame.color;
  if (image.data.empty() || image.width <= 0 || image.height <= 0)
    return MakeError("invalid_argument", "camera frame " + std::to_string(frames_) + " is empty");
  if (image.channels != 3)
    return MakeError("invalid_argument", "camera frame " + std::to_string(frames_) + " has " +
                                             std::to_string(image.channels) +
                                             " channels, RGB has 3");
  if (image.width != camera_.width || image.height != camera_.height)
    return MakeError("invalid_argument",
                     "camera frame " + std::to_string(frames_) + " is " +
                         SizeText(image.width, image.height) + " but the calibration is for " +
                         SizeText(camera_.width, camera_.height) +
                         ": use the calibration of this camera at this resolution");
  if (!std::isfinite(frame.timestamp_s))
    return MakeError("invalid_argument",
                     "camera frame " + std::to_string(frames_) + " has no finite timestamp");

  const auto start = Clock::now();
  ArLocatedFrame located;
  ArFrame& out = located.frame;
  out.camera_frame = frames_++;
  out.timestamp_s = frame.timestamp_s;
  if (!first_timestamp_s_) first_timestamp_s_ = frame.timestamp_s;
  const int count = reenactment_.frame_count();
  if (options_.clock == ClipClock::kFrameIndex) {
    out.clip_frame = out.camera_frame % count;
  } else {
    const double elapsed = std::max(0.0, frame.timestamp_s - *first_timestamp_s_);
    // The small epsilon keeps a timestamp exactly on a frame boundary on that frame.
    const double index = std::floor(elapsed * reenactment_.manifest().frame_rate_hz + 1e-6);
    out.clip_frame = static_cast<int>(std::fmod(index, static_cast<double>(count)));
  }

  auto reloc = relocaliser_.ProcessFrame(image);
  if (!reloc.ok()) return reloc.error();
  out.reloc = std::move(reloc).value();
  out.true_world_from_viewer = frame.true_world_from_viewer;
  if (out.true_world_from_viewer && out.reloc.viewer_from_world) {
    const Eigen::Isometry3d estimate = out.reloc.viewer_from_world->inverse();
    const Eigen::Isometry3d& truth = *out.true_world_from_viewer;
    out.err_cm = 100 * (estimate.translation() - truth.translation()).norm();
    out.err_deg = Eigen::AngleAxisd(truth.linear().transpose() * estimate.linear()).angle() * 180 /
                  std::numbers::pi;
  }
  located.image = std::move(frame.color);
  out.total_ms = MsSince(start);
  return located;
}

ArFrame ArCompositor::Compose(ArLocatedFrame located, std::optional<int> clip_frame) {
  const auto start = Clock::now();
  ArFrame out = std::move(located.frame);
  REENACT_CHECK(located.image.width == camera_.width && located.image.height == camera_.height &&
                    located.image.channels == 3,
                "Compose takes a frame Locate returned");
  if (clip_frame) {
    REENACT_CHECK(*clip_frame >= 0 && *clip_frame < reenactment_.frame_count(),
                  "clip_frame out of range");
    out.clip_frame = *clip_frame;
  }
  auto t = Clock::now();
  ImageRgb8 background = Undistorted(located.image, camera_);
  out.composite_ms = MsSince(t);
  if (out.reloc.viewer_from_world) {
    t = Clock::now();
    ReenactedFrame rf =
        reenactment_.Build(out.clip_frame, render_camera_, *out.reloc.viewer_from_world,
                           std::ref(textures_), &selection_history_);
    rf.draw.background = &background;
    rf.draw.textured = options_.textured;
    if (!options_.draw_skeleton) rf.draw.bones.clear();
    out.texture_frame = rf.texture_frame;
    out.select_ms = MsSince(t);
    t = Clock::now();
    out.out = renderer_.Render(rf.draw);
    out.render_ms = MsSince(t);
  } else {
    out.out.color = std::move(background);
    out.out.subject_mask = ImageGray8(camera_.width, camera_.height, 1, 0);
  }
  t = Clock::now();
  if (options_.draw_status) DrawArStatus(out.reloc, out.out.color);
  out.composite_ms += MsSince(t);
  out.total_ms += MsSince(start);
  return out;
}

void DrawArStatus(const RelocFrameResult& reloc, ImageRgb8& image) {
  REENACT_CHECK(image.channels == 3 && !image.data.empty(), "status needs an RGB image");
  cv::Mat canvas = Wrap(image);
  const int band = std::min(28, image.height);
  const bool lost = reloc.status == RelocStatus::kLost;
  const cv::Scalar fill = lost ? cv::Scalar(190, 30, 30) : cv::Scalar(20, 120, 40);  // RGB
  char text[160];
  if (lost)
    std::snprintf(text, sizeof text, "LOST - point the camera at the clip's scene");
  else
    std::snprintf(text, sizeof text, "%s - %d inliers",
                  std::string(RelocStatusName(reloc.status)).c_str(), reloc.inliers);
  const int width = lost ? image.width : std::min(image.width, 260);
  cv::rectangle(canvas, cv::Rect(0, 0, width, band), fill, cv::FILLED);
  const double scale = std::clamp(image.width / 1000.0, 0.3, 0.6);
  cv::putText(canvas, text, cv::Point(6, std::max(1, band - 9)), cv::FONT_HERSHEY_SIMPLEX, scale,
              cv::Scalar(255, 255, 255), 1, cv::LINE_AA);
}

void ArSummaryBuilder::Add(const ArFrame& frame) {
  const RelocFrameResult& r = frame.reloc;
  ++counts_.frames;
  counts_.relocalised += r.status == RelocStatus::kRelocalised;
  counts_.tracked += r.status == RelocStatus::kTracked;
  counts_.lost += r.status == RelocStatus::kLost;
  reloc_ms_.push_back(r.ms);
  if (r.viewer_from_world) render_ms_.push_back(frame.render_ms);
  if (!frame.true_world_from_viewer) return;
  ++counts_.truth_frames;
  if (!frame.err_cm || !frame.err_deg) return;
  err_cm_.push_back(*frame.err_cm);
  err_deg_.push_back(*frame.err_deg);
  counts_.within_2cm_1deg += *frame.err_cm <= 2 && *frame.err_deg <= 1;
}

ArPlaySummary ArSummaryBuilder::summary() const {
  const auto median = [](const std::vector<double>& v) { return v.empty() ? 0 : UpperMedian(v); };
  ArPlaySummary s = counts_;
  s.reloc_ms_median = median(reloc_ms_);
  s.render_ms_median = median(render_ms_);
  s.median_err_cm = median(err_cm_);
  s.median_err_deg = median(err_deg_);
  return s;
}

namespace {

// Writes an AR frame's output as frames/frame_NNNN.png (and its subject mask as
// mask_NNNN.png when asked); returns the frame's file name.
Expected<std::string> WriteArFramePngs(const ArFrame& frame, const ArPlayOptions& options) {
  const int i = frame.camera_frame;
  char name[32];
  std::snprintf(name, sizeof name, "frame_%04d.png", i);
  if (Status s = WritePng((options.out_dir / "frames" / name).string(), frame.out.color); !s.ok())
    return s.error();
  if (options.write_masks) {
    char mask[32];
    std::snprintf(mask, sizeof mask, "mask_%04d.png", i);
    if (Status s = WritePng((options.out_dir / "frames" / mask).string(), frame.out.subject_mask);
        !s.ok())
      return s.error();
  }
  return std::string(name);
}

// render.json's entry of an AR frame written as `name`.
nlohmann::json ArFrameJson(const ArFrame& frame, const std::string& name) {
  const RelocFrameResult& r = frame.reloc;
  nlohmann::json f = {
      {"output", frame.camera_frame},
      {"timestamp_s", frame.timestamp_s},
      {"clip_frame", frame.clip_frame},
      {"texture_frame", frame.texture_frame},
      {"state", std::string(RelocStatusName(r.status))},
      {"features", r.features},
      {"matches", r.matches},
      {"inliers", r.inliers},
      {"reloc_ms", r.ms},
      {"reason", r.reason},
      {"world_from_viewer",
       r.viewer_from_world ? PoseJson(r.viewer_from_world->inverse()) : nlohmann::json(nullptr)},
      {"file", std::string("frames/") + name}};
  if (frame.true_world_from_viewer) {
    f["true_world_from_viewer"] = PoseJson(*frame.true_world_from_viewer);
    f["err_cm"] = frame.err_cm ? nlohmann::json(*frame.err_cm) : nlohmann::json(nullptr);
    f["err_deg"] = frame.err_deg ? nlohmann::json(*frame.err_deg) : nlohmann::json(nullptr);
  }
  return f;
}

// The camera's frames through the AR pipeline, each written as PNGs, with their summary and
// render.json's entries.
struct ArFrames {
  ArSummaryBuilder builder;
  std::vector<ImageRgb8> written;
  nlohmann::json json = nlohmann::json::array();
};

Expected<ArFrames> PlayArFrames(ArCompositor& compositor, CameraSource& camera,
                                const ArPlayOptions& options) {
  ArFrames frames;
  ArPipeline pipeline(compositor, CameraFrames(camera, options.max_frames));
  while (true) {
    auto next = pipeline.Next();
    if (!next.ok()) return next.error();
    if (!next->has_value()) break;
    const std::optional<ArFrame>& frame = *next;
    auto name = WriteArFramePngs(*frame, options);
    if (!name.ok()) return name.error();
    frames.builder.Add(*frame);
    frames.json.push_back(ArFrameJson(*frame, *name));
    frames.written.push_back(std::move(frame->out.color));
  }
  return frames;
}

}  // namespace

Expected<ArPlaySummary> PlayArHeadless(const Reenactment& reenactment, proto::ClipMap map,
                                       CameraSource& camera, const std::string& clip_id,
                                       const ArPlayOptions& options) {
  options.Check();
  const auto start = Clock::now();
  const PinholeCamera& intrinsics = camera.camera();
  auto renderer = Renderer::CreateHeadless(intrinsics.width, intrinsics.height);
  if (!renderer.ok()) return renderer.error();
  auto compositor =
      ArCompositor::Create(reenactment, std::move(map), intrinsics, *renderer, options.frame);
  if (!compositor.ok()) return compositor.error();
  std::error_code ec;
  std::filesystem::create_directories(options.out_dir / "frames", ec);
  if (ec)
    return MakeError(
        "io", "cannot create output folder " + options.out_dir.string() + ": " + ec.message());

  auto frames = PlayArFrames(*compositor, camera, options);
  if (!frames.ok()) return frames.error();
  const std::vector<ImageRgb8>& written = frames->written;
  ArPlaySummary summary = frames->builder.summary();
  if (summary.frames == 0)
    return MakeError("empty", "camera " + camera.description() +
                                  " delivered no frames: check the path, the sequence's rgb.txt "
                                  "or that the camera is not in use by another program");

  const ImageRgb8 sheet =
      MakeContactSheet(written, options.contact_sheet_columns, options.contact_sheet_thumb_width);
  if (Status s = WritePng((options.out_dir / "contact_sheet.png").string(), sheet); !s.ok())
    return s.error();
  if (options.write_mp4) {
    if (Status s =
            WriteMp4(written, (options.out_dir / "reenactment.mp4").string(), intrinsics.width,
                     intrinsics.height, reenactment.manifest().frame_rate_hz, &summary.mp4_path,
                     &summary.mp4_warning);
        !s.ok())
      return s.error();
  }
  nlohmann::json render = {{"clip_id", clip_id},
                           {"presentation", "ar"},
                           {"camera_source", camera.description()},
                           {"clip_clock", std::string(ClipClockName(options.frame.clock))},
                           {"camera", CameraJson(intrinsics)},
                           {"relocalised", summary.relocalised},
                           {"tracked", summary.tracked},
                           {"lost", summary.lost},
                           {"reloc_ms_median", summary.reloc_ms_median},
                           {"render_ms_median", summary.render_ms_median},
                           {"subject_light", SubjectLightJson(reenactment.subject_light())},
                           {"frames", frames->json}};
  if (summary.truth_frames > 0)
    render["truth"] = {{"frames", summary.truth_frames},
                       {"within_2cm_1deg", summary.within_2cm_1deg},
                       {"median_err_cm", summary.median_err_cm},
                       {"median_err_deg", summary.median_err_deg}};
  std::ofstream json(options.out_dir / "render.json");
  json << render.dump(2) << "\n";
  if (!json) return MakeError("io", "cannot write " + (options.out_dir / "render.json").string());
  summary.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return summary;
}

}  // namespace reenact::viewer
