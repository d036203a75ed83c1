// The upload progress formatter and the schedule of its plain lines.
#include <gtest/gtest.h>

#include "capture-client/publish/upload_progress.h"

namespace reenact::capture {
namespace {

TEST(UploadProgress, FormatsBytesInSiUnits) {
  EXPECT_EQ(FormatBytes(0), "0 B");
  EXPECT_EQ(FormatBytes(999), "999 B");
  EXPECT_EQ(FormatBytes(1000), "1.00 kB");
  EXPECT_EQ(FormatBytes(48213), "48.2 kB");
  EXPECT_EQ(FormatBytes(999499), "999 kB");
  EXPECT_EQ(FormatBytes(999500), "1.00 MB");  // rounds up into the next unit
  EXPECT_EQ(FormatBytes(4'600'000), "4.60 MB");
  EXPECT_EQ(FormatBytes(1'200'000'000), "1.20 GB");
}

TEST(UploadProgress, FormatsDurationsRoundedUp) {
  EXPECT_EQ(FormatDuration(0), "0 s");
  EXPECT_EQ(FormatDuration(-2), "0 s");
  EXPECT_EQ(FormatDuration(0.2), "1 s");
  EXPECT_EQ(FormatDuration(42), "42 s");
  EXPECT_EQ(FormatDuration(185), "3 min 05 s");
  EXPECT_EQ(FormatDuration(2 * 3600 + 7 * 60), "2 h 07 min");
}

TEST(UploadProgress, RateAndEtaFromBytesSentThisRun) {
  // 4 MB clip; 1 MB was on the server already, 1 MB sent in 2 s: 0.5 MB/s, 2 MB left -> 4 s.
  UploadSnapshot s{4'000'000, 2'000'000, 1'000'000, 40, 20, 2.0};
  EXPECT_EQ(s.Percent(), 50);
  EXPECT_DOUBLE_EQ(s.RateBytesPerS(), 500'000.0);
  ASSERT_TRUE(s.EtaS());
  EXPECT_DOUBLE_EQ(*s.EtaS(), 4.0);
  EXPECT_EQ(FormatProgressLine(s), "progress  50% (20/40 parts, 2.00/4.00 MB) 500 kB/s ETA 4 s");
  EXPECT_EQ(FormatProgressBar(s, 10), "[#####-----]  50%  2.00/4.00 MB  500 kB/s  ETA 4 s");
}

TEST(UploadProgress, UnknownRateBeforeTheFirstByteAndEdgeCases) {
  UploadSnapshot start{3000, 0, 0, 3, 0, 0.0};
  EXPECT_EQ(start.Percent(), 0);
  EXPECT_FALSE(start.EtaS());
  EXPECT_EQ(FormatProgressLine(start), "progress   0% (0/3 parts, 0.00/3.00 kB) -- B/s ETA --");
  // floor: 2999 of 3000 bytes is 99%, never a premature 100%.
  UploadSnapshot almost{3000, 2999, 2999, 3, 2, 1.0};
  EXPECT_EQ(almost.Percent(), 99);
  UploadSnapshot empty{0, 0, 0, 1, 1, 0.0};
  EXPECT_EQ(empty.Percent(), 100);
  EXPECT_EQ(FormatProgressBar(empty, 4), "[####] 100%  0/0 B  -- B/s  ETA 0 s");
}

TEST(UploadProgress, LinesAtEveryTenthAndAfterTheInterval) {
  ProgressLineSchedule schedule(5.0);
  EXPECT_TRUE(schedule.Due(0, 0.0));  // first update
  EXPECT_FALSE(schedule.Due(4, 0.5));
  EXPECT_TRUE(schedule.Due(10, 1.0));  // entered 10..19
  EXPECT_FALSE(schedule.Due(15, 2.0));
  EXPECT_TRUE(schedule.Due(16, 6.5));    // 5.5 s since the last line, with progress
  EXPECT_FALSE(schedule.Due(16, 20.0));  // no progress, no line however long
  EXPECT_TRUE(schedule.Due(37, 20.5));   // jumped two tenths: one line
  EXPECT_FALSE(schedule.Due(39, 21.0));
  EXPECT_TRUE(schedule.Due(100, 21.5));
  EXPECT_FALSE(schedule.Due(100, 30.0));
}

}  // namespace
}  // namespace reenact::capture
