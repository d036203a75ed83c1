#include "tests/bench/viewer_bench.h"

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <opencv2/core/persistence.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <string>
#include <vector>

#include "capture-client/record/clip_recorder.h"
#include "capture-client/source/synthetic_source.h"
#include "common/render/reference_renderer.h"
#include "proto/clip/clip_directory.h"
#include "proto/report/report_table.h"
#include "tests/bench/bench_support.h"
#include "viewer-client/camera/synthetic_camera_source.h"
#include "viewer-client/play/ar_pipeline.h"
#include "viewer-client/play/ar_player.h"
#include "viewer-client/play/texture_cache.h"
#include "viewer-client/play/texturing_presets.h"
#include "viewer-client/play/viewer_camera.h"
#include "viewer-client/render/reference_draw.h"
#include "viewer-client/render/renderer.h"

namespace reenact::bench {
namespace {

namespace fs = std::filesystem;

constexpr double kThesisFps = 9;
constexpr int kClipFrames = 60;
constexpr const char* kScenario = "turn-and-kick";

double MsSince(Clock::time_point t) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
}

struct Setup {
  std::optional<viewer::Reenactment> reenactment;
  proto::ClipMap map;
  std::vector<viewer::CameraFrame> camera_frames;
  PinholeCamera camera;
  std::vector<double> source_ms;  // the synthetic camera's own rendering, per frame
};

Expected<Setup> MakeSetup(int frames, const viewer::TexturingOptions& texturing,
                          const fs::path& scratch) {
  Setup s;
  auto source = capture::SyntheticSource::Open(kScenario);
  if (!source.ok()) return source.error();
  capture::RecordOptions record;
  record.max_frames = kClipFrames;
  if (auto r = capture::RecordClip(**source, scratch / "clip", record); !r.ok()) return r.error();
  auto clip = proto::ReadClipDirectory(scratch / "clip");
  if (!clip.ok()) return clip.error();
  std::vector<proto::ClipFrame> clip_frames;
  for (int64_t n = 0; n < clip->manifest().frame_count; ++n) {
    auto f = clip->ReadFrame(n);
    if (!f.ok()) return f.error();
    clip_frames.push_back(std::move(f).value());
  }
  auto map = clip->ReadMap();
  if (!map.ok()) return map.error();
  s.map = std::move(map).value();
  viewer::ReenactmentOptions options;
  options.texturing = texturing;
  s.reenactment.emplace(clip->manifest(), std::move(clip_frames), options);

  auto camera = viewer::OpenCameraSource(
      std::string("synthetic:") + kScenario + "?frames=" + std::to_string(frames), std::nullopt);
  if (!camera.ok()) return camera.error();
  s.camera = (*camera)->camera();
  for (;;) {
    const auto t = Clock::now();
    auto next = (*camera)->Next();
    if (!next.ok()) return next.error();
    if (!next->has_value()) break;
    s.source_ms.push_back(MsSince(t));
    s.camera_frames.push_back(std::move(**next));
  }
  return s;
}

// The camera frames as a TUM directory (rgb.txt, PNGs, calibration.yaml), as a recorded
// camera delivers them.
Status WriteTumDirectory(const Setup& s, const fs::path& dir) {
  std::error_code ec;
  fs::create_directories(dir / "rgb", ec);
  if (ec) return MakeError("io", "cannot create " + dir.string() + ": " + ec.message());
  std::ofstream list(dir / "rgb.txt");
  list << "# timestamp filename\n";
  for (size_t i = 0; i < s.camera_frames.size(); ++i) {
    const ImageRgb8& c = s.camera_frames[i].color;
    const cv::Mat rgb(c.height, c.width, CV_8UC3, const_cast<uint8_t*>(c.data.data()));
    cv::Mat bgr;
    cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
    char name[32];
    std::snprintf(name, sizeof name, "rgb/%04zu.png", i);
    if (!cv::imwrite((dir / name).string(), bgr))
      return MakeError("io", "cannot write " + (dir / name).string());
    char line[64];
    std::snprintf(line, sizeof line, "%.6f %s\n", 1000 + s.camera_frames[i].timestamp_s, name);
    list << line;
  }
  cv::FileStorage fs((dir / "calibration.yaml").string(), cv::FileStorage::WRITE);
  fs << "image_width" << s.camera.width << "image_height" << s.camera.height;
  fs << "camera_matrix"
     << (cv::Mat_<double>(3, 3) << s.camera.fx, 0, s.camera.cx, 0, s.camera.fy, s.camera.cy, 0, 0,
         1);
  fs.release();
  if (!list) return MakeError("io", "cannot write " + (dir / "rgb.txt").string());
  return {};
}

struct Timing {
  std::vector<double> source_ms, reloc_ms, select_ms, render_ms, composite_ms, loop_ms;
  std::vector<double> run_fps;
  int lost = 0;  // camera frames without a pose
};

// A row of `table`; `ratio` names the column of fps / baseline_fps (none when empty).
void AddRow(proto::Report& report, const std::string& table, const std::string& name,
            const Timing& t, int frames, double goal_fps, const std::string& ratio = "",
            double baseline_fps = 0) {
  const double fps = Median(t.run_fps);
  proto::ReportRow row;
  row.table = table;
  row.Add("case", name).Add("frames", static_cast<long long>(frames));
  const auto stage = [&](const char* column, const std::vector<double>& v) {
    if (!v.empty()) row.Add(column, Median(v));
  };
  stage("source_ms", t.source_ms);
  stage("reloc_ms", t.reloc_ms);
  stage("select_ms", t.select_ms);
  stage("render_ms", t.render_ms);
  stage("composite_ms", t.composite_ms);
  stage("ms_per_frame", t.loop_ms);  // the whole loop
  row.Add("fps", fps);
  if (goal_fps > 0) row.Add("goal_fps", goal_fps).Add("meets_goal", fps >= goal_fps ? "yes" : "NO");
  row.Add("x_thesis", fps / kThesisFps);
  if (!ratio.empty() && baseline_fps > 0) row.Add(ratio, fps / baseline_fps);
  report.rows.push_back(std::move(row));
}

void AddThesisRow(proto::Report& report, const std::string& table) {
  proto::ReportRow row;
  row.table = table;
  row.Add("case", "thesis (Surface Pro 2, reference)").Add("fps", kThesisFps).Add("x_thesis", 1.0);
  report.rows.push_back(std::move(row));
}

// Runs `frame(i)` over frames 0..n-1, `repeats` times after one warm-up pass.
void Runs(int repeats, int n, Timing& t, const std::function<void(int)>& frame) {
  for (int i = 0; i < n; ++i) frame(i);  // warm-up: shaders, texture uploads, first track
  t = Timing{};
  for (int r = 0; r < repeats; ++r) {
    const auto start = Clock::now();
    for (int i = 0; i < n; ++i) frame(i);
    t.run_fps.push_back(n / (MsSince(start) / 1000));
  }
}

// The AR loop over the synthetic camera's frames: ArCompositor::Process one frame after the
// other, or pipelined as the viewer plays (ar_pipeline.h: frame i + 1 read and located on a
// worker while frame i is composed). loop_ms is each frame's own time (reading, locating,
// composing); pipelined, frames overlap, so fps exceeds 1000 / loop_ms.
Expected<Timing> RunArLoop(Setup& s, viewer::Renderer& renderer, int repeats, bool pipelined,
                           const std::function<Expected<viewer::CameraFrame>(int)>& next) {
  auto compositor = viewer::ArCompositor::Create(*s.reenactment, s.map, s.camera, renderer);
  if (!compositor.ok()) return compositor.error();
  Timing m;
  std::optional<Error> failed;
  const int n = static_cast<int>(s.camera_frames.size());
  std::optional<viewer::ArPipeline> pipeline;
  int read = 0;
  std::vector<double> read_ms(n, 0.0);
  const auto add = [&](const viewer::ArFrame& out, double source_ms) {
    m.source_ms.push_back(source_ms);
    m.reloc_ms.push_back(out.reloc.ms);
    if (out.reloc.viewer_from_world) {
      m.select_ms.push_back(out.select_ms);
      m.render_ms.push_back(out.render_ms);
    } else {
      ++m.lost;
    }
    m.composite_ms.push_back(out.composite_ms);
    m.loop_ms.push_back(source_ms + out.total_ms);
  };
  Runs(repeats, n, m, [&](int i) {
    if (failed) return;
    if (!pipelined) {
      const auto t = Clock::now();
      auto frame = next(i);
      if (!frame.ok()) {
        failed = frame.error();
        return;
      }
      const double source_ms = MsSince(t);
      auto out = compositor->Process(*frame);
      if (!out.ok()) {
        failed = out.error();
        return;
      }
      add(*out, source_ms);
      return;
    }
    if (i == 0) {
      pipeline.reset();
      read = 0;
      pipeline.emplace(*compositor, [&]() -> Expected<std::optional<viewer::CameraFrame>> {
        if (read >= n) return std::optional<viewer::CameraFrame>{};
        const auto t = Clock::now();
        auto frame = next(read);
        read_ms[read++] = MsSince(t);
        if (!frame.ok()) return frame.error();
        return std::optional<viewer::CameraFrame>(std::move(frame).value());
      });
    }
    auto out = pipeline->Next();
    if (!out.ok() || !out->has_value()) {
      failed = out.ok() ? MakeError("empty", "the camera ended early") : out.error();
      return;
    }
    add(**out, read_ms[i]);
  });
  if (failed) return *failed;
  return m;
}

}  // namespace

int RunViewerBench(const CommandLine& cl) {
  const auto fail = [](const Error& e) { return ReportFailure("reenact-bench", e); };
  const auto repeats = cl.GetInt("repeats", 3);
  if (!repeats.ok()) return fail(repeats.error());
  const auto frames = cl.GetInt("frames", 60);
  if (!frames.ok()) return fail(frames.error());
  if (*repeats < 1 || *repeats > 1000)
    return fail(MakeError("usage", "--repeats must be a whole number in [1, 1000]"));
  if (*frames < 2 || *frames > 100000)
    return fail(MakeError("usage", "--frames must be a whole number in [2, 100000]"));
  const int r = static_cast<int>(*repeats);
  const std::string texturing_name =
      cl.GetOr("texturing", std::string(viewer::kDefaultTexturingPreset));
  const auto texturing = viewer::TexturingPreset(texturing_name);
  if (!texturing.ok()) return fail(texturing.error());

  auto renderer = viewer::Renderer::CreateHeadless(640, 480);
  if (!renderer.ok())
    return fail(MakeError(renderer.error().code,
                          "no OpenGL for the viewer benchmark: " + renderer.error().message));
  const fs::path scratch =
      fs::temp_directory_path() / ("reenact-bench-viewer-" + std::to_string(getpid()));
  fs::remove_all(scratch);
  struct Cleanup {
    fs::path dir;
    ~Cleanup() {
      std::error_code ec;
      fs::remove_all(dir, ec);
    }
  } cleanup{scratch};
  std::printf("setting up: recording %s (%d frames), rendering %lld synthetic camera frames...\n",
              kScenario, kClipFrames, static_cast<long long>(*frames));
  std::fflush(stdout);
  auto setup = MakeSetup(static_cast<int>(*frames), *texturing, scratch);
  if (!setup.ok()) return fail(setup.error());
  Setup& s = *setup;
  const viewer::Reenactment& reenactment = *s.reenactment;
  const int clip_frames = reenactment.frame_count();
  const int n = static_cast<int>(s.camera_frames.size());

  // Orbit draws (render only, CPU reference, orbit loop).
  const PinholeCamera orbit_camera =
      viewer::ScaledViewerCamera(reenactment.manifest().color_camera, 640, 480);
  const auto view = viewer::OrbitViewFor(reenactment, viewer::OrbitCameraOptions{});
  if (!view) return fail(MakeError("degenerate", "cannot place the orbit camera"));
  viewer::TextureCache textures(*renderer, reenactment);
  std::vector<viewer::FrameDraw> orbit_draws;
  for (int k = 0; k < clip_frames; ++k) {
    viewer::ReenactedFrame rf =
        reenactment.Build(k, orbit_camera, view->viewer_from_world, std::ref(textures));
    rf.draw.floor = view->floor;
    rf.draw.bones.clear();
    orbit_draws.push_back(std::move(rf.draw));
  }

  proto::Report report{"viewer", {}};

  // The CPU reference renderer drawing the same draw lists: crops indexed by stored frame.
  std::map<int, ReferenceCrop> crops;
  std::vector<std::vector<ReferencePart>> cpu_parts;
  for (int k = 0; k < clip_frames; ++k) {
    const viewer::ReenactedFrame rf =
        reenactment.Build(k, orbit_camera, view->viewer_from_world, [](int m) { return m; });
    cpu_parts.push_back(viewer::ReferencePartsOf(rf.draw, [&](int texture) {
      if (!crops.count(texture))
        crops[texture] = viewer::ReferenceCropOf(reenactment.Texture(texture));
      return viewer::ReferenceTexture{&crops[texture], texture};
    }));
  }
  const ReferenceRenderOptions cpu_options = viewer::ReferenceOptionsOf(orbit_draws.front());
  Timing cpu;
  Runs(r, clip_frames, cpu, [&](int k) {
    const auto t = Clock::now();
    RenderReference(orbit_camera, cpu_parts[k], cpu_options);
    cpu.render_ms.push_back(MsSince(t));
  });
  const double cpu_fps = Median(cpu.run_fps);

  Timing t;
  Runs(r, clip_frames, t, [&](int k) {
    const auto start = Clock::now();
    renderer->Render(orbit_draws[k]);
    t.render_ms.push_back(MsSince(start));
  });
  AddRow(report, "render", "render-orbit (GL draw + read-back)", t, clip_frames, 60, "x_cpu",
         cpu_fps);

  std::vector<viewer::FrameDraw> ar_draws;
  for (int i = 0; i < n; ++i) {
    viewer::ReenactedFrame rf =
        reenactment.Build(i % clip_frames, s.camera,
                          s.camera_frames[i].true_world_from_viewer->inverse(), std::ref(textures));
    rf.draw.bones.clear();
    rf.draw.background = &s.camera_frames[i].color;
    ar_draws.push_back(std::move(rf.draw));
  }
  Runs(r, n, t, [&](int i) {
    const auto start = Clock::now();
    renderer->Render(ar_draws[i]);
    t.render_ms.push_back(MsSince(start));
  });
  AddRow(report, "render", "render-ar (over the camera image)", t, n, 60, "x_cpu", cpu_fps);
  AddRow(report, "render", "cpu-reference (orbit, baseline)", cpu, clip_frames, 0);
  AddThesisRow(report, "render");

  Runs(r, clip_frames, t, [&](int k) {
    auto start = Clock::now();
    viewer::ReenactedFrame rf =
        reenactment.Build(k, orbit_camera, view->viewer_from_world, std::ref(textures));
    rf.draw.floor = view->floor;
    rf.draw.bones.clear();
    t.select_ms.push_back(MsSince(start));
    const auto drawn = Clock::now();
    renderer->Render(rf.draw);
    t.render_ms.push_back(MsSince(drawn));
    t.loop_ms.push_back(MsSince(start));
  });
  const Timing orbit_loop = t;
  const double orbit_fps = Median(orbit_loop.run_fps);

  const auto synthetic_frame = [&](int i) -> Expected<viewer::CameraFrame> {
    return s.camera_frames[i];
  };
  auto sequential = RunArLoop(s, *renderer, r, false, synthetic_frame);
  if (!sequential.ok()) return fail(sequential.error());
  auto synthetic = RunArLoop(s, *renderer, r, true, synthetic_frame);
  if (!synthetic.ok()) return fail(synthetic.error());
  sequential->source_ms = s.source_ms;  // the scene's rasteriser, done before timing
  synthetic->source_ms = s.source_ms;

  if (Status w = WriteTumDirectory(s, scratch / "tum"); !w.ok()) return fail(w.error());
  std::unique_ptr<viewer::CameraSource> tum;
  auto tum_loop = RunArLoop(s, *renderer, r, true, [&](int i) -> Expected<viewer::CameraFrame> {
    if (i == 0) {
      auto opened = viewer::OpenCameraSource("tum:" + (scratch / "tum").string(), std::nullopt);
      if (!opened.ok()) return opened.error();
      tum = std::move(opened).value();
    }
    auto next = tum->Next();
    if (!next.ok()) return next.error();
    if (!next->has_value()) return MakeError("empty", "the TUM copy ended early");
    return std::move(**next);
  });
  if (!tum_loop.ok()) return fail(tum_loop.error());
  const double sequential_fps = Median(sequential->run_fps);
  AddRow(report, "loop", "loop-ar-synthetic (whole AR loop, pipelined)", *synthetic, n, 30,
         "x_sequential", sequential_fps);
  AddRow(report, "loop", "loop-ar-tum (camera frames from PNG, pipelined)", *tum_loop, n, 30,
         "x_orbit_loop", orbit_fps);
  AddRow(report, "loop", "loop-ar-sequential (synthetic, one step after the other, baseline)",
         *sequential, n, 30, "x_orbit_loop", orbit_fps);
  AddRow(report, "loop", "loop-orbit (select + render, baseline)", orbit_loop, clip_frames, 30);
  AddThesisRow(report, "loop");

  std::printf(
      "%s; 640x480, texturing %s, %d runs after a warm-up; clip %s (%d frames, map of %zu points); "
      "synthetic "
      "viewer camera of %d frames (0 -> +45 -> 0 -> -45 -> 0 degrees), lost frames per run: "
      "%d synthetic, %d tum. Stage times are medians over frames; fps the median over runs of "
      "frames / wall time; source_ms of the synthetic loops is the scene's CPU rasteriser, "
      "outside the loop; ms_per_frame is a frame's own time (reading, locating, composing), "
      "and pipelined (the viewer's loop: the next frame read and located while this one is "
      "composed) frames overlap, so fps exceeds 1000 / ms_per_frame.\n",
      renderer->driver().c_str(), texturing_name.c_str(), r, kScenario, clip_frames,
      s.map.points.size(), n, synthetic->lost / r, tum_loop->lost / r);
  const Status printed = report.Print(cl.Get("json"));
  return printed.ok() ? 0 : fail(printed.error());
}

}  // namespace reenact::bench
