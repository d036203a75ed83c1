#pragma once
// `reenact-eval reloc`: the viewer's relocaliser (viewer-client/reloc/relocaliser.h) against
// ground truth.
//
//   reenact-eval reloc [--scenario S] [--body FILE.glb] [--frames N] [--max-deg D]
//                      [--record-frames M] [--features F] [--methods track|reloc|both]
//                      [--json FILE]
//
// 1. The scenario is recorded through the real capture pipeline (RecordClip on its synthetic
//    source, the first M frames, default all), and the clip's map is read back from the clip
//    directory as a viewer would (the recorder builds it from the scene's true sensor poses).
// 2. A hand-held viewer walks N frames (default: the scenario's frame count) around the
//    subject: frame k's eye is frame 0's sensor position turned about the vertical through
//    the subject's centre (the skeleton's waist at frame 0) by
//        a_k = D sin(2 pi k / (N - 1))      (0 -> +D -> 0 -> -D -> 0 degrees; D default 45)
//    at the sensor's distance and height, aimed at the centre, with walk-handheld's bob and
//    hand shake (synthetic/handheld_trajectory.h), the path of the viewer's
//    synthetic camera (viewer-client/camera/synthetic_camera_source.h). Viewer frame k shows the
//    scene at frame k mod frame_count (the subject keeps moving), rendered with the sensor's
//    intrinsics; its true viewer_from_world is known by construction.
//    --features F: ORB features per viewer frame (RelocaliserOptions::features.num_features,
//    default the relocaliser's).
// 3. Two methods: "track" runs the relocaliser over the sequence (relocalise, then track frame
//    to frame, relocalise when lost), "reloc" relocalises every frame from scratch.
//
// Rows per method and band of |a_k| ([0, 15), [15, 30), [30, D] degrees) and over all
// frames: n, within_2cm_1deg (share of the band's frames whose pose is within 2 cm (camera
// centre) and 1 degree (rotation angle) of the truth; a lost frame counts as outside),
// tracked_rate (share with a pose), median_err_cm and median_err_deg (over frames with a
// pose), ms_per_frame (median wall time of Relocaliser::ProcessFrame; rendering excluded)
// and p99_ms, and the median CPU time per frame (RelocFrameResult::cpu: the process's CPU
// time, steadier than wall time on a shared machine) in all and per stage: cpu_ms,
// orb_ms (OpenCV's ORB: pyramid, FAST, Harris, orientation, descriptors), subpixel_ms,
// match_ms (by projection), refine_ms, reloc_ms (descriptor search and RANSAC), smooth_ms, and
// the median descriptor comparisons per frame of matching by projection.

#include <optional>
#include <set>
#include <string>
#include <vector>

#include "common/cli/command_line.h"
#include "common/error/expected.h"
#include "proto/report/report_table.h"
#include "viewer-client/reloc/relocaliser.h"

namespace reenact::eval {

struct RelocEvalOptions {
  std::string scenario = "turn-and-kick";
  std::string body;        // a skinned glTF body, empty = the procedural one
  int viewer_frames = 0;   // N, >= 2; 0 = the scenario's frame count
  double max_deg = 45;     // D, in (0, 90]
  int record_frames = -1;  // M, frames recorded for the map; -1 = all, else >= 1
  viewer::RelocaliserOptions relocaliser;
  bool run_track = true, run_reloc = true;  // the methods run, at least one

  void Check() const;
};

struct RelocEvalRow {
  std::string method;  // "track" or "reloc"
  std::string band;    // "0-15", "15-30", "30-45", "all"
  int frames = 0;
  double within_2cm_1deg = 0;
  double tracked_rate = 0;
  double median_err_cm = 0, median_err_deg = 0;
  double ms_per_frame = 0, p99_ms = 0;
  // Medians of the CPU time per frame and stage, milliseconds.
  double cpu_ms = 0, orb_ms = 0, subpixel_ms = 0, match_ms = 0, refine_ms = 0, reloc_ms = 0,
         smooth_ms = 0;
  double comparisons = 0;  // median descriptor comparisons per frame (matching by projection)
};

struct RelocEvalRun {
  size_t map_points = 0;
  std::vector<RelocEvalRow> rows;
};

// Errors: those of the scenario (unknown name, body), of recording and reading the clip, and
// of Relocaliser::Create (a map too small to relocalise).
Expected<RelocEvalRun> RunRelocEval(const RelocEvalOptions& options);

// Command "reloc": method, band, n, within_2cm_1deg, tracked_rate, median_err_cm,
// median_err_deg, ms_per_frame, p99_ms, cpu_ms, orb_ms, subpixel_ms, match_ms, refine_ms,
// reloc_ms, smooth_ms, comparisons.
proto::Report RelocReport(const RelocEvalRun& run);

struct RelocCommand {
  RelocEvalOptions options;
  std::optional<std::string> json_path;
};

std::set<std::string> RelocFlags();

// Errors (code "usage", naming the flag): --frames not a whole number >= 2, --max-deg not a
// number in (0, 90], --record-frames not a whole number >= 1, --features not a whole number in
// [100, 100000], --methods not track, reloc or both, an empty --scenario; (code "io")
// a --json file that cannot be written.
Expected<RelocCommand> ParseRelocCommand(const CommandLine& command_line);

// The whole command: parse, run, print (exit codes as every reenact-eval command).
int RunRelocCommand(const CommandLine& command_line);

}  // namespace reenact::eval
