#include "capture-client/source/frame_source.h"

#include "capture-client/source/synthetic_source.h"

namespace reenact::capture {

Expected<std::unique_ptr<FrameSource>> OpenFrameSource(const std::string& spec) {
  const auto colon = spec.find(':');
  const std::string kind = spec.substr(0, colon);
  const std::string arg = colon == std::string::npos ? "" : spec.substr(colon + 1);
  if (kind == "synthetic") {
    if (arg.empty())
      return MakeError("usage", "--source synthetic:SCENARIO needs a scenario name, e.g. "
                                "synthetic:turn-and-kick");
    return SyntheticSource::Open(arg);
  }
  if (kind == "oni" || kind == "openni" || kind == "tum" || kind == "clip")
    return MakeError("unsupported",
                     "source '" + kind + ":' is not available in this build yet (real sensor "
                     "sources arrive with the capture work); use --source synthetic:SCENARIO");
  return MakeError("usage", "unknown source '" + spec +
                                "'; expected synthetic:SCENARIO, oni:FILE, openni[:URI], "
                                "tum:DIR or clip:DIR");
}

}  // namespace reenact::capture
