#include "tests/eval/holdout_cli.h"

#include <iostream>

#include "tests/eval/quality_cli.h"
#include "tests/eval/quality_eval.h"

namespace reenact::eval {
namespace {

// A whole-number flag in [least, 1'000'000].
Expected<int> WholeNumber(const CommandLine& cl, const std::string& flag, long long fallback,
                          long long least, const std::string& meaning) {
  const auto value = cl.GetInt(flag, fallback);
  if (!value.ok()) return value.error();
  if (*value < least || *value > 1'000'000)
    return MakeError("usage", "--" + flag + " must be a whole number >= " + std::to_string(least) +
                                  " (" + meaning + "), got " + std::to_string(*value));
  return static_cast<int>(*value);
}

}  // namespace

std::set<std::string> HoldoutFlags() {
  return {"source", "skeleton", "poses", "every", "window", "methods", "frames", "json", "images"};
}

Expected<HoldoutCommand> ParseHoldoutCommand(const CommandLine& cl) {
  HoldoutCommand command;
  HoldoutOptions& o = command.options;
  for (const char* flag : {"source", "every", "window"})
    if (!cl.Has(flag))
      return MakeError("usage", std::string("holdout needs --") + flag +
                                    " (reenact-eval holdout --source SRC --every K --window W)");
  o.source = cl.GetOr("source", "");
  if (o.source.empty()) return MakeError("usage", "--source: empty source");
  o.skeleton = cl.GetOr("skeleton", o.skeleton);
  if (o.skeleton.empty())
    return MakeError("usage", "--skeleton: empty (give source, track or a skeleton track file)");
  const std::string poses = cl.GetOr("poses", "auto");
  if (poses != "auto" && poses != "slam")
    return MakeError("usage", "--poses must be auto or slam, got '" + poses + "'");
  o.slam_poses = poses == "slam";
  const auto every = WholeNumber(cl, "every", o.every, 1, "every K-th frame is held out");
  if (!every.ok()) return every.error();
  o.every = *every;
  const auto window =
      WholeNumber(cl, "window", o.window, 0, "frames left out on each side of a held-out one");
  if (!window.ok()) return window.error();
  o.window = *window;
  if (cl.Has("frames")) {
    const auto frames = WholeNumber(cl, "frames", -1, 1, "source frames to read");
    if (!frames.ok()) return frames.error();
    o.max_frames = *frames;
  }
  if (auto text = cl.Get("methods")) {
    auto list = ParseMethodList(*text);
    if (!list.ok()) return list.error();
    o.methods = *list;
  }
  if (auto dir = cl.Get("images")) {
    if (Status s = CheckCreatableFolder("images", *dir); !s.ok()) return s.error();
    o.image_dir = *dir;
  }
  if (auto path = cl.Get("json")) {
    if (Status s = CheckWritableFile("json", *path); !s.ok()) return s.error();
    command.json_path = *path;
  }
  return command;
}

proto::Report HoldoutReport(const HoldoutRun& run) {
  proto::Report report;
  report.command = "holdout";
  for (const HoldoutRow& r : run.rows) {
    proto::ReportRow row;
    row.Add("method", r.method)
        .Add("n", static_cast<long long>(r.n))
        .Add("psnr_db", r.psnr_db)
        .Add("ssim", r.ssim)
        .Add("iou", r.iou)
        .Add("colour_mae", r.colour_mae)
        .Add("texture_gap", r.texture_gap)
        .Add("held_out", static_cast<long long>(run.held_out))
        .Add("recorded", static_cast<long long>(run.kept));
    report.rows.push_back(std::move(row));
  }
  return report;
}

int RunHoldoutCommand(const CommandLine& cl) {
  const auto command = ParseHoldoutCommand(cl);
  if (!command.ok()) return ReportFailure("reenact-eval", command.error());
  const HoldoutOptions& o = command->options;
  const auto run = RunHoldout(o);
  if (!run.ok()) return ReportFailure("reenact-eval", run.error());
  std::cout << run->source << ": " << run->source_frames << " frames, " << run->recorded_frames
            << " with skeleton and pose; held out: frames K, 2K, ... (K = " << o.every
            << ") with W = " << o.window << " on each side left out too: " << run->held_out
            << " held out, " << run->excluded << " left out in all; the clip textures from "
            << run->kept << " frames; " << run->compared << " compared";
  if (run->lost_held_out || run->empty_mask_held_out)
    std::cout << " (" << run->lost_held_out << " held out without skeleton or pose, "
              << run->empty_mask_held_out << " with no person in the mask)";
  std::cout << "\n";
  const Status printed = HoldoutReport(*run).Print(command->json_path);
  std::cout << "Viewer camera at each held-out frame's sensor pose with the colour camera's "
               "intrinsics; truth: the frame's colour image inside the person's mask from the "
               "recording.\n"
            << "Crop rule: " << kCropRule << ".\n"
            << "texture_gap: mean distance in frames from a held-out frame to the frame that "
               "textures it (per-part methods: the upper torso's first candidate).\n"
            << "GL: " << run->gl_renderer << "\n";
  for (const HoldoutFrame& f : run->frames)
    if (!f.image_path.empty()) std::cout << "wrote " << f.image_path << "\n";
  if (!printed.ok()) return ReportFailure("reenact-eval", printed.error());
  return 0;
}

}  // namespace reenact::eval
