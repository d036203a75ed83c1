#include <openssl/rand.h>

#include "proto/clip/content_hash.h"
#include "proto/clip/manifest.h"
#include "server/http/handlers.h"

namespace reenact::server::handlers {

namespace {

bool HasMediaType(const Request& request, std::string_view media_type) {
  const auto header = request.Header("Content-Type");
  if (!header) return false;
  std::string_view value = *header;
  value = value.substr(0, value.find(';'));
  while (!value.empty() && value.back() == ' ') value.remove_suffix(1);
  return EqualsIgnoreCase(value, media_type);
}

Response WrongMediaType(std::string_view expected) {
  return ErrorResponse(415, "unsupported_media_type",
                       "Content-Type must be " + std::string(expected));
}

// 96 random bits as 24 lowercase hex digits.
Expected<std::string> NewClipId() {
  unsigned char bytes[12];
  if (RAND_bytes(bytes, sizeof(bytes)) != 1) {
    return MakeError("crypto", "random generator failed");
  }
  static constexpr char kHex[] = "0123456789abcdef";
  std::string id;
  for (unsigned char b : bytes) {
    id.push_back(kHex[b >> 4]);
    id.push_back(kHex[b & 15]);
  }
  return id;
}

std::string PartName(int index) {
  return index == kMapPart ? std::string("the map") : "frame " + std::to_string(index);
}

std::string MissingList(const std::vector<int>& missing) {
  constexpr size_t kShown = 20;
  std::vector<std::string> frames;
  bool map = false;
  size_t frame_total = 0;
  for (int index : missing) {
    if (index == kMapPart) {
      map = true;
    } else if (++frame_total <= kShown) {
      frames.push_back(std::to_string(index));
    }
  }
  std::string text;
  if (frame_total > 0) {
    text = frame_total == 1 ? "frame " : "frames ";
    for (size_t i = 0; i < frames.size(); ++i) text += (i ? ", " : "") + frames[i];
    if (frame_total > kShown) text += " (and " + std::to_string(frame_total - kShown) + " more)";
  }
  if (map) text += std::string(text.empty() ? "" : " and ") + "the map";
  return text;
}

}  // namespace

Response CreateClip(const Request& request, ServiceContext& context) {
  auto user = RequireUser(request, context);
  if (auto* response = std::get_if<Response>(&user)) return std::move(*response);
  const UserRecord& owner = std::get<UserRecord>(user);
  const ServiceLimits& limits = context.limits;
  if (!HasMediaType(request, "application/json")) return WrongMediaType("application/json");
  if (request.body.size() > limits.max_manifest_bytes) {
    return ErrorResponse(413, "too_large",
                         "manifest is " + std::to_string(request.body.size()) +
                             " bytes; the limit is " + std::to_string(limits.max_manifest_bytes));
  }
  if (!nlohmann::json::accept(request.body)) {
    return ErrorResponse(400, "bad_request", "request body is not valid JSON");
  }
  auto manifest = proto::ParseManifest(request.body);
  if (!manifest) return ErrorResponse(422, "invalid_manifest", manifest.error().message);
  if (manifest->frame_count > limits.max_frame_count) {
    return ErrorResponse(422, "invalid_manifest",
                         "manifest declares " + std::to_string(manifest->frame_count) +
                             " frames; this server accepts at most " +
                             std::to_string(limits.max_frame_count));
  }
  NewClip clip;
  for (size_t i = 0; i < manifest->frame_parts.size(); ++i) {
    const proto::PartInfo& part = manifest->frame_parts[i];
    if (part.bytes > limits.max_frame_bytes) {
      return ErrorResponse(422, "invalid_manifest",
                           "frame " + std::to_string(i) + " declares " +
                               std::to_string(part.bytes) + " bytes; the limit is " +
                               std::to_string(limits.max_frame_bytes) + " bytes per frame");
    }
    clip.parts.push_back(
        PartSpec{static_cast<int>(i), static_cast<int64_t>(part.bytes), part.sha256});
  }
  if (manifest->map_part.bytes > limits.max_map_bytes) {
    return ErrorResponse(422, "invalid_manifest",
                         "the map declares " + std::to_string(manifest->map_part.bytes) +
                             " bytes; the limit is " + std::to_string(limits.max_map_bytes));
  }
  clip.parts.push_back(PartSpec{kMapPart, static_cast<int64_t>(manifest->map_part.bytes),
                                manifest->map_part.sha256});
  clip.manifest_json = request.body;
  ClipRecord& record = clip.record;
  record.owner_id = owner.id;
  record.title = manifest->title;
  record.author = manifest->author;
  record.lat_deg = manifest->location.lat_deg;
  record.lon_deg = manifest->location.lon_deg;
  record.alt_m = manifest->location.alt_m;
  record.duration_s = manifest->DurationS();
  record.frame_count = static_cast<int>(manifest->frame_count);
  record.manifest_sha256 = proto::Sha256Hex(request.body);
  auto id = NewClipId();
  if (!id) return StorageFailure(id.error());
  record.id = *id;
  if (Status s = context.metadata.CreateClip(clip); !s) return StorageFailure(s.error());
  Response response = JsonResponse(201, {{"id", record.id}});
  response.headers.emplace_back("Location", "/v1/clips/" + record.id);
  return response;
}

namespace {

// What a PUT of a part writes to, once the caller is known to own it.
struct PartTarget {
  int index = 0;
  PartRecord part;
};

// The part a PUT names if the caller may write it with this Content-Type: 401, 403/404,
// 400 for a malformed frame number, 415, 404 for a part the manifest does not promise.
std::variant<PartTarget, Response> WritablePart(const Request& request, ServiceContext& context,
                                                const RouteMatch& match) {
  auto user = RequireUser(request, context);
  if (auto* response = std::get_if<Response>(&user)) return std::move(*response);
  auto clip = LoadOwnedClip(context, match.clip_id, std::get<UserRecord>(user));
  if (auto* response = std::get_if<Response>(&clip)) return std::move(*response);
  auto index_or = PartIndex(match);
  if (auto* response = std::get_if<Response>(&index_or)) return std::move(*response);
  const int index = std::get<int>(index_or);
  if (!HasMediaType(request, "application/octet-stream")) {
    return WrongMediaType("application/octet-stream");
  }
  auto part = context.metadata.GetPart(match.clip_id, index);
  if (!part) return StorageFailure(part.error());
  if (!*part) {
    return ErrorResponse(404, "not_found",
                         "clip '" + match.clip_id + "' has no " + PartName(index) + " (it has " +
                             std::to_string(std::get<ClipRecord>(clip).frame_count) +
                             " frames, numbered from 0)");
  }
  return PartTarget{index, **part};
}

Response SizeMismatch(int index, uint64_t got, int64_t promised) {
  return ErrorResponse(422, "size_mismatch",
                       PartName(index) + " is " + std::to_string(got) +
                           " bytes but the manifest says " + std::to_string(promised));
}

}  // namespace

std::optional<Response> AdmitCreateClip(const Request& head, ServiceContext& context) {
  auto user = RequireUser(head, context);
  if (auto* response = std::get_if<Response>(&user)) return std::move(*response);
  if (!HasMediaType(head, "application/json")) return WrongMediaType("application/json");
  return std::nullopt;
}

std::optional<Response> AdmitPutPart(const Request& head, std::optional<uint64_t> content_length,
                                     ServiceContext& context, const RouteMatch& match) {
  auto target = WritablePart(head, context, match);
  if (auto* response = std::get_if<Response>(&target)) return std::move(*response);
  const PartTarget& part = std::get<PartTarget>(target);
  if (content_length && static_cast<int64_t>(*content_length) != part.part.spec.bytes) {
    return SizeMismatch(part.index, *content_length, part.part.spec.bytes);
  }
  return std::nullopt;
}

Response PutPart(const Request& request, ServiceContext& context, const RouteMatch& match) {
  auto target = WritablePart(request, context, match);
  if (auto* response = std::get_if<Response>(&target)) return std::move(*response);
  const auto& [index, part] = std::get<PartTarget>(target);
  const size_t limit =
      index == kMapPart ? context.limits.max_map_bytes : context.limits.max_frame_bytes;
  if (request.body.size() > limit) {
    return ErrorResponse(413, "too_large",
                         PartName(index) + " is " + std::to_string(request.body.size()) +
                             " bytes; the limit is " + std::to_string(limit));
  }
  const PartSpec& spec = part.spec;
  if (static_cast<int64_t>(request.body.size()) != spec.bytes) {
    return SizeMismatch(index, request.body.size(), spec.bytes);
  }
  if (proto::Sha256Hex(request.body) != spec.sha256) {
    return ErrorResponse(422, "hash_mismatch",
                         "the SHA-256 of " + PartName(index) +
                             " differs from the manifest's; the upload was corrupted or the "
                             "manifest is stale");
  }
  Response done;
  done.status = 204;
  done.content_type.clear();
  // A part sent again is written again: the bytes are the verified ones, so this is
  // idempotent, and it repairs a stored copy that was damaged (GET .../parts shows which).
  if (Status s = context.blobs.Put(BlobKey(match.clip_id, index), request.body); !s) {
    return StorageFailure(s.error());
  }
  if (part.present) return done;
  if (Status s = context.metadata.MarkPartPresent(match.clip_id, index); !s) {
    return StorageFailure(s.error());
  }
  return done;
}

Response Publish(const Request& request, ServiceContext& context, const RouteMatch& match) {
  auto user = RequireUser(request, context);
  if (auto* response = std::get_if<Response>(&user)) return std::move(*response);
  auto clip = LoadOwnedClip(context, match.clip_id, std::get<UserRecord>(user));
  if (auto* response = std::get_if<Response>(&clip)) return std::move(*response);
  if (std::get<ClipRecord>(clip).state == ClipState::kDraft) {
    // Every stored part is read back and hashed: a draft whose stored bytes were damaged
    // after upload is never made visible.
    auto damaged = DamagedParts(context, match.clip_id);
    if (!damaged) return StorageFailure(damaged.error());
    if (!damaged->empty()) {
      return ErrorResponse(409, "incomplete",
                           "clip '" + match.clip_id + "' cannot be published yet: the server's "
                           "copy of " + MissingList(*damaged) +
                               " differs from the manifest; upload them again");
    }
  }
  auto result = context.metadata.Publish(match.clip_id);
  if (!result) return StorageFailure(result.error());
  if (!result->published) {
    return ErrorResponse(409, "incomplete",
                         "clip '" + match.clip_id + "' cannot be published yet: missing " +
                             MissingList(result->missing_parts));
  }
  return JsonResponse(200, {{"id", match.clip_id}, {"state", "published"}});
}

Response DeleteClip(const Request& request, ServiceContext& context, const RouteMatch& match) {
  auto user = RequireUser(request, context);
  if (auto* response = std::get_if<Response>(&user)) return std::move(*response);
  auto clip = LoadOwnedClip(context, match.clip_id, std::get<UserRecord>(user));
  if (auto* response = std::get_if<Response>(&clip)) return std::move(*response);
  auto deleted = context.metadata.DeleteClip(match.clip_id);
  if (!deleted) return StorageFailure(deleted.error());
  if (Status s = context.blobs.DeletePrefix(match.clip_id + "/"); !s) {
    return StorageFailure(s.error());
  }
  Response done;
  done.status = 204;
  done.content_type.clear();
  return done;
}

}  // namespace reenact::server::handlers
