#pragma once
// BlobStore as files under one directory (e.g. an object store mounted there), with the
// semantics of SqliteBlobStore and PostgresBlobStore; the metadata stay in the database.
//
// Layout: a key is split on '/'; each component is percent-encoded (every byte outside
// [A-Za-z0-9_-] becomes %XX, upper-case hex; the empty component becomes "%"), so no key can
// name ".", "..", an absolute path or another key's file. All components but the last are
// directories; the last is a file named <encoded>.blob ('.' is never part of an encoded name,
// so keys "a/b" and "a/b/c" coexist as a/b.blob and a/b/c.blob). Key "<clip>/frames/3" is
// the file <dir>/<clip>/frames/3.blob. Files are created 0600, directories 0700.
//
// Put writes a temporary file (.put-<random>.tmp) in the target's directory, fsyncs it,
// renames it over the target and fsyncs the directory (and the parents of directories it
// created): a Put is stored whole or not at all, durable once it returns, and a failed Put
// leaves the old payload and no temporary file. A Put of the bytes already stored writes
// nothing, so it keeps readers of that payload going. A BlobReader reads its open file; each
// Read checks that the key still names the file it opened (inode and size), else "changed":
// any other Put or a delete makes readers of the key "changed".
//
// DeletePrefix looks only into the directory named by the prefix up to its last '/' and
// removes the files and directories there whose decoded name starts with the rest, then the
// directories that became empty (never the root). Names that are not encoded keys (another
// program's files) are left alone and never listed. Open removes temporary files untouched
// for kStaleTempAge (left by a killed process; younger ones may belong to a Put of another
// server process sharing the directory).
//
// Thread-safe without locks: every change is one rename or unlink, and a Put whose directory
// another thread or process removed in the meantime creates it again. Errors of the file
// system: code "storage" naming the path and the system's reason.

#include <chrono>
#include <memory>
#include <string>

#include "server/storage/blob_store.h"

namespace reenact::server {

class FileBlobStore : public BlobStore {
 public:
  // Temporary files older than this are a killed Put's.
  static constexpr std::chrono::seconds kStaleTempAge{600};

  // Opens the store in `dir`, which must exist and be writable by this process: code "io"
  // naming the directory and what to do otherwise. Removes stale temporary files.
  static Expected<std::unique_ptr<FileBlobStore>> Open(const std::string& dir);

  Status Put(const std::string& key, std::string_view bytes) override;
  Expected<std::optional<std::string>> Get(const std::string& key) override;
  Expected<std::unique_ptr<BlobReader>> OpenReader(const std::string& key) override;
  Status DeletePrefix(const std::string& prefix) override;
  Expected<std::vector<std::string>> ListKeys() override;

  // The file that holds `key` (whether or not it exists), or an error with code
  // "invalid_argument" when a component is too long for a file name.
  Expected<std::string> PathOfKey(const std::string& key) const;

 private:
  explicit FileBlobStore(std::string root) : root_(std::move(root)) {}

  std::string root_;  // absolute, without a trailing '/'
};

}  // namespace reenact::server
