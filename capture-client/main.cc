// reenact-capture: record a clip from an RGB-D source, inspect it, publish it.
#include <cstdio>
#include <iostream>

#include "capture-client/publish/clip_publisher.h"
#include "capture-client/record/clip_recorder.h"
#include "capture-client/skeleton/skeleton_track_spec.h"
#include "capture-client/source/frame_source.h"
#include "capture-client/tracker/tracker_skeleton_source.h"
#include "common/cli/command_line.h"
#include "proto/clip/clip_directory.h"

namespace {

using namespace reenact;

constexpr const char* kUsage =
    "usage:\n"
    "  reenact-capture record --source SRC --out DIR [--frames N] [--skeleton SKEL]\n"
    "                         [--poses auto|slam] [--title S] [--author S]\n"
    "      SRC: synthetic:SCENARIO[?body=FILE.glb[&body_height=M]] | oni:FILE |\n"
    "           openni[:URI] | tum:DIR | clip:DIR |\n"
    "           rgbd:DIR[?calibration=FILE&depth_unit=M&fps=F&mirrored=0|1] (DIR/depth/*.png,\n"
    "           16-bit; colour in DIR/rgb/ or DIR/color/, needed to record; DIR/camera.json\n"
    "           or calibration.yml: capture-client/source/rgbd_folder_source.h)\n"
    "      SCENARIO: turn-and-kick | raise-and-crouch | upper-body-turn (close-up, no\n"
    "                floor or legs in view) | walk-handheld (moving sensor) |\n"
    "                calibration | model-walk | bvh:FILE.bvh   (model-walk and bvh: need\n"
    "                body=)\n"
    "      body=FILE.glb: a glTF skinned mesh (e.g. ../shared/data/models/CesiumMan.glb)\n"
    "                instead of the procedural body; body_height=M scales it\n"
    "      SKEL: source (default: the source's own skeletons) | track (our depth tracker:\n"
    "            start in the calibration pose, facing the sensor, arms out to the sides) |\n"
    "            json:FILE | FILE.json | kinect:FILE (UTKinect, MSR Action3D skeleton3D,\n"
    "            MSR DailyActivity3D, UTD-MHAD), each with ?frame_offset=N, ?time_offset_s=S,\n"
    "            ?tolerance_s=S\n"
    "      --poses: auto (default) = the source's poses when it has them, else RGB-D SLAM;\n"
    "               slam = SLAM even for sources with poses\n"
    "  reenact-capture info DIR\n"
    "  reenact-capture publish DIR --server URL --token T --lat DEG --lon DEG [--alt M]\n"
    "                          [--accuracy M] [--title S] [--retries N]\n"
    "      resumable: after an interruption the same command sends only what is missing;\n"
    "      --retries N: retries per request on connection errors, 5xx and 429 (default 5)\n";

int Fail(const Error& e) { return ReportFailure("reenact-capture", e); }

int Record(const CommandLine& cl) {
  const auto source_spec = cl.Require("source");
  if (!source_spec.ok()) return Fail(source_spec.error());
  const auto out = cl.Require("out");
  if (!out.ok()) return Fail(out.error());
  const auto frames = cl.GetInt("frames", -1);
  if (!frames.ok()) return Fail(frames.error());
  if (*frames == 0 || *frames < -1) return Fail(MakeError("usage", "--frames must be >= 1"));
  capture::RecordOptions options;
  const std::string poses = cl.GetOr("poses", "auto");
  if (poses != "auto" && poses != "slam")
    return Fail(MakeError("usage", "--poses " + poses + ": expected auto or slam"));
  options.poses = poses == "slam" ? capture::PoseSource::kSlam : capture::PoseSource::kAuto;
  std::optional<capture::SkeletonTrack> track;
  const std::string skeleton_spec = cl.GetOr("skeleton", "source");
  if (const std::string& skeleton = skeleton_spec; skeleton != "source" && skeleton != "track") {
    auto loaded = capture::LoadSkeletonTrack(skeleton);
    if (!loaded.ok()) return Fail(loaded.error());
    track = std::move(loaded).value();
    options.skeletons = [&track](int64_t index, double timestamp_s) {
      return track->ForFrame(index, timestamp_s);
    };
    std::cout << "skeletons from " << track->description() << std::endl;
  }
  auto source = capture::OpenFrameSource(*source_spec);
  if (!source.ok()) return Fail(source.error());
  if (Status recordable = capture::CheckRecordableSource((*source)->info()); !recordable.ok())
    return Fail(recordable.error());
  std::optional<capture::TrackerSkeletonSource> tracker;
  if (skeleton_spec == "track") {
    tracker.emplace((*source)->info());
    options.frame_skeletons = tracker->Function();
    std::cout << "skeletons from the depth tracker" << std::endl;
  }

  options.max_frames = static_cast<int>(*frames);
  options.title = cl.GetOr("title", "");
  options.author = cl.GetOr("author", "");
  std::cout << "recording " << (*source)->info().description << " -> " << *out << std::endl;
  const auto summary = capture::RecordClip(**source, *out, options);
  if (tracker) std::cout << tracker->stats().Describe() << std::endl;
  if (!summary.ok()) return Fail(summary.error());
  std::printf(
      "recorded %d frames in %.1f s: %.1f KB per frame, map %zu points (%.1f KB), "
      "representative frame %d, %d of 11 radii fitted\n",
      summary->frames, summary->seconds, summary->frame_bytes / 1024.0 / summary->frames,
      summary->map_points, summary->map_bytes / 1024.0, summary->representative_frame,
      summary->fitted_parts);
  if (summary->slam_poses)
    std::printf("poses by SLAM: %d keyframes, %d frames by the odometry fallback, %d "
                "relocalised\n",
                summary->slam_keyframes, summary->slam_fallback_frames,
                summary->slam_relocalised_frames);
  if (summary->frames < summary->source_frames)
    std::printf("not stored: %d of %d source frames without a skeleton, %d without a pose\n",
                summary->frames_without_skeleton, summary->source_frames,
                summary->frames_without_pose);
  if (summary->segmented_frames > 0 || summary->inconsistent_skeletons > 0)
    std::printf("%d frames segmented; %d skeletons flagged by the consistency check (kept out "
                "of the model and of texturing)\n",
                summary->segmented_frames, summary->inconsistent_skeletons);
  return 0;
}

int Info(const CommandLine& cl) {
  if (cl.positionals().size() != 2) return Fail(MakeError("usage", "info needs a clip DIR"));
  const auto clip = proto::ReadClipDirectory(cl.positionals()[1]);
  if (!clip.ok()) return Fail(clip.error());
  const proto::ClipManifest& m = clip->manifest();
  uint64_t bytes = m.map_part.bytes;
  for (const auto& p : m.frame_parts) bytes += p.bytes;
  std::printf("clip        %s\n", clip->path().c_str());
  std::printf("title       %s\nauthor      %s\ncaptured    %s\n", m.title.c_str(), m.author.c_str(),
              m.capture_time.c_str());
  std::printf("frames      %lld at %.1f Hz (%.2f s)\n", static_cast<long long>(m.frame_count),
              m.frame_rate_hz, m.DurationS());
  std::printf("camera      %dx%d fx %.1f fy %.1f cx %.1f cy %.1f\n", m.color_camera.width,
              m.color_camera.height, m.color_camera.fx, m.color_camera.fy, m.color_camera.cx,
              m.color_camera.cy);
  std::printf("model       representative frame %lld; radius ratios:",
              static_cast<long long>(m.representative_frame));
  for (int p = 0; p < kBodyPartCount; ++p)
    std::printf(" %s=%.3f", std::string(PartName(static_cast<BodyPart>(p))).c_str(),
                m.radius_ratio[p]);
  std::printf("\nskeletons   %zu flagged by the consistency check (not used for texturing)",
              m.flagged_skeleton_frames.size());
  std::printf("\nmap         %lld points, %llu bytes\n", static_cast<long long>(m.map.point_count),
              static_cast<unsigned long long>(m.map_part.bytes));
  std::printf("size        %llu bytes (%.1f KB per frame)\n",
              static_cast<unsigned long long>(bytes),
              (bytes - m.map_part.bytes) / 1024.0 / m.frame_count);
  return 0;
}

int Publish(const CommandLine& cl) {
  if (cl.positionals().size() != 2) return Fail(MakeError("usage", "publish needs a clip DIR"));
  capture::PublishOptions options;
  for (const char* flag : {"server", "token"})
    if (!cl.Get(flag))
      return Fail(MakeError("usage", std::string("missing required option --") + flag));
  options.server_url = *cl.Get("server");
  options.token = *cl.Get("token");
  const auto lat = cl.RequireDouble("lat");
  if (!lat.ok()) return Fail(lat.error());
  const auto lon = cl.RequireDouble("lon");
  if (!lon.ok()) return Fail(lon.error());
  const auto alt = cl.GetDouble("alt", 0);
  if (!alt.ok()) return Fail(alt.error());
  const auto accuracy = cl.GetDouble("accuracy", 10);
  if (!accuracy.ok()) return Fail(accuracy.error());
  if (auto checked = ParseLatLon(std::to_string(*lat) + "," + std::to_string(*lon)); !checked.ok())
    return Fail(checked.error());
  options.location = {*lat, *lon, *alt, *accuracy, std::nullopt};
  if (auto title = cl.Get("title")) options.title = *title;
  const auto retries = cl.GetInt("retries", options.retry.max_attempts - 1);
  if (!retries.ok()) return Fail(retries.error());
  if (*retries < 0 || *retries > 100)
    return Fail(MakeError("usage", "--retries must be in 0..100"));
  options.retry.max_attempts = static_cast<int>(*retries) + 1;
  options.progress = capture::DefaultProgressStyle();
  const auto summary = capture::PublishClip(cl.positionals()[1], options);
  if (!summary.ok()) return Fail(summary.error());
  if (!summary->already_published) {
    std::printf("published clip %s (%d frames) in %.1f s: sent %d of %d parts (%.1f KB)%s\n",
                summary->clip_id.c_str(), summary->frames, summary->seconds,
                summary->parts_sent, summary->parts_total, summary->bytes_sent / 1024.0,
                summary->resumed ? ", resumed an earlier upload" : "");
  }
  std::printf("parts_total=%d parts_sent=%d parts_skipped=%d parts_repaired=%d bytes_sent=%llu "
              "retries=%d resumed=%d already_published=%d\n",
              summary->parts_total, summary->parts_sent, summary->parts_skipped,
              summary->parts_repaired, static_cast<unsigned long long>(summary->bytes_sent),
              summary->retries, summary->resumed ? 1 : 0, summary->already_published ? 1 : 0);
  std::printf("clip_id=%s\n", summary->clip_id.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const CommandLineSpec spec{{"source", "out", "frames", "skeleton", "poses", "title", "author", "server",
                              "token", "lat", "lon", "alt", "accuracy", "retries"},
                             {}};
  return RunTool("reenact-capture", kUsage, spec,
                 {{"record", Record}, {"info", Info}, {"publish", Publish}}, argc, argv);
}
