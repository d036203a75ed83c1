#pragma once
// A clip on disk:
//   DIR/manifest.json        SerializeManifest
//   DIR/frames/000000.rfrm   EncodeFrame, one per frame, six-digit index (more if needed)
//   DIR/map.rmap             EncodeMap
// A clip directory appears whole or not at all: WriteClipDirectory writes everything into a
// sibling DIR.tmp-XXXXXXXX, flushes it to disk, and renames it to DIR in one step.
//
// Errors (Error.code): "already_exists" (DIR exists), "invalid_argument" (parts disagree with
// the manifest, or the manifest is invalid), "not_found" (a file of the clip is missing),
// "corrupt" (a part's size or SHA-256 differs from the manifest), "io" (the file system
// refused), plus ParseManifest's codes for manifest.json.

#include <cstdint>
#include <filesystem>
#include <vector>

#include "common/error/expected.h"
#include "proto/clip/frame_codec.h"
#include "proto/clip/manifest.h"
#include "proto/clip/map_codec.h"

namespace reenact::proto {

// Sets manifest.frame_count, frame_parts and map_part (sizes and SHA-256) from the encoded
// parts. Other fields are left alone.
void FillPartHashes(ClipManifest& manifest, const std::vector<std::vector<uint8_t>>& frames,
                    const std::vector<uint8_t>& map);

// Writes a clip directory atomically. Fails without touching DIR if DIR already exists, if
// the manifest does not validate (ParseManifest of its serialisation), or if the parts'
// count, sizes or hashes differ from the manifest (call FillPartHashes first). Creates DIR's
// parent directories if needed. Leaves no temporary directory behind on failure.
Status WriteClipDirectory(const std::filesystem::path& dir, const ClipManifest& manifest,
                          const std::vector<std::vector<uint8_t>>& encoded_frames,
                          const std::vector<uint8_t>& map);

// Path of frame `index` inside a clip directory ("frames/000042.rfrm").
std::filesystem::path ClipFramePath(const std::filesystem::path& dir, int64_t index);

// An opened clip directory: the validated manifest, and parts read on demand, each verified
// against the manifest's size and SHA-256 when read.
class ClipDirectory {
 public:
  const std::filesystem::path& path() const { return path_; }
  const ClipManifest& manifest() const { return manifest_; }

  // Bytes of frame `index` in [0, frame_count) (else "invalid_argument"), verified.
  Expected<std::vector<uint8_t>> ReadFrameBytes(int64_t index) const;
  Expected<std::vector<uint8_t>> ReadMapBytes() const;

  // ReadFrameBytes / ReadMapBytes, then DecodeFrame / DecodeMap.
  Expected<ClipFrame> ReadFrame(int64_t index) const;
  Expected<ClipMap> ReadMap() const;

 private:
  friend Expected<ClipDirectory> ReadClipDirectory(const std::filesystem::path& dir);
  ClipDirectory(std::filesystem::path path, ClipManifest manifest)
      : path_(std::move(path)), manifest_(std::move(manifest)) {}

  std::filesystem::path path_;
  ClipManifest manifest_;
};

// Opens a clip directory: reads and validates manifest.json and checks that every part file
// exists (contents are verified when read).
Expected<ClipDirectory> ReadClipDirectory(const std::filesystem::path& dir);

// Longest manifest.json accepted, bytes.
inline constexpr uintmax_t kMaxManifestFileBytes = 64u << 20;

}  // namespace reenact::proto
