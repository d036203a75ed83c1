// Fallback candidates in the reenactment (issue 9): where none of a part's ranked stored frames
// sees a point of it, the renderer falls back to a frame chosen to see it, instead of the
// first usable one, whose texel there shows whatever stood in front of the part.
#include <gtest/gtest.h>

#include <map>
#include <set>

#include "common/render/reference_renderer.h"
#include "tests/unit/viewer-client/recorded_synthetic_clip.h"
#include "viewer-client/play/texturing_presets.h"
#include "viewer-client/play/viewer_camera.h"
#include "viewer-client/render/reference_draw.h"

namespace reenact::viewer {
namespace {

// The first 3 s of the synthetic "turn-and-kick" scenario, recorded and read back.
const Reenactment& Clip() {
  static const Reenactment clip = testing::RecordedSyntheticClip("turn-and-kick", 90);
  return clip;
}

// Stored crops as the reference renderer samples them, texture index = stored frame.
class Crops {
 public:
  const ReferenceCrop& Of(int n) {
    auto it = crops_.find(n);
    if (it == crops_.end()) it = crops_.emplace(n, ReferenceCropOf(Clip().Texture(n))).first;
    return it->second;
  }

 private:
  std::map<int, ReferenceCrop> crops_;
};

struct View {
  PinholeCamera camera;
  Eigen::Isometry3d viewer_from_world;
};

View OrbitView(double angle_deg) {
  OrbitCameraOptions orbit;
  orbit.angle_deg = angle_deg;
  const auto view = OrbitViewFor(Clip(), orbit);
  EXPECT_TRUE(view.has_value());
  return {ScaledViewerCamera(Clip().manifest().color_camera, 320, 240), view->viewer_from_world};
}

ReenactedFrame Build(int k, const View& view, std::string_view preset) {
  return Clip().BuildPosed(
      k, Clip().frame(k).skeleton_in_world, view.camera, view.viewer_from_world,
      [](int n) { return n; }, TexturingPreset(preset).value());
}

// Subject pixels the reference renderer colours from a single stored texel that the stored
// frame's part labels give to another part than the one drawn: the occluder's colour.
int OccluderTexels(const ReenactedFrame& frame, Crops& crops) {
  for (const CylinderDraw& c : frame.draw.cylinders)
    for (const TextureCandidate& t : c.candidates) crops.Of(t.texture);
  const ReferenceRender r =
      RenderReference(frame.draw.camera,
                      ReferencePartsOf(frame.draw,
                                       [&crops](int n) {
                                         return ReferenceTexture{&crops.Of(n), n};
                                       }),
                      ReferenceOptionsOf(frame.draw));
  int count = 0;
  for (int y = 0; y < r.mask.height; ++y)
    for (int x = 0; x < r.mask.width; ++x) {
      const int n = r.source_frame.at(x, y, 0);
      if (n < 0 || r.source_frame.at(x, y, 1) >= 0) continue;
      const ReferenceCrop& crop = crops.Of(n);
      const int u = std::clamp(static_cast<int>(std::lround(r.source_pixel.at(x, y, 0))), 0,
                               crop.part_labels.width - 1);
      const int v = std::clamp(static_cast<int>(std::lround(r.source_pixel.at(x, y, 1))), 0,
                               crop.part_labels.height - 1);
      const BodyPart drawn = frame.cylinder_parts.at(static_cast<size_t>(r.part.at(x, y)));
      count += crop.part_labels.at(u, v) != PartLabel(drawn);
    }
  return count;
}

TEST(ReenactmentFallback, FallbacksFollowTheUnchangedRankedCandidatesWithWeightZero) {
  const View view = OrbitView(90);
  int fallbacks = 0;
  for (int k : {30, 60, 85}) {
    const ReenactedFrame ranked = Build(k, view, "relit");
    const ReenactedFrame with = Build(k, view, "fallback");
    ASSERT_EQ(ranked.draw.cylinders.size(), with.draw.cylinders.size());
    for (size_t i = 0; i < with.draw.cylinders.size(); ++i) {
      const auto& r = ranked.draw.cylinders[i].candidates;
      const auto& w = with.draw.cylinders[i].candidates;
      ASSERT_GE(w.size(), r.size());
      EXPECT_LE(w.size(), static_cast<size_t>(kMaxTextureCandidates));
      std::set<int> frames;
      for (size_t j = 0; j < w.size(); ++j) {
        EXPECT_TRUE(frames.insert(w[j].texture).second) << "a frame twice, part " << i;
        if (j < r.size()) {
          EXPECT_EQ(w[j].texture, r[j].texture);
          EXPECT_EQ(w[j].weight, r[j].weight);
        } else {
          EXPECT_EQ(w[j].weight, 0.0);
          ++fallbacks;
        }
      }
    }
  }
  EXPECT_GT(fallbacks, 0);  // seen side on, turning and kicking, some part is hidden somewhere
}

TEST(ReenactmentFallback, FallbacksCutTheOccludersTexelsDrawnOnAPart) {
  // The bound: at least a fifth fewer, over three frames at two side views, of a count that
  // is itself large enough (hundreds of pixels) for the cut not to be a few border pixels.
  // (Not all go: where no stored frame sees the point, or the 12 x 5 cells of the coverage
  // are coarser than the occluder's outline, the ranked texel stays.)
  Crops crops;
  int ranked = 0, with = 0;
  for (double angle : {90.0, 135.0}) {
    const View view = OrbitView(angle);
    for (int k : {30, 60, 85}) {
      ranked += OccluderTexels(Build(k, view, "relit"), crops);
      with += OccluderTexels(Build(k, view, "fallback"), crops);
    }
  }
  EXPECT_GT(ranked, 300);
  EXPECT_LT(with, 4 * ranked / 5) << "ranked only " << ranked << ", with fallbacks " << with;
}

}  // namespace
}  // namespace reenact::viewer
