#include <algorithm>
#include <vector>

#include "proto/api/api_types.h"
#include "proto/clip/content_hash.h"
#include "server/http/handlers.h"

namespace reenact::server::handlers {

namespace {

// Bytes read and hashed at a time: a part's hash costs at most this much memory.
constexpr uint64_t kHashChunkBytes = uint64_t{1} << 20;

// The size and SHA-256 of the payload under key, read in pieces; nullopt when absent. Code
// "changed" when the payload was replaced or deleted while being read.
Expected<std::optional<proto::HeldBytes>> HashBlob(BlobStore& blobs, const std::string& key) {
  auto reader = blobs.OpenReader(key);
  if (!reader) return reader.error();
  if (!*reader) return std::optional<proto::HeldBytes>();
  const uint64_t size = (*reader)->size();
  std::vector<char> buffer(std::max<uint64_t>(1, std::min(size, kHashChunkBytes)));
  proto::Sha256Hasher hasher;
  for (uint64_t offset = 0; offset < size;) {
    auto n = (*reader)->Read(offset, buffer);
    if (!n) return n.error();
    if (*n == 0) {
      return MakeError("storage", "blob " + key + " ended after " + std::to_string(offset) +
                                      " of its " + std::to_string(size) + " bytes");
    }
    hasher.Update(std::string_view(buffer.data(), *n));
    offset += *n;
  }
  return std::optional<proto::HeldBytes>(proto::HeldBytes{size, hasher.FinalHex()});
}

// What the blob store holds for a part the metadata marks present: its size and fresh
// SHA-256, or nullopt when the part is not marked present or its blob is missing.
Expected<std::optional<proto::HeldBytes>> Held(ServiceContext& context, const std::string& clip_id,
                                               const PartRecord& part) {
  if (!part.present) return std::optional<proto::HeldBytes>();
  const std::string key = BlobKey(clip_id, part.spec.index);
  auto held = HashBlob(context.blobs, key);
  // Replaced (an upload of the part again) while being hashed: hash what is there now.
  if (!held && held.error().code == "changed") held = HashBlob(context.blobs, key);
  return held;
}

}  // namespace

Response ListParts(const Request& request, ServiceContext& context, const RouteMatch& match) {
  auto user = RequireUser(request, context);
  if (auto* response = std::get_if<Response>(&user)) return std::move(*response);
  auto clip = LoadOwnedClip(context, match.clip_id, std::get<UserRecord>(user));
  if (auto* response = std::get_if<Response>(&clip)) return std::move(*response);
  auto records = context.metadata.ListParts(match.clip_id);
  if (!records) {
    if (records.error().code == "not_found") {
      return ErrorResponse(404, "not_found", "no clip '" + match.clip_id + "'");
    }
    return StorageFailure(records.error());
  }
  proto::ClipParts parts;
  parts.id = match.clip_id;
  parts.published = std::get<ClipRecord>(clip).state == ClipState::kPublished;
  for (const PartRecord& record : *records) {
    proto::PartStatus status;
    status.index = record.spec.index == kMapPart ? proto::kMapPartIndex : record.spec.index;
    status.bytes = static_cast<uint64_t>(record.spec.bytes);
    status.sha256 = record.spec.sha256;
    auto held = Held(context, match.clip_id, record);
    if (!held) return StorageFailure(held.error());
    status.held = *held;
    parts.parts.push_back(std::move(status));
  }
  return JsonResponse(200, proto::ClipPartsToJson(parts));
}

Expected<std::vector<int>> DamagedParts(ServiceContext& context, const std::string& clip_id) {
  auto records = context.metadata.ListParts(clip_id);
  if (!records) return records.error();
  std::vector<int> damaged;
  for (const PartRecord& record : *records) {
    if (!record.present) continue;  // missing, not damaged: Publish reports it
    auto held = Held(context, clip_id, record);
    if (!held) return held.error();
    if (!*held || (*held)->bytes != static_cast<uint64_t>(record.spec.bytes) ||
        (*held)->sha256 != record.spec.sha256) {
      damaged.push_back(record.spec.index);
    }
  }
  return damaged;
}

}  // namespace reenact::server::handlers
