// reenact-eval: accuracy against ground truth: quality, holdout, segment, slam, reloc and
// tracker.
#include <iostream>

#include "common/cli/command_line.h"
#include "tests/eval/holdout_cli.h"
#include "tests/eval/kinect_reference_eval.h"
#include "tests/eval/quality_cli.h"
#include "tests/eval/quality_report.h"
#include "tests/eval/reloc_eval.h"
#include "tests/eval/segment_eval.h"
#include "tests/eval/slam_eval.h"
#include "tests/eval/tracker_eval.h"

namespace {

using namespace reenact;

constexpr const char* kUsage =
    "usage:\n"
    "  reenact-eval quality [--scenario S] [--body FILE.glb] [--methods LIST] [--views DEG,...]\n"
    "                       [--step K] [--json FILE] [--markdown FILE] [--images DIR]\n"
    "                       [--image-pairs FRAME@DEG,...] [--skeleton-noise M]\n"
    "                       [--skeletons truth|track]\n"
    "                       [--lighting scene|flat]\n"
    "      S: a synthetic scenario (default turn-and-kick); --body: a skinned glTF subject\n"
    "      (default: the procedural body); LIST: methods (default thesis);\n"
    "      views default 0,30,60,90,135,180; every K-th frame (default 10); --images writes\n"
    "      ground truth | reenactment | error pictures (default pairs: the middle frame at\n"
    "      every view); --skeleton-noise: Gaussian jitter (metres per axis) on the recorded\n"
    "      skeletons, as a tracker's (default 0: exact); --skeletons track: the recorded\n"
    "      skeletons from our depth tracker (default truth; a frame it loses is not in\n"
    "      the clip, and frame numbers count the clip's frames); --lighting flat: the\n"
    "      subject lit flat in recording and truth (no shading to carry between poses;\n"
    "      default scene)\n"
    "  reenact-eval holdout --source SRC [--skeleton source|track|SPEC] [--poses auto|slam]\n"
    "                       --every K --window W [--methods LIST] [--frames N] [--json FILE]\n"
    "                       [--images DIR]\n"
    "      quality on held-out real views: frames K, 2K, ... (each with its window inside\n"
    "      the recording) and their W neighbours on each side are left out, the clip is\n"
    "      recorded from the rest, and each held-out frame is reenacted from its skeleton\n"
    "      and sensor pose at the sensor's own view and compared with its colour image\n"
    "      inside the person's mask: PSNR, SSIM over the union box, silhouette IoU per\n"
    "      method (default thesis); SRC: any source with colour (synthetic:, oni:, tum:,\n"
    "      clip:, rgbd:DIR with colour); --skeleton as reenact-capture record's (default\n"
    "      source: the source's own; track: our depth tracker); --frames: read at most N;\n"
    "      --images: ground truth | reenactment | error pictures per method and frame\n"
    "  reenact-eval segment [--scenario S[,S...]] [--step K] [--json FILE] [--noise on|off]\n"
    "      person segmentation against the synthetic ground-truth mask (default\n"
    "      turn-and-kick, every frame, Kinect-like depth noise on): IoU and ms per frame\n"
    "  reenact-eval slam --tum DIR [--camera fr1|fr2|fr3] [--max-frames N] [--methods LIST]\n"
    "                    [--readout-ratio R] [--json FILE]\n"
    "      trajectory error (ATE, RPE) and ms per frame against TUM RGB-D ground truth for\n"
    "      reenact, opencv-rgbd and opencv-fasticp (default: all three)\n"
    "  reenact-eval reloc [--scenario S] [--body FILE.glb] [--frames N] [--max-deg D]\n"
    "                     [--record-frames M] [--json FILE]\n"
    "      the viewer's relocalisation against the recorded clip's map: a hand-held viewer\n"
    "      turning 0..D degrees (default 45) around the capture viewpoint, N frames (default\n"
    "      the scenario's); share within 2 cm / 1 degree, median errors, ms per frame, per\n"
    "      15-degree band, tracking frame to frame and relocalising every frame\n"
    "  reenact-eval tracker [--scenario S[,S...]] [--variants normal,fast,near,drops]\n"
    "                       [--iterations N,...] [--subsample K,...]\n"
    "                       [--body FILE.glb|procedural] [--turn-starts DEG]\n"
    "                       [--without PART,...] [--noise on|off]\n"
    "                       [--sensor-pose truth|slam|none] [--timestamps on|off]\n"
    "                       [--floor on|off] [--frames on|off] [--seeds N,...]\n"
    "                       [--json FILE]\n"
    "      the depth skeleton tracker against the synthetic ground-truth skeleton (default\n"
    "      turn-and-kick,walk-handheld; bvh:FILE plays on --body, default CesiumMan; an\n"
    "      explicit --body plays every scenario on it, --body procedural on the procedural\n"
    "      body): MPJPE, share of frames tracked, ms per frame per speed setting (default 8\n"
    "      iterations, subsample 2); hard cases broken down (fast: every 2nd frame; near:\n"
    "      the sensor moved up to 1.2 m closer, the subject 1.8 m away and cut off; drops:\n"
    "      0-3 frames dropped after each frame seen, 1.6 intervals apart on average); per\n"
    "      joint: mean error, bias (mean error vector in the body frame: x to the subject's\n"
    "      right, y forward, z up the spine) and spread (RMS about the bias), cm; per\n"
    "      reported confidence (bins of 0.25): share of joints, mean error, share > 10 cm;\n"
    "      for the joints in the image (upper-body-turn: knees and feet never are) their\n"
    "      MPJPE and share reported, and the share of the others reported (invented);\n"
    "      --turn-starts DEG: every frame the fit also started from the prediction turned\n"
    "      by -DEG and +DEG about up, the cheapest kept (default 25; 0: off);\n"
    "      --without PART,...: the tracker's method without these correction steps or\n"
    "      parts of steps: turned-starts, limb-jump, uncross-arms, uncross-legs,\n"
    "      uncross-return, front-check, front-confirm, travel-heading, limb-search,\n"
    "      held-twists, static-scene, trunk-breadth, torso-depth (docs/tracker.md);\n"
    "      --sensor-pose: the sensor pose the tracker is given, the truth (default),\n"
    "      RGB-D SLAM's prediction for the frame, as a recording without poses gives it,\n"
    "      or none (no pose and no world up: a real camera without SLAM);\n"
    "      --timestamps: each frame's time given to the tracker, its prediction scaled by\n"
    "      the gap since the last frame (default on; off: frames taken as evenly spaced);\n"
    "      --floor: the body model's floor beside the track, the tracker's body posed\n"
    "      from the truth's skeleton on each tracked frame (floor_posed_mpjpe_cm) and\n"
    "      fitted from there (floor_mpjpe_cm; default off); --frames: one row per frame\n"
    "      given to the tracker (default off);\n"
    "      --seeds: one run per scene seed (the depth noise; default 1), with their\n"
    "      mean, least and largest MPJPE per setting\n"
    "  reenact-eval tracker --source rgbd:DIR --reference kinect:FILE [--json FILE]\n"
    "                       [--pictures DIR]\n"
    "  reenact-eval tracker --dataset utd-mhad:ROOT [--sequences aA_sS_tT,...]\n"
    "                       [--json FILE] [--pictures DIR]\n"
    "      the depth skeleton tracker on real depth against the Kinect SDK's skeletons of\n"
    "      the same frames (UTD-MHAD: ROOT holds the aA_sS_tT folders, e.g.\n"
    "      ../shared/data/utd-mhad; its depth read mirrored, as its skeletons are): MPJPE\n"
    "      over all 16 joints and over the moving ones (the reference's joints more than\n"
    "      10 cm from their mean position), raw and after a constant per-joint offset in\n"
    "      the body's frame fitted on the other subjects' sequences, PCK at 10 cm, share\n"
    "      of frames tracked after the first second, frames before the first skeleton,\n"
    "      ms per frame; overall with the mean-pose baseline, per action, per subject\n"
    "      (--json: per sequence too); --pictures DIR: the 6 frames farthest off, depth\n"
    "      with the reference (green) and the tracker's skeleton (red)\n";

int Fail(const Error& e) { return ReportFailure("reenact-eval", e); }

int Quality(const CommandLine& cl) {
  const auto command = eval::ParseQualityCommand(cl);
  if (!command.ok()) return Fail(command.error());
  const auto run = eval::RunQuality(command->options);
  if (!run.ok()) return Fail(run.error());

  const Status printed = eval::QualityReport(*run).Print(command->json_path);
  if (const std::string lost = eval::LostFramesNote(*run); !lost.empty())
    std::cout << "Clip: " << run->clip_frames << " frames; " << lost << ".\n";
  std::cout << eval::SubjectLightLine(*run) << "\n";
  std::cout << eval::SurfaceFitLine(*run) << "\n";
  for (const std::string& rule : eval::QualityRules()) std::cout << rule << "\n";
  for (const eval::QualityImage& image : run->images) std::cout << "wrote " << image.path << "\n";
  if (!printed.ok()) return Fail(printed.error());
  if (command->markdown_path) {
    const std::string markdown = eval::QualityMarkdown(
        command->options, *run, *command->markdown_path, eval::MachineLine(run->gl_renderer));
    if (Status s = eval::WriteTextFile(*command->markdown_path, markdown); !s.ok())
      return Fail(s.error());
    std::cout << "wrote " << *command->markdown_path << "\n";
  }
  return 0;
}

int Segment(const CommandLine& cl) {
  const auto command = eval::ParseSegmentCommand(cl);
  if (!command.ok()) return Fail(command.error());
  const auto rows = eval::RunSegmentEval(command->options);
  if (!rows.ok()) return Fail(rows.error());
  const Status printed = eval::SegmentReport(*rows).Print(command->json_path);
  return printed.ok() ? 0 : Fail(printed.error());
}

int Tracker(const CommandLine& cl) {
  if (eval::WantsKinectReference(cl)) return eval::RunKinectReferenceCommand(cl);
  const auto command = eval::ParseTrackerCommand(cl);
  if (!command.ok()) return Fail(command.error());
  const auto run = eval::RunTrackerEval(command->options);
  if (!run.ok()) return Fail(run.error());
  const Status printed = eval::TrackerReport(*run).Print(command->json_path);
  return printed.ok() ? 0 : Fail(printed.error());
}

}  // namespace

int main(int argc, char** argv) {
  CommandLineSpec spec{eval::QualityFlags(), {}};
  spec.value_flags.merge(eval::SegmentFlags());
  spec.value_flags.merge(eval::SlamFlags());
  spec.value_flags.merge(eval::RelocFlags());
  spec.value_flags.merge(eval::TrackerFlags());
  spec.value_flags.merge(eval::KinectReferenceFlags());
  spec.value_flags.merge(eval::HoldoutFlags());
  return RunTool("reenact-eval", kUsage, spec,
                 {{"quality", Quality},
                  {"segment", Segment},
                  {"slam", eval::RunSlamCommand},
                  {"reloc", eval::RunRelocCommand},
                  {"tracker", Tracker},
                  {"holdout", eval::RunHoldoutCommand}},
                 argc, argv);
}
