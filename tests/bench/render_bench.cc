#include <random>
#include <string>
#include <vector>

#include "common/model/cylinder_model.h"
#include "common/render/reference_renderer.h"
#include "common/texture/texture_mapping.h"
#include "tests/bench/bench_support.h"
#include "tests/bench/core_bench.h"
#include "viewer-client/render/renderer.h"

namespace reenact::bench {
namespace {

// One reenacted 640x480 frame: 11 cylinders posed from a standing person 2-4 m away, each
// textured from a stored full-frame crop (random colours, all subject) through its Eq. 16
// mapping onto another person's pose.
struct RenderScene {
  PinholeCamera camera = PinholeCamera::KinectLike();
  ReferenceCrop crop;
  std::vector<ReferencePart> parts;
};

RenderScene MakeScene() {
  RenderScene scene;
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> byte(0, 255);
  scene.crop.camera = scene.camera;
  scene.crop.color = ImageRgb8(scene.camera.width, scene.camera.height, 3);
  for (uint8_t& v : scene.crop.color.data) v = static_cast<uint8_t>(byte(rng));
  scene.crop.mask = ImageGray8(scene.camera.width, scene.camera.height, 1, 255);
  const Skeleton viewer = RandomSkeleton(rng), stored = RandomSkeleton(rng);
  const auto cylinders = PoseCylinders(viewer, DefaultRadiusRatios());
  for (int p = 0; p < kBodyPartCount; ++p) {
    if (!cylinders[p]) continue;
    const auto [ja, jb] = PartJoints(static_cast<BodyPart>(p));
    ReferencePart part;
    part.cylinder = *cylinders[p];
    if (auto m =
            StoredFromViewerMapping(part.cylinder.a, part.cylinder.b, stored[ja], stored[jb])) {
      part.candidates.push_back({&scene.crop, 0, *m, 1.0});
    }
    scene.parts.push_back(part);
  }
  return scene;
}

}  // namespace

// The CPU reference renderer against the GL renderer (headless, with read-back) on the same
// frame; the GL row is replaced by a note when no OpenGL is available.
void AddRenderRows(proto::Report& report, const CoreBenchOptions& options) {
  const RenderScene scene = MakeScene();
  const long long parts = static_cast<long long>(scene.parts.size());
  long long subject_pixels = 0;
  const double cpu_ms = Median(TimeRepeated(options.repeats, 1,
                                            [&] {
                                              const ReferenceRender r =
                                                  RenderReference(scene.camera, scene.parts);
                                              subject_pixels = 0;
                                              for (uint8_t m : r.mask.data)
                                                subject_pixels += m != 0;
                                            })) /
                        1000.0;
  proto::ReportRow cpu;
  cpu.Add("op", "render_cpu_reference_640x480")
      .Add("n", parts)
      .Add("subject_px", subject_pixels)
      .Add("ms_per_frame", cpu_ms)
      .Add("fps", 1000.0 / cpu_ms);

  Expected<viewer::Renderer> renderer =
      viewer::Renderer::CreateHeadless(scene.camera.width, scene.camera.height);
  if (!renderer.ok()) {
    report.rows.push_back(cpu);
    report.rows.push_back(proto::ReportRow{}
                              .Add("op", "render_gl_headless_640x480")
                              .Add("note", "no OpenGL: " + renderer.error().message));
    return;
  }
  viewer::FrameDraw draw;
  draw.camera = scene.camera;
  const int texture =
      renderer->UploadTexture({scene.crop.color, scene.crop.mask, scene.crop.camera, {}, {}, {}});
  for (const ReferencePart& p : scene.parts) {
    viewer::CylinderDraw c;
    c.a = p.cylinder.a;
    c.b = p.cylinder.b;
    c.radius = p.cylinder.radius;
    for (const ReferenceCandidate& candidate : p.candidates)
      c.candidates.push_back({texture, candidate.stored_from_viewer, candidate.weight});
    draw.cylinders.push_back(c);
  }
  renderer->Render(draw);  // warm-up: shader compilation and first allocation
  const double gl_ms =
      Median(TimeRepeated(options.repeats, 1, [&] { renderer->Render(draw); })) / 1000.0;
  cpu.Add("cpu_over_gl", cpu_ms / gl_ms);
  report.rows.push_back(cpu);
  report.rows.push_back(proto::ReportRow{}
                            .Add("op", "render_gl_headless_640x480")
                            .Add("n", parts)
                            .Add("ms_per_frame", gl_ms)
                            .Add("fps", 1000.0 / gl_ms));

  // The same with three candidates per cylinder blended by visibility (the costliest mode:
  // every candidate sampled with its part-label and depth texture).
  const int labelled = renderer->UploadTexture(
      {scene.crop.color,
       scene.crop.mask,
       scene.crop.camera,
       ImageLabel8(scene.crop.color.width, scene.crop.color.height, 1, 1),
       Image<float>(scene.crop.color.width, scene.crop.color.height, 1, 0.0f),
       {}});
  for (viewer::CylinderDraw& c : draw.cylinders) {
    c.texturing = TexturingMode::kBlendVisible;
    if (c.candidates.empty()) continue;
    const Eigen::Matrix4d m = c.candidates[0].stored_from_viewer;
    c.candidates = {{labelled, m, 1.0}, {labelled, m, 2.0}, {labelled, m, 3.0}};
  }
  renderer->Render(draw);
  const double blend_ms =
      Median(TimeRepeated(options.repeats, 1, [&] { renderer->Render(draw); })) / 1000.0;
  report.rows.push_back(proto::ReportRow{}
                            .Add("op", "render_gl_headless_640x480_blend3")
                            .Add("n", parts)
                            .Add("ms_per_frame", blend_ms)
                            .Add("fps", 1000.0 / blend_ms));
}

}  // namespace reenact::bench
