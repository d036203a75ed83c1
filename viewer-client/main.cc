// reenact-viewer: find clips nearby and watch them reenacted.
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "common/cli/command_line.h"
#include "proto/api/api_client.h"
#include "viewer-client/camera/camera_source.h"
#include "viewer-client/fetch/clip_fetcher.h"
#include "viewer-client/play/ar_player.h"
#include "viewer-client/play/ar_window_player.h"
#include "viewer-client/play/headless_player.h"
#include "viewer-client/play/texturing_presets.h"
#include "viewer-client/play/window_player.h"

namespace {

using namespace reenact;

constexpr const char* kUsage =
    "usage:\n"
    "  reenact-viewer browse --server URL --near LAT,LON [--radius-m M] [--limit N] [--json]\n"
    "  reenact-viewer play CLIP_ID --server URL [--camera orbit] [--orbit-deg D]\n"
    "                      [--headless --out DIR] [--frames N] [--width W --height H]\n"
    "                      [--cache DIR] [--bare] [--skeleton] [--masks] [--no-mp4] [--steady]\n"
    "                      [--texturing NAME]\n"
    "  reenact-viewer play CLIP_ID --server URL --camera CAMERA [--calibration FILE]\n"
    "                      [--clip-clock time|frames] [--headless --out DIR] [--frames N]\n"
    "                      [--cache DIR] [--bare] [--skeleton] [--masks] [--no-mp4] [--no-status]\n"
    "                      [--steady] [--texturing NAME]\n"
    "      CAMERA: tum:DIR | video:FILE | live[:N] |\n"
    "              synthetic:SCENARIO[?frames=N&max_deg=D&subject=0|1&seed=S]\n"
    "      without --headless: the AR view in a window (space, arrows, +/-, s, c, t, q)\n"
    "  --steady: steady motion (flagged skeletons interpolated across, joints One Euro filtered,\n"
    "            for the pose shown and the stored frames alike)\n"
    "  --texturing NAME: ";

// The usage with the texturing presets and the default as texturing_presets.h defines them.
std::string Usage() {
  std::string usage = kUsage;
  usage += viewer::TexturingPresetNames();
  usage += " (default ";
  usage += viewer::kDefaultTexturingPreset;
  usage += ")\n      (viewer-client/play/texturing_presets.h; docs/quality.md compares them)\n";
  return usage;
}

int Fail(const Error& e) { return ReportFailure("reenact-viewer", e); }

// --steady and --texturing.
// Whether the texturing relights the clip, and with what light (or why not).
void PrintRelighting(const viewer::Reenactment& reenactment) {
  if (!reenactment.options().texturing.relight) return;
  const SubjectLightFit& fit = reenactment.subject_light();
  if (fit.found)
    std::printf(
        "relighting under the clip's light: strength %.2f, explains %.0f%% of how the "
        "subject's colours vary as it turns\n",
        fit.light.norm(), 100 * fit.gain);
  else
    std::printf("not relighting: %s\n", fit.reason.c_str());
}

Expected<viewer::ReenactmentOptions> ReenactmentOptionsFrom(const CommandLine& cl) {
  viewer::ReenactmentOptions options;
  options.steady_motion = cl.Has("steady");
  auto texturing =
      viewer::TexturingPreset(cl.GetOr("texturing", std::string(viewer::kDefaultTexturingPreset)));
  if (!texturing.ok()) return texturing.error();
  options.texturing = *texturing;
  return options;
}

int Browse(const CommandLine& cl) {
  const auto server = cl.Require("server");
  if (!server.ok()) return Fail(server.error());
  const auto near = cl.Require("near");
  if (!near.ok()) return Fail(near.error());
  const auto latlon = ParseLatLon(*near);
  if (!latlon.ok()) return Fail(latlon.error());
  const auto radius = cl.GetDouble("radius-m", 1000);
  if (!radius.ok()) return Fail(radius.error());
  const auto limit = cl.GetInt("limit", 20);
  if (!limit.ok()) return Fail(limit.error());
  const proto::ApiClient api(*server, "");
  const auto clips = api.Nearby(latlon->first, latlon->second, *radius, static_cast<int>(*limit));
  if (!clips.ok()) return Fail(clips.error());
  if (cl.Has("json")) {
    nlohmann::json out = nlohmann::json::array();
    for (const auto& c : *clips) out.push_back(proto::ClipSummaryToJson(c));
    std::cout << out.dump(2) << "\n";
    return 0;
  }
  std::printf("%-24s %-28s %-12s %10s %9s %7s\n", "ID", "TITLE", "AUTHOR", "DISTANCE", "DURATION",
              "FRAMES");
  for (const auto& c : *clips)
    std::printf("%-24s %-28.28s %-12.12s %8.1f m %7.1f s %7lld\n", c.id.c_str(), c.title.c_str(),
                c.author.c_str(), c.distance_m, c.duration_s,
                static_cast<long long>(c.frame_count));
  std::printf("%zu clip(s) within %.0f m of %.6f,%.6f\n", clips->size(), *radius, latlon->first,
              latlon->second);
  return 0;
}

void PrintTruth(const viewer::ArPlaySummary& s) {
  if (s.truth_frames > 0)
    std::printf(
        "against the camera's true pose: %d of %d frames within 2 cm and 1 degree; median "
        "error %.2f cm, %.3f degrees\n",
        s.within_2cm_1deg, s.truth_frames, s.median_err_cm, s.median_err_deg);
}

// The flags that only --headless output takes, refused in the window.
Status CheckNoHeadlessFlags(const CommandLine& cl) {
  for (const char* flag : {"out", "masks", "no-mp4"})
    if (cl.Has(flag) || cl.Get(flag))
      return MakeError("usage", std::string("--") + flag +
                                    " is for --headless output; the window writes no files");
  if (cl.Get("clip-clock"))
    return MakeError("usage",
                     "--clip-clock is for --headless; in the window the clip follows the "
                     "window's clock (space pauses, +/- change the speed)");
  return {};
}

Expected<viewer::ArPlayOptions> ArPlayOptionsFrom(const CommandLine& cl, bool headless) {
  viewer::ArPlayOptions options;
  if (headless) {
    const auto out = cl.Require("out");
    if (!out.ok()) return MakeError("usage", "--headless needs --out DIR");
    options.out_dir = *out;
  }
  const auto frames = cl.GetInt("frames", -1);
  if (!frames.ok()) return frames.error();
  if (*frames == 0 || *frames < -1) return MakeError("usage", "--frames must be >= 1");
  options.max_frames = static_cast<int>(*frames);
  const std::string clock = cl.GetOr("clip-clock", "time");
  if (clock != "time" && clock != "frames")
    return MakeError("usage", "--clip-clock must be 'time' or 'frames', not '" + clock + "'");
  options.frame.clock =
      clock == "time" ? viewer::ClipClock::kCameraTime : viewer::ClipClock::kFrameIndex;
  options.frame.textured = !cl.Has("bare");
  options.frame.draw_skeleton = cl.Has("skeleton");
  options.frame.draw_status = !cl.Has("no-status");
  options.write_mp4 = !cl.Has("no-mp4");
  options.write_masks = cl.Has("masks");
  return options;
}

int RunArWindow(const viewer::Reenactment& reenactment, proto::ClipMap map,
                viewer::CameraSource& source, const viewer::ArPlayOptions& options) {
  viewer::ArWindowOptions window;
  window.max_frames = options.max_frames;
  window.frame = options.frame;
  window.title = "reenact AR - " + reenactment.manifest().title;
  const auto shown = viewer::PlayArInWindow(reenactment, std::move(map), source, window);
  if (!shown.ok()) return Fail(shown.error());
  std::printf(
      "showed %d camera frames from %s: %d relocalised, %d tracked, %d lost; relocaliser "
      "%.1f ms, render %.1f ms per frame (medians), %.1f s in all\n",
      shown->frames, source.description().c_str(), shown->relocalised, shown->tracked, shown->lost,
      shown->reloc_ms_median, shown->render_ms_median, shown->seconds);
  PrintTruth(*shown);
  return 0;
}

int RunArHeadless(const viewer::Reenactment& reenactment, proto::ClipMap map,
                  viewer::CameraSource& source, const std::string& clip_id,
                  const viewer::ArPlayOptions& options) {
  const auto summary =
      viewer::PlayArHeadless(reenactment, std::move(map), source, clip_id, options);
  if (!summary.ok()) return Fail(summary.error());
  std::printf(
      "composited %d camera frames from %s: %d relocalised, %d tracked, %d lost; relocaliser "
      "%.1f ms, render %.1f ms per frame (medians), %.1f s in all\n",
      summary->frames, source.description().c_str(), summary->relocalised, summary->tracked,
      summary->lost, summary->reloc_ms_median, summary->render_ms_median, summary->seconds);
  std::printf("wrote %s/frames/, %s/contact_sheet.png%s, %s/render.json\n",
              options.out_dir.string().c_str(), options.out_dir.string().c_str(),
              summary->mp4_path.empty() ? "" : (", " + summary->mp4_path).c_str(),
              options.out_dir.string().c_str());
  PrintTruth(*summary);
  if (!summary->mp4_warning.empty())
    std::cerr << "reenact-viewer: warning: no MP4 written: " << summary->mp4_warning << "\n";
  if (summary->lost == summary->frames)
    std::cerr << "reenact-viewer: warning: every frame was lost: the camera never saw the clip's "
                 "scene (render.json gives each frame's reason)\n";
  return 0;
}

// AR: the reenactment over the viewer's own camera (viewer-client/play/ar_player.h).
int PlayAr(const CommandLine& cl, const std::string& clip_id, const std::string& server,
           const std::string& camera_spec) {
  for (const char* flag : {"width", "height", "orbit-deg"})
    if (cl.Get(flag))
      return Fail(MakeError(
          "usage",
          std::string("--") + flag + " is for --camera orbit; AR output has the camera's size"));
  const auto reenact_options = ReenactmentOptionsFrom(cl);
  if (!reenact_options.ok()) return Fail(reenact_options.error());
  const bool headless = cl.Has("headless");
  if (!headless) {
    if (Status s = CheckNoHeadlessFlags(cl); !s.ok()) return Fail(s.error());
  }
  const auto options = ArPlayOptionsFrom(cl, headless);
  if (!options.ok()) return Fail(options.error());
  std::optional<std::filesystem::path> calibration;
  if (auto c = cl.Get("calibration")) calibration = *c;

  auto source = viewer::OpenCameraSource(camera_spec, calibration);
  if (!source.ok()) return Fail(source.error());
  const proto::ApiClient api(server, "");
  auto clip = viewer::FetchClip(api, clip_id, cl.GetOr("cache", ".cache/reenact-viewer"));
  if (!clip.ok()) return Fail(clip.error());
  const viewer::Reenactment reenactment(clip->manifest, std::move(clip->frames), *reenact_options);
  PrintRelighting(reenactment);
  if (!headless) return RunArWindow(reenactment, std::move(clip->map), **source, *options);
  return RunArHeadless(reenactment, std::move(clip->map), **source, clip_id, *options);
}

int Play(const CommandLine& cl) {
  if (cl.positionals().size() != 2) return Fail(MakeError("usage", "play needs a CLIP_ID"));
  const std::string clip_id = cl.positionals()[1];
  const auto server = cl.Require("server");
  if (!server.ok()) return Fail(server.error());
  const std::string camera = cl.GetOr("camera", "orbit");
  if (camera != "orbit") return PlayAr(cl, clip_id, *server, camera);
  const auto reenact_options = ReenactmentOptionsFrom(cl);
  if (!reenact_options.ok()) return Fail(reenact_options.error());
  viewer::HeadlessPlayOptions options;
  const auto frames = cl.GetInt("frames", -1);
  if (!frames.ok()) return Fail(frames.error());
  if (*frames == 0 || *frames < -1) return Fail(MakeError("usage", "--frames must be >= 1"));
  options.max_frames = static_cast<int>(*frames);
  const auto angle = cl.GetDouble("orbit-deg", 60);
  if (!angle.ok()) return Fail(angle.error());
  options.orbit.angle_deg = *angle;
  const auto width = cl.GetInt("width", 640);
  const auto height = cl.GetInt("height", 480);
  if (!width.ok()) return Fail(width.error());
  if (!height.ok()) return Fail(height.error());
  if (*width < 16 || *height < 16 || *width > 8192 || *height > 8192)
    return Fail(MakeError("usage", "--width and --height must lie in [16, 8192]"));
  options.width = static_cast<int>(*width);
  options.height = static_cast<int>(*height);
  options.textured = !cl.Has("bare");
  options.draw_skeleton = cl.Has("skeleton");
  options.write_mp4 = !cl.Has("no-mp4");
  options.write_masks = cl.Has("masks");
  if (cl.Has("headless")) {
    const auto out = cl.Require("out");
    if (!out.ok()) return Fail(MakeError("usage", "--headless needs --out DIR"));
    options.out_dir = *out;
  }

  const proto::ApiClient api(*server, "");
  const std::string cache = cl.GetOr("cache", ".cache/reenact-viewer");
  auto clip = viewer::FetchClip(api, clip_id, cache);
  if (!clip.ok()) return Fail(clip.error());
  std::printf("fetched clip %s: %lld frames, %.1f KB (%.1f KB downloaded)\n", clip_id.c_str(),
              static_cast<long long>(clip->manifest.frame_count), clip->bytes_total / 1024.0,
              clip->bytes_downloaded / 1024.0);
  const viewer::Reenactment reenactment(clip->manifest, std::move(clip->frames), *reenact_options);
  PrintRelighting(reenactment);

  if (!cl.Has("headless")) {
    const Status played = viewer::PlayInWindow(reenactment, options);
    return played.ok() ? 0 : Fail(played.error());
  }
  const auto summary = viewer::PlayHeadless(reenactment, clip_id, options);
  if (!summary.ok()) return Fail(summary.error());
  std::printf(
      "rendered %d frames from %.0f degrees around the subject in %.1f s "
      "(render %.1f fps)\n",
      summary->frames, options.orbit.angle_deg, summary->seconds, summary->render_fps);
  std::printf("wrote %s/frames/, %s/contact_sheet.png%s, %s/render.json\n", options.out_dir.c_str(),
              options.out_dir.c_str(),
              summary->mp4_path.empty() ? "" : (", " + summary->mp4_path).c_str(),
              options.out_dir.c_str());
  if (!summary->mp4_warning.empty())
    std::cerr << "reenact-viewer: warning: no MP4 written: " << summary->mp4_warning << "\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const CommandLineSpec spec{
      {"server", "near", "radius-m", "limit", "camera", "orbit-deg", "out", "frames", "width",
       "height", "cache", "calibration", "clip-clock", "texturing"},
      {"json", "headless", "bare", "skeleton", "no-mp4", "masks", "no-status", "steady"}};
  return RunTool("reenact-viewer", Usage(), spec, {{"browse", Browse}, {"play", Play}}, argc, argv);
}
