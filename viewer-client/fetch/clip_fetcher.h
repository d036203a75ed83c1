#pragma once
// Downloads a published clip for playing, through a local content-addressed cache: every part
// (manifest, frames, map) is stored as cache_dir/objects/<sha256> and verified against the
// manifest's hash before use; a cached object that fails verification is fetched again, and
// a download that fails verification is an error, never rendered.

#include <filesystem>
#include <string>
#include <vector>

#include "common/error/expected.h"
#include "proto/api/api_client.h"
#include "proto/clip/frame_codec.h"
#include "proto/clip/manifest.h"
#include "proto/clip/map_codec.h"

namespace reenact::viewer {

struct FetchedClip {
  std::string id;
  proto::ClipManifest manifest;
  std::vector<proto::ClipFrame> frames;
  proto::ClipMap map;
  uint64_t bytes_downloaded = 0;  // 0 when everything came from the cache
  uint64_t bytes_total = 0;
};

Expected<FetchedClip> FetchClip(const proto::ApiClient& api, const std::string& clip_id,
                                const std::filesystem::path& cache_dir);

}  // namespace reenact::viewer
