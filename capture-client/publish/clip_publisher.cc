#include "capture-client/publish/clip_publisher.h"

#include <chrono>

#include "common/error/check.h"
#include "proto/api/api_client.h"
#include "proto/clip/clip_directory.h"

namespace reenact::capture {
namespace {

std::string AsString(const std::vector<uint8_t>& bytes) {
  return std::string(bytes.begin(), bytes.end());
}

}  // namespace

void PublishOptions::Check() const {
  REENACT_CHECK(!server_url.empty(), "server_url must be set");
  REENACT_CHECK(!token.empty(), "token must be set");
}

Expected<PublishSummary> PublishClip(const std::filesystem::path& clip_dir,
                                     const PublishOptions& options) {
  options.Check();
  const auto start = std::chrono::steady_clock::now();
  auto clip = proto::ReadClipDirectory(clip_dir);
  if (!clip.ok()) return clip.error();
  proto::ClipManifest manifest = clip->manifest();
  manifest.location = options.location;
  if (options.title) manifest.title = *options.title;
  const std::string manifest_json = proto::SerializeManifest(manifest);
  if (auto valid = proto::ParseManifest(manifest_json); !valid.ok()) return valid.error();

  // Every part is read and verified before the first byte goes out: a damaged clip is
  // refused without leaving a draft behind.
  std::vector<std::string> frames;
  for (int64_t n = 0; n < manifest.frame_count; ++n) {
    auto bytes = clip->ReadFrameBytes(n);
    if (!bytes.ok()) return bytes.error();
    frames.push_back(AsString(*bytes));
  }
  auto map = clip->ReadMapBytes();
  if (!map.ok()) return map.error();

  const proto::ApiClient api(options.server_url, options.token);
  auto id = api.CreateClip(manifest_json);
  if (!id.ok()) return id.error();
  PublishSummary summary;
  summary.clip_id = *id;
  summary.bytes_sent = manifest_json.size();
  for (int64_t n = 0; n < manifest.frame_count; ++n) {
    if (Status s = api.PutFrame(*id, n, frames[n]); !s.ok()) return s.error();
    summary.bytes_sent += frames[n].size();
    ++summary.frames;
  }
  if (Status s = api.PutMap(*id, AsString(*map)); !s.ok()) return s.error();
  summary.bytes_sent += map->size();
  if (Status s = api.Publish(*id); !s.ok()) return s.error();
  summary.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace reenact::capture
