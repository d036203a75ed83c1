#include "server/storage/file_blob_store.h"

#include <dirent.h>
#include <fcntl.h>
#include <limits.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <optional>
#include <random>
#include <thread>
#include <utility>

namespace reenact::server {

namespace {

constexpr std::string_view kBlobSuffix = ".blob";
constexpr std::string_view kTempPrefix = ".put-";
constexpr std::string_view kTempSuffix = ".tmp";
constexpr size_t kNameMax = NAME_MAX;      // bytes of one file name
constexpr size_t kPathMax = PATH_MAX - 1;  // bytes of a path
constexpr int kPutAttempts = 8;            // tries while other processes remove its directory

Error SystemError(const std::string& what, const std::string& path, int err) {
  return MakeError("storage", what + " " + path + ": " + std::strerror(err));
}

// A file descriptor closed when it goes.
class Fd {
 public:
  explicit Fd(int fd = -1) : fd_(fd) {}
  ~Fd() { Reset(); }
  Fd(Fd&& other) noexcept : fd_(std::exchange(other.fd_, -1)) {}
  Fd& operator=(Fd&& other) noexcept {
    Reset();
    fd_ = std::exchange(other.fd_, -1);
    return *this;
  }
  int get() const { return fd_; }
  explicit operator bool() const { return fd_ >= 0; }
  // Closes now; the error of close(), 0 when none.
  int Close() {
    if (fd_ < 0) return 0;
    const int rc = ::close(std::exchange(fd_, -1));
    return rc == 0 ? 0 : errno;
  }

 private:
  void Reset() {
    if (fd_ >= 0) ::close(std::exchange(fd_, -1));
  }
  int fd_;
};

std::string Join(const std::string& dir, std::string_view name) {
  std::string path = dir;
  if (path.empty() || path.back() != '/') path += '/';
  path += name;
  return path;
}

std::string Parent(const std::string& path) {
  const size_t slash = path.rfind('/');
  return slash == 0 ? "/" : path.substr(0, slash);
}

bool IsPlain(unsigned char c) {
  return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' ||
         c == '-';
}

// One key component as a file name: bytes outside [A-Za-z0-9_-] as %XX; "" as "%".
std::string Encode(std::string_view component) {
  if (component.empty()) return "%";
  static constexpr char kHex[] = "0123456789ABCDEF";
  std::string name;
  name.reserve(component.size());
  for (char ch : component) {
    const auto c = static_cast<unsigned char>(ch);
    if (IsPlain(c)) {
      name += ch;
    } else {
      name += '%';
      name += kHex[c >> 4];
      name += kHex[c & 15];
    }
  }
  return name;
}

int HexValue(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

// The component a file name encodes, or nullopt for a name Encode never gives.
std::optional<std::string> Decode(std::string_view name) {
  if (name == "%") return std::string();
  if (name.empty()) return std::nullopt;
  std::string component;
  for (size_t i = 0; i < name.size(); ++i) {
    const auto c = static_cast<unsigned char>(name[i]);
    if (IsPlain(c)) {
      component += name[i];
      continue;
    }
    if (c != '%' || i + 2 >= name.size()) return std::nullopt;
    const int hi = HexValue(name[i + 1]), lo = HexValue(name[i + 2]);
    if (hi < 0 || lo < 0) return std::nullopt;
    const auto byte = static_cast<unsigned char>(hi * 16 + lo);
    if (IsPlain(byte)) return std::nullopt;  // Encode keeps plain bytes as they are
    component += static_cast<char>(byte);
    i += 2;
  }
  return component;
}

// The key component a blob file's name holds, or nullopt for another name.
std::optional<std::string> DecodeBlobFileName(std::string_view name) {
  if (name.size() <= kBlobSuffix.size() || !name.ends_with(kBlobSuffix)) return std::nullopt;
  return Decode(name.substr(0, name.size() - kBlobSuffix.size()));
}

bool IsTempName(std::string_view name) {
  return name.starts_with(kTempPrefix) && name.ends_with(kTempSuffix);
}

std::vector<std::string_view> SplitKey(std::string_view key) {
  std::vector<std::string_view> parts;
  size_t start = 0;
  for (;;) {
    const size_t slash = key.find('/', start);
    parts.push_back(key.substr(start, slash == std::string_view::npos ? slash : slash - start));
    if (slash == std::string_view::npos) return parts;
    start = slash + 1;
  }
}

// Where a key lives: the directories from the root's child down to the file's directory, and
// the file.
struct Location {
  std::vector<std::string> dirs;
  std::string dir;  // the file's directory (the root for a key without '/')
  std::string file;
};

enum class Kind { kFile, kDirectory, kOther };

struct Entry {
  std::string name;
  Kind kind = Kind::kOther;
};

// The entries of `dir` (none when it does not exist), without following symbolic links.
Expected<std::vector<Entry>> ListDirectory(const std::string& dir) {
  DIR* handle = ::opendir(dir.c_str());
  if (handle == nullptr) {
    if (errno == ENOENT || errno == ENOTDIR) return std::vector<Entry>();
    return SystemError("cannot list blob directory", dir, errno);
  }
  std::vector<Entry> entries;
  for (;;) {
    errno = 0;
    const dirent* d = ::readdir(handle);
    if (d == nullptr) break;
    const std::string_view name = d->d_name;
    if (name == "." || name == "..") continue;
    Entry entry{std::string(name), Kind::kOther};
    unsigned char type = d->d_type;
    if (type == DT_UNKNOWN) {
      struct stat st;
      if (::fstatat(::dirfd(handle), d->d_name, &st, AT_SYMLINK_NOFOLLOW) != 0) continue;
      type = S_ISREG(st.st_mode) ? DT_REG : S_ISDIR(st.st_mode) ? DT_DIR : DT_UNKNOWN;
    }
    if (type == DT_REG) entry.kind = Kind::kFile;
    if (type == DT_DIR) entry.kind = Kind::kDirectory;
    entries.push_back(std::move(entry));
  }
  const int error = errno;
  ::closedir(handle);
  if (error != 0) return SystemError("cannot list blob directory", dir, error);
  return entries;
}

// Syncs the entries of `dir`; nothing to do when another thread or process removed it.
Status FsyncDirectory(const std::string& dir) {
  Fd fd(::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC));
  if (!fd && errno == ENOENT) return {};
  if (!fd) return SystemError("cannot open blob directory", dir, errno);
  if (::fsync(fd.get()) != 0) return SystemError("cannot sync blob directory", dir, errno);
  return {};
}

// Creates a new temporary file in `dir` (mode 0600) and sets `path`; the descriptor, or
// -errno.
int CreateTemp(const std::string& dir, std::string& path) {
  thread_local std::mt19937_64 random([] {
    std::random_device device;
    return (uint64_t{device()} << 32) ^ device() ^
           std::hash<std::thread::id>()(std::this_thread::get_id());
  }());
  for (;;) {
    char name[64];
    std::snprintf(name, sizeof(name), "%.*s%016llx%.*s", static_cast<int>(kTempPrefix.size()),
                  kTempPrefix.data(), static_cast<unsigned long long>(random()),
                  static_cast<int>(kTempSuffix.size()), kTempSuffix.data());
    path = Join(dir, name);
    const int fd = ::open(path.c_str(), O_CREAT | O_EXCL | O_WRONLY | O_CLOEXEC, 0600);
    if (fd >= 0) {
      ::fchmod(fd, 0600);  // whatever the umask
      return fd;
    }
    if (errno != EEXIST) return -errno;
  }
}

// Whether the file at `path` holds exactly `bytes`.
Expected<bool> HoldsExactly(const std::string& path, std::string_view bytes) {
  Fd fd(::open(path.c_str(), O_RDONLY | O_CLOEXEC));
  if (!fd) {
    if (errno == ENOENT || errno == ENOTDIR) return false;
    return SystemError("cannot open blob file", path, errno);
  }
  struct stat st;
  if (::fstat(fd.get(), &st) != 0) return SystemError("cannot stat blob file", path, errno);
  if (static_cast<uint64_t>(st.st_size) != bytes.size()) return false;
  std::vector<char> buffer(std::min<size_t>(bytes.size(), 1 << 16));
  size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n =
        ::pread(fd.get(), buffer.data(), std::min(buffer.size(), bytes.size() - done), done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return SystemError("cannot read blob file", path, errno);
    if (n == 0) return false;
    if (std::memcmp(buffer.data(), bytes.data() + done, n) != 0) return false;
    done += n;
  }
  return true;
}

// Removes the blob files and key directories under `dir`, then `dir` itself unless another
// file remains (a Put in progress, another program's file): then its removals are synced.
Status RemoveTree(const std::string& dir) {
  auto entries = ListDirectory(dir);
  if (!entries) return entries.error();
  for (const Entry& e : *entries) {
    const std::string path = Join(dir, e.name);
    if (e.kind == Kind::kFile && DecodeBlobFileName(e.name)) {
      if (::unlink(path.c_str()) != 0 && errno != ENOENT) {
        return SystemError("cannot delete blob file", path, errno);
      }
    } else if (e.kind == Kind::kDirectory && Decode(e.name)) {
      if (Status s = RemoveTree(path); !s) return s;
    }
  }
  if (::rmdir(dir.c_str()) == 0 || errno == ENOENT) return {};
  if (errno != ENOTEMPTY && errno != EEXIST) {
    return SystemError("cannot remove blob directory", dir, errno);
  }
  return FsyncDirectory(dir);
}

using FileTime = std::filesystem::file_time_type;

// Removes temporary files last changed before `stale_before` under `dir`.
void RemoveStaleTemps(const std::string& dir, FileTime stale_before) {
  auto entries = ListDirectory(dir);
  if (!entries) return;
  for (const Entry& e : *entries) {
    const std::string path = Join(dir, e.name);
    if (e.kind == Kind::kFile && IsTempName(e.name)) {
      std::error_code ec;
      const auto changed = std::filesystem::last_write_time(path, ec);
      if (!ec && changed < stale_before) ::unlink(path.c_str());
    } else if (e.kind == Kind::kDirectory && Decode(e.name)) {
      RemoveStaleTemps(path, stale_before);
    }
  }
}

class FileBlobReader : public BlobReader {
 public:
  FileBlobReader(Fd fd, std::string path, std::string key, const struct stat& st)
      : fd_(std::move(fd)),
        path_(std::move(path)),
        key_(std::move(key)),
        device_(st.st_dev),
        inode_(st.st_ino),
        size_(static_cast<uint64_t>(st.st_size)) {}

  uint64_t size() const override { return size_; }

  Expected<size_t> Read(uint64_t offset, std::span<char> out) override {
    if (offset >= size_ || out.empty()) return size_t{0};
    // A Put renames a new file over the key's, so the key naming the file opened, with its
    // size, means the bytes read are the payload's.
    struct stat named, opened;
    if (::stat(path_.c_str(), &named) != 0) {
      if (errno == ENOENT || errno == ENOTDIR) return Changed();
      return SystemError("cannot stat blob file", path_, errno);
    }
    if (::fstat(fd_.get(), &opened) != 0) {
      return SystemError("cannot stat blob file", path_, errno);
    }
    if (named.st_dev != device_ || named.st_ino != inode_ ||
        static_cast<uint64_t>(named.st_size) != size_ ||
        static_cast<uint64_t>(opened.st_size) != size_) {
      return Changed();
    }
    const size_t count = static_cast<size_t>(std::min<uint64_t>(out.size(), size_ - offset));
    size_t done = 0;
    while (done < count) {
      const ssize_t n =
          ::pread(fd_.get(), out.data() + done, count - done, static_cast<off_t>(offset + done));
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) return SystemError("cannot read blob file", path_, errno);
      if (n == 0) return Changed();  // cut short in place by another program
      done += static_cast<size_t>(n);
    }
    return count;
  }

 private:
  Error Changed() const {
    return MakeError("changed",
                     "blob " + key_ + " was replaced or deleted while being read; read it again");
  }

  Fd fd_;
  std::string path_;
  std::string key_;
  dev_t device_;
  ino_t inode_;
  uint64_t size_;  // bytes
};

// The location of `key` under `root`; code "invalid_argument" when it cannot be a path.
Expected<Location> Locate(const std::string& root, const std::string& key) {
  const std::vector<std::string_view> parts = SplitKey(key);
  Location at;
  at.dir = root;
  for (size_t i = 0; i + 1 < parts.size(); ++i) {
    const std::string name = Encode(parts[i]);
    if (name.size() > kNameMax) {
      return MakeError("invalid_argument",
                       "blob key " + key + " has a component too long for a file name");
    }
    at.dir = Join(at.dir, name);
    at.dirs.push_back(at.dir);
  }
  std::string name = Encode(parts.back());
  name += kBlobSuffix;
  if (name.size() > kNameMax) {
    return MakeError("invalid_argument",
                     "blob key " + key + " has a component too long for a file name");
  }
  at.file = Join(at.dir, name);
  if (at.file.size() > kPathMax) {
    return MakeError("invalid_argument", "blob key " + key + " is too long for a path");
  }
  return at;
}

// Creates the directories of `at` that are missing, syncing the parent of each one created;
// 0, or the errno and the directory that failed.
int MakeDirectories(const Location& at, const std::string& root, std::string& failed) {
  std::string parent = root;
  for (const std::string& dir : at.dirs) {
    if (::mkdir(dir.c_str(), 0700) == 0) {
      Fd fd(::open(parent.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC));
      if (!fd || ::fsync(fd.get()) != 0) {
        const int error = errno;
        failed = parent;
        return error;
      }
    } else if (errno != EEXIST) {
      failed = dir;
      return errno;
    }
    parent = dir;
  }
  return 0;
}

// Writes `bytes` to the new file `fd` and syncs it; 0 or the errno and what failed.
int WriteAndSync(int fd, std::string_view bytes, const char*& what) {
  size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      what = "cannot write blob file";
      return errno;
    }
    done += static_cast<size_t>(n);
  }
  if (::fsync(fd) != 0) {
    what = "cannot sync blob file";
    return errno;
  }
  return 0;
}

// Adds the keys of the files under `dir`, whose keys start with key_prefix.
Status CollectKeys(const std::string& dir, const std::string& key_prefix,
                   std::vector<std::string>& keys) {
  auto entries = ListDirectory(dir);
  if (!entries) return entries.error();
  for (const Entry& e : *entries) {
    if (e.kind == Kind::kFile) {
      if (auto component = DecodeBlobFileName(e.name)) keys.push_back(key_prefix + *component);
    } else if (e.kind == Kind::kDirectory) {
      if (auto component = Decode(e.name)) {
        if (Status s = CollectKeys(Join(dir, e.name), key_prefix + *component + "/", keys); !s) {
          return s;
        }
      }
    }
  }
  return {};
}

}  // namespace

Expected<std::unique_ptr<FileBlobStore>> FileBlobStore::Open(const std::string& dir) {
  std::error_code ec;
  std::string root = std::filesystem::absolute(dir, ec).lexically_normal().string();
  if (ec || dir.empty()) {
    return MakeError("io", "blob directory '" + dir +
                               "' is not a usable path; name an existing "
                               "directory the server may write to");
  }
  while (root.size() > 1 && root.back() == '/') root.pop_back();
  struct stat st;
  if (::stat(root.c_str(), &st) != 0) {
    return MakeError("io", "blob directory '" + dir + "': " + std::strerror(errno) +
                               "; create it (writable by the server's user) or name another");
  }
  if (!S_ISDIR(st.st_mode)) {
    return MakeError("io", "blob directory '" + dir +
                               "' is not a directory; name a directory the server may write to");
  }
  std::string probe;
  const int fd = CreateTemp(root, probe);
  if (fd < 0) {
    return MakeError("io", "blob directory '" + dir + "' is not writable: " + std::strerror(-fd) +
                               "; give the server's user write access to it or name another");
  }
  ::close(fd);
  ::unlink(probe.c_str());
  RemoveStaleTemps(root, FileTime::clock::now() - kStaleTempAge);
  return std::unique_ptr<FileBlobStore>(new FileBlobStore(std::move(root)));
}

Expected<std::string> FileBlobStore::PathOfKey(const std::string& key) const {
  auto at = Locate(root_, key);
  if (!at) return at.error();
  return at->file;
}

Status FileBlobStore::Put(const std::string& key, std::string_view bytes) {
  auto at = Locate(root_, key);
  if (!at) return at.error();
  // Unchanged bytes write nothing, so readers of them go on.
  auto same = HoldsExactly(at->file, bytes);
  if (!same) return same.error();
  if (*same) return {};
  std::string temp;
  Fd fd;
  for (int attempt = 1;; ++attempt) {
    std::string failed;
    int error = MakeDirectories(*at, root_, failed);
    const char* what = "cannot create blob directory";
    if (error == 0) {
      const int opened = CreateTemp(at->dir, temp);
      if (opened >= 0) {
        fd = Fd(opened);
        break;
      }
      error = -opened;
      failed = at->dir;
      what = "cannot create a temporary file in blob directory";
    }
    // ENOENT: a DeletePrefix removed a directory on the way once it was empty; again.
    if (error != ENOENT || attempt == kPutAttempts) return SystemError(what, failed, error);
  }
  const char* what = "";
  int error = WriteAndSync(fd.get(), bytes, what);
  if (error == 0 && (error = fd.Close()) != 0) what = "cannot close blob file";
  if (error == 0 && ::rename(temp.c_str(), at->file.c_str()) != 0) {
    error = errno;
    what = "cannot rename a temporary file to blob file";
  }
  if (error != 0) {
    ::unlink(temp.c_str());
    return SystemError(what, at->file, error);
  }
  return FsyncDirectory(at->dir);
}

Expected<std::optional<std::string>> FileBlobStore::Get(const std::string& key) {
  auto at = Locate(root_, key);
  if (!at) return std::optional<std::string>();  // no such file can exist
  Fd fd(::open(at->file.c_str(), O_RDONLY | O_CLOEXEC));
  if (!fd) {
    if (errno == ENOENT || errno == ENOTDIR) return std::optional<std::string>();
    return SystemError("cannot open blob file", at->file, errno);
  }
  struct stat st;
  if (::fstat(fd.get(), &st) != 0) return SystemError("cannot stat blob file", at->file, errno);
  std::string bytes(static_cast<size_t>(st.st_size), '\0');
  size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::pread(fd.get(), bytes.data() + done, bytes.size() - done, done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return SystemError("cannot read blob file", at->file, errno);
    if (n == 0) {
      return MakeError("storage", "blob file " + at->file + " ended at byte " +
                                      std::to_string(done) + " of " + std::to_string(bytes.size()));
    }
    done += static_cast<size_t>(n);
  }
  return std::optional<std::string>(std::move(bytes));
}

Expected<std::unique_ptr<BlobReader>> FileBlobStore::OpenReader(const std::string& key) {
  auto at = Locate(root_, key);
  if (!at) return std::unique_ptr<BlobReader>();  // no such file can exist
  Fd fd(::open(at->file.c_str(), O_RDONLY | O_CLOEXEC));
  if (!fd) {
    if (errno == ENOENT || errno == ENOTDIR) return std::unique_ptr<BlobReader>();
    return SystemError("cannot open blob file", at->file, errno);
  }
  struct stat st;
  if (::fstat(fd.get(), &st) != 0) return SystemError("cannot stat blob file", at->file, errno);
  return std::unique_ptr<BlobReader>(new FileBlobReader(std::move(fd), at->file, key, st));
}

Status FileBlobStore::DeletePrefix(const std::string& prefix) {
  // Every key starting with prefix lives in the directory of the part before the last '/',
  // as a file or directory whose decoded name starts with the rest.
  const size_t slash = prefix.rfind('/');
  std::string dir = root_;
  if (slash != std::string::npos) {
    for (std::string_view part : SplitKey(std::string_view(prefix).substr(0, slash))) {
      const std::string name = Encode(part);
      if (name.size() > kNameMax) return {};  // no such directory can exist
      dir = Join(dir, name);
    }
  }
  const std::string_view rest = slash == std::string::npos
                                    ? std::string_view(prefix)
                                    : std::string_view(prefix).substr(slash + 1);
  auto entries = ListDirectory(dir);
  if (!entries) return entries.error();
  bool removed = false;
  for (const Entry& e : *entries) {
    const std::string path = Join(dir, e.name);
    if (e.kind == Kind::kFile) {
      const auto component = DecodeBlobFileName(e.name);
      if (!component || !component->starts_with(rest)) continue;
      if (::unlink(path.c_str()) != 0 && errno != ENOENT) {
        return SystemError("cannot delete blob file", path, errno);
      }
      removed = true;
    } else if (e.kind == Kind::kDirectory) {
      const auto component = Decode(e.name);
      if (!component || !component->starts_with(rest)) continue;
      if (Status s = RemoveTree(path); !s) return s;
      removed = true;
    }
  }
  if (removed) {
    if (Status s = FsyncDirectory(dir); !s) return s;
  }
  // Directories left empty go, up to the root.
  while (dir != root_) {
    if (::rmdir(dir.c_str()) != 0 && errno != ENOENT) break;
    dir = Parent(dir);
    if (Status s = FsyncDirectory(dir); !s) return s;
  }
  return {};
}

Expected<std::vector<std::string>> FileBlobStore::ListKeys() {
  std::vector<std::string> keys;
  if (Status s = CollectKeys(root_, "", keys); !s) return s.error();
  std::sort(keys.begin(), keys.end());  // std::string compares bytes as unsigned char
  return keys;
}

}  // namespace reenact::server
