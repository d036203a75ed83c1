#pragma once
// Publishes a recorded clip directory, resumably: sets the location (and title) in its
// manifest, verifies every part against the manifest, then
//   1. finds the caller's clip made from this exact manifest on the server
//      (GET /v1/me/clips?manifest_sha256=H): a draft left by an interrupted run is resumed,
//      a clip already published is reported as such; otherwise creates a new draft;
//   2. asks which parts the server already holds, with their hashes (GET .../parts), and
//      uploads only the parts that are missing or whose stored copy differs;
//   3. publishes once every part is there (the server checks again and refuses otherwise).
// Requests that fail for a transient reason (connection refused or lost, timeout, 5xx, 429)
// are retried with exponential backoff and jitter (proto/api/retry_policy.h); when the
// last attempt fails the error says the same command resumes the upload. The clip directory
// is never changed, and nothing is visible to others until step 3 succeeds.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "capture-client/publish/upload_progress.h"
#include "common/error/expected.h"
#include "proto/api/retry_policy.h"
#include "proto/clip/manifest.h"

namespace reenact::capture {

struct PublishOptions {
  std::string server_url;  // http://host:port
  std::string token;       // bearer token from `reenact-server user add`
  proto::ClipLocation location;
  std::optional<std::string> title;  // replaces the manifest's title if set
  // Retries of each request; the defaults wait 0.25, 0.5, 1, 2, 4 s (less with jitter).
  proto::RetryPolicy retry;
  ProgressStyle progress = ProgressStyle::kLines;

  void Check() const;
};

struct PublishSummary {
  std::string clip_id;
  int frames = 0;
  int parts_total = 0;             // frames + map
  int parts_sent = 0;              // uploaded by this run (missing or damaged on the server)
  int parts_skipped = 0;           // already held intact by the server
  int parts_repaired = 0;          // of parts_sent: held by the server, but with other bytes
  uint64_t bytes_sent = 0;         // payload bytes of the parts sent (the manifest included)
  bool resumed = false;            // continued a draft left by an earlier run
  bool already_published = false;  // the same clip was published before: nothing to do
  int retries = 0;                 // requests sent again after a transient failure
  double seconds = 0;
};

Expected<PublishSummary> PublishClip(const std::filesystem::path& clip_dir,
                                     const PublishOptions& options);

}  // namespace reenact::capture
