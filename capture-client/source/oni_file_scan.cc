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
constexpr size_t kFileHeaderBytes = 24;

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

Error Corrupt(const std::string& p, const std::string& what) {
  return MakeError("corrupt", p + ": " + what);
}

// A file that ends early at byte `at`: "empty" while no frame was reached, else "corrupt".
Error Truncated(const std::string& p, const OniFileSummary& summary, uint64_t at) {
  if (summary.frame_records == 0)
    return MakeError("empty", p + ": the recording has no frames: its " +
                                  std::to_string(summary.file_bytes) +
                                  " bytes end inside the headers, at byte " + std::to_string(at) +
                                  ", before the first frame (stopped before recording "
                                  "anything, or cut short); record again");
  return Corrupt(p, "the recording is truncated at byte " + std::to_string(at) + " of " +
                        std::to_string(summary.file_bytes) + " (after " +
                        std::to_string(summary.frame_records) +
                        " frame records): it was cut short while copying or recording; copy it "
                        "again or re-record it");
}

// Reads the file header's version into the summary; returns the size of the records'
// headers, which follows from it.
Expected<uint32_t> ReadFileHeader(std::ifstream& in, const std::string& p,
                                  OniFileSummary& summary) {
  char header[kFileHeaderBytes];
  if (!in.read(header, sizeof header) || std::memcmp(header, "NI10", 4) != 0)
    return Corrupt(p,
                   "not an OpenNI recording (no \"NI10\" header); oni: plays .oni files "
                   "recorded with OpenNI or OpenNI2");
  summary.version_major = static_cast<uint8_t>(header[4]);
  summary.version_minor = static_cast<uint8_t>(header[5]);
  uint16_t maintenance;
  std::memcpy(&maintenance, header + 6, 2);
  summary.version_maintenance = maintenance;
  const bool old_header = std::make_tuple(summary.version_major, summary.version_minor,
                                          summary.version_maintenance) < std::make_tuple(1, 0, 1);
  return old_header ? 24u : 28u;
}

struct RecordHeader {
  uint32_t type = 0, node = 0, fields_bytes = 0, payload_bytes = 0;
};

// Reads the header and fields (header included) of the record at byte `offset`.
Expected<RecordHeader> ReadRecord(std::ifstream& in, uint64_t offset, uint32_t header_bytes,
                                  const std::string& p, const OniFileSummary& summary,
                                  std::vector<char>& fields) {
  if (summary.file_bytes - offset < header_bytes) return Truncated(p, summary, offset);
  fields.resize(header_bytes);
  in.seekg(static_cast<std::streamoff>(offset));
  if (!in.read(fields.data(), header_bytes)) return Truncated(p, summary, offset);
  const uint32_t magic = U32(fields, 0), type = U32(fields, 4), node = U32(fields, 8),
                 fields_bytes = U32(fields, 12), payload_bytes = U32(fields, 16);
  if (magic != kRecordMagic || fields_bytes < header_bytes || fields_bytes > kMaxFieldsBytes)
    return Corrupt(p, "malformed record at byte " + std::to_string(offset) +
                          ": the file is damaged; copy it again or re-record it");
  if (offset + fields_bytes + payload_bytes > summary.file_bytes)
    return Truncated(p, summary, offset);
  fields.resize(fields_bytes);
  if (!in.read(fields.data() + header_bytes, fields_bytes - header_bytes))
    return Truncated(p, summary, offset);
  return RecordHeader{type, node, fields_bytes, payload_bytes};
}

// A node-added record's node, from its fields after the header (at); nullopt if malformed.
std::optional<OniNodeInfo> AddedNode(const RecordHeader& record, const std::vector<char>& fields,
                                     size_t at) {
  auto name = Name(fields, at);
  if (!name || at + 8 > fields.size()) return std::nullopt;
  OniNodeInfo info;
  info.id = record.node;
  info.name = *name;
  info.type = U32(fields, at);
  if (record.type != kNodeAdded1004 && at + 12 <= fields.size())
    info.frame_count = U32(fields, at + 8);
  return info;
}

// The properties of a property record (fields after the header at `at`) that the summary
// keeps, set on its node; false if the record is malformed.
bool ApplyProperty(const RecordHeader& record, const std::vector<char>& fields, size_t at,
                   OniFileSummary& summary) {
  auto name = Name(fields, at);
  if (!name || at + 4 > fields.size()) return false;
  const uint32_t size = U32(fields, at);
  at += 4;
  for (OniNodeInfo& n : summary.nodes) {
    if (n.id != record.node) continue;
    if (record.type == kIntProperty && *name == "AlternativeViewPoint" && size == 8 &&
        at + 8 <= fields.size()) {
      uint64_t value;
      std::memcpy(&value, fields.data() + at, 8);
      n.alternative_view_point = value;
    }
    if (record.type == kGeneralProperty && *name == "xnCropping") n.has_cropping = true;
  }
  return true;
}

// Adds what a record says to the summary (nodes, their properties, frame records); *ended
// set at the end record.
Status ApplyRecord(const RecordHeader& record, const std::vector<char>& fields,
                   uint32_t header_bytes, uint64_t offset, const std::string& p,
                   OniFileSummary& summary, bool* ended) {
  const uint32_t type = record.type;
  if (type == kNodeAdded1004 || type == kNodeAdded1005 || type == kNodeAdded) {
    std::optional<OniNodeInfo> info = AddedNode(record, fields, header_bytes);
    if (!info) return Corrupt(p, "malformed node record at byte " + std::to_string(offset));
    summary.nodes.push_back(*info);
  } else if (type == kIntProperty || type == kGeneralProperty) {
    if (!ApplyProperty(record, fields, header_bytes, summary))
      return Corrupt(p, "malformed property record at byte " + std::to_string(offset));
  } else if (type == kNewData) {
    ++summary.frame_records;
    for (OniNodeInfo& n : summary.nodes)
      if (n.id == record.node) ++n.frame_records;
  } else if (type == kEnd) {
    *ended = true;
  }
  return {};
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
  const Expected<uint32_t> header_bytes = ReadFileHeader(in, p, summary);
  if (!header_bytes.ok()) return header_bytes.error();

  uint64_t offset = kFileHeaderBytes;
  bool ended = false;
  std::vector<char> fields;
  while (offset < summary.file_bytes && !ended) {
    const auto record = ReadRecord(in, offset, *header_bytes, p, summary, fields);
    if (!record.ok()) return record.error();
    if (Status applied = ApplyRecord(*record, fields, *header_bytes, offset, p, summary, &ended);
        !applied.ok())
      return applied.error();
    offset += static_cast<uint64_t>(record->fields_bytes) + record->payload_bytes;
  }
  if (summary.frame_records == 0)
    return MakeError("empty", p + ": the recording has no frames (" +
                                  std::to_string(summary.file_bytes) +
                                  " bytes of headers only); record again");
  if (!ended) return Truncated(p, summary, offset);
  return summary;
}

}  // namespace reenact::capture
