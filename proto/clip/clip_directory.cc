#include "proto/clip/clip_directory.h"

#include <fcntl.h>
#include <stdio.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <random>
#include <string>

#include "proto/clip/content_hash.h"

namespace reenact::proto {
namespace {

namespace fs = std::filesystem;

Error IoError(const std::string& what, const fs::path& path, int error) {
  return MakeError("io", what + " " + path.string() + ": " + std::strerror(error));
}

Status SyncPath(const fs::path& path, bool directory) {
  const int fd = ::open(path.c_str(), (directory ? O_RDONLY | O_DIRECTORY : O_RDONLY) | O_CLOEXEC);
  if (fd < 0) return IoError("cannot open", path, errno);
  const int result = ::fsync(fd);
  const int error = errno;
  ::close(fd);
  if (result != 0) return IoError("cannot flush", path, error);
  return {};
}

Status WriteFileDurably(const fs::path& path, std::span<const uint8_t> bytes) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) return IoError("cannot create", path, errno);
  size_t written = 0;
  while (written < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + written, bytes.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int error = n < 0 ? errno : EIO;
      ::close(fd);
      return IoError("cannot write", path, error);
    }
    written += static_cast<size_t>(n);
  }
  const int result = ::fsync(fd);
  const int error = errno;
  if (::close(fd) != 0 || result != 0) return IoError("cannot flush", path, result != 0 ? error : errno);
  return {};
}

std::string RandomSuffix() {
  std::random_device device;
  char text[9];
  std::snprintf(text, sizeof(text), "%08x", static_cast<unsigned>(device()));
  return text;
}

// Renames from -> to, failing with EEXIST instead of replacing an existing (empty) `to`.
int RenameNoReplace(const fs::path& from, const fs::path& to) {
  if (::renameat2(AT_FDCWD, from.c_str(), AT_FDCWD, to.c_str(), RENAME_NOREPLACE) == 0) return 0;
  if (errno != EINVAL && errno != ENOSYS) return errno;
  std::error_code ec;  // file system without RENAME_NOREPLACE: check, then rename
  if (fs::exists(to, ec)) return EEXIST;
  return ::rename(from.c_str(), to.c_str()) == 0 ? 0 : errno;
}

Status CheckParts(const ClipManifest& manifest, const std::vector<std::vector<uint8_t>>& frames,
                  const std::vector<uint8_t>& map) {
  const auto mismatch = [](const std::string& what) {
    return MakeError("invalid_argument",
                     "clip: " + what + " differs from the manifest (call FillPartHashes first)");
  };
  if (static_cast<int64_t>(frames.size()) != manifest.frame_count ||
      frames.size() != manifest.frame_parts.size())
    return mismatch("the number of frames (" + std::to_string(frames.size()) + ")");
  for (size_t i = 0; i < frames.size(); ++i)
    if (frames[i].size() != manifest.frame_parts[i].bytes ||
        Sha256Hex(frames[i]) != manifest.frame_parts[i].sha256)
      return mismatch("frame " + std::to_string(i));
  if (map.size() != manifest.map_part.bytes || Sha256Hex(map) != manifest.map_part.sha256)
    return mismatch("the map");
  return {};
}

Status WriteTree(const fs::path& tmp, const ClipManifest& manifest,
                 const std::vector<std::vector<uint8_t>>& frames, const std::vector<uint8_t>& map) {
  std::error_code ec;
  if (!fs::create_directory(tmp / "frames", ec)) return IoError("cannot create", tmp / "frames", ec.value());
  for (size_t i = 0; i < frames.size(); ++i)
    if (Status s = WriteFileDurably(ClipFramePath(tmp, static_cast<int64_t>(i)), frames[i]); !s) return s;
  if (Status s = WriteFileDurably(tmp / "map.rmap", map); !s) return s;
  const std::string text = SerializeManifest(manifest);
  if (Status s = WriteFileDurably(tmp / "manifest.json",
                                  std::span(reinterpret_cast<const uint8_t*>(text.data()), text.size()));
      !s)
    return s;
  if (Status s = SyncPath(tmp / "frames", true); !s) return s;
  return SyncPath(tmp, true);
}

Expected<std::vector<uint8_t>> ReadVerified(const fs::path& path, const PartInfo& part) {
  std::error_code ec;
  const uintmax_t size = fs::file_size(path, ec);
  if (ec) {
    if (ec == std::errc::no_such_file_or_directory)
      return MakeError("not_found", "clip: " + path.string() + " is missing");
    return IoError("cannot stat", path, ec.value());
  }
  if (size != part.bytes)
    return MakeError("corrupt", "clip: " + path.string() + " is " + std::to_string(size) +
                                    " bytes but the manifest says " + std::to_string(part.bytes));
  std::vector<uint8_t> bytes(static_cast<size_t>(size));
  std::ifstream in(path, std::ios::binary);
  if (!in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(size)) ||
      in.peek() != std::ifstream::traits_type::eof())
    return MakeError("io", "clip: cannot read " + path.string() + " (changed while reading?)");
  if (Sha256Hex(bytes) != part.sha256)
    return MakeError("corrupt", "clip: " + path.string() +
                                    " does not match its SHA-256 in the manifest (damaged)");
  return bytes;
}

}  // namespace

void FillPartHashes(ClipManifest& manifest, const std::vector<std::vector<uint8_t>>& frames,
                    const std::vector<uint8_t>& map) {
  manifest.frame_count = static_cast<int64_t>(frames.size());
  manifest.frame_parts.clear();
  for (const auto& frame : frames) manifest.frame_parts.push_back({frame.size(), Sha256Hex(frame)});
  manifest.map_part = {map.size(), Sha256Hex(map)};
}

fs::path ClipFramePath(const fs::path& dir, int64_t index) {
  char name[32];
  std::snprintf(name, sizeof(name), "%06lld.rfrm", static_cast<long long>(index));
  return dir / "frames" / name;
}

Status WriteClipDirectory(const fs::path& dir, const ClipManifest& manifest,
                          const std::vector<std::vector<uint8_t>>& encoded_frames,
                          const std::vector<uint8_t>& map) {
  if (auto parsed = ParseManifest(SerializeManifest(manifest)); !parsed) return parsed.error();
  if (Status s = CheckParts(manifest, encoded_frames, map); !s) return s;

  std::error_code ec;
  const fs::path target = dir.has_filename() ? dir : dir.parent_path();
  if (fs::exists(target, ec))
    return MakeError("already_exists", "clip: " + target.string() + " already exists");
  const fs::path parent = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  fs::create_directories(parent, ec);
  if (ec) return IoError("cannot create", parent, ec.value());

  fs::path tmp;
  for (int attempt = 0;; ++attempt) {
    tmp = parent / (target.filename().string() + ".tmp-" + RandomSuffix());
    if (fs::create_directory(tmp, ec)) break;
    if (ec || attempt == 8) return IoError("cannot create", tmp, ec ? ec.value() : EEXIST);
  }
  Status written = WriteTree(tmp, manifest, encoded_frames, map);
  if (written) {
    if (const int error = RenameNoReplace(tmp, target); error != 0)
      written = error == EEXIST || error == ENOTEMPTY
                    ? MakeError("already_exists", "clip: " + target.string() + " already exists")
                    : IoError("cannot rename into", target, error);
  }
  if (!written) {
    fs::remove_all(tmp, ec);
    return written;
  }
  return SyncPath(parent, true);
}

Expected<std::vector<uint8_t>> ClipDirectory::ReadFrameBytes(int64_t index) const {
  if (index < 0 || index >= manifest_.frame_count)
    return MakeError("invalid_argument", "clip: frame " + std::to_string(index) +
                                             " is outside [0, " +
                                             std::to_string(manifest_.frame_count) + ")");
  return ReadVerified(ClipFramePath(path_, index), manifest_.frame_parts[static_cast<size_t>(index)]);
}

Expected<std::vector<uint8_t>> ClipDirectory::ReadMapBytes() const {
  return ReadVerified(path_ / "map.rmap", manifest_.map_part);
}

Expected<ClipFrame> ClipDirectory::ReadFrame(int64_t index) const {
  auto bytes = ReadFrameBytes(index);
  if (!bytes) return bytes.error();
  return DecodeFrame(*bytes);
}

Expected<ClipMap> ClipDirectory::ReadMap() const {
  auto bytes = ReadMapBytes();
  if (!bytes) return bytes.error();
  return DecodeMap(*bytes);
}

Expected<ClipDirectory> ReadClipDirectory(const fs::path& dir) {
  const fs::path manifest_path = dir / "manifest.json";
  std::error_code ec;
  const uintmax_t size = fs::file_size(manifest_path, ec);
  if (ec)
    return MakeError(ec == std::errc::no_such_file_or_directory ? "not_found" : "io",
                     "clip: cannot open " + manifest_path.string() + ": " + ec.message());
  if (size > kMaxManifestFileBytes)
    return MakeError("invalid_argument", "clip: " + manifest_path.string() + " is too large");
  std::string text(static_cast<size_t>(size), '\0');
  std::ifstream in(manifest_path, std::ios::binary);
  if (!in.read(text.data(), static_cast<std::streamsize>(size)))
    return MakeError("io", "clip: cannot read " + manifest_path.string());
  auto manifest = ParseManifest(text);
  if (!manifest) return manifest.error();
  for (int64_t i = 0; i < manifest->frame_count; ++i)
    if (!fs::is_regular_file(ClipFramePath(dir, i), ec))
      return MakeError("not_found", "clip: " + ClipFramePath(dir, i).string() + " is missing");
  if (!fs::is_regular_file(dir / "map.rmap", ec))
    return MakeError("not_found", "clip: " + (dir / "map.rmap").string() + " is missing");
  return ClipDirectory(dir, std::move(manifest).value());
}

}  // namespace reenact::proto
