// UTD-MHAD's folder names, action names, listing and the 20-joint reader, on constructed
// folders and files, and on the real data set when ../shared/data is there.
#include "tests/eval/utd_mhad.h"
#include "tests/support/temp_dir.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace reenact::eval {
namespace {

namespace fs = std::filesystem;

// ../shared/data/utd-mhad (the build's REENACT_SHARED_DATA_DIR).
fs::path UtdMhadRoot() { return fs::path(REENACT_SHARED_DATA_DIR) / "utd-mhad"; }

TEST(UtdMhad, ParsesSequenceNames) {
  const auto s = ParseUtdMhadName("a14_s3_t1");
  ASSERT_TRUE(s.has_value());
  EXPECT_EQ(s->action, 14);
  EXPECT_EQ(s->subject, 3);
  EXPECT_EQ(s->trial, 1);
  EXPECT_EQ(s->name, "a14_s3_t1");
  for (const char* bad : {"a0_s1_t1", "a28_s1_t1", "a1_s1", "a1_s1_t", "a01_s1_t1", "b1_s1_t1",
                          "a1_s-1_t1", "a1_t1_s1", "a1_s1_t1x", ""})
    EXPECT_FALSE(ParseUtdMhadName(bad).has_value()) << bad;
}

TEST(UtdMhad, NamesTheActionsOfTheDataSet) {
  EXPECT_EQ(UtdMhadActionName(1), "right arm swipe to the left");
  EXPECT_EQ(UtdMhadActionName(14), "baseball swing");
  EXPECT_EQ(UtdMhadActionName(27), "squat");
  EXPECT_EQ(UtdMhadActionName(0), "");
  EXPECT_EQ(UtdMhadActionName(28), "");
}

TEST(UtdMhad, ReadsTwentyJointsPerFrame) {
  const test_support::TempDir dir("utd-mhad");
  const fs::path file = dir.path() / "skeleton.txt";
  {
    std::ofstream out(file);
    for (int f = 0; f < 2; ++f)
      for (int j = 0; j < 20; ++j)
        if (f == 1 && j == 5) out << "0 0 0\n";
        else out << 0.01 * j << " " << -0.5 + f << " " << 2.5 << "\n";
  }
  const auto frames = ReadUtdMhadJoints20(file.string());
  ASSERT_TRUE(frames.ok()) << frames.error().message;
  ASSERT_EQ(frames->size(), 2u);
  ASSERT_EQ((*frames)[1]->size(), 20u);
  EXPECT_FALSE((*(*frames)[1])[5].has_value());  // (0, 0, 0): not given
  EXPECT_TRUE((*(*frames)[0])[5].has_value());
  EXPECT_EQ(*(*(*frames)[1])[19], Eigen::Vector3d(0.19, 0.5, 2.5));
}

TEST(UtdMhad, RefusesBrokenSkeletonFiles) {
  const test_support::TempDir dir("utd-mhad");
  const auto write = [&](const std::string& text) {
    std::ofstream(dir.path() / "s.txt") << text;
    return ReadUtdMhadJoints20((dir.path() / "s.txt").string());
  };
  const auto cut = write("1 2 3\n4 5 6\n");
  ASSERT_FALSE(cut.ok());
  EXPECT_EQ(cut.error().code, "corrupt");
  EXPECT_NE(cut.error().message.find("6 numbers"), std::string::npos) << cut.error().message;
  const auto word = write("1 2 x\n");
  ASSERT_FALSE(word.ok());
  EXPECT_NE(word.error().message.find("'x'"), std::string::npos) << word.error().message;
  const auto nan = write("1 2 nan\n");
  ASSERT_FALSE(nan.ok());
  EXPECT_EQ(nan.error().code, "corrupt");
  const auto missing = ReadUtdMhadJoints20((dir.path() / "none.txt").string());
  ASSERT_FALSE(missing.ok());
  EXPECT_EQ(missing.error().code, "not_found");
}

TEST(UtdMhad, ListsTheRealDataSet) {
  const fs::path root = UtdMhadRoot();
  if (!fs::is_directory(root)) GTEST_SKIP() << root << " is absent (shared data)";
  const auto sequences = ListUtdMhad(root.string());
  ASSERT_TRUE(sequences.ok()) << sequences.error().message;
  ASSERT_EQ(sequences->size(), 108u);  // 27 actions x 4 subjects, first trial
  EXPECT_EQ(sequences->front().name, "a1_s1_t1");
  EXPECT_EQ((*sequences)[4].name, "a2_s1_t1");
  EXPECT_EQ(sequences->back().name, "a27_s4_t1");
  const auto frames = ReadUtdMhadJoints20(UtdMhadSkeletonPath(sequences->front()));
  ASSERT_TRUE(frames.ok()) << frames.error().message;
  EXPECT_EQ(frames->size(), 48u);  // camera.json's frame count for a1_s1_t1
}

}  // namespace
}  // namespace reenact::eval
