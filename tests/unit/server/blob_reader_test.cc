// BlobStore and its BlobReaders on each engine (SQLite in a temp dir; files in a temp dir
// beside SQLite metadata; PostgreSQL in the tests' throwaway cluster, skipped with a message
// where none is installed): put, replace, get and delete by prefix, payloads read back in
// pieces, the "changed" error when a payload is replaced or deleted between reads, and reads
// that hold no transaction open between calls.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdint>
#include <string>
#include <thread>
#include <vector>

#include "server/storage/open_storage.h"
#include "server/storage/postgres.h"
#include "server/storage/sqlite.h"
#include "tests/unit/server/postgres_test_cluster.h"
#include "tests/unit/server/server_test_util.h"

namespace reenact::server {
namespace {

using testing::Engine;
using testing::TempDir;

// `size` bytes of every value 0..255, in an order that no shifted or repeated read matches.
std::string Payload(size_t size, uint32_t seed) {
  std::string bytes(size, '\0');
  uint32_t state = seed;
  for (char& c : bytes) {
    state = state * 1664525u + 1013904223u;  // the Numerical Recipes LCG
    c = static_cast<char>(state >> 24);
  }
  return bytes;
}

// Reads the whole payload through `reader` in pieces of `chunk` bytes.
std::string ReadAll(BlobReader& reader, size_t chunk) {
  std::string all;
  std::vector<char> buffer(chunk);
  for (;;) {
    auto n = reader.Read(all.size(), buffer);
    EXPECT_TRUE(n.ok()) << n.error().message;
    if (!n.ok() || *n == 0) return all;
    EXPECT_LE(*n, chunk);
    all.append(buffer.data(), *n);
  }
}

class BlobReaderTest : public ::testing::TestWithParam<Engine> {
 protected:
  void SetUp() override {
    if (GetParam() == Engine::kPostgres) {
      auto url = testing::NewPostgresTestDatabase();
      if (!url && url.error().code == "unavailable") GTEST_SKIP() << url.error().message;
      ASSERT_TRUE(url.ok()) << url.error().message;
      url_ = *url;
    }
    auto opened = GetParam() == Engine::kPostgres ? OpenPostgresStorage(url_)
                  : GetParam() == Engine::kSqlite ? OpenSqliteStorage(path_)
                                                  : testing::OpenTestStorage(GetParam(), dir_);
    ASSERT_TRUE(opened.ok()) << opened.error().message;
    storage_ = std::move(*opened);
  }

  std::unique_ptr<BlobReader> Reader(const std::string& key) {
    auto reader = storage_.blobs->OpenReader(key);
    EXPECT_TRUE(reader.ok()) << reader.error().message;
    return reader.ok() ? std::move(*reader) : nullptr;
  }

  TempDir dir_;
  const std::string path_ = (dir_.path() / "db.sqlite").string();  // SQLite (as OpenTestStorage)
  std::string url_;                                                  // PostgreSQL
  Storage storage_;
};

INSTANTIATE_TEST_SUITE_P(Engines, BlobReaderTest,
                         ::testing::Values(Engine::kSqlite, Engine::kPostgres,
                                           Engine::kSqliteFiles),
                         testing::EngineName);

TEST_P(BlobReaderTest, PutReplaceGetAndDeleteByPrefix) {
  BlobStore& blobs = *storage_.blobs;
  const std::string binary("a\0b\xff", 4);
  ASSERT_TRUE(blobs.Put("ab/frames/0", binary).ok());
  ASSERT_TRUE(blobs.Put("ab/map", "old").ok());
  ASSERT_TRUE(blobs.Put("ab/map", "new").ok());
  ASSERT_TRUE(blobs.Put("abc/map", "other clip").ok());
  ASSERT_TRUE(blobs.Put("ab/empty", "").ok());
  EXPECT_EQ(**blobs.Get("ab/frames/0"), binary);
  EXPECT_EQ(**blobs.Get("ab/map"), "new");
  EXPECT_EQ(**blobs.Get("ab/empty"), "");
  EXPECT_FALSE(blobs.Get("ab/frames/1")->has_value());
  ASSERT_TRUE(blobs.DeletePrefix("ab/").ok());
  EXPECT_FALSE(blobs.Get("ab/frames/0")->has_value());
  EXPECT_FALSE(blobs.Get("ab/map")->has_value());
  EXPECT_FALSE(blobs.Get("ab/empty")->has_value());
  EXPECT_EQ(**blobs.Get("abc/map"), "other clip");
}

TEST_P(BlobReaderTest, ListKeysGivesEveryKeyInBytewiseOrder) {
  BlobStore& blobs = *storage_.blobs;
  EXPECT_TRUE(blobs.ListKeys()->empty());
  // Bytewise: upper case before lower case, "1" before "9", UTF-8 (0xc3) after ASCII; a
  // locale's collation would order these otherwise.
  for (const char* key : {"a/map", "\xc3\xa9/map", "a/frames/9", "Z/map", "a/frames/10", "B/x"}) {
    ASSERT_TRUE(blobs.Put(key, key).ok()) << key;
  }
  ASSERT_TRUE(blobs.Put("a/map", "replaced").ok());
  ASSERT_TRUE(blobs.DeletePrefix("B/").ok());
  auto keys = blobs.ListKeys();
  ASSERT_TRUE(keys.ok()) << keys.error().message;
  EXPECT_EQ(*keys, (std::vector<std::string>{"Z/map", "a/frames/10", "a/frames/9", "a/map",
                                             "\xc3\xa9/map"}));
}

TEST_P(BlobReaderTest, DeletePrefixTakesEveryCharacterLiterally) {
  // "_" and "%" are wildcards of SQL LIKE and "\\" its escape; here they are only characters.
  BlobStore& blobs = *storage_.blobs;
  for (const char* key : {"a_/map", "ab/map", "a%/map", "a%b/map", "a\\/map", "a\\b/map"}) {
    ASSERT_TRUE(blobs.Put(key, key).ok()) << key;
  }
  ASSERT_TRUE(blobs.DeletePrefix("a_/").ok());
  ASSERT_TRUE(blobs.DeletePrefix("a%/").ok());
  ASSERT_TRUE(blobs.DeletePrefix("a\\/").ok());
  for (const char* gone : {"a_/map", "a%/map", "a\\/map"}) {
    EXPECT_FALSE(blobs.Get(gone)->has_value()) << gone;
  }
  for (const char* kept : {"ab/map", "a%b/map", "a\\b/map"}) {
    auto got = blobs.Get(kept);
    ASSERT_TRUE(got.ok() && got->has_value()) << kept;
    EXPECT_EQ(**got, kept);
  }
}

TEST_P(BlobReaderTest, ReadsThePayloadInPiecesOfAnySize) {
  const std::string small = Payload(5000, 1);
  const std::string large = Payload(300 * 1024 + 5, 2);  // over many overflow pages
  ASSERT_TRUE(storage_.blobs->Put("c/frames/0", small).ok());
  ASSERT_TRUE(storage_.blobs->Put("c/frames/1", large).ok());
  for (size_t chunk : {size_t{1}, size_t{7}, size_t{64 * 1024}, small.size() + 100}) {
    auto reader = Reader("c/frames/0");
    ASSERT_NE(reader, nullptr);
    EXPECT_EQ(reader->size(), small.size());
    EXPECT_EQ(ReadAll(*reader, chunk), small) << "chunk " << chunk;
  }
  for (size_t chunk : {size_t{7}, size_t{64 * 1024}, large.size() + 100}) {
    auto reader = Reader("c/frames/1");
    ASSERT_NE(reader, nullptr);
    EXPECT_EQ(reader->size(), large.size());
    EXPECT_EQ(ReadAll(*reader, chunk), large) << "chunk " << chunk;
  }
}

TEST_P(BlobReaderTest, ReadsFromAnyOffsetAndNothingAtOrPastTheEnd) {
  const std::string payload = Payload(1000, 3);
  ASSERT_TRUE(storage_.blobs->Put("c/map", payload).ok());
  auto reader = Reader("c/map");
  ASSERT_NE(reader, nullptr);
  std::vector<char> buffer(64, 'z');
  auto n = reader->Read(990, buffer);  // only 10 bytes left
  ASSERT_TRUE(n.ok());
  EXPECT_EQ(*n, 10u);
  EXPECT_EQ(std::string(buffer.data(), 10), payload.substr(990));
  EXPECT_EQ(buffer[10], 'z');  // nothing written past what was read
  for (uint64_t offset : {uint64_t{1000}, uint64_t{1001}, uint64_t{1} << 40}) {
    auto none = reader->Read(offset, buffer);
    ASSERT_TRUE(none.ok());
    EXPECT_EQ(*none, 0u) << "offset " << offset;
  }
}

TEST_P(BlobReaderTest, AbsentKeyGivesNoReader) {
  ASSERT_TRUE(storage_.blobs->Put("c/frames/0", "x").ok());
  auto reader = storage_.blobs->OpenReader("c/frames/1");
  ASSERT_TRUE(reader.ok());
  EXPECT_EQ(*reader, nullptr);
}

TEST_P(BlobReaderTest, PayloadReplacedByAnotherSizeBetweenReadsIsChanged) {
  ASSERT_TRUE(storage_.blobs->Put("c/frames/0", Payload(4096, 4)).ok());
  auto reader = Reader("c/frames/0");
  ASSERT_NE(reader, nullptr);
  std::vector<char> buffer(1024);
  ASSERT_TRUE(reader->Read(0, buffer).ok());
  ASSERT_TRUE(storage_.blobs->Put("c/frames/0", Payload(4000, 5)).ok());
  auto n = reader->Read(1024, buffer);
  ASSERT_FALSE(n.ok());
  EXPECT_EQ(n.error().code, "changed");
  EXPECT_NE(n.error().message.find("c/frames/0"), std::string::npos);
  // A new reader sees the new payload.
  auto fresh = Reader("c/frames/0");
  ASSERT_NE(fresh, nullptr);
  EXPECT_EQ(ReadAll(*fresh, 1024), Payload(4000, 5));
}

TEST_P(BlobReaderTest, PayloadDeletedBetweenReadsIsChanged) {
  ASSERT_TRUE(storage_.blobs->Put("c/frames/0", Payload(4096, 6)).ok());
  auto reader = Reader("c/frames/0");
  ASSERT_NE(reader, nullptr);
  std::vector<char> buffer(1024);
  ASSERT_TRUE(reader->Read(0, buffer).ok());
  ASSERT_TRUE(storage_.blobs->DeletePrefix("c/").ok());
  auto n = reader->Read(1024, buffer);
  ASSERT_FALSE(n.ok());
  EXPECT_EQ(n.error().code, "changed");
}

TEST_P(BlobReaderTest, KeyDeletedAndPutAgainAtTheSameRowIsChangedIfTheSizeDiffers) {
  // Without AUTOINCREMENT SQLite gives a new row the largest rowid + 1, so a deleted last row's
  // rowid comes back for the next insert: the key and rowid match, the size does not.
  ASSERT_TRUE(storage_.blobs->Put("c/frames/0", Payload(4096, 7)).ok());
  auto reader = Reader("c/frames/0");
  ASSERT_NE(reader, nullptr);
  ASSERT_TRUE(storage_.blobs->DeletePrefix("c/").ok());
  ASSERT_TRUE(storage_.blobs->Put("c/frames/0", Payload(100, 8)).ok());
  std::vector<char> buffer(1024);
  auto n = reader->Read(0, buffer);
  ASSERT_FALSE(n.ok());
  EXPECT_EQ(n.error().code, "changed");
}

TEST_P(BlobReaderTest, NoReadTransactionStaysOpenBetweenReads) {
  if (GetParam() == Engine::kSqliteFiles) {
    GTEST_SKIP() << "a file reader holds its open file only, no database transaction";
  }
  ASSERT_TRUE(storage_.blobs->Put("c/frames/0", Payload(64 * 1024, 9)).ok());
  auto reader = Reader("c/frames/0");
  ASSERT_NE(reader, nullptr);
  std::vector<char> buffer(4096);
  ASSERT_TRUE(reader->Read(0, buffer).ok());
  ASSERT_TRUE(storage_.blobs->Get("c/frames/0").ok());
  ASSERT_TRUE(storage_.blobs->Put("c/frames/1", Payload(64 * 1024, 10)).ok());
  if (GetParam() == Engine::kSqlite) {
    // A TRUNCATE checkpoint must wait for every reader's snapshot; with a busy timeout of 0 it
    // reports busy (first column 1) if any read transaction were still open.
    auto db = sqlite::Database::Open(path_, sqlite::Sync::kFull, /*busy_timeout_ms=*/0);
    ASSERT_TRUE(db.ok());
    auto checkpoint = db->Prepare("PRAGMA wal_checkpoint(TRUNCATE)");
    ASSERT_TRUE(checkpoint.ok());
    auto row = checkpoint->Step();
    ASSERT_TRUE(row.ok() && *row);
    EXPECT_EQ(checkpoint->ColumnInt(0), 0) << "a reader held a snapshot";
    EXPECT_EQ(checkpoint->ColumnInt(1), 0);  // WAL frames left: none
  } else {
    // Any transaction that read blobs would hold a lock on it until its end; an exclusive lock
    // taken without waiting fails if one is held.
    auto db = pg::Connection::Open(url_);
    ASSERT_TRUE(db.ok()) << db.error().message;
    ASSERT_TRUE(db->Exec("BEGIN").ok());
    Status locked = db->Exec("LOCK TABLE blobs IN ACCESS EXCLUSIVE MODE NOWAIT");
    EXPECT_TRUE(locked.ok()) << "a reader held a lock: " << locked.error().message;
    ASSERT_TRUE(db->Exec("ROLLBACK").ok());
  }
  // The reader goes on.
  auto n = reader->Read(4096, buffer);
  ASSERT_TRUE(n.ok());
  EXPECT_EQ(std::string(buffer.data(), *n), Payload(64 * 1024, 9).substr(4096, 4096));
}

TEST_P(BlobReaderTest, PutOfTheSameBytesKeepsReadersGoing) {
  const std::string payload = Payload(8192, 12);
  ASSERT_TRUE(storage_.blobs->Put("c/frames/0", payload).ok());
  auto reader = Reader("c/frames/0");
  ASSERT_NE(reader, nullptr);
  std::vector<char> buffer(4096);
  ASSERT_TRUE(reader->Read(0, buffer).ok());
  ASSERT_TRUE(storage_.blobs->Put("c/frames/0", payload).ok());  // an idempotent upload again
  auto n = reader->Read(4096, buffer);
  ASSERT_TRUE(n.ok()) << n.error().message;
  EXPECT_EQ(std::string(buffer.data(), *n), payload.substr(4096));
}

TEST_P(BlobReaderTest, PayloadReplacedByOtherBytesOfTheSameSizeIsChanged) {
  if (GetParam() == Engine::kSqlite) {
    GTEST_SKIP() << "SQLite readers tell a replacement by its row and size only (parts are "
                    "content-addressed, so a same-size replacement holds the same bytes)";
  }
  ASSERT_TRUE(storage_.blobs->Put("c/frames/0", Payload(4096, 13)).ok());
  auto reader = Reader("c/frames/0");
  ASSERT_NE(reader, nullptr);
  std::vector<char> buffer(1024);
  ASSERT_TRUE(reader->Read(0, buffer).ok());
  ASSERT_TRUE(storage_.blobs->Put("c/frames/0", Payload(4096, 14)).ok());
  auto n = reader->Read(1024, buffer);
  ASSERT_FALSE(n.ok());
  EXPECT_EQ(n.error().code, "changed");
}

TEST_P(BlobReaderTest, ReadsAreCorrectWhileAnotherThreadWrites) {
  const std::string payload = Payload(512 * 1024, 11);
  ASSERT_TRUE(storage_.blobs->Put("c/frames/0", payload).ok());
  std::atomic<bool> stop{false};
  std::atomic<int> puts{0};
  std::thread writer([&] {
    for (int i = 0; !stop.load(); ++i) {
      if (!storage_.blobs->Put("d/frames/" + std::to_string(i % 8), Payload(256 * 1024, i)).ok()) {
        return;
      }
      puts.fetch_add(1);
    }
  });
  std::vector<std::thread> readers;
  std::atomic<int> good{0};
  for (int t = 0; t < 3; ++t) {
    readers.emplace_back([&, t] {
      for (int round = 0; round < 5; ++round) {
        auto reader = storage_.blobs->OpenReader("c/frames/0");
        if (!reader.ok() || !*reader) return;
        if (ReadAll(**reader, 4096 * (t + 1)) == payload) good.fetch_add(1);
      }
    });
  }
  for (std::thread& t : readers) t.join();
  stop = true;
  writer.join();
  EXPECT_EQ(good.load(), 15);
  EXPECT_GT(puts.load(), 0);
  auto last = storage_.blobs->Get("d/frames/0");
  ASSERT_TRUE(last.ok() && last->has_value());
  EXPECT_EQ((*last)->size(), 256u * 1024);
}

}  // namespace
}  // namespace reenact::server
