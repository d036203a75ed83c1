#include "tests/eval/kinect_reference_eval.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <numeric>
#include <sstream>

#include "capture-client/skeleton/skeleton_track_spec.h"
#include "common/estimate/median.h"
#include "tests/eval/quality_cli.h"
#include "tests/eval/skeleton_overlay.h"
#include "tests/eval/tracker_eval.h"
#include "tests/eval/utd_mhad.h"
#include "viewer-client/output/png_writer.h"

namespace reenact::eval {
namespace {

namespace fs = std::filesystem;

// The frames a track covers, counted as the depth source counts them (see the header).
long long ReferenceFrameCount(const capture::SkeletonTrack& track) {
  if (track.keyed_by_timestamp() || track.frames().empty()) return track.size();
  const auto& last = track.frames().back().frame_index;
  const long long index = last ? *last : static_cast<long long>(track.size()) - 1;
  return index + 1 - track.lookup_options().frame_index_offset;
}

Error FrameCountMismatch(const ReferenceSequenceSpec& spec, long long reference_frames,
                         long long depth_frames) {
  std::string m = spec.name;
  m += ": the skeleton track ";
  m += spec.reference_spec;
  m += " has ";
  m += std::to_string(reference_frames);
  m += " frames but the depth source ";
  m += spec.source_spec;
  m += " has ";
  m += std::to_string(depth_frames);
  m += "; frame i of the track must belong to depth frame i (give both of one recording)";
  return MakeError("invalid_argument", std::move(m));
}

std::vector<std::optional<JointPoints>> Points(const std::vector<std::optional<Skeleton>>& v) {
  std::vector<std::optional<JointPoints>> out(v.size());
  for (size_t f = 0; f < v.size(); ++f)
    if (v[f]) out[f] = PointsOf(*v[f]);
  return out;
}

}  // namespace

Expected<TrackedSequence> TrackSequence(const ReferenceSequenceSpec& spec,
                                        capture::FrameSource* source,
                                        const capture::SkeletonTrack& reference,
                                        const capture::SkeletonTrackerOptions& tracker_options,
                                        int max_frames) {
  const capture::SensorInfo& info = source->info();
  const long long reference_frames = ReferenceFrameCount(reference);
  if (info.frame_count >= 0 && info.frame_count != reference_frames)
    return FrameCountMismatch(spec, reference_frames, info.frame_count);
  capture::SkeletonTracker tracker(info.depth_camera, info.depth_scale_m, tracker_options);
  TrackedSequence out;
  out.spec = spec;
  out.frame_rate_hz = info.frame_rate_hz > 0 ? info.frame_rate_hz : 30;
  for (int index = 0; max_frames < 0 || index < max_frames; ++index) {
    auto next = source->Next();
    if (!next.ok()) return next.error();
    if (!next->has_value()) break;
    const capture::SensorFrame& frame = **next;
    out.reference.push_back(reference.ForFrame(index, frame.timestamp_s));
    const auto t0 = std::chrono::steady_clock::now();
    const capture::TrackFrameResult r =
        tracker.Track(frame.depth, std::nullopt, std::nullopt, frame.timestamp_s);
    const auto t1 = std::chrono::steady_clock::now();
    out.track_ms.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
    out.tracked.push_back(r.skeleton);
  }
  const long long yielded = static_cast<long long>(out.tracked.size());
  if (info.frame_count < 0 && max_frames < 0 && yielded != reference_frames)
    return FrameCountMismatch(spec, reference_frames, yielded);
  return out;
}

namespace {

// Per sequence, what EvaluateSequences keeps beside the figures for the pictures.
struct Corrected {
  std::vector<std::optional<Skeleton>> tracked;  // after the offsets (raw without them)
};

SequenceResult Evaluate(const TrackedSequence& s, const std::optional<JointOffsets>& offsets,
                        int offset_fit_frames,
                        const std::vector<std::optional<JointPoints>>* joints20,
                        Corrected* corrected) {
  AgreementOptions options;
  options.warmup_frames = static_cast<int>(std::lround(s.frame_rate_hz));
  SequenceResult r;
  r.spec = s.spec;
  r.track_ms = s.track_ms;
  const auto reference = Points(s.reference);
  const std::vector<bool> moving = MovingJoints(reference);
  r.raw = CompareSequence(Points(s.tracked), reference, moving, options);
  corrected->tracked = s.tracked;
  if (offsets) {
    for (auto& t : corrected->tracked)
      if (t) t = offsets->Apply(*t);
    r.offset = CompareSequence(Points(corrected->tracked), reference, moving, options);
    r.offset_fit_frames = offset_fit_frames;
  }
  r.baseline = CompareSequence(MeanPoseAtCentre(reference, Index(Joint::kWaist)), reference,
                               moving, options);
  if (joints20 && !joints20->empty())
    r.baseline20 = CompareSequence(MeanPoseAtCentre(*joints20, kUtdMhadHipCentre), *joints20,
                                   MovingJoints(*joints20), options);
  return r;
}

// Every sequence's figures and corrected skeletons (EvaluateSequences' work).
std::vector<SequenceResult> EvaluateAll(
    const std::vector<TrackedSequence>& sequences,
    const std::vector<std::vector<std::optional<JointPoints>>>& joints20,
    std::vector<Corrected>* corrected) {
  std::vector<JointOffsetFit> fits(sequences.size());
  for (size_t i = 0; i < sequences.size(); ++i) {
    const TrackedSequence& s = sequences[i];
    for (size_t f = 0; f < s.tracked.size() && f < s.reference.size(); ++f)
      if (s.tracked[f] && s.reference[f]) fits[i].Add(*s.tracked[f], *s.reference[f]);
  }
  std::vector<SequenceResult> out;
  corrected->assign(sequences.size(), {});
  for (size_t i = 0; i < sequences.size(); ++i) {
    const std::optional<int> subject = sequences[i].spec.subject;
    std::optional<JointOffsets> offsets;
    JointOffsetFit others;
    if (subject) {
      for (size_t k = 0; k < sequences.size(); ++k)
        if (sequences[k].spec.subject && *sequences[k].spec.subject != *subject)
          others.Merge(fits[k]);
      if (others.frames() > 0) offsets = others.Offsets();
    }
    out.push_back(Evaluate(sequences[i], offsets, others.frames(),
                           i < joints20.size() ? &joints20[i] : nullptr, &(*corrected)[i]));
  }
  return out;
}

// The kPictureCount (or fewer) frames with the largest error after the offsets, written.
Expected<std::vector<WorstFrame>> WritePictures(const std::vector<TrackedSequence>& sequences,
                                                const std::vector<SequenceResult>& results,
                                                const std::vector<Corrected>& corrected,
                                                const std::string& dir, int count) {
  struct Candidate {
    double error_cm;
    size_t sequence;
    int frame;
  };
  std::vector<Candidate> candidates;
  for (size_t i = 0; i < results.size(); ++i) {
    const SequenceAgreement& a = results[i].offset ? *results[i].offset : results[i].raw;
    for (size_t f = 0; f < a.frame_error_cm.size(); ++f)
      if (a.frame_error_cm[f]) candidates.push_back({*a.frame_error_cm[f], i, static_cast<int>(f)});
  }
  const size_t n = std::min(candidates.size(), static_cast<size_t>(std::max(count, 0)));
  std::partial_sort(candidates.begin(), candidates.begin() + n, candidates.end(),
                    [](const Candidate& a, const Candidate& b) { return a.error_cm > b.error_cm; });
  candidates.resize(n);
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) return MakeError("io", "--pictures: cannot create " + dir + ": " + ec.message());
  std::vector<WorstFrame> out;
  std::map<size_t, std::vector<Candidate>> by_sequence;
  for (const Candidate& c : candidates) by_sequence[c.sequence].push_back(c);
  for (auto& [i, frames] : by_sequence) {
    std::sort(frames.begin(), frames.end(),
              [](const Candidate& a, const Candidate& b) { return a.frame < b.frame; });
    const TrackedSequence& s = sequences[i];
    auto source = capture::OpenFrameSource(s.spec.source_spec);
    if (!source.ok()) return source.error();
    const PinholeCamera camera = (*source)->info().depth_camera;
    int index = 0;
    for (const Candidate& c : frames) {
      std::optional<capture::SensorFrame> frame;
      for (; index <= c.frame; ++index) {
        auto next = (*source)->Next();
        if (!next.ok()) return next.error();
        if (!next->has_value()) break;
        frame = std::move(**next);
      }
      if (!frame || index != c.frame + 1)
        return MakeError("io", s.spec.source_spec + " ended before frame " +
                                   std::to_string(c.frame) + " on a second reading");
      char name[32];
      std::snprintf(name, sizeof name, "_f%04d.png", c.frame);
      const std::string path = (fs::path(dir) / (s.spec.name + name)).string();
      const ImageRgb8 picture = SkeletonOverlay(frame->depth, camera, s.reference[c.frame],
                                                corrected[i].tracked[c.frame]);
      if (Status st = viewer::WritePng(path, picture); !st.ok()) return st.error();
      out.push_back({s.spec.name, path, c.frame, c.error_cm});
    }
  }
  std::sort(out.begin(), out.end(),
            [](const WorstFrame& a, const WorstFrame& b) { return a.error_cm > b.error_cm; });
  return out;
}

}  // namespace

std::vector<SequenceResult> EvaluateSequences(
    const std::vector<TrackedSequence>& sequences,
    const std::vector<std::vector<std::optional<JointPoints>>>& joints20) {
  std::vector<Corrected> corrected;
  return EvaluateAll(sequences, joints20, &corrected);
}

Expected<KinectReferenceRun> RunKinectReferenceEval(const KinectReferenceOptions& options) {
  options.tracker.Check();
  std::vector<TrackedSequence> tracked;
  std::vector<std::vector<std::optional<JointPoints>>> joints20;
  for (const ReferenceSequenceSpec& spec : options.sequences) {
    auto reference = capture::LoadSkeletonTrack(spec.reference_spec);
    if (!reference.ok()) return reference.error();
    auto source = capture::OpenFrameSource(spec.source_spec);
    if (!source.ok()) return source.error();
    auto sequence =
        TrackSequence(spec, source->get(), *reference, options.tracker, options.max_frames);
    if (!sequence.ok()) return sequence.error();
    if (options.progress) {
      const auto given = std::count_if(sequence->tracked.begin(), sequence->tracked.end(),
                                       [](const auto& s) { return s.has_value(); });
      *options.progress << spec.name << ": " << sequence->tracked.size() << " frames, " << given
                        << " with a skeleton" << std::endl;
    }
    tracked.push_back(std::move(*sequence));
    auto& j20 = joints20.emplace_back();
    if (!spec.joints20_path.empty()) {
      auto read = ReadUtdMhadJoints20(spec.joints20_path);
      if (!read.ok()) return read.error();
      j20 = std::move(*read);
      if (options.max_frames >= 0 && static_cast<int>(j20.size()) > options.max_frames)
        j20.resize(options.max_frames);
    }
  }
  std::vector<Corrected> corrected;
  KinectReferenceRun run;
  run.sequences = EvaluateAll(tracked, joints20, &corrected);
  if (options.pictures_dir && options.pictures > 0) {
    auto pictures =
        WritePictures(tracked, run.sequences, corrected, *options.pictures_dir, options.pictures);
    if (!pictures.ok()) return pictures.error();
    run.pictures = std::move(*pictures);
  }
  return run;
}

namespace {

// A figure of a row: the value, or "-" (for_json: left out) where there is none.
void AddFigure(proto::ReportRow* row, const std::string& name, std::optional<double> value,
               bool for_json, double scale = 1) {
  if (value) row->Add(name, *value * scale);
  else if (!for_json) row->Add(name, std::string("-"));
}

std::optional<double> Median(const std::vector<double>& v) {
  return v.empty() ? std::nullopt : std::optional(reenact::Median(v));
}

std::optional<double> Mean(const std::vector<double>& v) {
  return v.empty() ? std::nullopt
                   : std::optional(std::accumulate(v.begin(), v.end(), 0.0) / v.size());
}

// The tracker's columns of a group of sequences.
// A row's figures from a group's raw agreement and, where given, the agreement after the
// offsets (a baseline repeats its raw figures there) and the tracker's times per frame.
void AddFigures(proto::ReportRow* row, const std::vector<const SequenceAgreement*>& raw,
                const std::optional<std::vector<const SequenceAgreement*>>& offset,
                const std::vector<double>& ms, bool for_json) {
  const GroupAgreement r = Aggregate(raw);
  const std::optional<GroupAgreement> o =
      !offset ? std::optional(r)
              : offset->empty() ? std::nullopt : std::optional(Aggregate(*offset));
  row->Add("sequences", static_cast<long long>(r.sequences))
      .Add("frames", static_cast<long long>(r.frames));
  AddFigure(row, "tracked_pct", r.tracked_share, for_json, 100);
  AddFigure(row, "first_skeleton", r.first_estimate_median, for_json);
  row->Add("untracked_seq", static_cast<long long>(r.untracked_sequences));
  AddFigure(row, "joints_pct", r.joint_share, for_json, 100);
  AddFigure(row, "mpjpe_cm", r.mpjpe_cm, for_json);
  AddFigure(row, "mpjpe_offset_cm", o ? o->mpjpe_cm : std::nullopt, for_json);
  AddFigure(row, "moving_cm", r.moving_mpjpe_cm, for_json);
  AddFigure(row, "moving_offset_cm", o ? o->moving_mpjpe_cm : std::nullopt, for_json);
  AddFigure(row, "pck10_offset_pct", o ? o->pck : std::nullopt, for_json, 100);
  AddFigure(row, "ms_median", Median(ms), for_json);
  AddFigure(row, "ms_mean", Mean(ms), for_json);
}

// The tracker's row of a group of sequences.
void AddTrackerFigures(proto::ReportRow* row, const std::vector<const SequenceResult*>& group,
                       bool for_json) {
  std::vector<const SequenceAgreement*> raw, offset;
  std::vector<double> ms;
  for (const SequenceResult* s : group) {
    raw.push_back(&s->raw);
    if (s->offset) offset.push_back(&*s->offset);
    ms.insert(ms.end(), s->track_ms.begin(), s->track_ms.end());
  }
  AddFigures(row, raw, offset, ms, for_json);
}

std::vector<const SequenceAgreement*> Baselines(const std::vector<const SequenceResult*>& group) {
  std::vector<const SequenceAgreement*> out;
  for (const SequenceResult* s : group) out.push_back(&s->baseline);
  return out;
}

// The groups by action or subject (sequences without one left out), in order.
std::map<int, std::vector<const SequenceResult*>> GroupBy(
    const KinectReferenceRun& run, std::optional<int> ReferenceSequenceSpec::*key) {
  std::map<int, std::vector<const SequenceResult*>> out;
  for (const SequenceResult& s : run.sequences)
    if (const auto k = s.spec.*key) out[*k].push_back(&s);
  return out;
}

// The row of a group in the actions or subjects table: the tracker's figures and the
// baseline's two MPJPE.
proto::ReportRow GroupRow(const std::string& table, const std::vector<const SequenceResult*>& g,
                          bool for_json, proto::ReportRow row) {
  row.table = table;
  AddTrackerFigures(&row, g, for_json);
  const GroupAgreement b = Aggregate(Baselines(g));
  AddFigure(&row, "baseline_cm", b.mpjpe_cm, for_json);
  AddFigure(&row, "baseline_moving_cm", b.moving_mpjpe_cm, for_json);
  return row;
}

// The worst action by moving_offset_cm (moving_cm where no sequence has offsets).
struct WorstAction {
  int action = 0;
  double moving_cm = 0;
  bool offset = false;
};
std::optional<WorstAction> FindWorstAction(const KinectReferenceRun& run) {
  bool any_offset = false;
  for (const SequenceResult& s : run.sequences)
    any_offset = any_offset || (s.offset && s.offset->moving_mpjpe_cm);
  std::optional<WorstAction> worst;
  for (const auto& [action, group] : GroupBy(run, &ReferenceSequenceSpec::action)) {
    std::vector<const SequenceAgreement*> a;
    for (const SequenceResult* s : group)
      if (any_offset ? s->offset.has_value() : true) a.push_back(any_offset ? &*s->offset : &s->raw);
    const auto moving = Aggregate(a).moving_mpjpe_cm;
    if (moving && (!worst || *moving > worst->moving_cm)) worst = {action, *moving, any_offset};
  }
  return worst;
}

}  // namespace

proto::Report KinectReferenceReport(const KinectReferenceRun& run, bool for_json) {
  proto::Report report;
  report.command = "tracker";
  std::vector<const SequenceResult*> all;
  std::vector<const SequenceAgreement*> baseline20;
  for (const SequenceResult& s : run.sequences) {
    all.push_back(&s);
    if (s.baseline20) baseline20.push_back(&*s.baseline20);
  }
  proto::ReportRow tracker;
  tracker.Add("method", std::string("tracker"));
  AddTrackerFigures(&tracker, all, for_json);
  report.rows.push_back(std::move(tracker));
  proto::ReportRow baseline;
  baseline.Add("method", std::string("baseline"));
  AddFigures(&baseline, Baselines(all), std::nullopt, {}, for_json);
  report.rows.push_back(std::move(baseline));
  if (!baseline20.empty()) {
    proto::ReportRow row;
    row.Add("method", std::string("baseline_kinect20"));
    AddFigures(&row, baseline20, std::nullopt, {}, for_json);
    report.rows.push_back(std::move(row));
  }
  for (const auto& [action, group] : GroupBy(run, &ReferenceSequenceSpec::action)) {
    proto::ReportRow row;
    row.Add("action", static_cast<long long>(action))
        .Add("name", std::string(UtdMhadActionName(action)));
    report.rows.push_back(GroupRow("actions", group, for_json, std::move(row)));
  }
  for (const auto& [subject, group] : GroupBy(run, &ReferenceSequenceSpec::subject)) {
    proto::ReportRow row;
    row.Add("subject", static_cast<long long>(subject));
    report.rows.push_back(GroupRow("subjects", group, for_json, std::move(row)));
  }
  if (const auto worst = FindWorstAction(run)) {
    proto::ReportRow row;
    row.table = "worst";
    row.Add("action", static_cast<long long>(worst->action))
        .Add("name", std::string(UtdMhadActionName(worst->action)))
        .Add(worst->offset ? "moving_offset_cm" : "moving_cm", worst->moving_cm);
    if (for_json) report.rows.push_back(std::move(row));
  }
  if (!for_json) return report;
  for (const SequenceResult& s : run.sequences) {
    proto::ReportRow row;
    row.table = "sequences";
    row.Add("sequence", s.spec.name);
    if (s.spec.action) row.Add("action", static_cast<long long>(*s.spec.action));
    if (s.spec.subject) row.Add("subject", static_cast<long long>(*s.spec.subject));
    row.Add("frames", static_cast<long long>(s.raw.frames))
        .Add("tracked", static_cast<long long>(s.raw.tracked))
        .Add("moving_joints", static_cast<long long>(s.raw.moving_joints));
    AddFigure(&row, "tracked_pct", s.raw.tracked_share, true, 100);
    if (s.raw.first_estimate)
      row.Add("first_skeleton", static_cast<long long>(*s.raw.first_estimate));
    AddFigure(&row, "joints_pct", s.raw.joint_share, true, 100);
    AddFigure(&row, "mpjpe_cm", s.raw.mpjpe_cm, true);
    AddFigure(&row, "moving_cm", s.raw.moving_mpjpe_cm, true);
    AddFigure(&row, "pck10_pct", s.raw.pck, true, 100);
    if (s.offset) {
      AddFigure(&row, "mpjpe_offset_cm", s.offset->mpjpe_cm, true);
      AddFigure(&row, "moving_offset_cm", s.offset->moving_mpjpe_cm, true);
      AddFigure(&row, "pck10_offset_pct", s.offset->pck, true, 100);
      row.Add("offset_fit_frames", static_cast<long long>(s.offset_fit_frames));
    }
    AddFigure(&row, "baseline_cm", s.baseline.mpjpe_cm, true);
    AddFigure(&row, "baseline_moving_cm", s.baseline.moving_mpjpe_cm, true);
    if (s.baseline20) {
      AddFigure(&row, "baseline20_cm", s.baseline20->mpjpe_cm, true);
      AddFigure(&row, "baseline20_moving_cm", s.baseline20->moving_mpjpe_cm, true);
    }
    AddFigure(&row, "ms_median", Median(s.track_ms), true);
    AddFigure(&row, "ms_mean", Mean(s.track_ms), true);
    report.rows.push_back(std::move(row));
  }
  for (const WorstFrame& w : run.pictures) {
    proto::ReportRow row;
    row.table = "pictures";
    row.Add("sequence", w.sequence)
        .Add("frame", static_cast<long long>(w.frame))
        .Add("error_cm", w.error_cm)
        .Add("path", w.path);
    report.rows.push_back(std::move(row));
  }
  return report;
}

std::string WorstActionLine(const KinectReferenceRun& run) {
  const auto worst = FindWorstAction(run);
  if (!worst) return "worst action: - (no tracked frame)";
  char figure[32];
  std::snprintf(figure, sizeof figure, "%.1f", worst->moving_cm);
  std::string line = "worst action: ";
  line += std::to_string(worst->action);
  line += " ";
  line += UtdMhadActionName(worst->action);
  line += " (moving joints ";
  line += figure;
  line += worst->offset ? " cm after the offsets)" : " cm, no offsets)";
  return line;
}

std::set<std::string> KinectReferenceFlags() {
  return {"source", "reference", "dataset", "sequences", "pictures"};
}

bool WantsKinectReference(const CommandLine& cl) {
  for (const std::string& flag : KinectReferenceFlags())
    if (cl.Has(flag)) return true;
  return false;
}

Expected<KinectReferenceCommand> ParseKinectReferenceCommand(const CommandLine& cl) {
  for (const std::string& flag : TrackerFlags())
    if (flag != "json" && cl.Has(flag))
      return MakeError("usage", "--" + flag +
                                    " is a setting of the synthetic scenes; it does not go with "
                                    "--source/--reference or --dataset");
  KinectReferenceCommand command;
  KinectReferenceOptions& o = command.options;
  const auto source = cl.Get("source"), reference = cl.Get("reference"),
             dataset = cl.Get("dataset"), sequences = cl.Get("sequences");
  if (dataset && (source || reference))
    return MakeError("usage",
                     "give either --dataset KIND:ROOT or --source SPEC with --reference SPEC, "
                     "not both");
  if (sequences && !dataset)
    return MakeError("usage", "--sequences picks sequences of --dataset KIND:ROOT; give that too");
  if (source.has_value() != reference.has_value())
    return MakeError("usage", source ? "--source needs --reference kinect:FILE (the skeletons "
                                       "recorded with the frames)"
                                     : "--reference needs --source SPEC (the depth frames the "
                                       "skeletons were recorded with)");
  if (source) {
    if (source->empty() || reference->empty())
      return MakeError("usage", "--source and --reference need a value each");
    ReferenceSequenceSpec spec;
    spec.source_spec = *source;
    spec.reference_spec = *reference;
    // The folder's name: the spec without its kind and options.
    std::string path = *source;
    if (const size_t colon = path.find(':'); colon != std::string::npos) path.erase(0, colon + 1);
    if (const size_t query = path.find('?'); query != std::string::npos) path.erase(query);
    while (path.size() > 1 && path.back() == '/') path.pop_back();
    spec.name = fs::path(path).filename().string();
    if (spec.name.empty()) spec.name = *source;
    if (const auto utd = ParseUtdMhadName(spec.name)) {
      spec.action = utd->action;
      spec.subject = utd->subject;
    }
    o.sequences.push_back(std::move(spec));
  } else if (dataset) {
    const size_t colon = dataset->find(':');
    const std::string kind = dataset->substr(0, colon);
    if (kind != "utd-mhad")
      return MakeError("usage", "--dataset: unknown kind '" + kind + "' (known: utd-mhad)");
    if (colon == std::string::npos || colon + 1 == dataset->size())
      return MakeError("usage", "--dataset utd-mhad:ROOT needs the data set's folder after the "
                                "colon");
    auto listed = ListUtdMhad(dataset->substr(colon + 1));
    if (!listed.ok()) return listed.error();
    std::vector<UtdMhadSequence> chosen = *listed;
    if (sequences) {
      chosen.clear();
      std::stringstream ss(*sequences);
      std::set<std::string> seen;
      for (std::string name; std::getline(ss, name, ',');) {
        const auto it = std::find_if(listed->begin(), listed->end(),
                                     [&](const UtdMhadSequence& s) { return s.name == name; });
        if (it == listed->end())
          return MakeError("usage", "--sequences: no sequence '" + name + "' under " +
                                        dataset->substr(colon + 1) +
                                        " (names like a1_s1_t1, comma-separated)");
        if (seen.insert(name).second) chosen.push_back(*it);
      }
      if (chosen.empty() || sequences->back() == ',')
        return MakeError("usage", "--sequences: give names like a1_s1_t1, comma-separated");
    }
    for (const UtdMhadSequence& s : chosen) {
      ReferenceSequenceSpec spec;
      spec.name = s.name;
      spec.source_spec = UtdMhadDepthSpec(s);
      spec.reference_spec = UtdMhadSkeletonSpec(s);
      spec.action = s.action;
      spec.subject = s.subject;
      spec.joints20_path = UtdMhadSkeletonPath(s);
      o.sequences.push_back(std::move(spec));
    }
  } else {
    return MakeError("usage", "give --dataset utd-mhad:ROOT, or --source SPEC with --reference "
                              "kinect:FILE");
  }
  if (auto dir = cl.Get("pictures")) {
    if (Status s = CheckCreatableFolder("pictures", *dir); !s.ok()) return s.error();
    o.pictures_dir = *dir;
  }
  if (auto path = cl.Get("json")) {
    if (Status s = CheckWritableFile("json", *path); !s.ok()) return s.error();
    command.json_path = *path;
  }
  return command;
}

int RunKinectReferenceCommand(const CommandLine& cl) {
  const auto command = ParseKinectReferenceCommand(cl);
  if (!command.ok()) return ReportFailure("reenact-eval", command.error());
  KinectReferenceOptions options = command->options;
  options.progress = &std::cerr;
  const auto run = RunKinectReferenceEval(options);
  if (!run.ok()) return ReportFailure("reenact-eval", run.error());
  std::cout << KinectReferenceReport(*run, false).FormatTable(1);
  std::cout << WorstActionLine(*run) << "\n"
            << "MPJPE: mean over a sequence's tracked frames of the mean joint distance to the "
               "Kinect SDK's skeleton, then over sequences; moving: the joints whose reference "
               "lies more than 10 cm from its mean position on some frame; offset: a constant "
               "per-joint offset in the tracked body's frame fitted on the other subjects' "
               "sequences taken out; tracked_pct after the first second; baseline: the "
               "sequence's mean pose placed at the reference's hip centre\n";
  for (const WorstFrame& w : run->pictures) std::cout << "wrote " << w.path << "\n";
  if (command->json_path) {
    if (Status s = KinectReferenceReport(*run, true).WriteJson(*command->json_path); !s.ok())
      return ReportFailure("reenact-eval", s.error());
    std::cout << "wrote " << *command->json_path << "\n";
  }
  return 0;
}

}  // namespace reenact::eval
