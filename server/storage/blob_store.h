#pragma once
// BlobStore: opaque payloads (frames, maps) by key. Keys are "<clip id>/frames/<n>" and
// "<clip id>/map" (BlobKey below). SqliteBlobStore and PostgresBlobStore keep them in the
// server's database by default, FileBlobStore as files in a directory; an S3-style object
// store can implement the same interface. Thread-safe.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "common/error/expected.h"

namespace reenact::server {

// The key of a clip's part: index >= 0 is a frame, kMapPart (-1) the map.
std::string BlobKey(const std::string& clip_id, int part_index);

// One stored payload, read in pieces (e.g. to hash or send a frame without holding all of it
// in memory). Not thread-safe: one user at a time. It holds no lock or transaction between
// reads, so a slow reader never blocks writers or WAL checkpoints.
class BlobReader {
 public:
  virtual ~BlobReader() = default;
  // The payload's size in bytes, as it was at BlobStore::OpenReader.
  virtual uint64_t size() const = 0;
  // Copies up to out.size() bytes starting at byte `offset` into out and returns how many:
  // min(out.size(), size() - offset), 0 at or past the end. Errors: code "storage" when the
  // store fails; code "changed" when the payload was replaced by one of another size or
  // deleted since OpenReader (the caller must start again from a new reader).
  virtual Expected<size_t> Read(uint64_t offset, std::span<char> out) = 0;
};

class BlobStore {
 public:
  virtual ~BlobStore() = default;
  // Writes or replaces the payload under key.
  virtual Status Put(const std::string& key, std::string_view bytes) = 0;
  // The payload, or nullopt when absent.
  virtual Expected<std::optional<std::string>> Get(const std::string& key) = 0;
  // A reader of the payload under key, or a null pointer when absent.
  virtual Expected<std::unique_ptr<BlobReader>> OpenReader(const std::string& key) = 0;
  // Removes every key starting with prefix.
  virtual Status DeletePrefix(const std::string& prefix) = 0;
  // Every key, in bytewise order (to copy a whole store: reenact-server migrate-db).
  virtual Expected<std::vector<std::string>> ListKeys() = 0;
};

}  // namespace reenact::server
