#include "viewer-client/play/headless_player.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>

#include "common/error/check.h"
#include "viewer-client/output/contact_sheet.h"
#include "viewer-client/output/mp4_writer.h"
#include "viewer-client/output/png_writer.h"
#include "viewer-client/output/render_json.h"
#include "viewer-client/play/texture_cache.h"
#include "viewer-client/play/viewer_camera.h"
#include "viewer-client/render/renderer.h"

namespace reenact::viewer {
namespace {

// The orbit view's frames, rendered and written as PNGs (frames/frame_NNNN.png, and
// mask_NNNN.png when asked), with the seconds each render took and render.json's entries.
struct OrbitFrames {
  std::vector<ImageRgb8> rendered;
  std::vector<double> render_seconds;
  nlohmann::json json = nlohmann::json::array();
};

Expected<OrbitFrames> RenderOrbit(const Reenactment& reenactment, Renderer& renderer,
                                  const PinholeCamera& camera, const OrbitView& view, int frames,
                                  const HeadlessPlayOptions& options) {
  TextureCache texture_for_frame(renderer, reenactment);
  OrbitFrames out_frames;
  PartSelectionHistory history;
  for (int k = 0; k < frames; ++k) {
    ReenactedFrame rf =
        reenactment.Build(k, camera, view.viewer_from_world, std::ref(texture_for_frame), &history);
    rf.draw.floor = view.floor;
    rf.draw.textured = options.textured;
    if (!options.draw_skeleton) rf.draw.bones.clear();
    const auto t0 = std::chrono::steady_clock::now();
    RenderedFrame out = renderer.Render(rf.draw);
    out_frames.render_seconds.push_back(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    char name[32];
    std::snprintf(name, sizeof name, "frame_%04d.png", k);
    if (Status s = WritePng((options.out_dir / "frames" / name).string(), out.color); !s.ok())
      return s.error();
    if (options.write_masks) {
      std::snprintf(name, sizeof name, "mask_%04d.png", k);
      if (Status s = WritePng((options.out_dir / "frames" / name).string(), out.subject_mask);
          !s.ok())
        return s.error();
      std::snprintf(name, sizeof name, "frame_%04d.png", k);
    }
    out_frames.json.push_back({{"output", k},
                               {"clip_frame", rf.clip_frame},
                               {"texture_frame", rf.texture_frame},
                               {"file", std::string("frames/") + name}});
    out_frames.rendered.push_back(std::move(out.color));
  }
  return out_frames;
}

}  // namespace

void HeadlessPlayOptions::Check() const {
  REENACT_CHECK(!out_dir.empty(), "out_dir must be set");
  REENACT_CHECK(max_frames == -1 || max_frames >= 1, "max_frames must be -1 or >= 1");
  REENACT_CHECK(width >= 16 && height >= 16, "output must be at least 16x16");
  REENACT_CHECK(contact_sheet_columns >= 1, "contact_sheet_columns must be >= 1");
  REENACT_CHECK(contact_sheet_thumb_width >= 16, "contact_sheet_thumb_width must be >= 16");
  orbit.Check();
}

Expected<PlaySummary> PlayHeadless(const Reenactment& reenactment, const std::string& clip_id,
                                   const HeadlessPlayOptions& options) {
  options.Check();
  const auto start = std::chrono::steady_clock::now();
  std::error_code ec;
  std::filesystem::create_directories(options.out_dir / "frames", ec);
  if (ec)
    return MakeError(
        "io", "cannot create output folder " + options.out_dir.string() + ": " + ec.message());

  auto renderer = Renderer::CreateHeadless(options.width, options.height);
  if (!renderer.ok()) return renderer.error();

  const proto::ClipManifest& manifest = reenactment.manifest();
  const PinholeCamera camera =
      ScaledViewerCamera(manifest.color_camera, options.width, options.height);
  const auto view = OrbitViewFor(reenactment, options.orbit);
  if (!view)
    return MakeError("degenerate",
                     "cannot place the orbit camera: the capture sensor stands on "
                     "the subject's vertical axis");

  const int frames = options.max_frames < 0
                         ? reenactment.frame_count()
                         : std::min(options.max_frames, reenactment.frame_count());
  auto orbit = RenderOrbit(reenactment, *renderer, camera, *view, frames, options);
  if (!orbit.ok()) return orbit.error();
  const std::vector<ImageRgb8>& rendered = orbit->rendered;

  PlaySummary summary;
  summary.clip_id = clip_id;
  summary.frames = frames;
  std::vector<double> sorted = orbit->render_seconds;
  std::sort(sorted.begin(), sorted.end());
  if (!sorted.empty() && sorted[sorted.size() / 2] > 0)
    summary.render_fps = 1.0 / sorted[sorted.size() / 2];

  const ImageRgb8 sheet =
      MakeContactSheet(rendered, options.contact_sheet_columns, options.contact_sheet_thumb_width);
  if (Status s = WritePng((options.out_dir / "contact_sheet.png").string(), sheet); !s.ok())
    return s.error();

  if (options.write_mp4 && !rendered.empty()) {
    if (Status s = WriteMp4(rendered, (options.out_dir / "reenactment.mp4").string(), options.width,
                            options.height, manifest.frame_rate_hz, &summary.mp4_path,
                            &summary.mp4_warning);
        !s.ok())
      return s.error();
  }

  const nlohmann::json render = {{"clip_id", clip_id},
                                 {"presentation", "orbit"},
                                 {"orbit_angle_deg", options.orbit.angle_deg},
                                 {"camera", CameraJson(camera)},
                                 {"world_from_viewer", PoseJson(view->world_from_viewer)},
                                 {"render_fps", summary.render_fps},
                                 {"subject_light", SubjectLightJson(reenactment.subject_light())},
                                 {"frames", std::move(orbit->json)}};
  std::ofstream(options.out_dir / "render.json") << render.dump(2) << "\n";
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace reenact::viewer
