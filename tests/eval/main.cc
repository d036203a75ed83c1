// reenact-eval: accuracy against ground truth. `quality` today; slam, reloc and tracker
// arrive with their components.
#include <sstream>

#include "common/cli/command_line.h"
#include "proto/report/report_table.h"
#include "tests/eval/quality_eval.h"

namespace {

using namespace reenact;

constexpr const char* kUsage =
    "usage:\n"
    "  reenact-eval quality [--scenario S] [--methods LIST] [--views DEG,...] [--step K]\n"
    "                       [--json FILE]\n"
    "  reenact-eval slam|reloc|tracker ...   (not in this build yet)\n";

int Fail(const Error& e) { return ReportFailure("reenact-eval", e); }

Expected<std::vector<std::string>> SplitList(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream ss(text);
  for (std::string item; std::getline(ss, item, ',');)
    if (!item.empty()) out.push_back(item);
  if (out.empty()) return MakeError("usage", "empty list '" + text + "'");
  return out;
}

int Quality(const CommandLine& cl) {
  eval::QualityOptions options;
  options.scenario = cl.GetOr("scenario", options.scenario);
  if (auto m = cl.Get("methods")) {
    auto list = SplitList(*m);
    if (!list.ok()) return Fail(list.error());
    options.methods = *list;
  }
  if (auto v = cl.Get("views")) {
    auto list = SplitList(*v);
    if (!list.ok()) return Fail(list.error());
    options.views_deg.clear();
    for (const std::string& s : *list) {
      char* end = nullptr;
      const double d = std::strtod(s.c_str(), &end);
      if (end != s.c_str() + s.size())
        return Fail(MakeError("usage", "--views: not a number: " + s));
      options.views_deg.push_back(d);
    }
  }
  const auto step = cl.GetInt("step", options.frame_step);
  if (!step.ok()) return Fail(step.error());
  if (*step < 1) return Fail(MakeError("usage", "--step must be >= 1"));
  options.frame_step = static_cast<int>(*step);

  const auto rows = eval::RunQuality(options);
  if (!rows.ok()) return Fail(rows.error());
  proto::Report report{"quality", {}};
  for (const auto& r : *rows)
    report.rows.push_back(proto::ReportRow{}
                              .Add("method", r.method)
                              .Add("scenario", r.scenario)
                              .Add("view_deg", r.view_deg)
                              .Add("n", static_cast<long long>(r.n))
                              .Add("psnr_db", r.psnr_db)
                              .Add("ssim", r.ssim)
                              .Add("iou", r.iou)
                              .Add("colour_mae", r.colour_mae)
                              .Add("ms_per_frame", r.ms_per_frame));
  const Status printed = report.Print(cl.Get("json"));
  return printed.ok() ? 0 : Fail(printed.error());
}

int NotYet(const CommandLine& cl) {
  return Fail(MakeError("unsupported", "'" + cl.positionals()[0] +
                                           "' is not in this build yet: it arrives with SLAM, "
                                           "relocalisation and the depth tracker"));
}

}  // namespace

int main(int argc, char** argv) {
  const CommandLineSpec spec{{"scenario", "methods", "views", "step", "json"}, {}};
  return RunTool("reenact-eval", kUsage, spec,
                 {{"quality", Quality}, {"slam", NotYet}, {"reloc", NotYet}, {"tracker", NotYet}},
                 argc, argv);
}
