// Recording from a source that gives no person mask (as a real sensor): the recorder segments
// each frame from depth and skeleton, and a skeleton with a stretched bone is kept out of the
// model.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "capture-client/record/clip_recorder.h"
#include "capture-client/source/synthetic_source.h"
#include "proto/clip/clip_directory.h"
#include "synthetic/synthetic_scene.h"
#include "tests/support/temp_dir.h"

namespace reenact::capture {
namespace {

using reenact::test_support::TempDir;

namespace fs = std::filesystem;

// The synthetic source without its ground-truth masks; frame `stretched` gets a left forearm
// 40% longer than the body's (the hand moved along the forearm).
class WithoutMasks : public FrameSource {
 public:
  WithoutMasks(std::unique_ptr<FrameSource> inner, int stretched)
      : inner_(std::move(inner)), stretched_(stretched) {}
  const SensorInfo& info() const override { return inner_->info(); }
  Expected<std::optional<SensorFrame>> Next() override {
    auto next = inner_->Next();
    if (!next.ok() || !next->has_value()) return next;
    SensorFrame& f = **next;
    f.person_mask.reset();
    if (index_++ == stretched_) {
      Skeleton& s = *f.skeleton_in_world;
      const Eigen::Vector3d elbow = s[Joint::kLeftElbow];
      s.Set(Joint::kLeftHand, elbow + 1.4 * (s[Joint::kLeftHand] - elbow));
    }
    return next;
  }

 private:
  std::unique_ptr<FrameSource> inner_;
  int stretched_;
  int index_ = 0;
};

double Iou(const ImageGray8& a, const ImageGray8& b) {
  int both = 0, either = 0;
  for (size_t i = 0; i < a.data.size(); ++i) {
    both += a.data[i] > 127 && b.data[i] > 127;
    either += a.data[i] > 127 || b.data[i] > 127;
  }
  return either ? static_cast<double>(both) / either : 1.0;
}

TEST(RecordWithoutMasks, SegmentsEveryFrameAndKeepsTheBadSkeletonOutOfTheModel) {
  constexpr int kFrames = 40, kStretched = 17;
  auto inner = SyntheticSource::Open("turn-and-kick");
  ASSERT_TRUE(inner.ok()) << inner.error().message;
  WithoutMasks source(std::move(inner).value(), kStretched);
  const SyntheticScene scene = SyntheticScene::Create("turn-and-kick").value();
  TempDir tmp;
  RecordOptions options;
  options.max_frames = kFrames;
  const auto summary = RecordClip(source, tmp.path() / "clip", options);
  ASSERT_TRUE(summary.ok()) << summary.error().message;
  EXPECT_EQ(summary->segmented_frames, kFrames);
  EXPECT_EQ(summary->inconsistent_skeletons, 1);
  EXPECT_NE(summary->representative_frame, kStretched);

  // The stored masks, put back into the full image, match the ground truth: the issue's
  // segmentation requirement is IoU >= 0.9.
  const auto clip = proto::ReadClipDirectory(tmp.path() / "clip");
  ASSERT_TRUE(clip.ok()) << clip.error().message;
  // The viewer learns which skeleton not to texture from.
  EXPECT_EQ(clip->manifest().flagged_skeleton_frames, std::vector<int64_t>{kStretched});
  for (int k = 0; k < kFrames; k += 7) {
    const auto frame = clip->ReadFrame(k);
    ASSERT_TRUE(frame.ok()) << frame.error().message;
    const ImageGray8 truth = scene.RenderSensor(k).mask;
    ImageGray8 stored(truth.width, truth.height, 1, 0);
    for (int y = 0; y < frame->mask.height; ++y)
      for (int x = 0; x < frame->mask.width; ++x)
        stored.at(frame->crop_x + x, frame->crop_y + y) = frame->mask.at(x, y);
    EXPECT_GE(Iou(stored, truth), 0.9) << "frame " << k;
  }
}

}  // namespace
}  // namespace reenact::capture
