#pragma once
// The output of `reenact-eval` and `reenact-bench` (DESIGN.md): a readable table on stdout
// and, with --json FILE, {"command": "...", "rows": [ {...}, ... ]} with one flat object per
// row, labels and figures under the names DESIGN.md fixes (psnr_db, iou, ms_per_frame, ...).

#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "common/error/expected.h"

namespace reenact::proto {

using ReportValue = std::variant<std::string, double, long long>;

struct ReportRow {
  std::string table;  // rows of one table share its columns; "" = the report's main table
  std::vector<std::pair<std::string, ReportValue>> cells;  // column name -> value, in order

  ReportRow& Add(std::string name, ReportValue value) {
    cells.emplace_back(std::move(name), std::move(value));
    return *this;
  }
};

struct Report {
  std::string command;  // e.g. "quality"
  std::vector<ReportRow> rows;

  // One table per ReportRow::table, in first-seen order, each with the union of its rows'
  // columns (missing cells blank); doubles with `precision` decimals.
  std::string FormatTable(int precision = 3) const;
  std::string ToJson() const;
  Status WriteJson(const std::string& path) const;
  // What every command does at its end: the table on stdout, the JSON file if a path is given.
  Status Print(const std::optional<std::string>& json_path) const;
};

}  // namespace reenact::proto
