#pragma once
// `reenact-eval segment`: the person segmentation (capture-client/segment/person_segmenter.h)
// against the synthetic scene's ground-truth subject mask.
//
//   reenact-eval segment [--scenario S[,S...]] [--step K] [--json FILE] [--noise on|off]
//
// Per scenario: every K-th sensor frame (default 1: all) is rendered (Kinect-like depth
// noise on by default), segmented with the ground-truth skeleton, the sensor pose and the
// world's up (as the synthetic source gives them), frames in order through one segmenter (so
// the floor cache works as in a recording), and compared with the true mask. Figures per
// scenario: IoU mean, min and p10 (nearest rank: the ceil(0.1 n)-th smallest), the worst
// frame, precision and recall (means), frames whose status is not ok, floor fits, and the
// median wall time of the segmentation alone (rendering excluded) in ms per frame, and its
// median CPU time (on a shared machine the wall time includes waiting for a core).

#include <cstdint>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "capture-client/segment/segment_options.h"
#include "common/cli/command_line.h"
#include "common/error/expected.h"
#include "proto/report/report_table.h"

namespace reenact::eval {

struct SegmentEvalOptions {
  std::vector<std::string> scenarios{"turn-and-kick"};
  int frame_step = 1;  // >= 1
  bool depth_noise = true;
  uint64_t seed = 1;  // scene seed (drives the depth noise)
  capture::PersonSegmentOptions segment;
};

struct SegmentEvalRow {
  std::string scenario;
  bool depth_noise = true;
  int frames = 0;
  double iou_mean = 0, iou_min = 0, iou_p10 = 0;
  int worst_frame = -1;
  double precision = 0, recall = 0;  // means over the frames
  int not_ok_frames = 0;             // status other than ok
  int floor_fits = 0;                // frames on which the floor was (re)fitted
  double ms_per_frame = 0;           // median wall time
  double cpu_ms_per_frame = 0;       // median CPU time of the thread
};

// Errors: "not_found" for an unknown scenario (listing the known ones).
Expected<std::vector<SegmentEvalRow>> RunSegmentEval(const SegmentEvalOptions& options);

// The table and --json rows (command "segment"): scenario, noise, n, iou, iou_min, iou_p10,
// worst_frame, precision, recall, not_ok, floor_fits, ms_per_frame, cpu_ms_per_frame.
proto::Report SegmentReport(const std::vector<SegmentEvalRow>& rows);

struct SegmentCommand {
  SegmentEvalOptions options;
  std::optional<std::string> json_path;
};

// The value flags ParseSegmentCommand reads.
std::set<std::string> SegmentFlags();

// Errors (code "usage", naming the flag): an empty scenario list or name, --step not a whole
// number >= 1, --noise other than on or off; (code "io") a --json file that cannot be written.
Expected<SegmentCommand> ParseSegmentCommand(const CommandLine& command_line);

}  // namespace reenact::eval
