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

Expected<std::vector<OwnClip>> ParseOwnClips(std::string_view body) {
  const json parsed = json::parse(body, nullptr, /*allow_exceptions=*/false);
  if (parsed.is_discarded() || !parsed.is_object() || !parsed.contains("clips") ||
      !parsed["clips"].is_array()) {
    return MakeError("invalid_argument", "clip listing is not a JSON object with a 'clips' array");
  }
  std::vector<OwnClip> clips;
  for (const json& item : parsed["clips"]) {
    auto summary = ClipSummaryFromJson(item);
    if (!summary) return summary.error();
    auto state = StringField(item, "state", "own clip");
    if (!state) return state.error();
    OwnClip clip;
    clip.summary = std::move(*summary);
    clip.published = *state == "published";
    if (auto hash = item.find("manifest_sha256"); hash != item.end() && hash->is_string()) {
      clip.manifest_sha256 = hash->get<std::string>();
    }
    clips.push_back(std::move(clip));
  }
  return clips;
}

json ClipPartsToJson(const ClipParts& parts) {
  json list = json::array();
  for (const PartStatus& part : parts.parts) {
    json item = {{"part", part.index == kMapPartIndex ? std::string("map")
                                                       : "frames/" + std::to_string(part.index)},
                 {"bytes", part.bytes},
                 {"sha256", part.sha256},
                 {"held", nullptr}};
    if (part.held) item["held"] = {{"bytes", part.held->bytes}, {"sha256", part.held->sha256}};
    list.push_back(std::move(item));
  }
  return json{{"id", parts.id},
              {"state", parts.published ? "published" : "draft"},
              {"parts", std::move(list)}};
}

Expected<ClipParts> ParseClipParts(std::string_view body) {
  constexpr const char* kWhere = "part listing";
  const json parsed = json::parse(body, nullptr, /*allow_exceptions=*/false);
  if (parsed.is_discarded() || !parsed.is_object()) {
    return MakeError("invalid_argument", "part listing is not a JSON object");
  }
  auto id = StringField(parsed, "id", kWhere);
  if (!id) return id.error();
  auto state = StringField(parsed, "state", kWhere);
  if (!state) return state.error();
  auto list = parsed.find("parts");
  if (list == parsed.end() || !list->is_array()) {
    return MakeError("invalid_argument", "part listing has no 'parts' array");
  }
  ClipParts parts;
  parts.id = *id;
  parts.published = *state == "published";
  for (const json& item : *list) {
    if (!item.is_object()) return MakeError("invalid_argument", "part listing: item not an object");
    auto name = StringField(item, "part", kWhere);
    auto sha = StringField(item, "sha256", kWhere);
    auto bytes = NumberField(item, "bytes", kWhere);
    if (!name) return name.error();
    if (!sha) return sha.error();
    if (!bytes) return bytes.error();
    PartStatus part;
    if (*name == "map") {
      part.index = kMapPartIndex;
    } else if (name->rfind("frames/", 0) == 0 && name->size() > 7 && name->size() < 17 &&
               name->find_first_not_of("0123456789", 7) == std::string::npos) {
      part.index = std::stoi(name->substr(7));
    } else {
      return MakeError("invalid_argument", "part listing: unknown part '" + name->substr(0, 40) +
                                               "' (expected frames/N or map)");
    }
    part.bytes = static_cast<uint64_t>(*bytes);
    part.sha256 = *sha;
    auto held = item.find("held");
    if (held != item.end() && held->is_object()) {
      auto held_bytes = NumberField(*held, "bytes", "part listing held");
      auto held_sha = StringField(*held, "sha256", "part listing held");
      if (!held_bytes) return held_bytes.error();
      if (!held_sha) return held_sha.error();
      part.held = HeldBytes{static_cast<uint64_t>(*held_bytes), *held_sha};
    } else if (held == item.end() || !held->is_null()) {
      return MakeError("invalid_argument", "part listing: 'held' must be an object or null");
    }
    parts.parts.push_back(std::move(part));
  }
  return parts;
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
