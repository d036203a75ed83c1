#pragma once
// Test support: a utd-mhad sequence of ../shared/data (real Kinect v1 depth of real people),
// read through the rgbd: source mirrored to a true camera, with the Kinect SDK's skeletons of
// the same frames.

#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "capture-client/skeleton/skeleton_track_spec.h"
#include "capture-client/source/frame_source.h"

namespace reenact::capture::testing {

struct UtdMhadSequence {
  std::unique_ptr<FrameSource> source;
  SkeletonTrack reference;
};

// nullopt when the data are absent; a failure (and nullopt) when they cannot be read.
inline std::optional<UtdMhadSequence> OpenUtdMhadSequence(const std::string& sequence) {
  const std::filesystem::path dir =
      std::filesystem::path(REENACT_SHARED_DATA_DIR) / "utd-mhad" / sequence;
  if (!std::filesystem::exists(dir)) return std::nullopt;
  auto source = OpenFrameSource("rgbd:" + dir.string() + "?mirrored=1");
  EXPECT_TRUE(source.ok()) << source.error().message;
  auto reference = LoadSkeletonTrack("kinect:" + (dir / "skeleton.txt").string());
  EXPECT_TRUE(reference.ok()) << reference.error().message;
  if (!source.ok() || !reference.ok()) return std::nullopt;
  return UtdMhadSequence{std::move(source).value(), std::move(reference).value()};
}

}  // namespace reenact::capture::testing
