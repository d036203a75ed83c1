#include "tests/eval/quality_eval.h"

#include <epoxy/gl.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>
#include <random>
#include <tuple>

#include "capture-client/record/clip_recorder.h"
#include "capture-client/source/synthetic_source.h"
#include "capture-client/tracker/tracker_skeleton_source.h"
#include "common/error/check.h"
#include "common/estimate/median.h"
#include "proto/clip/clip_directory.h"
#include "synthetic/room.h"
#include "tests/eval/clip_scene_frames.h"
#include "tests/eval/side_by_side.h"
#include "viewer-client/output/png_writer.h"
#include "viewer-client/play/viewer_camera.h"
#include "viewer-client/render/reference_draw.h"

namespace reenact::eval {
namespace {

// The scene and the frame source of the options' scenario: the one place both are made, so
// that a further scene choice (a body, a seed) is passed on to both.
struct OpenedScenario {
  capture::SyntheticScene scene;
  std::unique_ptr<capture::FrameSource> source;
};
Expected<OpenedScenario> OpenScenario(const QualityOptions& options) {
  const capture::SyntheticBodySpec body{
      .gltf_path = options.body, .ambient = options.flat_lighting ? 1.0 : capture::kSceneAmbient};
  auto scene = capture::SyntheticScene::Create(options.scenario, 1, body);
  if (!scene.ok()) return scene.error();
  auto source = capture::SyntheticSource::Open(options.scenario, 1, body);
  if (!source.ok()) return source.error();
  return OpenedScenario{std::move(scene).value(), std::move(source).value()};
}

// Records the source into a clip directory under `dir` and reads it back, as a viewer would.
// With noise_m > 0 the recorder takes the scene's true skeletons with Gaussian jitter added
// (QualityOptions::skeleton_noise_m) instead of the source's own; with `tracked`, our depth
// tracker's (QualityOptions::tracked_skeletons).
Expected<viewer::Reenactment> CaptureClip(capture::FrameSource& source,
                                          const capture::SyntheticScene& scene, double noise_m,
                                          bool tracked, const std::filesystem::path& dir) {
  capture::RecordOptions options;
  std::optional<capture::TrackerSkeletonSource> tracker;
  if (tracked) {
    tracker.emplace(source.info());
    options.frame_skeletons = tracker->Function();
  }
  if (noise_m > 0)
    options.skeletons = [&scene, noise_m](int64_t index, double) -> std::optional<Skeleton> {
      if (index < 0 || index >= scene.frame_count()) return std::nullopt;
      const int n = static_cast<int>(index);
      Skeleton s = scene.skeleton_in_world(n).Transformed(scene.world_from_sensor(n).inverse());
      std::mt19937_64 rng(0x5eed0000ULL + static_cast<uint64_t>(n));
      std::normal_distribution<double> noise(0.0, noise_m);
      for (Eigen::Vector3d& p : s.position)
        p += Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
      return s;
    };
  auto recorded = capture::RecordClip(source, dir, options);
  if (!recorded.ok() && tracker && tracker->stats().tracked == 0)
    return MakeError("tracking", "the depth tracker gave no skeleton on any of the " +
                                     std::to_string(scene.frame_count()) + " frames (" +
                                     tracker->stats().Describe() + ")");
  if (!recorded.ok()) return recorded.error();
  auto clip = proto::ReadClipDirectory(dir);
  if (!clip.ok()) return clip.error();
  std::vector<proto::ClipFrame> frames;
  for (int64_t n = 0; n < clip->manifest().frame_count; ++n) {
    auto frame = clip->ReadFrame(n);
    if (!frame.ok()) return frame.error();
    frames.push_back(std::move(frame).value());
  }
  return viewer::Reenactment(clip->manifest(), std::move(frames));
}

double SilhouetteIou(const ImageGray8& a, const ImageGray8& b) {
  int both = 0, either = 0;
  for (size_t i = 0; i < a.data.size(); ++i) {
    const bool x = a.data[i] > 127, y = b.data[i] > 127;
    both += x && y;
    either += x || y;
  }
  return either ? static_cast<double>(both) / either : 1.0;
}

std::string ImageName(const std::string& method, const ImagePair& pair) {
  char name[96];
  std::snprintf(name, sizeof(name), "_f%03d_v%03ld.png", pair.frame, std::lround(pair.view_deg));
  return method + name;
}

}  // namespace

void QualityOptions::Check() const {
  REENACT_CHECK(frame_step >= 1, "frame_step must be >= 1");
  REENACT_CHECK(std::isfinite(skeleton_noise_m) && skeleton_noise_m >= 0,
                "skeleton_noise_m must be finite and >= 0");
  REENACT_CHECK(!(tracked_skeletons && skeleton_noise_m > 0),
                "tracked_skeletons and skeleton_noise_m exclude each other");
  REENACT_CHECK(width >= 16 && height >= 16, "output must be at least 16x16");
  REENACT_CHECK(!methods.empty() && !views_deg.empty(), "need a method and a view");
  for (double v : views_deg) REENACT_CHECK(std::isfinite(v), "view angles must be finite");
  for (const ImagePair& p : image_pairs)
    REENACT_CHECK(p.frame >= 0 && std::isfinite(p.view_deg),
                  "image pairs need a frame >= 0 and a finite angle");
}

struct QualityHarness::State {
  capture::SyntheticScene scene;
  viewer::Reenactment clip;
  viewer::Renderer renderer;
  PinholeCamera camera;
  std::string gl_renderer;
  std::vector<int> scene_frame;  // clip frame -> the scene frame it was recorded from
  // The same clip with steady_motion (its stored frames on the steady track), on first use.
  std::optional<viewer::Reenactment> steady_clip;
  // (stored frame, body shape, steady clip) -> GL texture index: the part-label maps follow
  // the shape and the stored skeleton.
  std::map<std::tuple<int, viewer::BodyShape, bool>, int> texture_of_frame;
  std::map<int, int> frame_of_texture;
  std::map<int, ReferenceCrop> crops;  // GL texture index -> the crop as the reference samples it
  std::map<int, ImageLabel8> sensor_labels;  // stored frame -> the scene's labels from the sensor

  const viewer::Reenactment& ClipFor(bool steady) {
    if (!steady) return clip;
    if (!steady_clip) {
      std::vector<proto::ClipFrame> frames;
      for (int n = 0; n < clip.frame_count(); ++n) frames.push_back(clip.frame(n));
      viewer::ReenactmentOptions options;
      options.steady_motion = true;
      steady_clip.emplace(clip.manifest(), std::move(frames), options);
    }
    return *steady_clip;
  }

  int TextureFor(int n, viewer::BodyShape shape, bool steady) {
    auto it = texture_of_frame.find({n, shape, steady});
    if (it != texture_of_frame.end()) return it->second;
    const viewer::StoredTexture t = ClipFor(steady).Texture(n, shape);
    const int index = renderer.UploadTexture(t);
    crops[index] = viewer::ReferenceCropOf(t);
    frame_of_texture[index] = n;
    return texture_of_frame[{n, shape, steady}] = index;
  }

  SourceLabels LabelsFor(int n) {
    auto it = sensor_labels.find(n);
    if (it == sensor_labels.end())
      it = sensor_labels.emplace(n, scene.RenderSensor(scene_frame[n]).part_labels).first;
    const proto::ClipFrame& f = clip.frame(n);
    return {&f.mask, f.crop_x, f.crop_y, &it->second};
  }
};

QualityHarness::QualityHarness(std::unique_ptr<State> state) : state_(std::move(state)) {}
QualityHarness::QualityHarness(QualityHarness&&) noexcept = default;
QualityHarness& QualityHarness::operator=(QualityHarness&&) noexcept = default;
QualityHarness::~QualityHarness() = default;

const viewer::Reenactment& QualityHarness::clip() const { return state_->clip; }
const capture::SyntheticScene& QualityHarness::scene() const { return state_->scene; }
const PinholeCamera& QualityHarness::camera() const { return state_->camera; }
const std::string& QualityHarness::gl_renderer() const { return state_->gl_renderer; }
int QualityHarness::SceneFrame(int n) const {
  REENACT_CHECK(n >= 0 && n < state_->clip.frame_count(), "clip frame out of range");
  return state_->scene_frame[n];
}

Expected<QualityHarness> QualityHarness::Create(const QualityOptions& options) {
  options.Check();
  auto opened = OpenScenario(options);
  if (!opened.ok()) return opened.error();

  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("reenact-eval-" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  auto clip = CaptureClip(*opened->source, opened->scene, options.skeleton_noise_m,
                          options.tracked_skeletons, dir / "clip");
  std::filesystem::remove_all(dir);
  if (!clip.ok()) return clip.error();
  std::vector<double> timestamps;
  for (int n = 0; n < clip->frame_count(); ++n) timestamps.push_back(clip->frame(n).timestamp_s);
  auto scene_frame =
      SceneFramesOfClip(timestamps, opened->scene.frame_rate_hz(), opened->scene.frame_count());
  if (!scene_frame.ok()) return scene_frame.error();
  if (!options.tracked_skeletons && clip->frame_count() != opened->scene.frame_count())
    return MakeError("internal", "the clip has " + std::to_string(clip->frame_count()) +
                                     " frames, the scene " +
                                     std::to_string(opened->scene.frame_count()));

  auto renderer = viewer::Renderer::CreateHeadless(options.width, options.height);
  if (!renderer.ok()) return renderer.error();
  const auto* gl_name = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  const PinholeCamera camera =
      viewer::ScaledViewerCamera(clip->manifest().color_camera, options.width, options.height);
  return QualityHarness(std::unique_ptr<State>(new State{std::move(opened->scene),
                                                         std::move(clip).value(),
                                                         std::move(renderer).value(),
                                                         camera,
                                                         gl_name ? gl_name : "unknown",
                                                         std::move(scene_frame).value(),
                                                         {},
                                                         {},
                                                         {},
                                                         {},
                                                         {}}));
}

Expected<Eigen::Isometry3d> QualityHarness::ViewerFromWorld(double view_deg) const {
  viewer::OrbitCameraOptions orbit;
  orbit.angle_deg = view_deg;
  const auto view = viewer::OrbitViewFor(state_->clip, orbit);
  if (!view)
    return MakeError("degenerate", "cannot place the orbit camera at " + std::to_string(view_deg) +
                                       " degrees: the sensor lies on the subject's vertical axis");
  return view->viewer_from_world;
}

Expected<FrameEvaluation> QualityHarness::Evaluate(const QualityMethod& method, double view_deg,
                                                   int k, PartSelectionHistory* history) {
  State& s = *state_;
  REENACT_CHECK(k >= 0 && k < s.clip.frame_count(), "output frame out of range");
  const auto viewer_from_world = ViewerFromWorld(view_deg);
  if (!viewer_from_world.ok()) return viewer_from_world.error();

  FrameEvaluation e;
  const auto t0 = std::chrono::steady_clock::now();
  e.frame = method.build(
      s.ClipFor(method.steady), k, s.camera, *viewer_from_world,
      [&s, &method](int n) { return s.TextureFor(n, method.shape, method.steady); }, history);
  e.rendered = s.renderer.Render(e.frame.draw);
  e.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  REENACT_CHECK(e.frame.cylinder_parts.size() == e.frame.draw.cylinders.size(),
                "method " + method.name + " must name the body part of every cylinder");

  const std::vector<ReferencePart> parts =
      viewer::ReferencePartsOf(e.frame.draw, [&s](int texture) {
        return viewer::ReferenceTexture{&s.crops.at(texture), s.frame_of_texture.at(texture)};
      });
  e.reference = RenderReference(s.camera, parts, viewer::ReferenceOptionsOf(e.frame.draw));
  e.truth = s.scene.Render(s.scene_frame[k], s.camera, viewer_from_world->inverse(),
                           {.draw_room = false});
  const SeenParts seen{.labels = &e.truth.part_labels, .focal_px = s.camera.fx};
  e.provenance = MeasurePartProvenance(
      e.reference, e.frame.cylinder_parts, [&s](int n) { return s.LabelsFor(n); }, &seen);
  e.reference_iou = SilhouetteIou(e.rendered.subject_mask, e.reference.mask);
  e.comparison =
      CompareSubject(e.rendered.color, e.rendered.subject_mask, e.truth.color, e.truth.mask);
  return e;
}

Expected<QualityRun> RunQuality(const QualityOptions& options) {
  options.Check();
  auto found = FindQualityMethods(options.methods);
  if (!found.ok()) return found.error();
  const std::vector<const QualityMethod*>& methods = *found;
  auto harness = QualityHarness::Create(options);
  if (!harness.ok()) return harness.error();

  QualityRun run;
  run.clip_frames = harness->clip().frame_count();
  run.scene_frames = harness->scene().frame_count();
  run.gl_renderer = harness->gl_renderer();
  run.subject_light = harness->clip().subject_light();
  run.surface_fit = harness->clip().surface_fit();
  if (!options.flat_lighting)
    run.true_subject_light =
        capture::SceneLightDirection() * ((1 - capture::kSceneAmbient) / capture::kSceneAmbient);
  std::vector<ImagePair> pairs = options.image_pairs;
  if (pairs.empty()) {
    const int step = options.frame_step;
    int middle = static_cast<int>(std::lround((run.clip_frames - 1) / 2.0 / step)) * step;
    if (middle >= run.clip_frames) middle -= step;
    for (double view : options.views_deg) pairs.push_back({middle, view});
  }
  if (!options.image_dir.empty()) {
    for (const ImagePair& p : pairs)
      if (p.frame >= run.clip_frames)
        return MakeError("usage", "image frame " + std::to_string(p.frame) +
                                      " is beyond the clip's " + std::to_string(run.clip_frames) +
                                      " frames");
    std::error_code ec;
    std::filesystem::create_directories(options.image_dir, ec);
    if (ec)
      return MakeError("io",
                       "cannot create the image folder " + options.image_dir + ": " + ec.message());
  }

  for (const QualityMethod* method : methods) {
    for (double view : options.views_deg) {
      QualityRow row{method->name, options.scenario, view};
      std::vector<double> ms;
      int psnr_frames = 0, flicker_pairs = 0;
      std::optional<FrameEvaluation> previous;
      PartSelectionHistory history;
      for (int k = 0; k < run.clip_frames; k += options.frame_step) {
        auto e = harness->Evaluate(*method, view, k, &history);
        if (!e.ok()) return e.error();
        ms.push_back(e->ms);
        if (previous) {
          const FlickerMeasure f =
              MeasureFlicker(previous->rendered.color, previous->rendered.subject_mask,
                             e->rendered.color, e->rendered.subject_mask, previous->truth.color,
                             previous->truth.mask, e->truth.color, e->truth.mask);
          row.reenacted_change += f.reenacted_change;
          row.truth_change += f.truth_change;
          row.error_change += f.error_change;
          ++flicker_pairs;
        }
        if (std::isfinite(e->comparison.psnr_db)) {
          row.psnr_db += e->comparison.psnr_db;
          ++psnr_frames;
        }
        row.ssim += e->comparison.ssim;
        row.iou += e->comparison.iou;
        row.colour_mae += e->comparison.colour_mae;
        row.wrong_part_rate += e->provenance.WrongPartRate();
        row.wrong_seen_part_rate += e->provenance.WrongSeenPartRate();
        row.wrong_texture_rate += e->provenance.WrongTextureRate();
        row.doubled_limb_rate += e->provenance.DoubledLimbRate();
        row.untextured_rate += e->provenance.UntexturedRate();
        row.reference_iou += e->reference_iou;
        ++row.n;
        previous = std::move(e).value();
      }
      if (flicker_pairs) {
        row.reenacted_change /= flicker_pairs;
        row.truth_change /= flicker_pairs;
        row.error_change /= flicker_pairs;
      }
      row.flicker = row.reenacted_change - row.truth_change;
      if (psnr_frames) row.psnr_db /= psnr_frames;
      for (double* mean : {&row.ssim, &row.iou, &row.colour_mae, &row.wrong_part_rate,
                           &row.wrong_seen_part_rate, &row.wrong_texture_rate,
                           &row.doubled_limb_rate, &row.untextured_rate, &row.reference_iou})
        *mean /= row.n;
      row.ms_per_frame = ms.empty() ? 0 : UpperMedian(ms);
      run.rows.push_back(row);
    }
    if (options.image_dir.empty()) continue;
    for (const ImagePair& pair : pairs) {
      auto e = harness->Evaluate(*method, pair.view_deg, pair.frame);
      if (!e.ok()) return e.error();
      const std::string path =
          (std::filesystem::path(options.image_dir) / ImageName(method->name, pair)).string();
      const Status written = viewer::WritePng(
          path,
          SideBySide(e->truth.color, e->truth.mask, e->rendered.color, e->rendered.subject_mask));
      if (!written.ok()) return written.error();
      run.images.push_back({method->name, pair, path, e->comparison, e->provenance.WrongPartRate(),
                            e->provenance.WrongSeenPartRate(), e->provenance.WrongTextureRate(),
                            e->provenance.DoubledLimbRate()});
    }
  }
  return run;
}

}  // namespace reenact::eval
