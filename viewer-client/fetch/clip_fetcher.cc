#include "viewer-client/fetch/clip_fetcher.h"

#include <fstream>
#include <sstream>

#include "proto/clip/content_hash.h"

namespace reenact::viewer {
namespace {

std::optional<std::string> ReadFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

Status WriteFileAtomically(const std::filesystem::path& path, const std::string& bytes) {
  const std::filesystem::path tmp = path.string() + ".part";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    if (!out) return MakeError("io", "cannot write cache file " + tmp.string());
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) return MakeError("io", "cannot move cache file into place: " + ec.message());
  return {};
}

// One part through the cache: cached and verified, or downloaded and verified.
template <typename Download>
Expected<std::string> CachedPart(const std::filesystem::path& objects, const proto::PartInfo& info,
                                 const std::string& what, Download download,
                                 uint64_t& bytes_downloaded) {
  const std::filesystem::path path = objects / info.sha256;
  if (auto cached = ReadFile(path);
      cached && cached->size() == info.bytes && proto::Sha256Hex(*cached) == info.sha256)
    return *cached;
  auto bytes = download();
  if (!bytes.ok()) return bytes.error();
  bytes_downloaded += bytes->size();
  if (bytes->size() != info.bytes || proto::Sha256Hex(*bytes) != info.sha256)
    return MakeError("corrupt", what + " arrived damaged (size or SHA-256 differs from the "
                                       "manifest); nothing was rendered, try again");
  if (Status s = WriteFileAtomically(path, *bytes); !s.ok()) return s.error();
  return bytes;
}

std::span<const uint8_t> Bytes(const std::string& s) {
  return {reinterpret_cast<const uint8_t*>(s.data()), s.size()};
}

}  // namespace

Expected<FetchedClip> FetchClip(const proto::ApiClient& api, const std::string& clip_id,
                                const std::filesystem::path& cache_dir) {
  const std::filesystem::path objects = cache_dir / "objects";
  std::error_code ec;
  std::filesystem::create_directories(objects, ec);
  if (ec) return MakeError("io", "cannot create cache folder " + objects.string() + ": " + ec.message());

  auto manifest_json = api.GetManifest(clip_id);
  if (!manifest_json.ok()) return manifest_json.error();
  auto manifest = proto::ParseManifest(*manifest_json);
  if (!manifest.ok()) return manifest.error();

  FetchedClip clip;
  clip.id = clip_id;
  clip.manifest = std::move(manifest).value();
  clip.bytes_downloaded = manifest_json->size();
  for (int64_t n = 0; n < clip.manifest.frame_count; ++n) {
    const proto::PartInfo& info = clip.manifest.frame_parts[n];
    auto bytes = CachedPart(objects, info, "frame " + std::to_string(n),
                            [&] { return api.GetFrame(clip_id, n); }, clip.bytes_downloaded);
    if (!bytes.ok()) return bytes.error();
    auto frame = proto::DecodeFrame(Bytes(*bytes));
    if (!frame.ok()) return frame.error();
    clip.frames.push_back(std::move(frame).value());
    clip.bytes_total += info.bytes;
  }
  auto map_bytes = CachedPart(objects, clip.manifest.map_part, "the map",
                              [&] { return api.GetMap(clip_id); }, clip.bytes_downloaded);
  if (!map_bytes.ok()) return map_bytes.error();
  auto map = proto::DecodeMap(Bytes(*map_bytes));
  if (!map.ok()) return map.error();
  clip.map = std::move(map).value();
  clip.bytes_total += clip.manifest.map_part.bytes + manifest_json->size();
  return clip;
}

}  // namespace reenact::viewer
