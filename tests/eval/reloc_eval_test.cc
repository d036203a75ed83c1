// `reenact-eval reloc`: its command line (bad input refused before the run) and a short run
// against the synthetic ground truth.
#include "tests/eval/reloc_eval.h"

#include <gtest/gtest.h>

#include "tests/eval/eval_cli_test_support.h"

namespace reenact::eval {
namespace {

Expected<RelocCommand> Parse(std::vector<std::string> args) {
  return cli_test::ParseEvalArgs("reloc", RelocFlags(), ParseRelocCommand, std::move(args));
}

void ExpectUsage(const std::vector<std::string>& args, const std::string& says) {
  cli_test::ExpectRefused(Parse(args), args, "usage", says);
}

TEST(RelocCli, DefaultsAndFlags) {
  const auto d = Parse({});
  ASSERT_TRUE(d.ok()) << d.error().message;
  EXPECT_EQ(d->options.scenario, "turn-and-kick");
  EXPECT_EQ(d->options.viewer_frames, 0);
  EXPECT_DOUBLE_EQ(d->options.max_deg, 45);
  EXPECT_EQ(d->options.record_frames, -1);
  EXPECT_EQ(d->options.relocaliser.features.num_features,
            viewer::RelocaliserOptions{}.features.num_features);
  const auto r = Parse({"--scenario", "walk-handheld", "--frames", "20", "--max-deg", "30",
                        "--record-frames", "40", "--body", "procedural", "--features", "1500"});
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_EQ(r->options.scenario, "walk-handheld");
  EXPECT_EQ(r->options.viewer_frames, 20);
  EXPECT_DOUBLE_EQ(r->options.max_deg, 30);
  EXPECT_EQ(r->options.record_frames, 40);
  EXPECT_TRUE(r->options.body.empty());
  EXPECT_EQ(r->options.relocaliser.features.num_features, 1500);
  EXPECT_TRUE(d->options.run_track && d->options.run_reloc);
  const auto t = Parse({"--methods", "track"});
  ASSERT_TRUE(t.ok()) << t.error().message;
  EXPECT_TRUE(t->options.run_track);
  EXPECT_FALSE(t->options.run_reloc);
  const auto f = Parse({"--methods", "reloc"});
  ASSERT_TRUE(f.ok()) << f.error().message;
  EXPECT_FALSE(f->options.run_track);
  EXPECT_TRUE(f->options.run_reloc);
}

TEST(RelocCli, BadInputIsRefused) {
  ExpectUsage({"--frames", "1"}, "--frames");
  ExpectUsage({"--frames", "many"}, "frames");
  ExpectUsage({"--max-deg", "0"}, "--max-deg");
  ExpectUsage({"--max-deg", "120"}, "--max-deg");
  ExpectUsage({"--record-frames", "0"}, "--record-frames");
  ExpectUsage({"--features", "50"}, "--features");
  ExpectUsage({"--features", "lots"}, "features");
  ExpectUsage({"--scenario", ""}, "--scenario");
  ExpectUsage({"--methods", "all"}, "--methods");
  const auto json = Parse({"--json", "/nonexistent-folder/out.json"});
  ASSERT_FALSE(json.ok());
  EXPECT_EQ(json.error().code, "io");
}

TEST(RelocEval, UnknownScenarioIsNotFound) {
  RelocEvalOptions o;
  o.scenario = "moonwalk";
  const auto run = RunRelocEval(o);
  ASSERT_FALSE(run.ok());
  EXPECT_EQ(run.error().code, "not_found");
}

// A short run: the map from the first 30 recorded frames (keyframes 0, 10, 20), 24 viewer
// frames up to 15 degrees around. Bounds from construction: within 15 degrees the background
// the map holds stays in view and the relocaliser's unit tests find poses from scratch up to
// 30 degrees, so every frame must get a pose; the error bounds are those of the unit tests
// (tests/unit/viewer-client/relocaliser_test.cc: keypoints on whole pixels of their level,
// a nearly planar background 5-5.5 m away), 4 cm and 0.5 degrees, here on the medians.
TEST(RelocEval, ShortRunPosesEveryFrameNearTheCaptureViewpoint) {
  RelocEvalOptions o;
  o.record_frames = 30;
  o.viewer_frames = 24;
  o.max_deg = 15;
  const auto run = RunRelocEval(o);
  ASSERT_TRUE(run.ok()) << run.error().message;
  EXPECT_GT(run->map_points, 200u);
  ASSERT_EQ(run->rows.size(), 4u);  // (0-15, all) x (track, reloc)
  for (const RelocEvalRow& row : run->rows) {
    SCOPED_TRACE(row.method + " " + row.band);
    EXPECT_EQ(row.frames, 24);
    EXPECT_DOUBLE_EQ(row.tracked_rate, 1.0);
    EXPECT_LT(row.median_err_cm, 4.0);
    EXPECT_LT(row.median_err_deg, 0.5);
    EXPECT_GE(row.within_2cm_1deg, 0.0);
    EXPECT_LE(row.within_2cm_1deg, 1.0);
    EXPECT_GT(row.ms_per_frame, 0.0);
    // CPU time per stage: each a part of the frame's total (frame by frame, so the medians
    // keep the order), and every frame extracts and matches.
    EXPECT_GT(row.orb_ms, 0.0);
    EXPECT_GT(row.comparisons, 0.0);
    for (double part :
         {row.orb_ms, row.subpixel_ms, row.match_ms, row.refine_ms, row.reloc_ms, row.smooth_ms})
      EXPECT_GE(row.cpu_ms, part);
    if (row.method == "reloc") {
      EXPECT_GT(row.reloc_ms, 0.0);
    }
  }
  EXPECT_EQ(run->rows[0].method, "track");
  EXPECT_EQ(run->rows[0].band, "0-15");
  EXPECT_EQ(run->rows[1].band, "all");
  EXPECT_EQ(run->rows[2].method, "reloc");

  const proto::Report report = RelocReport(*run);
  EXPECT_EQ(report.command, "reloc");
  EXPECT_NE(report.ToJson().find("\"within_2cm_1deg\""), std::string::npos);
}

}  // namespace
}  // namespace reenact::eval
