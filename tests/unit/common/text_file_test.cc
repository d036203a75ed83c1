#include "common/io/text_file.h"

#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "tests/support/temp_dir.h"

namespace reenact {
namespace {

using test_support::TempDir;

TEST(TextFile, ReadsEveryByteAsWritten) {
  TempDir dir;
  const std::string bytes = std::string("HIERARCHY\r\nROOT Hips\n") + '\0' + "\xff tail";
  std::ofstream(dir.path() / "a.bvh", std::ios::binary) << bytes;
  const Expected<std::string> text = ReadTextFile(dir.path() / "a.bvh", "BVH file");
  ASSERT_TRUE(text.ok()) << text.error().message;
  EXPECT_EQ(*text, bytes);
}

TEST(TextFile, AnEmptyFileIsEmptyText) {
  TempDir dir;
  std::ofstream(dir.path() / "empty.json");
  const Expected<std::string> text = ReadTextFile(dir.path() / "empty.json", "track");
  ASSERT_TRUE(text.ok()) << text.error().message;
  EXPECT_TRUE(text->empty());
}

TEST(TextFile, AMissingFileOrAFolderIsNotFoundNamingTheKind) {
  TempDir dir;
  for (const auto& path : {dir.path() / "missing.bvh", dir.path()}) {
    const Expected<std::string> text = ReadTextFile(path, "BVH file");
    ASSERT_FALSE(text.ok()) << path;
    EXPECT_EQ(text.error().code, "not_found");
    EXPECT_EQ(text.error().message, path.string() + ": no such BVH file");
  }
}

}  // namespace
}  // namespace reenact
