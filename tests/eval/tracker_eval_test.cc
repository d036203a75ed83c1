// `reenact-eval tracker`: its command line (bad input refused before the run) and a short run
// against the synthetic ground truth.
#include "tests/eval/tracker_eval.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "tests/eval/eval_cli_test_support.h"

namespace reenact::eval {
namespace {

namespace fs = std::filesystem;

// A file of ../shared/data, found from the repository root (this file is tests/eval/ in it).
std::string SharedData(const std::string& name) {
  return (fs::path(__FILE__).parent_path().parent_path().parent_path().parent_path() / "shared" /
          "data" / name)
      .string();
}

Expected<TrackerCommand> Parse(std::vector<std::string> args) {
  return cli_test::ParseEvalArgs("tracker", TrackerFlags(), ParseTrackerCommand, std::move(args));
}

void ExpectUsage(const std::vector<std::string>& args, const std::string& says) {
  cli_test::ExpectRefused(Parse(args), args, "usage", says);
}

TEST(TrackerCli, Defaults) {
  const auto r = Parse({});
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_EQ(r->options.scenarios, (std::vector<std::string>{"turn-and-kick", "walk-handheld"}));
  EXPECT_EQ(r->options.variants, std::vector<std::string>{"normal"});
  EXPECT_EQ(r->options.iterations, std::vector<int>{8});
  EXPECT_EQ(r->options.subsample, std::vector<int>{2});
  EXPECT_TRUE(r->options.depth_noise);
  EXPECT_FALSE(r->options.body_for_all);
  EXPECT_EQ(r->options.tracker.turn_start_deg, capture::SkeletonTrackerOptions{}.turn_start_deg);
  EXPECT_EQ(r->options.seeds, std::vector<int>{1});
  EXPECT_TRUE(r->options.without.empty());
  EXPECT_FALSE(r->json_path);
}

TEST(TrackerCli, Flags) {
  const auto r =
      Parse({"--scenario", "turn-and-kick", "--variants", "normal,fast,near", "--iterations", "4,8",
             "--subsample", "1,2,3", "--noise", "off", "--body", "x.glb"});
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_EQ(r->options.scenarios, std::vector<std::string>{"turn-and-kick"});
  EXPECT_EQ(r->options.variants, (std::vector<std::string>{"normal", "fast", "near"}));
  EXPECT_EQ(r->options.iterations, (std::vector<int>{4, 8}));
  EXPECT_EQ(r->options.subsample, (std::vector<int>{1, 2, 3}));
  EXPECT_FALSE(r->options.depth_noise);
  EXPECT_EQ(r->options.body_path, "x.glb");
  EXPECT_TRUE(r->options.body_for_all);
  const auto turns = Parse({"--turn-starts", "0"});
  ASSERT_TRUE(turns.ok()) << turns.error().message;
  EXPECT_EQ(turns->options.tracker.turn_start_deg, 0);
  EXPECT_EQ(Parse({"--turn-starts", "40"})->options.tracker.turn_start_deg, 40);
  EXPECT_EQ(Parse({"--without", "uncross-return,static-scene"})->options.without,
            (std::set<std::string>{"uncross-return", "static-scene"}));
  EXPECT_FALSE(Parse({"--timestamps", "off"})->options.timestamps);
  EXPECT_TRUE(Parse({"--timestamps", "on"})->options.timestamps);
  EXPECT_FALSE(Parse({})->options.floor);
  EXPECT_TRUE(Parse({"--floor", "on"})->options.floor);
  EXPECT_TRUE(Parse({"--frames", "on"})->options.frames);
  EXPECT_FALSE(Parse({"--frames", "off"})->options.frames);
  EXPECT_EQ(Parse({"--variants", "drops,normal"})->options.variants,
            (std::vector<std::string>{"drops", "normal"}));
  EXPECT_TRUE(Parse({"--sensor-pose", "slam"})->options.slam_poses);
  EXPECT_FALSE(Parse({"--sensor-pose", "slam"})->options.withhold_sensor_pose);
  EXPECT_FALSE(Parse({"--sensor-pose", "truth"})->options.slam_poses);
  EXPECT_FALSE(Parse({"--sensor-pose", "truth"})->options.withhold_sensor_pose);
  EXPECT_TRUE(Parse({"--sensor-pose", "none"})->options.withhold_sensor_pose);
  EXPECT_FALSE(Parse({"--sensor-pose", "none"})->options.slam_poses);
  EXPECT_EQ(Parse({"--seeds", "3,1,2"})->options.seeds, (std::vector<int>{3, 1, 2}));
}

TEST(TrackerCli, BodyProceduralPlaysEveryScenarioOnTheProceduralBody) {
  const auto r = Parse({"--body", "procedural"});
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_TRUE(r->options.body_path.empty());
  EXPECT_TRUE(r->options.body_for_all);
  // Without --body, bvh: keeps its default skinned body.
  const auto d = Parse({"--scenario", "bvh:x.bvh"});
  ASSERT_TRUE(d.ok()) << d.error().message;
  EXPECT_EQ(d->options.body_path, "../shared/data/models/CesiumMan.glb");
  EXPECT_FALSE(d->options.body_for_all);
}

TEST(TrackerCli, BadInputIsRefused) {
  ExpectUsage({"--scenario", ""}, "--scenario");
  ExpectUsage({"--scenario", "turn-and-kick,"}, "--scenario");
  ExpectUsage({"--variants", "slow"}, "unknown variant 'slow'");
  ExpectUsage({"--iterations", "0"}, "--iterations");
  ExpectUsage({"--iterations", "8,x"}, "--iterations");
  ExpectUsage({"--iterations", "8,101"}, "--iterations: at most 100");
  ExpectUsage({"--subsample", "2.5"}, "--subsample");
  ExpectUsage({"--noise", "maybe"}, "--noise must be on or off");
  ExpectUsage({"--floor", "yes"}, "--floor must be on or off");
  ExpectUsage({"--frames", "all"}, "--frames must be on or off");
  ExpectUsage({"--body", ""}, "--body");
  ExpectUsage({"--without", "hanging-arm"}, "--without: unknown part 'hanging-arm'");
  ExpectUsage({"--without", ""}, "--without");
  ExpectUsage({"--turn-starts", "90"}, "--turn-starts takes one whole number from 0 (off) to 89");
  ExpectUsage({"--turn-starts", "-5"}, "--turn-starts");
  ExpectUsage({"--turn-starts", "12.5"}, "--turn-starts");
  ExpectUsage({"--timestamps", "yes"}, "--timestamps must be on or off");
  ExpectUsage({"--sensor-pose", "gt"}, "--sensor-pose must be truth, slam or none");
  ExpectUsage({"--seeds", "0"}, "--seeds");
  ExpectUsage({"--seeds", "1,x"}, "--seeds");
  ExpectUsage({"--seeds", ""}, "--seeds");
  ExpectUsage({"--seeds", "2,2"}, "--seeds: a seed given twice");
  const auto json = Parse({"--json", "/nonexistent-folder/out.json"});
  ASSERT_FALSE(json.ok());
  EXPECT_EQ(json.error().code, "io");
}

TEST(TrackerEval, UnknownScenarioIsNotFound) {
  TrackerEvalOptions o;
  o.scenarios = {"moonwalk"};
  const auto run = RunTrackerEval(o);
  ASSERT_FALSE(run.ok());
  EXPECT_EQ(run.error().code, "not_found");
}

TEST(TrackerEval, NoSeedIsAUsageError) {
  TrackerEvalOptions o;
  o.seeds = {};
  EXPECT_EQ(RunTrackerEval(o).error().code, "usage");
  o.seeds = {0};
  EXPECT_EQ(RunTrackerEval(o).error().code, "usage");
}

TEST(TrackerEval, SlamPosesAndNoPoseExcludeEachOther) {
  TrackerEvalOptions o;
  o.slam_poses = o.withhold_sensor_pose = true;
  const auto run = RunTrackerEval(o);
  ASSERT_FALSE(run.ok());
  EXPECT_EQ(run.error().code, "usage");
}

TEST(TrackerEval, SeedSummaryAveragesEachSettingOverItsSeeds) {
  auto row = [](std::string variant, int seed, double mpjpe, double p90, double rate) {
    TrackerEvalRow r;
    r.scenario = "turn-and-kick";
    r.variant = std::move(variant);
    r.iterations = 8;
    r.subsample = 2;
    r.seed = seed;
    r.mpjpe_cm = mpjpe;
    r.p90_cm = p90;
    r.tracked_rate = rate;
    return r;
  };
  const std::vector<TrackerEvalRow> rows = {
      row("normal", 1, 2.0, 3.0, 1.0), row("near", 1, 4.0, 6.0, 0.5),
      row("normal", 2, 5.0, 7.0, 0.5), row("normal", 3, 2.0, 2.0, 1.0)};
  const std::vector<TrackerSeedSummary> s = SummariseSeeds(rows);
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s[0].variant, "normal");
  EXPECT_EQ(s[0].seeds, 3);
  EXPECT_DOUBLE_EQ(s[0].mpjpe_cm, 3.0);
  EXPECT_DOUBLE_EQ(s[0].min_mpjpe_cm, 2.0);
  EXPECT_DOUBLE_EQ(s[0].max_mpjpe_cm, 5.0);
  EXPECT_DOUBLE_EQ(s[0].p90_cm, 4.0);
  EXPECT_DOUBLE_EQ(s[0].tracked_rate, 2.5 / 3);
  EXPECT_EQ(s[1].variant, "near");
  EXPECT_EQ(s[1].seeds, 1);
  EXPECT_DOUBLE_EQ(s[1].mpjpe_cm, 4.0);
  EXPECT_TRUE(SummariseSeeds({}).empty());
}

TEST(TrackerEval, EachSeedIsARunOfItsOwnWithItsOwnDepthNoise) {
  TrackerEvalOptions o;
  o.scenarios = {"turn-and-kick"};
  o.seeds = {1, 2};
  o.max_frames = 5;
  const auto run = RunTrackerEval(o);
  ASSERT_TRUE(run.ok()) << run.error().message;
  ASSERT_EQ(run->rows.size(), 2u);
  EXPECT_EQ(run->rows[0].seed, 1);
  EXPECT_EQ(run->rows[1].seed, 2);
  // Other depth noise, other fits: the same frames give another error.
  EXPECT_NE(run->rows[0].mpjpe_cm, run->rows[1].mpjpe_cm);
  for (const TrackerJointRow& j : run->joints) EXPECT_TRUE(j.seed == 1 || j.seed == 2);
  const proto::Report report = TrackerReport(*run);
  int seed_rows = 0;
  for (const proto::ReportRow& r : report.rows) seed_rows += r.table == "seeds";
  EXPECT_EQ(seed_rows, 1);
  // One seed: no seeds table.
  o.seeds = {1};
  const auto one = RunTrackerEval(o);
  ASSERT_TRUE(one.ok()) << one.error().message;
  for (const proto::ReportRow& r : TrackerReport(*one).rows) EXPECT_NE(r.table, "seeds");
}

TEST(TrackerEval, ShortRunTracksEveryFrameAndWritesTheReport) {
  TrackerEvalOptions o;
  o.scenarios = {"turn-and-kick"};
  o.variants = {"normal", "near"};
  o.max_frames = 20;  // the calibration pose and the arms coming down
  const auto run = RunTrackerEval(o);
  ASSERT_TRUE(run.ok()) << run.error().message;
  ASSERT_EQ(run->rows.size(), 2u);
  for (const TrackerEvalRow& row : run->rows) {
    EXPECT_EQ(row.frames, 20);
    EXPECT_EQ(row.tracked, 20) << row.variant;
    EXPECT_EQ(row.calibration_frame, 0) << row.variant;
    // The goal is 5 cm; whole runs of turn-and-kick measure 2.5 cm (normal) and
    // 3.5 cm (near).
    EXPECT_LT(row.mpjpe_cm, 5.0) << row.variant;
    EXPECT_LE(row.mpjpe_cm, row.p90_cm + 1e-9);  // few large errors: mean below the 90th
    // Heading (median): shoulders each up to 5 cm off (twice the bound on the mean joint
    // error), in opposite directions across the 37 cm shoulder line, turn it by
    // atan(10 / 37) = 15 degrees; the subject faces the sensor, so never reversed.
    EXPECT_LT(row.heading_deg, 15.0) << row.variant;
    EXPECT_EQ(row.reversed_rate, 0.0) << row.variant;
    // Started from the calibration pose, so the row has the error after the calibration
    // frame's offsets are removed; on the procedural body the truth's joints sit where the
    // tracker's model puts them, so that removes little and the same bound holds.
    ASSERT_TRUE(row.aligned_mpjpe_cm) << row.variant;
    EXPECT_LT(*row.aligned_mpjpe_cm, 5.0) << row.variant;
    // The calibrated trunk (no side view in these frames): broader than deep, both within a
    // human trunk's (the procedural body's is 29-34 cm broad and 20-22 cm deep).
    EXPECT_GT(row.torso_breadth_cm, row.torso_depth_cm) << row.variant;
    EXPECT_GT(row.torso_depth_cm, 10) << row.variant;
    EXPECT_LT(row.torso_breadth_cm, 40) << row.variant;
    EXPECT_GT(row.ms_per_frame, 0);
  }
  // Normal: the whole subject in view, every joint reported (the tracker reports all 16 of a
  // tracked frame), so the in-view error is the 16-joint error and nothing is invented.
  const TrackerEvalRow& normal = run->rows[0];
  ASSERT_EQ(normal.variant, "normal");
  EXPECT_DOUBLE_EQ(normal.in_view_reported, 1.0);
  EXPECT_DOUBLE_EQ(normal.invented, 0.0);
  EXPECT_NEAR(normal.in_view_mpjpe_cm, normal.mpjpe_cm, 1e-9);
  // The near variant cuts the subject off at the image's lower edge.
  bool partly_outside = false;
  for (const TrackerCaseRow& c : run->cases)
    if (c.variant == "near" && c.hard_case == "partly_outside") partly_outside = c.frames == 20;
  EXPECT_TRUE(partly_outside);

  const fs::path path =
      fs::temp_directory_path() / ("reenact-tracker-eval-" + std::to_string(::getpid()) + ".json");
  ASSERT_TRUE(TrackerReport(*run).WriteJson(path.string()).ok());
  std::stringstream text;
  text << std::ifstream(path).rdbuf();
  fs::remove(path);
  for (const char* field :
       {"\"command\": \"tracker\"", "\"scenario\": \"turn-and-kick\"", "\"mpjpe_cm\":",
        "\"aligned_mpjpe_cm\":", "\"tracked_rate\":", "\"heading_deg\":", "\"in_view_mpjpe_cm\":",
        "\"in_view_reported\":", "\"invented\":", "\"reversed_rate\":", "\"torso_depth_cm\":",
        "\"torso_breadth_cm\":", "\"ms_per_frame\":", "\"case\": \"partly_outside\""})
    EXPECT_NE(text.str().find(field), std::string::npos) << field << " in " << text.str();
  // The joints table: every joint of every row, over the tracked frames where the tracker
  // reported it: all of them in the normal variant; in the near one the feet leave the image
  // on some frames and are then reported missing (MarkJointsOutOfView).
  ASSERT_EQ(run->joints.size(), 2u * kJointCount);
  for (const TrackerJointRow& j : run->joints) {
    if (j.variant == "normal") {
      EXPECT_EQ(j.stats.frames, 20);
    }
    EXPECT_LE(j.stats.frames, 20);
    EXPECT_GT(j.stats.frames, 0);
    // mean |e|^2 = bias^2 + spread^2 >= (mean |e|)^2 (Jensen).
    EXPECT_GE(std::hypot(j.stats.bias_norm_cm, j.stats.spread_cm), j.stats.mean_cm - 1e-9);
    EXPECT_LE(j.stats.bias_norm_cm, j.stats.mean_cm + 1e-9);
  }
  EXPECT_NE(text.str().find("\"joint\": \"l_hand\""), std::string::npos);
  // The confidence table: every reported joint estimate of a row in one of its bins. The
  // tracker reports every joint of a tracked frame in the image (min_confidence > 0), so in
  // the normal variant the bins hold 16 per frame, and their mean errors, weighted by n, give
  // the row's MPJPE (both the mean over all joint estimates); in the near one the feet and
  // shins out of the image on some frames are missing (at most 4 of 16 a frame).
  ASSERT_EQ(run->confidence.size(), 2u * kConfidenceBinCount);
  for (size_t r = 0; r < run->rows.size(); ++r) {
    int n = 0;
    double share = 0, error_cm = 0;
    for (int b = 0; b < kConfidenceBinCount; ++b) {
      const TrackerConfidenceRow& c = run->confidence[r * kConfidenceBinCount + b];
      EXPECT_EQ(c.variant, run->rows[r].variant);
      EXPECT_EQ(c.bin, b);
      n += c.stats.n;
      share += c.stats.share;
      error_cm += c.stats.n * c.stats.mean_cm;
    }
    EXPECT_NEAR(share, 1.0, 1e-9);
    if (run->rows[r].variant == "normal") {
      EXPECT_EQ(n, run->rows[r].tracked * kJointCount);
      EXPECT_NEAR(error_cm / n, run->rows[r].mpjpe_cm, 1e-9);
    } else {
      EXPECT_LE(n, run->rows[r].tracked * kJointCount);
      EXPECT_GE(n, run->rows[r].tracked * (kJointCount - 4));
    }
  }
  EXPECT_NE(text.str().find("\"confidence\": \"0.75-1\""), std::string::npos);
  // The limbs table: every tracked frame of a row in view or hidden for each limb. In these
  // frames the subject faces the sensor with the arms out and then coming down, and stands in
  // the image (normal): nothing hides a limb.
  ASSERT_EQ(run->limbs.size(), 2u * kEvalLimbCount);
  for (size_t r = 0; r < run->rows.size(); ++r)
    for (int l = 0; l < kEvalLimbCount; ++l) {
      const TrackerLimbRow& limb = run->limbs[r * kEvalLimbCount + l];
      EXPECT_EQ(limb.limb, l);
      EXPECT_EQ(limb.stats.in_view + limb.stats.hidden, run->rows[r].tracked);
      if (limb.variant == "normal") {
        EXPECT_EQ(limb.stats.hidden, 0) << EvalLimbName(l);
      }
    }
  EXPECT_NE(text.str().find("\"limb\": \"l_arm\""), std::string::npos);
}

TEST(TrackerEval, TheFarArmIsHiddenWhereTheTurnPassesSideOn) {
  // turn-and-kick's shoulders turn to h(t) = 360 (3 s^2 - 2 s^3) + 12 sin(2 pi s) degrees,
  // s = (t - 1.2 s) / 2.8 s (TurningFramesAreTheTurnsConstruction), towards the subject's left
  // (root_yaw grows), so its left side turns away from the sensor: h is within 30 degrees of
  // side-on on the 12 frames 56-67 (h(55) = 59, h(67) = 120), where the trunk hides the left
  // arm. The right arm, the near one, stays in view.
  TrackerEvalOptions o;
  o.scenarios = {"turn-and-kick"};
  o.max_frames = 75;
  const auto run = RunTrackerEval(o);
  ASSERT_TRUE(run.ok()) << run.error().message;
  ASSERT_EQ(run->limbs.size(), static_cast<size_t>(kEvalLimbCount));
  const LimbVisibilityStats& left = run->limbs[0].stats;
  const LimbVisibilityStats& right = run->limbs[1].stats;
  EXPECT_EQ(left.in_view + left.hidden, run->rows[0].tracked);
  EXPECT_GE(left.hidden, 3);
  EXPECT_LE(left.hidden, 12);
  EXPECT_EQ(right.hidden, 0);
}

TEST(TrackerEval, TheDropsVariantSeesFramesUnevenlyAndTracksThem) {
  // After each frame seen, 0-3 frames are dropped (probabilities 0.6, 0.25, 0.1, 0.05): 1.6
  // frame intervals between the frames seen on average, so about 180 / 1.6 = 112 of
  // turn-and-kick's 180 frames are seen; the drops' spread over about 112 draws (standard
  // deviation sqrt(112 x 0.74) = 9 frames) keeps the count within 95-130.
  TrackerEvalOptions o;
  o.scenarios = {"turn-and-kick"};
  o.variants = {"drops"};
  const auto run = RunTrackerEval(o);
  ASSERT_TRUE(run.ok()) << run.error().message;
  ASSERT_EQ(run->rows.size(), 1u);
  const TrackerEvalRow& row = run->rows[0];
  EXPECT_GE(row.frames, 95);
  EXPECT_LE(row.frames, 130);
  EXPECT_EQ(row.tracked, row.frames);
  // The 5 cm; seeds 1-6 measure 1.95-2.19 cm.
  EXPECT_LT(row.mpjpe_cm, 5.0);
}

// The CMU walk at `bvh` on the procedural body (its ground-truth joints where the tracker's
// model puts them).
TrackerEvalOptions ProceduralWalk(const std::string& bvh) {
  TrackerEvalOptions o;
  o.scenarios = {"bvh:" + bvh};
  o.body_path.clear();
  o.body_for_all = true;
  return o;
}

TEST(TrackerEval, TimestampsCarryThePredictionAcrossDroppedFrames) {
  // The procedural body walking CMU 131_01 with frames dropped (seed 1): given the frames'
  // times the tracker carries the last root displacement on for as many intervals as have
  // passed; taking every frame as one interval after the last, its start lags the subject by
  // the dropped frames' motion. Measured 4.21 cm with timestamps, 7.52 without; bounds: the
  // issue's 5 cm, and 6.
  const std::string bvh = SharedData("mocap/cmu-131_01-walk.bvh");
  if (!fs::exists(bvh)) GTEST_SKIP() << bvh << " not present";
  TrackerEvalOptions o = ProceduralWalk(bvh);
  o.variants = {"drops"};
  const auto timed = RunTrackerEval(o);
  o.timestamps = false;
  const auto untimed = RunTrackerEval(o);
  ASSERT_TRUE(timed.ok() && untimed.ok());
  ASSERT_EQ(timed->rows.size(), 1u);
  EXPECT_LT(timed->rows[0].mpjpe_cm, 5.0);
  EXPECT_GT(untimed->rows[0].mpjpe_cm, 6.0);
}

TEST(TrackerEval, TurningFramesAreTheTurnsConstruction) {
  // turn-and-kick (scenario.cc) turns the root by 2 pi SmoothStep(s), s = (t - 1.2 s) / 2.8 s,
  // and twists the chest on it by 12 sin(2 pi s) degrees: the shoulders' heading is
  // h(t) = 360 (3 s^2 - 2 s^3) + 12 sin(2 pi s) degrees. Its change from frame f - 1 to f,
  // times 30 fps, exceeds 60 degrees per second from frame 41 on (40: 56.8, 41: 64.5), so 19
  // of frames 0-59 (41-59) are turning; over all 180 frames, 76 (41-116).
  TrackerEvalOptions o;
  o.scenarios = {"turn-and-kick"};
  o.max_frames = 60;
  const auto run = RunTrackerEval(o);
  ASSERT_TRUE(run.ok()) << run.error().message;
  int turning = -1;
  for (const TrackerCaseRow& c : run->cases)
    if (c.hard_case == "turning") turning = c.frames;
  EXPECT_EQ(turning, 19);
}

// The first `frames` frames of turn-and-kick (the calibration pose first) on the skinned body
// at `glb`.
TrackerEvalOptions SkinnedTurnAndKick(const std::string& glb, int frames) {
  TrackerEvalOptions o;
  o.scenarios = {"turn-and-kick"};
  o.body_path = glb;
  o.body_for_all = true;
  o.max_frames = frames;
  return o;
}

TEST(TrackerEval, CalibrationAlignmentRemovesTheRigsJointPlacement) {
  // CesiumMan's rig puts its hips at the crotch and its shoulders where a collarbone starts
  // (10-19 cm from where a surface model puts them), so while the subject holds the calibration
  // pose (turn-and-kick's first frames) the track is off the truth's joints by more than the
  // issue's 5 cm, by offsets that stay as they are. With the calibration frame's offsets removed,
  // what is left is the frame-to-frame wobble of the track of a subject nearly standing still:
  // within 2 cm, about the tracker's whole error on the procedural body's calibration frame
  // (1.6-1.7 cm), where the truth's joints follow the tracker's model.
  const std::string glb = SharedData("models/CesiumMan.glb");
  if (!fs::exists(glb)) GTEST_SKIP() << glb << " not present";
  const auto run = RunTrackerEval(SkinnedTurnAndKick(glb, 10));
  ASSERT_TRUE(run.ok()) << run.error().message;
  ASSERT_EQ(run->rows.size(), 1u);
  const TrackerEvalRow& row = run->rows[0];
  EXPECT_EQ(row.calibration_frame, 0);
  ASSERT_TRUE(row.aligned_mpjpe_cm);
  EXPECT_GT(row.mpjpe_cm, 5.0);
  EXPECT_LT(*row.aligned_mpjpe_cm, 2.0);
}

TEST(TrackerEval, TheFloorPosesTheTrackersBodyFromTheTruth) {
  // --floor: CesiumMan's rig puts its hips at the crotch and its shoulders where a collarbone
  // starts, where the tracker's model, a surface model, does not put
  // them. Posed from the truth's root and bone directions, the calibrated body is farther off
  // than on the procedural body, whose joints follow the model (under 3 cm there:
  // SkeletonTracker.FitsTheLastFrameFromTheTruthWithoutTouchingTheTrack); fitted to the data
  // from there, its trunk goes where the surface puts it, more than the 5 cm from the
  // rig's joints (measured 4.5 and 6.1 cm on these frames). Written only when asked for.
  const std::string glb = SharedData("models/CesiumMan.glb");
  if (!fs::exists(glb)) GTEST_SKIP() << glb << " not present";
  TrackerEvalOptions o = SkinnedTurnAndKick(glb, 6);
  const auto plain = RunTrackerEval(o);
  ASSERT_TRUE(plain.ok()) << plain.error().message;
  ASSERT_EQ(plain->rows.size(), 1u);
  EXPECT_FALSE(plain->rows[0].floor_mpjpe_cm);
  o.floor = true;
  const auto run = RunTrackerEval(o);
  ASSERT_TRUE(run.ok()) << run.error().message;
  const TrackerEvalRow& row = run->rows[0];
  EXPECT_EQ(row.mpjpe_cm, plain->rows[0].mpjpe_cm);  // the oracle leaves the track as it is
  ASSERT_TRUE(row.floor_posed_mpjpe_cm && row.floor_mpjpe_cm && row.floor_cheaper_rate);
  EXPECT_GE(*row.floor_cheaper_rate, 0.0);
  EXPECT_LE(*row.floor_cheaper_rate, 1.0);
  EXPECT_GT(*row.floor_posed_mpjpe_cm, 3.0);
  EXPECT_GT(*row.floor_mpjpe_cm, 5.0);
}

TEST(TrackerEval, TheFramesTableListsEveryFrameTheRowIsMadeOf) {
  // --frames: one row per frame given to the tracker, the fast variant every 2nd frame of the
  // scene. The row's mean is the mean of its frames' errors, and each frame's hand and foot
  // errors average, over the frames, to the "limbs" table's in-view and hidden means together
  // (limb_visibility_table.h measures them on its own). Off, as by default, no frame is kept,
  // and the table changes nothing of the run.
  TrackerEvalOptions o;
  o.scenarios = {"turn-and-kick"};
  o.variants = {"fast"};
  o.max_frames = 12;
  o.floor = true;
  const auto plain = RunTrackerEval(o);
  ASSERT_TRUE(plain.ok()) << plain.error().message;
  EXPECT_TRUE(plain->frames.empty());
  o.frames = true;
  const auto run = RunTrackerEval(o);
  ASSERT_TRUE(run.ok()) << run.error().message;
  ASSERT_EQ(run->rows.size(), 1u);
  const TrackerEvalRow& row = run->rows[0];
  EXPECT_EQ(row.mpjpe_cm, plain->rows[0].mpjpe_cm);
  ASSERT_EQ(run->frames.size(), 12u);
  double sum = 0, floor_sum = 0;
  int floors = 0, cheaper = 0;
  std::array<double, kEvalLimbCount> end_sum{};
  for (size_t i = 0; i < run->frames.size(); ++i) {
    const TrackerFrameRow& f = run->frames[i];
    EXPECT_EQ(f.frame, static_cast<int>(2 * i));
    EXPECT_EQ(f.variant, "fast");
    EXPECT_EQ(f.calibrated, i == 0);  // the calibration pose: the track starts on frame 0
    EXPECT_EQ(f.state, capture::TrackState::kTracking);
    EXPECT_GT(f.points, 0);
    ASSERT_TRUE(f.mpjpe_cm) << f.frame;
    sum += *f.mpjpe_cm;
    for (const double e : {*f.mpjpe_cm, f.l_hand_cm, f.r_hand_cm, f.l_foot_cm, f.r_foot_cm})
      EXPECT_LE(e, f.worst_cm + 1e-9) << f.frame;
    end_sum[0] += f.l_hand_cm, end_sum[1] += f.r_hand_cm;
    end_sum[2] += f.l_foot_cm, end_sum[3] += f.r_foot_cm;
    EXPECT_EQ(f.floor_mpjpe_cm.has_value(), i > 0);  // no floor on the track's start
    if (f.floor_mpjpe_cm) floor_sum += *f.floor_mpjpe_cm, cheaper += f.floor_cheaper, ++floors;
  }
  EXPECT_NEAR(sum / 12, row.mpjpe_cm, 1e-9);
  ASSERT_TRUE(row.floor_mpjpe_cm);
  EXPECT_NEAR(floor_sum / floors, *row.floor_mpjpe_cm, 1e-9);
  ASSERT_TRUE(row.floor_cheaper_rate);
  EXPECT_NEAR(static_cast<double>(cheaper) / floors, *row.floor_cheaper_rate, 1e-12);
  ASSERT_EQ(run->limbs.size(), static_cast<size_t>(kEvalLimbCount));
  for (int l = 0; l < kEvalLimbCount; ++l) {
    const LimbVisibilityStats& s = run->limbs[l].stats;
    ASSERT_EQ(s.in_view + s.hidden, 12) << EvalLimbName(l);
    const double both = (s.in_view * s.in_view_end_cm + s.hidden * s.hidden_end_cm) / 12;
    EXPECT_NEAR(end_sum[l] / 12, both, 1e-6) << EvalLimbName(l);
  }
  const proto::Report report = TrackerReport(*run);
  const auto frames_rows =
      std::count_if(report.rows.begin(), report.rows.end(),
                    [](const proto::ReportRow& r) { return r.table == "frames"; });
  EXPECT_EQ(frames_rows, 12);
  EXPECT_NE(report.FormatTable().find("worst_joint"), std::string::npos);
}

TEST(TrackerEval, TheFramesTableKeepsTheFramesWithoutASkeleton) {
  // A walk starts without the calibration pose: the tracker waits
  // (SkeletonTrackerOptions::start_without_calibration_after frames) before it starts from the
  // proportions. Those frames are in the table, waiting and without errors; the row's mean is
  // over the frames that gave a skeleton.
  const std::string bvh = SharedData("mocap/cmu-131_01-walk.bvh");
  if (!fs::exists(bvh)) GTEST_SKIP() << bvh << " not present";
  TrackerEvalOptions o = ProceduralWalk(bvh);
  const int wait = o.tracker.start_without_calibration_after;
  ASSERT_GT(wait, 0);
  o.max_frames = wait + 3;
  o.frames = true;
  const auto run = RunTrackerEval(o);
  ASSERT_TRUE(run.ok()) << run.error().message;
  ASSERT_EQ(run->frames.size(), static_cast<size_t>(o.max_frames));
  const TrackerEvalRow& row = run->rows[0];
  ASSERT_GT(row.tracked, 0);
  double sum = 0;
  for (const TrackerFrameRow& f : run->frames) {
    if (f.frame < row.calibration_frame) {
      EXPECT_EQ(f.state, capture::TrackState::kWaitingForCalibration) << f.frame;
      EXPECT_FALSE(f.mpjpe_cm) << f.frame;
    } else {
      EXPECT_EQ(f.calibrated, f.frame == row.calibration_frame) << f.frame;
      ASSERT_TRUE(f.mpjpe_cm) << f.frame;
      sum += *f.mpjpe_cm;
    }
  }
  EXPECT_NEAR(sum / row.tracked, row.mpjpe_cm, 1e-9);
  const std::string table = TrackerReport(*run).FormatTable();
  EXPECT_NE(table.find("waiting_for_calibration"), std::string::npos);
}

TEST(TrackerEval, SlamPosesAreSlamsPredictions) {
  // --sensor-pose slam: the tracker is given RGB-D SLAM's prediction for each frame, as the
  // recorder gives it for a sensor without poses. From a static sensor SLAM's poses hold to
  // millimetres, and on the first frame, which has no pose yet, the detector looks for the
  // floor below the sensor's own up (the sensor is tilted 7 degrees down) and finds the one
  // the truth's up finds: the rows agree (bound 0.5 cm, a third of each row's error).
  TrackerEvalOptions o;
  o.scenarios = {"turn-and-kick"};
  o.max_frames = 20;
  const auto truth = RunTrackerEval(o);
  o.slam_poses = true;
  const auto slam = RunTrackerEval(o);
  ASSERT_TRUE(truth.ok() && slam.ok());
  ASSERT_EQ(slam->rows.size(), 1u);
  EXPECT_EQ(slam->rows[0].tracked, 20);
  EXPECT_NEAR(slam->rows[0].mpjpe_cm, truth->rows[0].mpjpe_cm, 0.5);
}

// The right hand's mean error (cm) over the first `frames` frames of walk-handheld seen from
// near (seed 5), the tracker given SLAM's predicted poses, with the turned starts' limb jump
// check on or off.
double NearWalkRightHandCm(bool jump_check, int frames) {
  TrackerEvalOptions o;
  o.scenarios = {"walk-handheld"};
  o.variants = {"near"};
  o.seeds = {5};
  o.slam_poses = true;
  o.max_frames = frames;
  if (!jump_check) o.without = {"limb-jump"};
  const auto run = RunTrackerEval(o);
  EXPECT_TRUE(run.ok());
  if (!run.ok()) return 0;
  for (const TrackerJointRow& j : run->joints)
    if (j.joint == Joint::kRightHand) return j.stats.mean_cm;
  ADD_FAILURE() << "no right hand row";
  return 0;
}

TEST(TrackerEval, ATurnedStartDoesNotSwingAnArmInViewBehindTheHead) {
  // On frame 108 the right hand touches a box that
  // the detector merged into the person's region, the own fit explains the frame poorly, and
  // the start turned by 25 degrees swings the arm up behind the head, where it costs nothing in
  // the free-space term: the hand 80 cm off from there on. Without the limb jump check the
  // right hand's mean over the first 120 frames is 9.2 cm (measured; bound 5, which a hand
  // tracked as on the first 100 frames, 1.6, does not reach); with it the arm stays at its
  // data, 1.9 (bound 3).
  EXPECT_GT(NearWalkRightHandCm(false, 120), 5.0);
  EXPECT_LT(NearWalkRightHandCm(true, 120), 3.0);
}

TEST(TrackerEval, TheCloseUpRunsWithAndWithoutTheSensorPose) {
  // upper-body-turn: the knees and feet never in view, so every frame is partly outside;
  // the in-view figures are shares (or 0 where nothing was tracked). Given no sensor pose
  // (--sensor-pose none) the run goes through the same frames.
  TrackerEvalOptions o;
  o.scenarios = {"upper-body-turn"};
  o.max_frames = 8;
  for (const bool withhold : {false, true}) {
    o.withhold_sensor_pose = withhold;
    const auto run = RunTrackerEval(o);
    ASSERT_TRUE(run.ok()) << run.error().message;
    ASSERT_EQ(run->rows.size(), 1u);
    const TrackerEvalRow& row = run->rows[0];
    EXPECT_EQ(row.frames, 8) << withhold;
    int partly_outside = -1;
    for (const TrackerCaseRow& c : run->cases)
      if (c.hard_case == "partly_outside") partly_outside = c.frames;
    EXPECT_EQ(partly_outside, 8) << withhold;
    for (const double share : {row.in_view_reported, row.invented}) {
      EXPECT_GE(share, 0.0) << withhold;
      EXPECT_LE(share, 1.0) << withhold;
    }
    EXPECT_GE(row.in_view_mpjpe_cm, 0.0) << withhold;
    if (row.tracked == 0) {
      EXPECT_EQ(row.in_view_reported, 0.0) << withhold;
    }
  }
}

TEST(TrackerEval, BvhPlaysOnTheProceduralBody) {
  const std::string bvh = SharedData("mocap/cmu-131_01-walk.bvh");
  if (!fs::exists(bvh)) GTEST_SKIP() << bvh << " not present";
  TrackerEvalOptions o = ProceduralWalk(bvh);
  o.max_frames = 3;
  const auto run = RunTrackerEval(o);
  ASSERT_TRUE(run.ok()) << run.error().message;
  ASSERT_EQ(run->rows.size(), 1u);
  EXPECT_EQ(run->rows[0].frames, 3);
}

}  // namespace
}  // namespace reenact::eval
