#pragma once
// Types of the HTTP API (proto/API.md) shared by the server and the clients, with their JSON
// forms. Distances in metres, angles in degrees (WGS84).

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/error/expected.h"

namespace reenact::proto {

// One published clip in a nearby listing.
struct ClipSummary {
  std::string id;  // opaque clip id
  std::string title;
  std::string author;
  double lat_deg = 0.0;
  double lon_deg = 0.0;
  double alt_m = 0.0;
  double distance_m = 0.0;  // great-circle distance from the query point
  double duration_s = 0.0;
  int64_t frame_count = 0;
};

// {"id","title","author","location":{"lat_deg","lon_deg","alt_m"},"distance_m","duration_s",
//  "frame_count"}
nlohmann::json ClipSummaryToJson(const ClipSummary& clip);
// code "invalid_argument" naming the missing or mistyped field.
Expected<ClipSummary> ClipSummaryFromJson(const nlohmann::json& json);

// A page of GET /v1/clips: the clips and, when more follow, the cursor to ask for them.
struct NearbyPage {
  std::vector<ClipSummary> clips;
  std::optional<std::string> next_cursor;
};
Expected<NearbyPage> ParseNearbyPage(std::string_view body);

// One of the caller's own clips (GET /v1/me/clips): the summary (distance_m 0), its state
// and the SHA-256 of the manifest it was created from.
struct OwnClip {
  ClipSummary summary;
  bool published = false;  // "state": "published" (else "draft")
  std::string manifest_sha256;
};
Expected<std::vector<OwnClip>> ParseOwnClips(std::string_view body);

// A part of a clip as GET /v1/clips/{id}/parts reports it: what the manifest promises and
// what the server holds. index >= 0 is a frame, kMapPartIndex the map; JSON
// {"part": "frames/N" | "map", "bytes", "sha256", "held": null | {"bytes", "sha256"}}.
inline constexpr int kMapPartIndex = -1;
struct HeldBytes {
  uint64_t bytes = 0;
  std::string sha256;  // of the bytes the server holds, hashed when it answered
};
struct PartStatus {
  int index = 0;
  uint64_t bytes = 0;  // the manifest's size
  std::string sha256;  // the manifest's hash
  std::optional<HeldBytes> held;  // nullopt: not uploaded yet

  // The server holds exactly the promised bytes: nothing to send.
  bool Complete() const { return held && held->bytes == bytes && held->sha256 == sha256; }
};
// {"id", "state": "draft" | "published", "parts": [...frames in order, then the map]}
struct ClipParts {
  std::string id;
  bool published = false;
  std::vector<PartStatus> parts;
};
nlohmann::json ClipPartsToJson(const ClipParts& parts);
// code "invalid_argument" naming what is malformed.
Expected<ClipParts> ParseClipParts(std::string_view body);

// The error body of every failed request: {"error":{"code":"...","message":"..."}}.
std::string ErrorBodyJson(std::string_view code, std::string_view message);
// The Error in such a body, or nullopt if the body is not one.
std::optional<Error> ParseErrorBody(std::string_view body);

}  // namespace reenact::proto
