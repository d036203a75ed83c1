// The GL renderer against its CPU oracle (common/render/reference_renderer.h): the same
// reenacted frames of a recorded synthetic clip, drawn by both, must agree in silhouette
// and in colour. Needs OpenGL (EGL surfaceless); suites start with "Gl".
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "capture-client/record/clip_recorder.h"
#include "capture-client/source/synthetic_source.h"
#include "common/render/reference_renderer.h"
#include "proto/clip/clip_directory.h"
#include "viewer-client/play/reenactment.h"
#include "viewer-client/play/viewer_camera.h"
#include "viewer-client/render/renderer.h"

namespace reenact::viewer {
namespace {

constexpr int kWidth = 640, kHeight = 480;

// The first 2 s of the synthetic "turn-and-kick" scenario through the real recording path
// (render, crop, JPEG/PNG encode, clip directory) and back.
const Reenactment& RecordedClip() {
  static const Reenactment clip = [] {
    const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                      ("reenact-gl-reference-" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir);
    auto source = capture::SyntheticSource::Open("turn-and-kick");
    EXPECT_TRUE(source.ok());
    capture::RecordOptions options;
    options.max_frames = 60;
    auto recorded = capture::RecordClip(**source, dir, options);
    EXPECT_TRUE(recorded.ok()) << recorded.error().message;
    auto directory = proto::ReadClipDirectory(dir);
    EXPECT_TRUE(directory.ok()) << directory.error().message;
    std::vector<proto::ClipFrame> frames;
    for (int64_t n = 0; n < directory->manifest().frame_count; ++n)
      frames.push_back(directory->ReadFrame(n).value());
    Reenactment reenactment(directory->manifest(), std::move(frames));
    std::filesystem::remove_all(dir);
    return reenactment;
  }();
  return clip;
}

struct Agreement {
  double iou = 0;
  double colour_mae = 0;  // mean absolute difference per channel on pixels both mark, 0-255
  int both = 0;           // pixels both mark as subject
  int textured = 0;       // of those, pixels whose colour came from a stored frame
};

Agreement Compare(const RenderedFrame& gl, const ReferenceRender& ref) {
  Agreement a;
  int either = 0;
  double sum = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const bool g = gl.subject_mask.at(x, y) != 0, r = ref.mask.at(x, y) != 0;
      either += g || r;
      if (!(g && r)) continue;
      ++a.both;
      a.textured += ref.source_frame.at(x, y) >= 0;
      for (int c = 0; c < 3; ++c) sum += std::abs(gl.color.at(x, y, c) - ref.color.at(x, y, c));
    }
  a.iou = either ? static_cast<double>(a.both) / either : 1.0;
  a.colour_mae = a.both ? sum / (3.0 * a.both) : 0.0;
  return a;
}

class GlReferenceAgreement : public ::testing::TestWithParam<double> {};

TEST_P(GlReferenceAgreement, ReenactedFrameAgreesWithTheCpuReference) {
  const Reenactment& clip = RecordedClip();
  ASSERT_EQ(clip.frame_count(), 60);
  Expected<Renderer> renderer = Renderer::CreateHeadless(kWidth, kHeight);
  ASSERT_TRUE(renderer.ok()) << renderer.error().message;

  std::map<int, int> texture_of_frame;
  std::map<int, ReferenceCrop> crop_of_frame;
  auto texture_for_frame = [&](int n) {
    auto it = texture_of_frame.find(n);
    if (it == texture_of_frame.end()) {
      const StoredTexture t = clip.Texture(n);
      crop_of_frame[n] = ReferenceCrop{t.color, t.mask, t.camera};
      it = texture_of_frame.emplace(n, renderer->UploadTexture(t)).first;
    }
    return it->second;
  };

  OrbitCameraOptions orbit;
  orbit.angle_deg = GetParam();
  const auto view = OrbitViewFor(clip, orbit);
  ASSERT_TRUE(view.has_value());
  const PinholeCamera camera = ScaledViewerCamera(clip.manifest().color_camera, kWidth, kHeight);
  for (int k : {10, 55}) {  // calibration pose; arms down, turning and stepping
    ReenactedFrame frame = clip.Build(k, camera, view->viewer_from_world, texture_for_frame);
    frame.draw.bones.clear();
    ASSERT_GE(frame.texture_frame, 0);
    const RenderedFrame gl = renderer->Render(frame.draw);

    std::vector<ReferencePart> parts;
    std::map<int, int> frame_of_texture;
    for (const auto& [n, t] : texture_of_frame) frame_of_texture[t] = n;
    for (const CylinderDraw& c : frame.draw.cylinders) {
      ReferencePart part;
      part.cylinder = Cylinder{c.a, c.b, c.radius};
      part.stored_from_viewer = c.stored_from_viewer;
      part.color = c.color;
      if (c.texture >= 0) {
        part.stored_frame = frame_of_texture.at(c.texture);
        part.crop = &crop_of_frame.at(part.stored_frame);
      }
      parts.push_back(part);
    }
    const ReferenceRender ref = RenderReference(camera, parts);

    const Agreement a = Compare(gl, ref);
    EXPECT_GT(a.both, 5000) << "k " << k;  // the subject fills a good part of the view
    EXPECT_GT(a.textured, a.both / 2) << "k " << k;
    EXPECT_GE(a.iou, 0.98) << "k " << k;
    EXPECT_LE(a.colour_mae, 2.0) << "k " << k;
  }
}

INSTANTIATE_TEST_SUITE_P(OrbitAngles, GlReferenceAgreement, ::testing::Values(0.0, 60.0, 150.0));

}  // namespace
}  // namespace reenact::viewer
