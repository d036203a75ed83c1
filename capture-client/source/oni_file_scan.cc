#include "capture-client/source/oni_file_scan.h"

#include <cstring>
#include <fstream>
#include <tuple>

namespace reenact::capture {
namespace {

constexpr uint32_t kRecordMagic = 0x0052494e;  // "NIR\0"
constexpr uint32_t kNodeAdded1004 = 0x02, kIntProperty = 0x03, kGeneralProperty = 0x06,
                   kNewData = 0x0A, kEnd = 0x0B, kNodeAdded1005 = 0x0C, kNodeAdded = 0x0D;
constexpr uint32_t kMaxFieldsBytes = 1 << 20;  // fields are names and small values

uint32_t U32(const std::vector<char>& b, size_t at) {
  uint32_t v;
  std::memcpy(&v, b.data() + at, 4);
  return v;
}

// Reads a length-prefixed, NUL-terminated name at `at` of the record's fields.
std::optional<std::string> Name(const std::vector<char>& fields, size_t& at) {
  if (at + 4 > fields.size()) return std::nullopt;
  const uint32_t length = U32(fields, at);
  at += 4;
  if (length == 0 || at + length > fields.size() || fields[at + length - 1] != '\0')
    return std::nullopt;
  std::string name(fields.data() + at, length - 1);
  at += length;
  return name;
}

}  // namespace

const OniNodeInfo* OniFileSummary::FirstNodeOfType(uint32_t type) const {
  for (const OniNodeInfo& n : nodes)
    if (n.type == type) return &n;
  return nullptr;
}

Expected<OniFileSummary> ScanOniFile(const std::filesystem::path& path) {
  const std::string p = path.string();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    return MakeError("not_found", p + ": no such recording (oni:FILE needs an existing .oni file)");
  OniFileSummary summary;
  summary.file_bytes = std::filesystem::file_size(path, ec);
  std::ifstream in(path, std::ios::binary);
  if (ec || !in) return MakeError("io", p + ": cannot read the file (check its permissions)");

  const auto corrupt = [&](const std::string& what) {
    return MakeError("corrupt", p + ": " + what);
  };
  char header[24];
  if (!in.read(header, sizeof header) || std::memcmp(header, "NI10", 4) != 0)
    return corrupt(
        "not an OpenNI recording (no \"NI10\" header); oni: plays .oni files "
        "recorded with OpenNI or OpenNI2");
  summary.version_major = static_cast<uint8_t>(header[4]);
  summary.version_minor = static_cast<uint8_t>(header[5]);
  uint16_t maintenance;
  std::memcpy(&maintenance, header + 6, 2);
  summary.version_maintenance = maintenance;
  const bool old_header = std::make_tuple(summary.version_major, summary.version_minor,
                                          summary.version_maintenance) < std::make_tuple(1, 0, 1);
  const uint32_t header_bytes = old_header ? 24 : 28;

  // A file that ends early: "empty" while no frame was reached, else "corrupt".
  const auto truncated = [&](uint64_t at) {
    if (summary.frame_records == 0)
      return MakeError("empty", p + ": the recording has no frames: its " +
                                    std::to_string(summary.file_bytes) +
                                    " bytes end inside the headers, at byte " + std::to_string(at) +
                                    ", before the first frame (stopped before recording "
                                    "anything, or cut short); record again");
    return corrupt("the recording is truncated at byte " + std::to_string(at) + " of " +
                   std::to_string(summary.file_bytes) + " (after " +
                   std::to_string(summary.frame_records) +
                   " frame records): it was cut short while copying or recording; copy it "
                   "again or re-record it");
  };
  uint64_t offset = sizeof header;
  bool ended = false;
  std::vector<char> fields;
  while (offset < summary.file_bytes && !ended) {
    if (summary.file_bytes - offset < header_bytes) return truncated(offset);
    fields.resize(header_bytes);
    in.seekg(static_cast<std::streamoff>(offset));
    if (!in.read(fields.data(), header_bytes)) return truncated(offset);
    const uint32_t magic = U32(fields, 0), type = U32(fields, 4), node = U32(fields, 8),
                   fields_bytes = U32(fields, 12), payload_bytes = U32(fields, 16);
    if (magic != kRecordMagic || fields_bytes < header_bytes || fields_bytes > kMaxFieldsBytes)
      return corrupt("malformed record at byte " + std::to_string(offset) +
                     ": the file is damaged; copy it again or re-record it");
    if (offset + fields_bytes + payload_bytes > summary.file_bytes) return truncated(offset);
    fields.resize(fields_bytes);
    if (!in.read(fields.data() + header_bytes, fields_bytes - header_bytes))
      return truncated(offset);

    size_t at = header_bytes;
    if (type == kNodeAdded1004 || type == kNodeAdded1005 || type == kNodeAdded) {
      auto name = Name(fields, at);
      if (!name || at + 8 > fields.size())
        return corrupt("malformed node record at byte " + std::to_string(offset));
      OniNodeInfo info;
      info.id = node;
      info.name = *name;
      info.type = U32(fields, at);
      if (type != kNodeAdded1004 && at + 12 <= fields.size())
        info.frame_count = U32(fields, at + 8);
      summary.nodes.push_back(info);
    } else if (type == kIntProperty || type == kGeneralProperty) {
      auto name = Name(fields, at);
      if (!name || at + 4 > fields.size())
        return corrupt("malformed property record at byte " + std::to_string(offset));
      const uint32_t size = U32(fields, at);
      at += 4;
      for (OniNodeInfo& n : summary.nodes) {
        if (n.id != node) continue;
        if (type == kIntProperty && *name == "AlternativeViewPoint" && size == 8 &&
            at + 8 <= fields.size()) {
          uint64_t value;
          std::memcpy(&value, fields.data() + at, 8);
          n.alternative_view_point = value;
        }
        if (type == kGeneralProperty && *name == "xnCropping") n.has_cropping = true;
      }
    } else if (type == kNewData) {
      ++summary.frame_records;
      for (OniNodeInfo& n : summary.nodes)
        if (n.id == node) ++n.frame_records;
    } else if (type == kEnd) {
      ended = true;
    }
    offset += static_cast<uint64_t>(fields_bytes) + payload_bytes;
  }
  if (summary.frame_records == 0)
    return MakeError("empty", p + ": the recording has no frames (" +
                                  std::to_string(summary.file_bytes) +
                                  " bytes of headers only); record again");
  if (!ended) return truncated(offset);
  return summary;
}

}  // namespace reenact::capture
