#pragma once
// Duplicate keys in JSON objects. RFC 8259 only says that names SHOULD be unique, and parsers
// differ on {"a": 1, "a": 2} (nlohmann keeps the last, others the first or refuse it), so two
// readers of one document could see different values: proto refuses such documents.

#include <optional>
#include <string>
#include <string_view>

namespace reenact::proto {

// Where the first key that repeats within its object sits, as a path from the document's
// root: "title", "location.lat_deg", "parts.frames[2].sha256". nullopt when every object at
// every depth has distinct keys, and when json_text is not valid JSON (the caller's parser
// reports that). Keys of different objects may be equal.
std::optional<std::string> FirstDuplicateKey(std::string_view json_text);

}  // namespace reenact::proto
