#pragma once
// Copies a whole store into an empty one (reenact-server migrate-db: an embedded SQLite file
// into PostgreSQL), then verifies the copy by reading the target back.
//
// Copied: every user with its token hashes (tokens are stored hashed, so issued tokens keep
// working), every clip (drafts and published; every ClipRecord field, the manifest byte for
// byte, owners matched by user name), every part with its present flag, and every blob.
// Users get the target's ids; created_at/published_at become the time of the copy.
//
// Rule: the source is only read. A clip becomes visible on the target only once complete:
// it is created as a draft, its payloads are stored and its parts marked present, and only
// then is it published (when it is published on the source). A copy that fails part way
// leaves drafts and orphan payloads at most, and says to drop the target and run again.
//
// Verification, after copying, from the target's own reads: users and their token hashes
// equal; every clip's record equals the source's and its manifest's SHA-256 equals its
// manifest_sha256; parts equal; blob keys equal and every blob's SHA-256 (read in pieces)
// equals the source's, and the part's recorded sha256 where the blob is a present part's;
// draft, published, part and blob counts equal.

#include <cstdint>

#include "common/error/expected.h"
#include "server/storage/open_storage.h"

namespace reenact::server {

struct CopySummary {
  int64_t users = 0;
  int64_t tokens = 0;
  int64_t clips = 0;            // drafts and published
  int64_t published_clips = 0;
  int64_t parts = 0;            // part records (present or not)
  int64_t blobs = 0;
  int64_t blob_bytes = 0;       // sum of the blobs' sizes
  double seconds = 0.0;         // wall time of copy and verification
};

// Codes: "not_empty" when the target already holds a user, clip or blob (nothing written);
// "damaged_source" when the source contradicts itself (a present part without its payload or
// with another hash, a manifest whose hash differs from manifest_sha256); "mismatch" when
// verification finds the target differs; the stores' own codes ("storage", ...) otherwise.
// Every error after the first write says the target can be dropped and the command rerun.
Expected<CopySummary> CopyStorage(Storage& source, Storage& target);

}  // namespace reenact::server
