#pragma once
// A synthetic scenario's first frames recorded through the real capture path (render, crop,
// JPEG/PNG encode, clip directory) and read back, as the viewer reenacts them.

#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "capture-client/record/clip_recorder.h"
#include "capture-client/source/synthetic_source.h"
#include "proto/clip/clip_directory.h"
#include "viewer-client/play/reenactment.h"

namespace reenact::testing {

// The first max_frames frames of `scenario` with `body`, recorded into a temporary directory
// (removed again) and read back. Recording failures fail the calling test.
inline viewer::Reenactment RecordedSyntheticClip(std::string_view scenario, int max_frames,
                                                 const capture::SyntheticBodySpec& body = {}) {
  static std::atomic<int> counter{0};
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() /
      ("reenact-recorded-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
  std::filesystem::remove_all(dir);
  auto source = capture::SyntheticSource::Open(scenario, 1, body);
  EXPECT_TRUE(source.ok());
  capture::RecordOptions options;
  options.max_frames = max_frames;
  auto recorded = capture::RecordClip(**source, dir, options);
  EXPECT_TRUE(recorded.ok()) << recorded.error().message;
  auto directory = proto::ReadClipDirectory(dir);
  EXPECT_TRUE(directory.ok()) << directory.error().message;
  std::vector<proto::ClipFrame> frames;
  for (int64_t n = 0; n < directory->manifest().frame_count; ++n)
    frames.push_back(directory->ReadFrame(n).value());
  viewer::Reenactment reenactment(directory->manifest(), std::move(frames));
  std::filesystem::remove_all(dir);
  return reenactment;
}

}  // namespace reenact::testing
