#include "proto/report/report_table.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>

#include <nlohmann/json.hpp>

namespace reenact::proto {
namespace {

std::string Format(const ReportValue& v, int precision) {
  if (const auto* s = std::get_if<std::string>(&v)) return *s;
  if (const auto* i = std::get_if<long long>(&v)) return std::to_string(*i);
  const double d = std::get<double>(v);
  if (!std::isfinite(d)) return d > 0 ? "inf" : (d < 0 ? "-inf" : "nan");
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", precision, d);
  return buf;
}

}  // namespace

std::string Report::FormatTable(int precision) const {
  std::vector<std::string> tables;
  for (const ReportRow& r : rows)
    if (std::find(tables.begin(), tables.end(), r.table) == tables.end()) tables.push_back(r.table);
  std::string out;
  for (const std::string& table : tables) {
    std::vector<std::string> columns;
    std::vector<const ReportRow*> members;
    for (const ReportRow& r : rows) {
      if (r.table != table) continue;
      members.push_back(&r);
      for (const auto& [name, _] : r.cells)
        if (std::find(columns.begin(), columns.end(), name) == columns.end())
          columns.push_back(name);
    }
    std::vector<std::vector<std::string>> text(members.size(),
                                               std::vector<std::string>(columns.size()));
    std::vector<size_t> width(columns.size());
    for (size_t c = 0; c < columns.size(); ++c) width[c] = columns[c].size();
    for (size_t r = 0; r < members.size(); ++r)
      for (const auto& [name, value] : members[r]->cells) {
        const size_t c = std::find(columns.begin(), columns.end(), name) - columns.begin();
        text[r][c] = Format(value, precision);
        width[c] = std::max(width[c], text[r][c].size());
      }
    if (!out.empty()) out += "\n";
    auto line = [&](const std::vector<std::string>& cells) {
      for (size_t c = 0; c < cells.size(); ++c) {
        out += cells[c];
        out += c + 1 < cells.size() ? std::string(width[c] - cells[c].size() + 2, ' ') : "\n";
      }
    };
    line(columns);
    for (const auto& t : text) line(t);
  }
  return out;
}

std::string Report::ToJson() const {
  nlohmann::json j = {{"command", command}, {"rows", nlohmann::json::array()}};
  for (const ReportRow& r : rows) {
    nlohmann::json row = nlohmann::json::object();
    for (const auto& [name, value] : r.cells) {
      if (const auto* s = std::get_if<std::string>(&value)) row[name] = *s;
      else if (const auto* i = std::get_if<long long>(&value)) row[name] = *i;
      else if (std::isfinite(std::get<double>(value))) row[name] = std::get<double>(value);
      else row[name] = nullptr;  // JSON has no infinity
    }
    j["rows"].push_back(row);
  }
  return j.dump(2);
}

Status Report::WriteJson(const std::string& path) const {
  std::ofstream out(path);
  out << ToJson() << "\n";
  if (!out) return MakeError("io", "cannot write " + path);
  return {};
}

Status Report::Print(const std::optional<std::string>& json_path) const {
  std::cout << FormatTable() << std::flush;
  return json_path ? WriteJson(*json_path) : Status{};
}

}  // namespace reenact::proto
