#include "tests/eval/quality_eval.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <functional>

#include "capture-client/record/clip_recorder.h"
#include "capture-client/source/synthetic_source.h"
#include "capture-client/synthetic/synthetic_scene.h"
#include "common/error/check.h"
#include "proto/clip/clip_directory.h"
#include "tests/eval/image_metrics.h"
#include "viewer-client/play/reenactment.h"
#include "viewer-client/play/texture_cache.h"
#include "viewer-client/play/viewer_camera.h"
#include "viewer-client/render/renderer.h"

namespace reenact::eval {
namespace {

double Median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

Expected<viewer::Reenactment> CaptureClip(const std::string& scenario,
                                          const std::filesystem::path& dir) {
  auto source = capture::SyntheticSource::Open(scenario);
  if (!source.ok()) return source.error();
  auto recorded = capture::RecordClip(**source, dir, {});
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

}  // namespace

void QualityOptions::Check() const {
  REENACT_CHECK(frame_step >= 1, "frame_step must be >= 1");
  REENACT_CHECK(width >= 16 && height >= 16, "output must be at least 16x16");
  REENACT_CHECK(!methods.empty() && !views_deg.empty(), "need a method and a view");
}

std::vector<std::string> QualityMethods() { return {"thesis"}; }

Expected<std::vector<QualityRow>> RunQuality(const QualityOptions& options) {
  options.Check();
  const auto known = QualityMethods();
  for (const std::string& m : options.methods)
    if (std::find(known.begin(), known.end(), m) == known.end())
      return MakeError("usage", "unknown method '" + m + "'; available: thesis");
  auto scene = capture::SyntheticScene::Create(options.scenario);
  if (!scene.ok()) return scene.error();

  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("reenact-eval-" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  auto reenactment = CaptureClip(options.scenario, dir / "clip");
  std::filesystem::remove_all(dir);
  if (!reenactment.ok()) return reenactment.error();

  auto renderer = viewer::Renderer::CreateHeadless(options.width, options.height);
  if (!renderer.ok()) return renderer.error();
  viewer::TextureCache texture_for_frame(*renderer, *reenactment);
  const PinholeCamera camera = viewer::ScaledViewerCamera(reenactment->manifest().color_camera,
                                                          options.width, options.height);
  std::vector<QualityRow> rows;
  for (const std::string& method : options.methods)
    for (double view : options.views_deg) {
      viewer::OrbitCameraOptions orbit;
      orbit.angle_deg = view;
      const auto pose = viewer::OrbitViewFor(*reenactment, orbit);
      if (!pose) return MakeError("degenerate", "cannot place the orbit camera");
      QualityRow row{method, options.scenario, view};
      std::vector<double> ms;
      int psnr_frames = 0;
      for (int k = 0; k < reenactment->frame_count(); k += options.frame_step) {
        const auto t0 = std::chrono::steady_clock::now();
        viewer::ReenactedFrame rf =
            reenactment->Build(k, camera, pose->viewer_from_world, std::ref(texture_for_frame));
        rf.draw.bones.clear();
        const viewer::RenderedFrame out = renderer->Render(rf.draw);
        ms.push_back(
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                .count());
        const capture::SyntheticView truth =
            scene->Render(k, camera, pose->world_from_viewer, {.draw_room = false});
        const SubjectComparison c =
            CompareSubject(out.color, out.subject_mask, truth.color, truth.mask);
        if (std::isfinite(c.psnr_db)) {
          row.psnr_db += c.psnr_db;
          ++psnr_frames;
        }
        row.ssim += c.ssim;
        row.iou += c.iou;
        row.colour_mae += c.colour_mae;
        ++row.n;
      }
      if (psnr_frames) row.psnr_db /= psnr_frames;
      row.ssim /= row.n;
      row.iou /= row.n;
      row.colour_mae /= row.n;
      row.ms_per_frame = Median(ms);
      rows.push_back(row);
    }
  return rows;
}

}  // namespace reenact::eval
