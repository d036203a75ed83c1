// libFuzzer: arbitrary bytes through proto's clip manifest parser and validator. It must
// return an error or a manifest that serialises and parses back to the same manifest.
#include <cstdint>
#include <cstdlib>
#include <string>

#include "proto/clip/manifest.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  auto manifest = reenact::proto::ParseManifest(text);
  if (!manifest) return 0;
  const std::string again = reenact::proto::SerializeManifest(*manifest);
  auto reparsed = reenact::proto::ParseManifest(again);
  if (!reparsed) std::abort();
  if (reenact::proto::SerializeManifest(*reparsed) != again) std::abort();
  return 0;
}
