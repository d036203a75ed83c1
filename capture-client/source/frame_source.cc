#include "capture-client/source/frame_source.h"

#include "capture-client/source/clip_source.h"
#include "capture-client/source/openni_source.h"
#include "capture-client/source/rgbd_folder_source.h"
#include "capture-client/source/synthetic_source.h"
#include "capture-client/source/tum_source.h"

namespace reenact::capture {

Expected<std::unique_ptr<FrameSource>> OpenFrameSource(const std::string& spec) {
  const auto colon = spec.find(':');
  const std::string kind = spec.substr(0, colon);
  const std::string arg = colon == std::string::npos ? "" : spec.substr(colon + 1);
  if (kind == "synthetic") return SyntheticSource::OpenSpec(arg);
  if (kind == "oni") return OpenNiSource::OpenFileSpec(arg);
  if (kind == "openni") return OpenNiSource::OpenDeviceSpec(arg);
  if (kind == "tum") {
    auto tum = TumSource::OpenSpec(arg);
    if (!tum.ok()) return tum.error();
    return std::unique_ptr<FrameSource>(std::move(tum).value());
  }
  if (kind == "rgbd") {
    auto rgbd = RgbdFolderSource::OpenSpec(arg);
    if (!rgbd.ok()) return rgbd.error();
    return std::unique_ptr<FrameSource>(std::move(rgbd).value());
  }
  if (kind == "clip") {
    if (arg.empty()) return MakeError("usage", "--source clip:DIR needs a clip directory");
    return ClipSource::Open(arg);
  }
  return MakeError("usage", "unknown source '" + spec +
                                "'; expected synthetic:SCENARIO, oni:FILE, openni[:URI], "
                                "tum:DIR, rgbd:DIR or clip:DIR");
}

}  // namespace reenact::capture
