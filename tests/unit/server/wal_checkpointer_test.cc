// WalCheckpointer on real SQLite files: checkpoints leave the committing connection and run on
// the checkpointer's thread; one checkpointer per file.
#include "server/storage/wal_checkpointer.h"

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <thread>

#include "tests/support/temp_dir.h"

namespace reenact::server::sqlite {
namespace {

using test_support::TempDir;

constexpr int kPageBytes = 4096;  // SQLite's default page size
constexpr int kRows = 64;         // each row's blob fills about one page

// Commits kRows rows of 4000-byte blobs, one transaction each.
void WriteRows(Database& db) {
  ASSERT_TRUE(db.Exec("CREATE TABLE t(x BLOB)").ok());
  const std::string blob(4000, 'x');
  for (int i = 0; i < kRows; ++i) {
    auto stmt = db.Prepare("INSERT INTO t(x) VALUES (?1)");
    ASSERT_TRUE(stmt.ok());
    stmt->BindBlob(1, blob);
    ASSERT_TRUE(stmt->Run().ok());
  }
}

TEST(WalCheckpointer, CopiesTheWalIntoTheDatabaseOnItsOwnThread) {
  TempDir dir;
  const std::string path = (dir.path() / "w.sqlite").string();
  auto db = Database::Open(path);
  ASSERT_TRUE(db.ok());
  constexpr int kStartFrames = 16;
  auto checkpointer = WalCheckpointer::ForFile(
      path, {.start_frames = kStartFrames, .restart_frames = kStartFrames});
  ASSERT_TRUE(checkpointer.ok());
  (*checkpointer)->Attach(*db);
  WriteRows(*db);
  // The rows reach the database file only through a checkpoint (SQLite's own would wait
  // for 1000 pages; the control test below shows the file stays under half the rows' pages
  // without one). The checkpoints run on their own thread while the rows are still being
  // committed, so which commits the last one copies depends on timing: a tail of fewer than
  // kStartFrames WAL pages (one row at least a page) can stay in the WAL, where no further
  // commit asks for a checkpoint. So the file holds at least kRows - kStartFrames rows' pages.
  const uintmax_t least = uintmax_t{kRows - kStartFrames} * kPageBytes;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while ((std::filesystem::file_size(path) < least || (*checkpointer)->checkpoints() < 1) &&
         std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  EXPECT_GE(std::filesystem::file_size(path), least);
  EXPECT_GE((*checkpointer)->checkpoints(), 1);
}

TEST(WalCheckpointer, WithoutOneSmallWalsStayInTheWal) {
  TempDir dir;
  const std::string path = (dir.path() / "w.sqlite").string();
  auto db = Database::Open(path);
  ASSERT_TRUE(db.ok());
  WriteRows(*db);
  EXPECT_LT(std::filesystem::file_size(path), uintmax_t{kRows} * kPageBytes / 2);
}

TEST(WalCheckpointer, OnePerFile) {
  TempDir dir;
  const std::string a = (dir.path() / "a.sqlite").string();
  const std::string b = (dir.path() / "b.sqlite").string();
  auto a1 = WalCheckpointer::ForFile(a);
  auto a2 = WalCheckpointer::ForFile((dir.path() / "." / "a.sqlite").string());
  auto b1 = WalCheckpointer::ForFile(b);
  ASSERT_TRUE(a1.ok() && a2.ok() && b1.ok());
  EXPECT_EQ(a1->get(), a2->get());
  EXPECT_NE(a1->get(), b1->get());
}

TEST(WalCheckpointer, MissingDirectoryIsAnError) {
  TempDir dir;
  auto checkpointer = WalCheckpointer::ForFile((dir.path() / "no" / "w.sqlite").string());
  ASSERT_FALSE(checkpointer.ok());
  EXPECT_EQ(checkpointer.error().code, "io");
}

}  // namespace
}  // namespace reenact::server::sqlite
