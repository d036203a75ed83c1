#include "proto/api/api_types.h"

namespace reenact::proto {

namespace {

using nlohmann::json;

Expected<double> NumberField(const json& object, const char* name, const char* where) {
  auto it = object.find(name);
  if (it == object.end() || !it->is_number()) {
    return MakeError("invalid_argument",
                     std::string(where) + ": field '" + name + "' is missing or not a number");
  }
  return it->get<double>();
}

Expected<std::string> StringField(const json& object, const char* name, const char* where) {
  auto it = object.find(name);
  if (it == object.end() || !it->is_string()) {
    return MakeError("invalid_argument",
                     std::string(where) + ": field '" + name + "' is missing or not a string");
  }
  return it->get<std::string>();
}

}  // namespace

json ClipSummaryToJson(const ClipSummary& clip) {
  return json{{"id", clip.id},
              {"title", clip.title},
              {"author", clip.author},
              {"location",
               {{"lat_deg", clip.lat_deg}, {"lon_deg", clip.lon_deg}, {"alt_m", clip.alt_m}}},
              {"distance_m", clip.distance_m},
              {"duration_s", clip.duration_s},
              {"frame_count", clip.frame_count}};
}

Expected<ClipSummary> ClipSummaryFromJson(const json& object) {
  constexpr const char* kWhere = "clip summary";
  if (!object.is_object()) return MakeError("invalid_argument", "clip summary is not an object");
  ClipSummary clip;
  auto id = StringField(object, "id", kWhere);
  auto title = StringField(object, "title", kWhere);
  auto author = StringField(object, "author", kWhere);
  for (const auto* s : {&id, &title, &author}) {
    if (!*s) return s->error();
  }
  clip.id = *id;
  clip.title = *title;
  clip.author = *author;
  auto location = object.find("location");
  if (location == object.end() || !location->is_object()) {
    return MakeError("invalid_argument", "clip summary: field 'location' is missing");
  }
  auto lat = NumberField(*location, "lat_deg", "clip summary location");
  auto lon = NumberField(*location, "lon_deg", "clip summary location");
  auto alt = NumberField(*location, "alt_m", "clip summary location");
  auto distance = NumberField(object, "distance_m", kWhere);
  auto duration = NumberField(object, "duration_s", kWhere);
  auto frames = NumberField(object, "frame_count", kWhere);
  for (const auto* n : {&lat, &lon, &alt, &distance, &duration, &frames}) {
    if (!*n) return n->error();
  }
  clip.lat_deg = *lat;
  clip.lon_deg = *lon;
  clip.alt_m = *alt;
  clip.distance_m = *distance;
  clip.duration_s = *duration;
  clip.frame_count = static_cast<int64_t>(*frames);
  return clip;
}

Expected<NearbyPage> ParseNearbyPage(std::string_view body) {
  const json parsed = json::parse(body, nullptr, /*allow_exceptions=*/false);
  if (parsed.is_discarded() || !parsed.is_object()) {
    return MakeError("invalid_argument", "nearby listing is not a JSON object");
  }
  auto clips = parsed.find("clips");
  if (clips == parsed.end() || !clips->is_array()) {
    return MakeError("invalid_argument", "nearby listing has no 'clips' array");
  }
  NearbyPage page;
  for (const json& item : *clips) {
    auto clip = ClipSummaryFromJson(item);
    if (!clip) return clip.error();
    page.clips.push_back(std::move(*clip));
  }
  auto cursor = parsed.find("next_cursor");
  if (cursor != parsed.end() && cursor->is_string()) page.next_cursor = cursor->get<std::string>();
  return page;
}

std::string ErrorBodyJson(std::string_view code, std::string_view message) {
  return json{{"error", {{"code", code}, {"message", message}}}}.dump(
      -1, ' ', false, json::error_handler_t::replace);
}

std::optional<Error> ParseErrorBody(std::string_view body) {
  const json parsed = json::parse(body, nullptr, /*allow_exceptions=*/false);
  if (parsed.is_discarded() || !parsed.is_object()) return std::nullopt;
  auto error = parsed.find("error");
  if (error == parsed.end() || !error->is_object()) return std::nullopt;
  auto code = error->find("code");
  auto message = error->find("message");
  if (code == error->end() || !code->is_string() || message == error->end() ||
      !message->is_string()) {
    return std::nullopt;
  }
  return Error{code->get<std::string>(), message->get<std::string>()};
}

}  // namespace reenact::proto
