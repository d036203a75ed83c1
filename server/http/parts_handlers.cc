#include "proto/api/api_types.h"
#include "proto/clip/content_hash.h"
#include "server/http/handlers.h"

namespace reenact::server::handlers {

namespace {

// What the blob store holds for a part the metadata marks present: its size and fresh
// SHA-256, or nullopt when the part is not marked present or its blob is missing.
Expected<std::optional<proto::HeldBytes>> Held(ServiceContext& context, const std::string& clip_id,
                                               const PartRecord& part) {
  if (!part.present) return std::optional<proto::HeldBytes>();
  auto blob = context.blobs.Get(BlobKey(clip_id, part.spec.index));
  if (!blob) return blob.error();
  if (!*blob) return std::optional<proto::HeldBytes>();
  return std::optional<proto::HeldBytes>(
      proto::HeldBytes{(*blob)->size(), proto::Sha256Hex(**blob)});
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
