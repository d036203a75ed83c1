#include "tests/eval/quality_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

namespace reenact::eval {
namespace {

std::string Fixed(double value, int decimals) {
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char text[64];
  std::snprintf(text, sizeof(text), "%.*f", decimals, value);
  return text;
}

std::string Number(double value) {  // shortest form for command lines: 30, 22.5
  std::ostringstream out;
  out << value;
  return out.str();
}

std::string EveryKth(int k) {
  if (k == 1) return "every frame";
  const int last = k % 10, tens = k % 100;
  const char* suffix = (tens >= 11 && tens <= 13) ? "th"
                       : last == 1                ? "st"
                       : last == 2                ? "nd"
                       : last == 3                ? "rd"
                                                  : "th";
  return "every " + std::to_string(k) + suffix + " frame";
}

std::string CpuModel() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("model name", 0) == 0) {
      const size_t colon = line.find(':');
      if (colon != std::string::npos && colon + 2 <= line.size()) return line.substr(colon + 2);
    }
  return "unknown CPU";
}

}  // namespace

proto::Report QualityReport(const QualityRun& run) {
  proto::Report report{"quality", {}};
  for (const QualityRow& r : run.rows)
    report.rows.push_back(proto::ReportRow{}
                              .Add("method", r.method)
                              .Add("scenario", r.scenario)
                              .Add("view_deg", r.view_deg)
                              .Add("n", static_cast<long long>(r.n))
                              .Add("psnr_db", r.psnr_db)
                              .Add("ssim", r.ssim)
                              .Add("iou", r.iou)
                              .Add("colour_mae", r.colour_mae)
                              .Add("wrong_part_rate", r.wrong_part_rate)
                              .Add("wrong_seen_part_rate", r.wrong_seen_part_rate)
                              .Add("wrong_texture_rate", r.wrong_texture_rate)
                              .Add("doubled_limb_rate", r.doubled_limb_rate)
                              .Add("untextured_rate", r.untextured_rate)
                              .Add("reference_iou", r.reference_iou)
                              .Add("ms_per_frame", r.ms_per_frame)
                              .Add("reenacted_change", r.reenacted_change)
                              .Add("truth_change", r.truth_change)
                              .Add("flicker", r.flicker)
                              .Add("error_change", r.error_change));
  return report;
}

std::vector<std::string> QualityRules() {
  return {
      std::string("Crop rule: ") + kCropRule + ".",
      "iou: silhouette IoU of the rendered and true subject masks; colour_mae: mean absolute "
      "RGB difference (0-255) where both masks are set.",
      "wrong_part_rate: share of rendered subject pixels whose colour came from source pixels "
      "that the source frame's ground-truth part labels assign to another body part or to the "
      "background than the drawn cylinder's part (a pixel blended across a border counts by "
      "its bilinear weights); it also counts the model's part borders against the body's "
      "(a pixel copy of the stored frame at the sensor's own view is not 0); "
      "wrong_seen_part_rate: the same against the part the ground truth shows at that output "
      "pixel (the drawn part where the truth shows no subject), so only what the viewer sees "
      "as another part's texture counts; wrong_texture_rate: the part of that where the "
      "ground truth shows the drawn cylinder's part (the texture's own error; the rest is the "
      "model's geometry: a cylinder drawn where the body shows another part); "
      "doubled_limb_rate: the part of the seen-part rate whose source "
      "texels show a part that the ground truth shows nowhere within " +
          Number(100 * kDoubledLimbBorderM) +
          " cm of the output pixel (measured in the image at the pixel's depth), so a seam a few "
          "centimetres off the body's part border does not count and a doubled limb (a forearm "
          "textured with the torso) does; untextured_rate: share drawn in flat colour, from no "
          "source pixel.",
      "Provenance (source frame, source pixel, cylinder part) comes from the CPU reference "
      "renderer drawing the same draw list as the GL renderer; reference_iou is the IoU of "
      "their two silhouettes.",
      "ms_per_frame: median over the frames of draw-list build (selection + mapping) + GL draw "
      "+ read-back on the headless context.",
      "flicker = reenacted_change - truth_change: at the same view, for each pair of "
      "consecutive evaluated frames (k, k + step), the absolute RGB change (0-255, mean over "
      "channels) from k to k + step of the reenactment, and of the ground truth, each subject "
      "on black, summed over all pixels and divided by the area of the union of the two true "
      "silhouettes; error_change the same for the error image (reenactment - truth), 0 only "
      "when the reenactment changes exactly as the truth does; means over the pairs.",
  };
}

std::string LostFramesNote(const QualityRun& run) {
  if (run.scene_frames <= run.clip_frames) return "";
  return "the tracker lost " + std::to_string(run.scene_frames - run.clip_frames) +
         " of the scenario's " + std::to_string(run.scene_frames) +
         " frames; the recorder stores no frame without a skeleton, so those are not "
         "reenacted, and each output frame is compared with the scene at its own time";
}

std::string SubjectLightLine(const QualityRun& run) {
  const SubjectLightFit& fit = run.subject_light;
  const double true_strength = run.true_subject_light.norm();
  const std::string truth = true_strength > 0
                                ? "the scene's light has strength " + Fixed(true_strength, 2)
                                : "the subject is lit flat (strength 0)";
  if (!fit.found) return "Subject light: none found at load (" + fit.reason + "); " + truth + ".";
  std::string line = "Subject light fitted at load: strength " + Fixed(fit.light.norm(), 2);
  if (true_strength > 0) {
    const double cosine = fit.light.normalized().dot(run.true_subject_light.normalized());
    line += ", " + Fixed(std::acos(std::clamp(cosine, -1.0, 1.0)) * 180 / M_PI, 1) +
            " degrees from the scene's light";
  }
  return line + " (gain " + Fixed(fit.gain, 3) + " over " + std::to_string(fit.samples) +
         " samples in " + std::to_string(fit.bins) + " surface bins); " + truth + ".";
}

std::string SurfaceFitLine(const QualityRun& run) {
  const SurfaceFitResult& fit = run.surface_fit;
  std::string parts;
  double rings_sum = 0, chosen_sum = 0;
  int64_t weight = 0;
  int nodes = 0;
  for (int p = 0; p < kBodyPartCount; ++p) {
    parts += (p ? ", " : "") + std::string(PartName(static_cast<BodyPart>(p))) + " " +
             std::to_string(fit.angles[p]);
    nodes += kShapeRings * fit.angles[p];
    if (!fit.scored[p]) continue;
    rings_sum += fit.rings_error_m[p] * fit.points[p];
    chosen_sum += fit.chosen_error_m[p] * fit.points[p];
    weight += fit.points[p];
  }
  const int floats = kBodyPartCount * (1 + 2 * kShapeRings) + nodes;
  std::string line = "Surface fitted at load: angles per part " + parts;
  if (weight > 0)
    line += "; held-out error " + Fixed(1000 * rings_sum / weight, 2) + " mm with the rings alone, " +
            Fixed(1000 * chosen_sum / weight, 2) + " mm as chosen";
  return line + "; body model " + std::to_string(4 * floats) +
         " bytes (extensions, rings and surface nodes as 4-byte floats, fitted at load: nothing "
         "is added to the clip).";
}

std::string QualityCommandLine(const QualityOptions& options) {
  std::ostringstream line;
  line << "reenact-eval quality --scenario " << options.scenario;
  if (!options.body.empty()) line << " --body " << options.body;
  line << " --methods ";
  for (size_t i = 0; i < options.methods.size(); ++i) line << (i ? "," : "") << options.methods[i];
  line << " --views ";
  for (size_t i = 0; i < options.views_deg.size(); ++i)
    line << (i ? "," : "") << Number(options.views_deg[i]);
  line << " --step " << options.frame_step;
  if (options.skeleton_noise_m > 0)
    line << " --skeleton-noise " << Number(options.skeleton_noise_m);
  if (options.tracked_skeletons) line << " --skeletons track";
  if (options.flat_lighting) line << " --lighting flat";
  if (!options.image_dir.empty() && !options.image_pairs.empty()) {
    line << " --images " << options.image_dir << " --image-pairs ";
    for (size_t i = 0; i < options.image_pairs.size(); ++i)
      line << (i ? "," : "") << options.image_pairs[i].frame << "@"
           << Number(options.image_pairs[i].view_deg);
  }
  return line.str();
}

std::string MachineLine(const std::string& gl_renderer) {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char date[32];
  std::strftime(date, sizeof(date), "%Y-%m-%d", &utc);
  return std::string(date) + " (UTC), " + CpuModel() + ", " +
         std::to_string(std::thread::hardware_concurrency()) + " logical cores, OpenGL renderer " +
         gl_renderer;
}

std::string QualityMarkdown(const QualityOptions& options, const QualityRun& run,
                            const std::string& markdown_path, const std::string& machine_line) {
  const std::string lost_frames = LostFramesNote(run);
  std::ostringstream md;
  md << "# Image quality against ground truth\n\n"
     << "Written by `reenact-eval quality` (`make eval` runs the standard set); do not edit by "
        "hand. To reproduce:\n\n```\n"
     << QualityCommandLine(options) << "\n```\n\n"
     << "Measured " << machine_line << ".\n\n"
     << "Synthetic scenario `" << options.scenario << "` with "
     << (options.body.empty() ? std::string("the procedural body")
                              : "the skinned glTF body `" +
                                    std::filesystem::path(options.body).filename().string() + "`")
     << ": " << run.clip_frames
     << " frames recorded through the real capture pipeline (render, crop, JPEG/PNG, clip "
        "directory) and read back"
     << (options.skeleton_noise_m > 0 ? ", the recorded skeletons with Gaussian jitter of " +
                                            Fixed(options.skeleton_noise_m * 100, 1) +
                                            " cm per axis on every joint (the ground truth exact)"
                                      : std::string())
     << (options.tracked_skeletons
             ? ", the recorded skeletons from our depth tracker (the ground truth exact)"
             : std::string())
     << (lost_frames.empty() ? "" : " (" + lost_frames + ")")
     << (options.flat_lighting ? ", the subject lit flat (no shading) in recording and truth"
                               : std::string())
     << "; " << EveryKth(options.frame_step) << " is reenacted at " << options.width << "x"
     << options.height
     << " from viewpoints turned by view_deg about the subject's vertical axis from the "
        "sensor's position at frame 0, and compared with the scene rendered from the same camera "
        "(subject only, no room). Figures are means over the frames.\n\n"
     << "Methods:\n\n";
  for (const std::string& name : options.methods)
    if (auto m = FindQualityMethod(name); m.ok())
      md << "- `" << name << "`: " << (*m)->summary << ".\n";
  md << "\n| method | view_deg | n | psnr_db | ssim | iou | colour_mae | wrong_part_rate | "
        "wrong_seen_part_rate | wrong_texture_rate | doubled_limb_rate | untextured_rate | "
        "reference_iou | ms_per_frame | flicker | reenacted_change | truth_change | "
        "error_change |\n"
     << "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const QualityRow& r : run.rows)
    md << "| " << r.method << " | " << Number(r.view_deg) << " | " << r.n << " | "
       << Fixed(r.psnr_db, 2) << " | " << Fixed(r.ssim, 3) << " | " << Fixed(r.iou, 3) << " | "
       << Fixed(r.colour_mae, 1) << " | " << Fixed(r.wrong_part_rate, 3) << " | "
       << Fixed(r.wrong_seen_part_rate, 3) << " | " << Fixed(r.wrong_texture_rate, 3) << " | "
       << Fixed(r.doubled_limb_rate, 3) << " | " << Fixed(r.untextured_rate, 3) << " | "
       << Fixed(r.reference_iou, 4) << " | " << Fixed(r.ms_per_frame, 1) << " | "
       << Fixed(r.flicker, 2) << " | " << Fixed(r.reenacted_change, 2) << " | "
       << Fixed(r.truth_change, 2) << " | " << Fixed(r.error_change, 2) << " |\n";
  md << "\n" << SubjectLightLine(run) << "\n";
  md << "\n" << SurfaceFitLine(run) << "\n";
  md << "\nHow the figures are made:\n\n";
  for (const std::string& rule : QualityRules()) md << "- " << rule << "\n";

  if (!run.images.empty()) {
    md << "\n## Pictures\n\n"
       << "Each picture: ground truth | reenactment | per-pixel error, cropped to the "
          "comparison box (grown by 8 px), subjects on black as compared. Error: mean absolute "
          "RGB difference on the inferno scale, black 0 to bright yellow at 128 and above.\n";
    const std::filesystem::path base =
        std::filesystem::absolute(markdown_path).lexically_normal().parent_path();
    for (const QualityImage& image : run.images) {
      const std::string link = std::filesystem::absolute(image.path)
                                   .lexically_normal()
                                   .lexically_relative(base)
                                   .generic_string();
      md << "\n`" << image.method << "`, frame " << image.pair.frame << ", view "
         << Number(image.pair.view_deg) << " degrees: PSNR " << Fixed(image.comparison.psnr_db, 2)
         << " dB, SSIM " << Fixed(image.comparison.ssim, 3) << ", IoU "
         << Fixed(image.comparison.iou, 3) << ", wrong-part rate "
         << Fixed(image.wrong_part_rate, 3) << ", seen-part rate "
         << Fixed(image.wrong_seen_part_rate, 3) << ", wrong-texture rate "
         << Fixed(image.wrong_texture_rate, 3) << ", doubled-limb rate "
         << Fixed(image.doubled_limb_rate, 3) << "\n\n"
         << "![" << image.method << " frame " << image.pair.frame << " view "
         << Number(image.pair.view_deg) << "](" << link << ")\n";
    }
  }
  return md.str();
}

Status WriteTextFile(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
  out.close();
  if (!out) return MakeError("io", "cannot write " + path + " (is the folder there and writable?)");
  return {};
}

}  // namespace reenact::eval
