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

// The error body of every failed request: {"error":{"code":"...","message":"..."}}.
std::string ErrorBodyJson(std::string_view code, std::string_view message);
// The Error in such a body, or nullopt if the body is not one.
std::optional<Error> ParseErrorBody(std::string_view body);

}  // namespace reenact::proto
