#pragma once
// FrameSource replaying a clip directory of our own format (clip:DIR, proto/clip/): each
// stored frame's crops of colour, depth and person mask are placed back into full sensor
// frames of the manifest's colour-camera size at the stored crop position, zeros (no colour,
// no depth reading, background) elsewhere; the frame's sensor pose, skeleton and timestamp
// are passed on as stored. Depth is converted to millimetres if the clip stores another
// depth unit (rounded, saturating at 65535). Every part is verified against the manifest's
// SHA-256 as it is read.

#include <filesystem>
#include <memory>
#include <string>

#include "capture-client/source/frame_source.h"
#include "proto/clip/clip_directory.h"

namespace reenact::capture {

class ClipSource : public FrameSource {
 public:
  // Errors: those of proto::ReadClipDirectory, prefixed with "clip:DIR: ".
  static Expected<std::unique_ptr<FrameSource>> Open(const std::filesystem::path& dir);

  const SensorInfo& info() const override { return info_; }
  // Errors: those of ClipDirectory::ReadFrame; "corrupt" for a crop outside the frame.
  Expected<std::optional<SensorFrame>> Next() override;

 private:
  explicit ClipSource(proto::ClipDirectory clip);
  proto::ClipDirectory clip_;
  SensorInfo info_;
  int64_t next_ = 0;
};

}  // namespace reenact::capture
