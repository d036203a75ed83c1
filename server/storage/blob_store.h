#pragma once
// BlobStore: opaque payloads (frames, maps) by key. Keys are "<clip id>/frames/<n>" and
// "<clip id>/map" (BlobKey below). SqliteBlobStore keeps them in the server's database by
// default; an S3-style object store can implement the same interface. Thread-safe.

#include <optional>
#include <string>
#include <string_view>

#include "common/error/expected.h"

namespace reenact::server {

// The key of a clip's part: index >= 0 is a frame, kMapPart (-1) the map.
std::string BlobKey(const std::string& clip_id, int part_index);

class BlobStore {
 public:
  virtual ~BlobStore() = default;
  // Writes or replaces the payload under key.
  virtual Status Put(const std::string& key, std::string_view bytes) = 0;
  // The payload, or nullopt when absent.
  virtual Expected<std::optional<std::string>> Get(const std::string& key) = 0;
  // Removes every key starting with prefix.
  virtual Status DeletePrefix(const std::string& prefix) = 0;
};

}  // namespace reenact::server
