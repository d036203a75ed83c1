#pragma once
// Publishes a recorded clip directory: sets the location (and title) in its manifest, creates
// a draft on the server, uploads every frame and the map (each verified against the manifest
// before it is sent), then publishes. Uploads are idempotent, so running it again after a lost
// connection re-sends parts to a new draft without harm; the directory itself is not changed.

#include <filesystem>
#include <optional>
#include <string>

#include "common/error/expected.h"
#include "proto/clip/manifest.h"

namespace reenact::capture {

struct PublishOptions {
  std::string server_url;  // http://host:port
  std::string token;       // bearer token from `reenact-server user add`
  proto::ClipLocation location;
  std::optional<std::string> title;  // replaces the manifest's title if set

  void Check() const;
};

struct PublishSummary {
  std::string clip_id;
  int frames = 0;
  uint64_t bytes_sent = 0;
  double seconds = 0;
};

Expected<PublishSummary> PublishClip(const std::filesystem::path& clip_dir,
                                     const PublishOptions& options);

}  // namespace reenact::capture
