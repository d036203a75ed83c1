#include "tests/eval/tracker_eval.h"

#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <numeric>
#include <random>
#include <sstream>
#include <string_view>

#include "capture-client/slam/rgbd_slam.h"
#include "common/estimate/median.h"
#include "synthetic/synthetic_scene.h"
#include "tests/eval/body_heading.h"
#include "tests/eval/calibration_aligned_error.h"
#include "tests/eval/in_view_error.h"
#include "tests/eval/quality_cli.h"
#include "tests/eval/tracker_experiment.h"

namespace reenact::eval {
namespace {

// CPU time of every thread of the process: the tracker's own threads count (nothing else runs
// while it tracks).
double ProcessCpuMs() {
  timespec t{};
  ::clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return t.tv_sec * 1e3 + t.tv_nsec * 1e-6;
}

// The near variant: the sensor moves forward along its axis until the subject's waist is
// kNearDistanceM ahead, by at most kNearMaxShiftM.
constexpr double kNearDistanceM = 1.8;
constexpr double kNearMaxShiftM = 1.2;
// SLAM's depth noise at 1 m for rendered frames, as the synthetic source declares it
// (synthetic_source.cc: the Kinect-like noise model's, doubled for keypoints on depth edges).
constexpr double kSlamDepthSigma1mM = 0.003;

// The variants (see the header), for checking and for naming them in a usage error.
constexpr std::array<std::string_view, 4> kVariantNames = {"normal", "fast", "near", "drops"};
bool IsVariant(const std::string& v) {
  return std::ranges::find(kVariantNames, v) != kVariantNames.end();
}
// Names joined by ", ", for a usage error.
template <typename Names>
std::string NameList(const Names& names) {
  std::string list;
  for (const std::string_view name : names) list += (list.empty() ? "" : ", ") + std::string(name);
  return list;
}
std::string VariantList() { return NameList(kVariantNames); }
std::string AblationList() { return NameList(TrackerAblations()); }

// The drops variant: after each frame seen, the frames dropped before the next, 0-3 with these
// probabilities (a mean of 0.6 dropped: 1.6 frame intervals between the frames seen).
constexpr std::array<double, 4> kDropProbabilities = {0.6, 0.25, 0.1, 0.05};

// The frames dropped after a frame seen, drawn from rng.
int DroppedAfter(std::mt19937_64* rng) {
  const double u = std::uniform_real_distribution<double>(0, 1)(*rng);
  double sum = 0;
  for (int k = 0; k + 1 < static_cast<int>(kDropProbabilities.size()); ++k)
    if (u < (sum += kDropProbabilities[k])) return k;
  return static_cast<int>(kDropProbabilities.size()) - 1;
}

constexpr int kCaseCount = 5;
const char* kCases[kCaseCount] = {"back_facing", "arm_in_front", "fast_motion", "partly_outside",
                                  "turning"};

// Which hard cases a ground-truth skeleton (sensor frame) shows; see the header. turn_deg: the
// body's heading change since the previous frame (nullopt for the first, or undefined).
std::array<bool, kCaseCount> HardCases(const Skeleton& s, const Skeleton* previous, double dt,
                                       const PinholeCamera& camera,
                                       std::optional<double> turn_deg) {
  std::array<bool, kCaseCount> c{};
  const auto forward = BodyForward(s);
  const Eigen::Vector3d to_sensor = -s[Joint::kWaist];
  if (forward && to_sensor.norm() > 1e-9)
    c[0] = forward->dot(to_sensor.normalized()) < std::cos(120 * M_PI / 180);
  const auto project = [&](const Eigen::Vector3d& p) { return camera.Project(p, 0.05); };
  const auto ls = project(s[Joint::kLeftShoulder]), rs = project(s[Joint::kRightShoulder]),
             nk = project(s[Joint::kNeck]), wa = project(s[Joint::kWaist]);
  if (ls && rs && nk && wa) {
    const double x0 = std::min(ls->x(), rs->x()), x1 = std::max(ls->x(), rs->x());
    const double y0 = std::min(nk->y(), wa->y()), y1 = std::max(nk->y(), wa->y());
    for (Joint j : {Joint::kLeftHand, Joint::kRightHand, Joint::kLeftElbow, Joint::kRightElbow}) {
      const auto p = project(s[j]);
      if (p && p->x() >= x0 && p->x() <= x1 && p->y() >= y0 && p->y() <= y1 &&
          s[j].z() <= s[Joint::kTorso].z() - 0.1)
        c[1] = true;
    }
  }
  if (previous)
    for (int j = 0; j < kJointCount; ++j)
      if ((s.position[j] - previous->position[j]).norm() / dt > 2.0) c[2] = true;
  for (int j = 0; j < kJointCount; ++j) {
    const auto p = project(s.position[j]);
    if (!p || p->x() < 0 || p->y() < 0 || p->x() >= camera.width || p->y() >= camera.height)
      c[3] = true;
  }
  c[4] = turn_deg && *turn_deg / dt > 60;
  return c;
}

double Mpjpe(const Skeleton& a, const Skeleton& b) {
  double sum = 0;
  for (int j = 0; j < kJointCount; ++j) sum += (a.position[j] - b.position[j]).norm();
  return sum / kJointCount;
}

double Mean(const std::vector<double>& v) {
  return v.empty() ? 0 : std::accumulate(v.begin(), v.end(), 0.0) / v.size();
}

// A tracked frame's errors (cm) into its frames row; mpjpe_m is Mpjpe(tracked, truth).
void AddJointErrors(const Skeleton& tracked, const Skeleton& truth, double mpjpe_m,
                    TrackerFrameRow* frame) {
  const auto cm = [&](Joint j) { return 100 * (tracked[j] - truth[j]).norm(); };
  frame->mpjpe_cm = 100 * mpjpe_m;
  for (int j = 0; j < kJointCount; ++j)
    if (const double e = cm(static_cast<Joint>(j)); e > frame->worst_cm) {
      frame->worst_cm = e;
      frame->worst_joint = static_cast<Joint>(j);
    }
  frame->l_hand_cm = cm(Joint::kLeftHand);
  frame->r_hand_cm = cm(Joint::kRightHand);
  frame->l_foot_cm = cm(Joint::kLeftFoot);
  frame->r_foot_cm = cm(Joint::kRightFoot);
}

struct CaseSum {
  int frames = 0, tracked = 0;
  double err = 0;
};

Expected<TrackerEvalRow> RunOne(const capture::SyntheticScene& scene, const std::string& variant,
                                int iterations, int subsample, const TrackerEvalOptions& o,
                                std::map<std::string, CaseSum>* cases, JointErrorTable* joints,
                                ConfidenceErrorTable* confidence, LimbVisibilityTable* limbs,
                                std::vector<TrackerFrameRow>* frames) {
  capture::SkeletonTrackerOptions to = o.tracker;
  to.iterations = iterations;
  to.subsample = subsample;
  capture::SkeletonTracker tracker(scene.sensor_camera(), 0.001, to,
                                   ExperimentMethod(to, o.without));
  capture::SyntheticRenderOptions render;
  render.depth_noise = o.depth_noise;
  const int step = variant == "fast" ? 2 : 1;
  const bool near = variant == "near";
  std::optional<std::mt19937_64> drops;
  if (variant == "drops") drops.emplace(scene.seed() * 0x9E3779B97F4A7C15ull + 1);
  const PinholeCamera& camera = scene.sensor_camera();

  TrackerEvalRow row;
  row.scenario = scene.scenario();
  row.variant = variant;
  row.iterations = iterations;
  row.subsample = subsample;
  row.seed = static_cast<int>(scene.seed());
  std::vector<double> errors, aligned_errors, floor_posed_errors, floor_errors, headings, ms, cpu;
  InViewErrorTable in_view;
  int floor_cheaper = 0;  // floor frames whose fit from the truth cost less than the track's
  std::optional<CalibrationAlignment> alignment;
  const Eigen::Vector3d world_up = scene.world_up();
  std::optional<Skeleton> previous_truth, previous_world;
  std::optional<capture::slam::RgbdSlam> slam;  // with o.slam_poses, from the first frame
  capture::TrackState last = capture::TrackState::kWaitingForCalibration;
  int previous_f = -1;
  for (int f = 0; f < scene.frame_count(); f += step + (drops ? DroppedAfter(&*drops) : 0)) {
    if (o.max_frames > 0 && row.frames >= o.max_frames) break;
    Eigen::Isometry3d world_from_sensor = scene.world_from_sensor(f);
    if (near) {
      const double z =
          (world_from_sensor.inverse() * scene.skeleton_in_world(f)[Joint::kWaist]).z();
      const double shift = std::clamp(z - kNearDistanceM, 0.0, kNearMaxShiftM);
      world_from_sensor.translation() += shift * world_from_sensor.linear().col(2);
    }
    const capture::SyntheticView view = scene.Render(f, camera, world_from_sensor, render);
    const Skeleton world = scene.skeleton_in_world(f);
    const Skeleton truth = world.Transformed(world_from_sensor.inverse());
    if (o.slam_poses && !slam) {
      capture::slam::SlamOptions so;
      so.noise.depth_sigma_1m_m = kSlamDepthSigma1mM;
      so.initial_world_from_sensor = world_from_sensor;
      slam.emplace(camera, 0.001, so);
    }
    const std::optional<Eigen::Isometry3d> given = o.withhold_sensor_pose ? std::nullopt
                                                   : slam ? slam->PredictedWorldFromSensor()
                                                          : std::optional(world_from_sensor);
    const double cpu0 = ProcessCpuMs();
    const auto t0 = std::chrono::steady_clock::now();
    const capture::TrackFrameResult r =
        tracker.Track(view.depth, given, given ? std::optional(world_up) : std::nullopt,
                      o.timestamps ? std::optional(f / scene.frame_rate_hz()) : std::nullopt);
    const auto t1 = std::chrono::steady_clock::now();
    cpu.push_back(ProcessCpuMs() - cpu0);
    ms.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
    if (slam) {
      auto tracked = slam->Track(f / scene.frame_rate_hz(), view.color, view.depth, &view.mask);
      if (!tracked.ok()) return tracked.error();
    }
    ++row.frames;
    if (r.calibrated && row.calibration_frame < 0) row.calibration_frame = f;
    if (r.recovered) ++row.recoveries;
    if (last == capture::TrackState::kTracking && r.state == capture::TrackState::kLost)
      ++row.losses;
    last = r.state;
    TrackerFrameRow frame;
    if (frames) {
      frame.scenario = row.scenario;
      frame.variant = row.variant;
      frame.iterations = iterations;
      frame.subsample = subsample;
      frame.seed = row.seed;
      frame.frame = f;
      frame.state = r.state;
      frame.calibrated = r.calibrated;
      frame.recovered = r.recovered;
      frame.points = r.points;
      frame.inlier_share = r.inlier_share;
      frame.outlier_share = r.outlier_share;
      frame.coverage = r.coverage;
    }
    double err = 0;
    if (r.skeleton) {
      ++row.tracked;
      err = Mpjpe(*r.skeleton, truth);
      errors.push_back(err);
      in_view.Add(*r.skeleton, truth, camera);
      // The aligned error, as mpjpe_cm, takes every joint where the model put it, a joint
      // outside the image (reported missing) too.
      Skeleton modelled = *r.skeleton;
      modelled.confidence.fill(1);
      if (r.calibrated)
        alignment = tracker.calibration()->from_calibration_pose
                        ? CalibrationAlignment::FromCalibrationFrame(modelled, truth)
                        : std::nullopt;
      else if (alignment)
        aligned_errors.push_back(Mpjpe(alignment->Aligned(modelled), truth));
      if (o.floor)
        if (const auto oracle = FitLastFrameFrom(tracker, truth)) {
          floor_posed_errors.push_back(Mpjpe(oracle->posed, truth));
          floor_errors.push_back(Mpjpe(oracle->fitted, truth));
          frame.floor_mpjpe_cm = 100 * floor_errors.back();
          frame.floor_cheaper = oracle->fitted_cost < oracle->track_cost;
          floor_cheaper += frame.floor_cheaper;
        }
      if (frames) AddJointErrors(*r.skeleton, truth, err, &frame);
      const Eigen::Vector3d up = world_from_sensor.linear().transpose() * world_up;
      if (const auto h = HeadingErrorDeg(*r.skeleton, truth, up)) headings.push_back(*h);
      joints->Add(*r.skeleton, truth);
      confidence->Add(*r.skeleton, truth);
      limbs->Add(VisiblePartAreas(view.part_labels, truth, camera), *r.skeleton, truth);
    }
    if (frames) frames->push_back(std::move(frame));
    const auto hard = HardCases(
        truth, previous_truth ? &*previous_truth : nullptr,
        (f - previous_f) / scene.frame_rate_hz(), camera,
        previous_world ? HeadingErrorDeg(world, *previous_world, world_up) : std::nullopt);
    for (int k = 0; k < kCaseCount; ++k) {
      if (!hard[k]) continue;
      CaseSum& c = (*cases)[kCases[k]];
      ++c.frames;
      if (r.skeleton) ++c.tracked, c.err += err;
    }
    previous_truth = truth;
    previous_world = world;
    previous_f = f;
  }
  row.tracked_rate = row.frames ? static_cast<double>(row.tracked) / row.frames : 0;
  row.mpjpe_cm = 100 * Mean(errors);
  row.p90_cm = errors.empty() ? 0 : 100 * Percentile(errors, 0.9);
  const InViewErrorStats seen = in_view.Stats();
  row.in_view_mpjpe_cm = seen.in_view_mpjpe_cm;
  row.in_view_reported = seen.in_view_reported_share;
  row.invented = seen.invented_share;
  if (!aligned_errors.empty()) row.aligned_mpjpe_cm = 100 * Mean(aligned_errors);
  if (!floor_errors.empty()) {
    row.floor_posed_mpjpe_cm = 100 * Mean(floor_posed_errors);
    row.floor_mpjpe_cm = 100 * Mean(floor_errors);
    row.floor_cheaper_rate = static_cast<double>(floor_cheaper) / floor_errors.size();
  }
  if (!headings.empty()) {
    row.heading_deg = Median(headings);
    row.reversed_rate = static_cast<double>(std::count_if(headings.begin(), headings.end(),
                                                          [](double h) { return h > 90; })) /
                        headings.size();
  }
  if (const auto& c = tracker.calibration()) {
    row.torso_depth_cm = 200 * c->shape.torso_radius;
    row.torso_breadth_cm = 200 * (c->shape.torso_radius + c->shape.torso_half_spread);
  }
  row.ms_per_frame = ms.empty() ? 0 : Median(ms);
  row.cpu_ms_per_frame = cpu.empty() ? 0 : Median(cpu);
  return row;
}

}  // namespace

Expected<TrackerEvalRun> RunTrackerEval(const TrackerEvalOptions& o) {
  o.tracker.Check();
  for (const std::string& v : o.variants)
    if (!IsVariant(v))
      return MakeError("usage", "unknown variant '" + v + "' (" + VariantList() + ")");
  if (o.seeds.empty() || *std::min_element(o.seeds.begin(), o.seeds.end()) < 1)
    return MakeError("usage", "seeds: give at least one, each at least 1");
  if (o.slam_poses && o.withhold_sensor_pose)
    return MakeError("usage", "sensor pose: SLAM's and none at once; choose one");
  TrackerEvalRun run;
  for (const std::string& name : o.scenarios)
    for (const int seed : o.seeds) {
      capture::SyntheticBodySpec body;
      if (o.body_for_all || name.rfind("bvh:", 0) == 0) body.gltf_path = o.body_path;
      auto scene = capture::SyntheticScene::Create(name, static_cast<uint64_t>(seed), body);
      if (!scene.ok()) return scene.error();
      for (const std::string& variant : o.variants)
        for (const int iterations : o.iterations)
          for (const int subsample : o.subsample) {
            std::map<std::string, CaseSum> cases;
            JointErrorTable joints;
            ConfidenceErrorTable confidence;
            LimbVisibilityTable limbs;
            auto row = RunOne(*scene, variant, iterations, subsample, o, &cases, &joints,
                              &confidence, &limbs, o.frames ? &run.frames : nullptr);
            if (!row.ok()) return row.error();
            run.rows.push_back(*row);
            const auto stats = joints.Stats();
            for (int j = 0; j < kJointCount; ++j)
              run.joints.push_back(
                  {name, variant, iterations, subsample, seed, static_cast<Joint>(j), stats[j]});
            const auto bins = confidence.Stats();
            for (int b = 0; b < kConfidenceBinCount; ++b)
              run.confidence.push_back({name, variant, iterations, subsample, seed, b, bins[b]});
            const auto limb_stats = limbs.Stats();
            for (int l = 0; l < kEvalLimbCount; ++l)
              run.limbs.push_back({name, variant, iterations, subsample, seed, l, limb_stats[l]});
            for (const char* name_case : kCases) {
              const auto it = cases.find(name_case);
              if (it == cases.end()) continue;
              TrackerCaseRow c;
              c.scenario = name;
              c.variant = variant;
              c.hard_case = name_case;
              c.iterations = iterations;
              c.subsample = subsample;
              c.seed = seed;
              c.frames = it->second.frames;
              c.tracked = it->second.tracked;
              c.tracked_rate = c.frames ? static_cast<double>(c.tracked) / c.frames : 0;
              c.mpjpe_cm = c.tracked ? 100 * it->second.err / c.tracked : 0;
              run.cases.push_back(c);
            }
          }
    }
  return run;
}

std::vector<TrackerSeedSummary> SummariseSeeds(const std::vector<TrackerEvalRow>& rows) {
  std::vector<TrackerSeedSummary> out;
  for (const TrackerEvalRow& r : rows) {
    auto it = std::find_if(out.begin(), out.end(), [&r](const TrackerSeedSummary& s) {
      return s.scenario == r.scenario && s.variant == r.variant && s.iterations == r.iterations &&
             s.subsample == r.subsample;
    });
    if (it == out.end()) {
      it = out.insert(out.end(), {r.scenario, r.variant, r.iterations, r.subsample, 0, 0,
                                  r.mpjpe_cm, r.mpjpe_cm, 0, 0});
    }
    ++it->seeds;
    it->mpjpe_cm += r.mpjpe_cm;
    it->min_mpjpe_cm = std::min(it->min_mpjpe_cm, r.mpjpe_cm);
    it->max_mpjpe_cm = std::max(it->max_mpjpe_cm, r.mpjpe_cm);
    it->p90_cm += r.p90_cm;
    it->tracked_rate += r.tracked_rate;
  }
  for (TrackerSeedSummary& s : out)
    for (double* mean : {&s.mpjpe_cm, &s.p90_cm, &s.tracked_rate}) *mean /= s.seeds;
  return out;
}

namespace {

// A row of `table` ("" the main one) opening with its run's setting.
template <typename Row>
proto::ReportRow SettingRow(std::string table, const Row& r) {
  proto::ReportRow row;
  row.table = std::move(table);
  row.Add("scenario", r.scenario)
      .Add("variant", r.variant)
      .Add("iterations", static_cast<long long>(r.iterations))
      .Add("subsample", static_cast<long long>(r.subsample))
      .Add("seed", static_cast<long long>(r.seed));
  return row;
}

}  // namespace

proto::Report TrackerReport(const TrackerEvalRun& run) {
  proto::Report report;
  report.command = "tracker";
  for (const TrackerEvalRow& r : run.rows) {
    proto::ReportRow row = SettingRow("", r);
    row.Add("n", static_cast<long long>(r.frames))
        .Add("tracked_rate", r.tracked_rate)
        .Add("mpjpe_cm", r.mpjpe_cm)
        .Add("p90_cm", r.p90_cm)
        .Add("in_view_mpjpe_cm", r.in_view_mpjpe_cm)
        .Add("in_view_reported", r.in_view_reported)
        .Add("invented", r.invented)
        .Add("heading_deg", r.heading_deg)
        .Add("reversed_rate", r.reversed_rate)
        .Add("calib_frame", static_cast<long long>(r.calibration_frame))
        .Add("losses", static_cast<long long>(r.losses))
        .Add("recoveries", static_cast<long long>(r.recoveries));
    if (r.aligned_mpjpe_cm) row.Add("aligned_mpjpe_cm", *r.aligned_mpjpe_cm);
    if (r.floor_mpjpe_cm)
      row.Add("floor_posed_mpjpe_cm", *r.floor_posed_mpjpe_cm)
          .Add("floor_mpjpe_cm", *r.floor_mpjpe_cm)
          .Add("floor_cheaper_rate", *r.floor_cheaper_rate);
    row.Add("torso_depth_cm", r.torso_depth_cm).Add("torso_breadth_cm", r.torso_breadth_cm);
    row.Add("ms_per_frame", r.ms_per_frame).Add("cpu_ms_per_frame", r.cpu_ms_per_frame);
    report.rows.push_back(std::move(row));
  }
  for (const TrackerCaseRow& c : run.cases) {
    proto::ReportRow row = SettingRow("cases", c);
    row.Add("case", c.hard_case)
        .Add("n", static_cast<long long>(c.frames))
        .Add("tracked_rate", c.tracked_rate)
        .Add("mpjpe_cm", c.mpjpe_cm);
    report.rows.push_back(std::move(row));
  }
  for (const TrackerJointRow& j : run.joints) {
    proto::ReportRow row = SettingRow("joints", j);
    row.Add("joint", std::string(JointName(j.joint)))
        .Add("n", static_cast<long long>(j.stats.frames))
        .Add("mean_cm", j.stats.mean_cm)
        .Add("bias_x_cm", j.stats.bias_cm.x())
        .Add("bias_y_cm", j.stats.bias_cm.y())
        .Add("bias_z_cm", j.stats.bias_cm.z())
        .Add("bias_cm", j.stats.bias_norm_cm)
        .Add("spread_cm", j.stats.spread_cm);
    report.rows.push_back(std::move(row));
  }
  for (const TrackerConfidenceRow& c : run.confidence) {
    proto::ReportRow row = SettingRow("confidence", c);
    row.Add("confidence", std::string(ConfidenceErrorTable::BinName(c.bin)))
        .Add("n", static_cast<long long>(c.stats.n))
        .Add("share", c.stats.share)
        .Add("mean_cm", c.stats.mean_cm)
        .Add("gross_share", c.stats.gross_share);
    report.rows.push_back(std::move(row));
  }
  for (const TrackerLimbRow& l : run.limbs) {
    proto::ReportRow row = SettingRow("limbs", l);
    row.Add("limb", std::string(EvalLimbName(l.limb)))
        .Add("in_view_n", static_cast<long long>(l.stats.in_view))
        .Add("hidden_n", static_cast<long long>(l.stats.hidden))
        .Add("in_view_end_cm", l.stats.in_view_end_cm)
        .Add("hidden_end_cm", l.stats.hidden_end_cm)
        .Add("in_view_middle_cm", l.stats.in_view_middle_cm)
        .Add("hidden_middle_cm", l.stats.hidden_middle_cm);
    report.rows.push_back(std::move(row));
  }
  for (const TrackerFrameRow& f : run.frames) {
    proto::ReportRow row = SettingRow("frames", f);
    row.Add("frame", static_cast<long long>(f.frame))
        .Add("state", std::string(capture::TrackStateName(f.state)))
        .Add("calibrated", static_cast<long long>(f.calibrated))
        .Add("recovered", static_cast<long long>(f.recovered))
        .Add("points", static_cast<long long>(f.points))
        .Add("inlier_share", f.inlier_share)
        .Add("outlier_share", f.outlier_share)
        .Add("coverage", f.coverage);
    if (f.mpjpe_cm)
      row.Add("mpjpe_cm", *f.mpjpe_cm)
          .Add("worst_joint", std::string(JointName(f.worst_joint)))
          .Add("worst_cm", f.worst_cm)
          .Add("l_hand_cm", f.l_hand_cm)
          .Add("r_hand_cm", f.r_hand_cm)
          .Add("l_foot_cm", f.l_foot_cm)
          .Add("r_foot_cm", f.r_foot_cm);
    if (f.floor_mpjpe_cm)
      row.Add("floor_mpjpe_cm", *f.floor_mpjpe_cm)
          .Add("floor_cheaper", static_cast<long long>(f.floor_cheaper));
    report.rows.push_back(std::move(row));
  }
  const std::vector<TrackerSeedSummary> seeds = SummariseSeeds(run.rows);
  if (seeds.size() < run.rows.size())
    for (const TrackerSeedSummary& s : seeds) {
      proto::ReportRow row;
      row.table = "seeds";
      row.Add("scenario", s.scenario)
          .Add("variant", s.variant)
          .Add("iterations", static_cast<long long>(s.iterations))
          .Add("subsample", static_cast<long long>(s.subsample))
          .Add("seeds", static_cast<long long>(s.seeds))
          .Add("mpjpe_cm", s.mpjpe_cm)
          .Add("min_mpjpe_cm", s.min_mpjpe_cm)
          .Add("max_mpjpe_cm", s.max_mpjpe_cm)
          .Add("p90_cm", s.p90_cm)
          .Add("tracked_rate", s.tracked_rate);
      report.rows.push_back(std::move(row));
    }
  return report;
}

std::set<std::string> TrackerFlags() {
  return {"scenario",    "variants", "iterations", "subsample",  "body",
          "turn-starts", "without",  "noise",      "seeds",      "json",
          "floor",       "frames",   "timestamps", "sensor-pose"};
}

namespace {

Expected<std::vector<std::string>> ParseList(const std::string& flag, const std::string& text) {
  std::vector<std::string> items;
  std::stringstream ss(text);
  for (std::string item; std::getline(ss, item, ',');) items.push_back(item);
  if (text.empty() || text.back() == ',') items.emplace_back();
  for (const std::string& item : items)
    if (item.empty())
      return MakeError("usage", "--" + flag + ": empty item in '" + text +
                                    "' (give a value or a comma-separated list)");
  return items;
}

Expected<std::vector<int>> ParseCounts(const std::string& flag, const std::string& text) {
  auto items = ParseList(flag, text);
  if (!items.ok()) return items.error();
  std::vector<int> out;
  for (const std::string& item : *items) {
    size_t used = 0;
    int value = 0;
    try {
      value = std::stoi(item, &used);
    } catch (...) {
      used = 0;
    }
    if (used != item.size() || value < 1 || value > 1000)
      return MakeError("usage",
                       "--" + flag + " takes whole numbers from 1 to 1000, got '" + item + "'");
    out.push_back(value);
  }
  return out;
}

Expected<bool> ParseOnOff(const std::string& flag, const std::string& text) {
  if (text != "on" && text != "off")
    return MakeError("usage", "--" + flag + " must be on or off, got '" + text + "'");
  return text == "on";
}

// One whole number from 0 (off) to max.
Expected<int> ParseSetting(const std::string& flag, const std::string& text, int max) {
  size_t used = 0;
  int value = -1;
  try {
    value = std::stoi(text, &used);
  } catch (...) {
    used = 0;
  }
  if (used == 0 || used != text.size() || value < 0 || value > max)
    return MakeError("usage", "--" + flag + " takes one whole number from 0 (off) to " +
                                  std::to_string(max) + ", got '" + text + "'");
  return value;
}

}  // namespace

Expected<TrackerCommand> ParseTrackerCommand(const CommandLine& cl) {
  TrackerCommand command;
  TrackerEvalOptions& o = command.options;
  if (auto text = cl.Get("scenario")) {
    auto list = ParseList("scenario", *text);
    if (!list.ok()) return list.error();
    o.scenarios = *list;
  }
  if (auto text = cl.Get("variants")) {
    auto list = ParseList("variants", *text);
    if (!list.ok()) return list.error();
    for (const std::string& v : *list)
      if (!IsVariant(v))
        return MakeError("usage",
                         "--variants: unknown variant '" + v + "' (" + VariantList() + ")");
    o.variants = *list;
  }
  if (auto text = cl.Get("iterations")) {
    auto list = ParseCounts("iterations", *text);
    if (!list.ok()) return list.error();
    if (std::ranges::any_of(*list, [](int n) { return n > 100; }))
      return MakeError("usage", "--iterations: at most 100, got '" + *text + "'");
    o.iterations = *list;
  }
  if (auto text = cl.Get("subsample")) {
    auto list = ParseCounts("subsample", *text);
    if (!list.ok()) return list.error();
    o.subsample = *list;
  }
  if (auto body = cl.Get("body")) {
    if (body->empty())
      return MakeError("usage", "--body needs a .glb or .gltf path, or 'procedural'");
    o.body_path = *body == "procedural" ? "" : *body;
    o.body_for_all = true;
  }
  if (auto text = cl.Get("turn-starts")) {
    auto value = ParseSetting("turn-starts", *text, 89);
    if (!value.ok()) return value.error();
    o.tracker.turn_start_deg = *value;
  }
  if (auto text = cl.Get("without")) {
    auto list = ParseList("without", *text);
    if (!list.ok()) return list.error();
    const auto& known = TrackerAblations();
    for (const std::string& name : *list) {
      if (std::find(known.begin(), known.end(), name) == known.end())
        return MakeError("usage",
                         "--without: unknown part '" + name + "' (" + AblationList() + ")");
      o.without.insert(name);
    }
  }
  for (const auto& [flag, value] :
       {std::pair{"timestamps", &o.timestamps}, std::pair{"noise", &o.depth_noise},
        std::pair{"floor", &o.floor}, std::pair{"frames", &o.frames}})
    if (auto text = cl.Get(flag)) {
      auto on = ParseOnOff(flag, *text);
      if (!on.ok()) return on.error();
      *value = *on;
    }
  if (auto pose = cl.Get("sensor-pose")) {
    if (*pose != "truth" && *pose != "slam" && *pose != "none")
      return MakeError("usage", "--sensor-pose must be truth, slam or none, got '" + *pose + "'");
    o.slam_poses = *pose == "slam";
    o.withhold_sensor_pose = *pose == "none";
  }
  if (auto text = cl.Get("seeds")) {
    auto list = ParseCounts("seeds", *text);
    if (!list.ok()) return list.error();
    if (std::set<int>(list->begin(), list->end()).size() != list->size())
      return MakeError("usage", "--seeds: a seed given twice in '" + *text + "'");
    o.seeds = *list;
  }
  if (auto path = cl.Get("json")) {
    if (Status s = CheckWritableFile("json", *path); !s.ok()) return s.error();
    command.json_path = *path;
  }
  return command;
}

}  // namespace reenact::eval
