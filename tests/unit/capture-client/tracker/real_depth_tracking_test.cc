// The depth tracker on real Kinect v1 depth of real people (../shared/data/utd-mhad: 320x240,
// no floor in view, no calibration pose, read through the rgbd: source, mirrored to a true
// camera), against the Kinect SDK's skeletons of the same frames (the reference; its joints
// sit elsewhere in the body than ours, by a few centimetres, so the bounds compare motions
// and sides rather than positions). The hard cases: sitting down, standing up, a squat, a
// forward lunge, arms crossed on the chest.
#include <gtest/gtest.h>

#include <cmath>

#include "capture-client/skeleton/skeleton_track_spec.h"
#include "capture-client/source/frame_source.h"
#include "capture-client/tracker/skeleton_tracker.h"
#include "tests/unit/capture-client/utd_mhad_sequence.h"

namespace reenact::capture {
namespace {


struct TrackedFrame {
  std::optional<Skeleton> tracked;  // sensor frame
  Skeleton reference;               // sensor frame
};

// Every frame of a utd-mhad sequence through one tracker; empty when the data are absent.
std::vector<TrackedFrame> TrackSequence(const std::string& sequence) {
  auto data = testing::OpenUtdMhadSequence(sequence);
  if (!data) return {};
  auto& source = data->source;
  auto& reference = data->reference;
  const SensorInfo& info = source->info();
  SkeletonTracker tracker(info.depth_camera, info.depth_scale_m);
  std::vector<TrackedFrame> out;
  for (int64_t i = 0;; ++i) {
    auto frame = source->Next();
    EXPECT_TRUE(frame.ok());
    if (!frame.ok() || !frame->has_value()) break;
    const SensorFrame& f = **frame;
    const auto ref = reference.ForFrame(i, f.timestamp_s);
    EXPECT_TRUE(ref.has_value()) << "frame " << i;
    if (!ref) break;
    out.push_back({tracker.Track(f.depth, std::nullopt, std::nullopt, f.timestamp_s).skeleton,
                   *ref});
  }
  return out;
}

#define SKIP_WITHOUT_DATA(frames) \
  if ((frames).empty()) GTEST_SKIP() << "../shared/data/utd-mhad is absent"

// Frames after the first second (30 frames) with a skeleton: the goal is 98 %.
double TrackedShare(const std::vector<TrackedFrame>& frames) {
  int n = 0, tracked = 0;
  for (size_t i = 30; i < frames.size(); ++i, ++n) tracked += frames[i].tracked.has_value();
  return n ? static_cast<double>(tracked) / n : 0;
}

// Sensor y grows downwards: a waist that sinks has a growing y (the sensor is level within 7
// degrees on these sequences).
double WaistY(const Skeleton& s) { return s[Joint::kWaist].y(); }

// The first tracked frame and the frame where the reference's waist is lowest (sinking) or
// highest (rising); the tracked waist's and the reference's travel between them.
struct WaistTravel {
  double tracked = 0, reference = 0;
};
WaistTravel WaistTravelTo(const std::vector<TrackedFrame>& frames, bool sinking) {
  size_t first = 0;
  while (first < frames.size() && !frames[first].tracked) ++first;
  size_t extreme = first;
  for (size_t i = first; i < frames.size(); ++i) {
    const double d = WaistY(frames[i].reference) - WaistY(frames[extreme].reference);
    if (frames[i].tracked && (sinking ? d > 0 : d < 0)) extreme = i;
  }
  if (first == frames.size()) return {};
  return {WaistY(*frames[extreme].tracked) - WaistY(*frames[first].tracked),
          WaistY(frames[extreme].reference) - WaistY(frames[first].reference)};
}

TEST(RealDepthTracking, ASquatLowersTheWaistWithTheReference) {
  // a27_s1_t1: a squat from standing, the reference's waist sinks 44 cm. A body that kept
  // standing and only bent its trunk would sink its waist by a few centimetres; the bound,
  // 3/4 of the reference's travel, leaves the two trackers' different hip placement (the
  // Kinect's hip centre sits lower; measured 0.37 m against 0.44 m of travel).
  const auto frames = TrackSequence("a27_s1_t1");
  SKIP_WITHOUT_DATA(frames);
  EXPECT_GE(TrackedShare(frames), 0.98);
  const WaistTravel t = WaistTravelTo(frames, true);
  EXPECT_GT(t.reference, 0.3);
  EXPECT_GT(t.tracked, 0.75 * t.reference);
}

TEST(RealDepthTracking, SittingDownLowersTheWaistWithTheReference) {
  // a25_s3_t1: standing to sitting on a chair the sensor's software removed with the
  // background (measured 0.26 m tracked against 0.33 m); bound as for the squat.
  const auto frames = TrackSequence("a25_s3_t1");
  SKIP_WITHOUT_DATA(frames);
  EXPECT_GE(TrackedShare(frames), 0.98);
  const WaistTravel t = WaistTravelTo(frames, true);
  EXPECT_GT(t.reference, 0.2);
  EXPECT_GT(t.tracked, 0.75 * t.reference);
}

TEST(RealDepthTracking, StandingUpFromAChairIsTrackedButTheBodyStartedSeatedStaysShort) {
  // a24_s2_t1 starts seated: without a calibration pose the body takes average proportions
  // for the height it shows seated, so once the person stands its legs are too short. It
  // starts again at the new height when the person's top stays 15 cm above the fitted body's
  // (BodyStartOptions::restart_taller_m), which within this sequence does not happen: the
  // waist rises by less than the reference's 32 cm (measured 12 cm). The bound states
  // what holds: every frame after the first second tracked and the waist rising by at least a
  // quarter of the reference's, against none for a track that lost the person.
  const auto frames = TrackSequence("a24_s2_t1");
  SKIP_WITHOUT_DATA(frames);
  EXPECT_GE(TrackedShare(frames), 0.98);
  const WaistTravel t = WaistTravelTo(frames, false);
  EXPECT_LT(t.reference, -0.25);
  EXPECT_LT(t.tracked, 0.25 * t.reference);
}

TEST(RealDepthTracking, AForwardLungeBringsTheSameKneeForward) {
  // a26_s4_t1: a forward lunge; the knee that comes nearest the sensor in the reference
  // (its left, 44 cm) must come forward in the track, by at least 3/4 of that (measured
  // 47 cm): a track with the legs swapped or not stepping moves it by far less.
  const auto frames = TrackSequence("a26_s4_t1");
  SKIP_WITHOUT_DATA(frames);
  EXPECT_GE(TrackedShare(frames), 0.98);
  size_t first = 0;
  while (first < frames.size() && !frames[first].tracked) ++first;
  ASSERT_LT(first, frames.size());
  double best_ref = 0, tracked_then = 0;
  for (const Joint knee : {Joint::kLeftKnee, Joint::kRightKnee})
    for (size_t i = first; i < frames.size(); ++i) {
      if (!frames[i].tracked) continue;
      const double ref = frames[first].reference[knee].z() - frames[i].reference[knee].z();
      if (ref > best_ref)
        best_ref = ref, tracked_then = (*frames[first].tracked)[knee].z() - (*frames[i].tracked)[knee].z();
    }
  EXPECT_GT(best_ref, 0.3);
  EXPECT_GT(tracked_then, 0.75 * best_ref);
}

TEST(RealDepthTracking, CrossedArmsBringBothHandsToTheChest) {
  // a6_s1_t1: arms crossed on the chest, then lowered. Where the reference's hands are
  // crossed (the left one on the sensor's left of the right one), both tracked hands lie near
  // the trunk's midline, within 20 cm of each other across the image; where the reference's
  // hang at the sides, more than 40 cm apart. Bound: 90 % of each kind of frame, as the arms
  // pass between the two within a frame or two (measured: 36 of 36 crossed within 12 cm, 15
  // of 16 at the sides 49-55 cm apart, one at 27). Which forearm lies in front is not resolved:
  // the track keeps each hand on its own side, a limit of the capsule model on arms that
  // overlap in depth at 3 m.
  const auto frames = TrackSequence("a6_s1_t1");
  SKIP_WITHOUT_DATA(frames);
  EXPECT_GE(TrackedShare(frames), 0.98);
  int crossed = 0, crossed_near = 0, apart = 0, apart_far = 0;
  for (const TrackedFrame& f : frames) {
    if (!f.tracked) continue;
    const double ref = f.reference[Joint::kLeftHand].x() - f.reference[Joint::kRightHand].x();
    const double got = (*f.tracked)[Joint::kLeftHand].x() - (*f.tracked)[Joint::kRightHand].x();
    if (ref < 0) {
      ++crossed;
      crossed_near += std::abs(got) < 0.2;
    } else if (ref > 0.4) {
      ++apart;
      apart_far += got > 0.4;
    }
  }
  ASSERT_GT(crossed, 20);
  ASSERT_GT(apart, 5);
  EXPECT_GE(crossed_near, 0.9 * crossed);
  EXPECT_GE(apart_far, 0.9 * apart);
}

}  // namespace
}  // namespace reenact::capture
