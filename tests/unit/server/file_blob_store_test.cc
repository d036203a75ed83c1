// FileBlobStore beyond the engine-parameterized blob tests (blob_reader_test.cc): keys that
// try to leave the directory or collide stay inside it and round-trip, the layout of the files,
// DeletePrefix at and inside a component, stale temporary files, Puts that cannot write, the
// errors of Open, PostgreSQL metadata with file blobs, threads and two stores on one directory,
// and a clip through the routes with its payloads as files.
#include "server/storage/file_blob_store.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "server/storage/postgres.h"
#include "server/storage/sqlite.h"
#include "tests/unit/server/server_test_util.h"

namespace reenact::server {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;

std::string ReadFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

void WriteFile(const fs::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out << bytes;
}

// Every regular file under `dir`, relative to it, sorted.
std::vector<std::string> FilesUnder(const fs::path& dir) {
  std::vector<std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    if (entry.is_regular_file()) files.push_back(fs::relative(entry.path(), dir).string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

class FileBlobStoreTest : public ::testing::Test {
 protected:
  void SetUp() override {
    fs::create_directory(root_);
    store_ = Open();
    ASSERT_NE(store_, nullptr);
  }

  std::unique_ptr<FileBlobStore> Open() {
    auto store = FileBlobStore::Open(root_.string());
    EXPECT_TRUE(store.ok()) << store.error().message;
    return store.ok() ? std::move(*store) : nullptr;
  }

  std::vector<std::string> Keys() {
    auto keys = store_->ListKeys();
    EXPECT_TRUE(keys.ok()) << keys.error().message;
    return keys.ok() ? *keys : std::vector<std::string>{};
  }

  std::string Get(const std::string& key) {
    auto got = store_->Get(key);
    EXPECT_TRUE(got.ok()) << got.error().message;
    if (!got.ok() || !got->has_value()) return "<absent>";
    return **got;
  }

  TempDir dir_;
  const fs::path root_ = dir_.path() / "blobs";
  std::unique_ptr<FileBlobStore> store_;
};

TEST_F(FileBlobStoreTest, KeysOfClipsAreFilesNamedByTheirComponents) {
  ASSERT_TRUE(store_->Put("c0ffee/frames/3", "frame three").ok());
  ASSERT_TRUE(store_->Put("c0ffee/map", "the map").ok());
  EXPECT_EQ(ReadFile(root_ / "c0ffee" / "frames" / "3.blob"), "frame three");
  EXPECT_EQ(ReadFile(root_ / "c0ffee" / "map.blob"), "the map");
  EXPECT_EQ(FilesUnder(root_),
            (std::vector<std::string>{"c0ffee/frames/3.blob", "c0ffee/map.blob"}));
  EXPECT_EQ(*store_->PathOfKey("c0ffee/map"), (root_ / "c0ffee" / "map.blob").string());
  EXPECT_EQ((fs::status(root_ / "c0ffee" / "map.blob").permissions() & fs::perms::all),
            fs::perms::owner_read | fs::perms::owner_write);
}

TEST_F(FileBlobStoreTest, HostileKeysStayInsideTheDirectoryAndRoundTrip) {
  const std::vector<std::string> keys = {"..",      "../x",     "../../etc/passwd",
                                         ".",       "a//b",     "%2F",
                                         "%",       "/abs",     "\xc3\xa9/map",
                                         "",        "a/",       "a/b",
                                         "a/b/c",   "a.blob",   "a.blob/x",
                                         "a%2Fb",   "a/b.blob", "~/.ssh/x",
                                         "\\..\\x", "a\nb",     std::string("nul\0/x", 6),
                                         "-/_",     "A/a"};
  for (size_t i = 0; i < keys.size(); ++i) {
    std::string payload = "payload ";
    payload += std::to_string(i);
    ASSERT_TRUE(store_->Put(keys[i], payload).ok()) << i;
  }
  // Each key reads back its own payload: no two keys share a file.
  for (size_t i = 0; i < keys.size(); ++i) {
    std::string payload = "payload ";
    payload += std::to_string(i);
    EXPECT_EQ(Get(keys[i]), payload) << i;
    auto path = store_->PathOfKey(keys[i]);
    ASSERT_TRUE(path.ok());
    const fs::path canonical = fs::weakly_canonical(*path);
    EXPECT_EQ(canonical.string().rfind(fs::canonical(root_).string() + "/", 0), 0u)
        << *path << " is outside " << root_;
  }
  // One file per key, all under the directory, and nothing beside it.
  EXPECT_EQ(FilesUnder(root_).size(), keys.size());
  std::vector<std::string> beside;
  for (const auto& entry : fs::directory_iterator(dir_.path())) {
    beside.push_back(entry.path().filename().string());
  }
  EXPECT_EQ(beside, std::vector<std::string>{"blobs"});
  // Names as the layout says: '.' and '/' encoded, an empty component as "%".
  EXPECT_EQ(*store_->PathOfKey(".."), (root_ / "%2E%2E.blob").string());
  EXPECT_EQ(*store_->PathOfKey("a//b"), (root_ / "a" / "%" / "b.blob").string());
  EXPECT_EQ(*store_->PathOfKey("/abs"), (root_ / "%" / "abs.blob").string());
  EXPECT_EQ(*store_->PathOfKey("%2F"), (root_ / "%252F.blob").string());
  EXPECT_EQ(*store_->PathOfKey("\xc3\xa9/map"), (root_ / "%C3%A9" / "map.blob").string());
  EXPECT_EQ(*store_->PathOfKey(""), (root_ / "%.blob").string());

  std::vector<std::string> sorted = keys;
  std::sort(sorted.begin(), sorted.end());  // bytewise
  EXPECT_EQ(Keys(), sorted);
  ASSERT_TRUE(store_->DeletePrefix("").ok());
  EXPECT_TRUE(Keys().empty());
  EXPECT_TRUE(fs::is_directory(root_));
  EXPECT_TRUE(fs::is_empty(root_));
}

TEST_F(FileBlobStoreTest, AKeyTooLongForAFileNameIsRefusedAndNeverFound) {
  const std::string key = "c/" + std::string(300, 'x');
  Status put = store_->Put(key, "x");
  ASSERT_FALSE(put.ok());
  EXPECT_EQ(put.error().code, "invalid_argument");
  EXPECT_FALSE(store_->Get(key)->has_value());
  EXPECT_EQ(*store_->OpenReader(key), nullptr);
  EXPECT_TRUE(store_->DeletePrefix(std::string(300, 'x') + "/").ok());
}

TEST_F(FileBlobStoreTest, DeletePrefixAtAndInsideAComponent) {
  for (const char* key : {"ab/map", "ab/frames/0", "ab/frames/10", "ab/frames/2", "abc/map", "ab",
                          "a/map", "b/x", "\xc3\xa9t\xc3\xa9/map", "\xc3\xa9/x"}) {
    ASSERT_TRUE(store_->Put(key, key).ok()) << key;
  }
  ASSERT_TRUE(store_->DeletePrefix("ab/frames/1").ok());
  EXPECT_EQ(Keys(),
            (std::vector<std::string>{"a/map", "ab", "ab/frames/0", "ab/frames/2", "ab/map",
                                      "abc/map", "b/x", "\xc3\xa9/x", "\xc3\xa9t\xc3\xa9/map"}));
  ASSERT_TRUE(store_->DeletePrefix("ab/fr").ok());  // the whole frames directory
  EXPECT_FALSE(fs::exists(root_ / "ab" / "frames"));
  EXPECT_EQ(Keys(), (std::vector<std::string>{"a/map", "ab", "ab/map", "abc/map", "b/x",
                                              "\xc3\xa9/x", "\xc3\xa9t\xc3\xa9/map"}));
  ASSERT_TRUE(store_->DeletePrefix("ab/").ok());  // the clip "ab"; the key "ab" is no prefix
  EXPECT_FALSE(fs::exists(root_ / "ab"));         // left empty: removed
  EXPECT_EQ(Keys(), (std::vector<std::string>{"a/map", "ab", "abc/map", "b/x", "\xc3\xa9/x",
                                              "\xc3\xa9t\xc3\xa9/map"}));
  ASSERT_TRUE(store_->DeletePrefix("\xc3").ok());  // half of a UTF-8 character
  EXPECT_EQ(Keys(), (std::vector<std::string>{"a/map", "ab", "abc/map", "b/x"}));
  ASSERT_TRUE(store_->DeletePrefix("a").ok());
  EXPECT_EQ(Keys(), std::vector<std::string>{"b/x"});
  ASSERT_TRUE(store_->DeletePrefix("nothing/here/").ok());
  ASSERT_TRUE(store_->DeletePrefix("").ok());
  EXPECT_TRUE(Keys().empty());
  EXPECT_TRUE(fs::is_empty(root_));
}

TEST_F(FileBlobStoreTest, DeleteLeavesOtherProgramsFilesAndTheirDirectories) {
  ASSERT_TRUE(store_->Put("c/frames/0", "x").ok());
  WriteFile(root_ / "c" / "frames" / "README.txt", "an operator's note");
  ASSERT_TRUE(store_->DeletePrefix("c/").ok());
  EXPECT_FALSE(store_->Get("c/frames/0")->has_value());
  EXPECT_EQ(ReadFile(root_ / "c" / "frames" / "README.txt"), "an operator's note");
  EXPECT_TRUE(Keys().empty());
}

TEST_F(FileBlobStoreTest, OpenRemovesStaleTemporaryFilesAndKeepsFreshOnes) {
  ASSERT_TRUE(store_->Put("c/map", "kept").ok());
  const fs::path stale_top = root_ / ".put-00000000000000aa.tmp";
  const fs::path stale_deep = root_ / "c" / ".put-00000000000000bb.tmp";
  const fs::path fresh = root_ / "c" / ".put-00000000000000cc.tmp";  // another server's Put
  const fs::path foreign = root_ / "notes.txt";
  for (const fs::path& p : {stale_top, stale_deep, fresh, foreign}) WriteFile(p, "partial");
  const auto old =
      fs::file_time_type::clock::now() - FileBlobStore::kStaleTempAge - std::chrono::seconds(60);
  fs::last_write_time(stale_top, old);
  fs::last_write_time(stale_deep, old);
  fs::last_write_time(foreign, old);
  EXPECT_EQ(Keys(), std::vector<std::string>{"c/map"});  // temporary files are never keys

  store_ = Open();
  ASSERT_NE(store_, nullptr);
  EXPECT_FALSE(fs::exists(stale_top));
  EXPECT_FALSE(fs::exists(stale_deep));
  EXPECT_TRUE(fs::exists(fresh));
  EXPECT_TRUE(fs::exists(foreign));
  EXPECT_EQ(Keys(), std::vector<std::string>{"c/map"});
  EXPECT_EQ(Get("c/map"), "kept");
}

TEST_F(FileBlobStoreTest, APutCutShortByTheFileSizeLimitLeavesTheOldPayloadAndNoTemporaryFile) {
  // RLIMIT_FSIZE makes write() fail with EFBIG part way, as a full disk would with ENOSPC, and
  // holds for root too.
  ASSERT_TRUE(store_->Put("c/frames/0", "old payload").ok());
  struct rlimit saved;
  ASSERT_EQ(getrlimit(RLIMIT_FSIZE, &saved), 0);
  auto* previous = signal(SIGXFSZ, SIG_IGN);
  struct rlimit small = saved;
  small.rlim_cur = 64 * 1024;
  ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &small), 0);
  Status put = store_->Put("c/frames/0", std::string(1 << 20, 'n'));
  setrlimit(RLIMIT_FSIZE, &saved);
  signal(SIGXFSZ, previous);
  ASSERT_FALSE(put.ok());
  EXPECT_EQ(put.error().code, "storage");
  EXPECT_NE(put.error().message.find((root_ / "c" / "frames" / "0.blob").string()),
            std::string::npos)
      << put.error().message;
  EXPECT_NE(put.error().message.find(std::strerror(EFBIG)), std::string::npos)
      << put.error().message;
  EXPECT_EQ(Get("c/frames/0"), "old payload");
  EXPECT_EQ(FilesUnder(root_), std::vector<std::string>{"c/frames/0.blob"});
}

TEST_F(FileBlobStoreTest, APutIntoAReadOnlyDirectoryLeavesTheOldPayload) {
  if (geteuid() == 0) GTEST_SKIP() << "root writes into read-only directories";
  ASSERT_TRUE(store_->Put("c/frames/0", "old payload").ok());
  fs::permissions(root_ / "c" / "frames", fs::perms::owner_read | fs::perms::owner_exec);
  Status put = store_->Put("c/frames/0", "new payload");
  fs::permissions(root_ / "c" / "frames", fs::perms::owner_all);
  ASSERT_FALSE(put.ok());
  EXPECT_EQ(put.error().code, "storage");
  EXPECT_NE(put.error().message.find(std::strerror(EACCES)), std::string::npos)
      << put.error().message;
  EXPECT_NE(put.error().message.find((root_ / "c" / "frames").string()), std::string::npos)
      << put.error().message;
  EXPECT_EQ(Get("c/frames/0"), "old payload");
  EXPECT_EQ(FilesUnder(root_), std::vector<std::string>{"c/frames/0.blob"});
}

TEST_F(FileBlobStoreTest, AFileWhereADirectoryMustBeFailsThePutAndSaysWhy) {
  WriteFile(root_ / "x", "someone else's file");
  Status put = store_->Put("x/map", "payload");
  ASSERT_FALSE(put.ok());
  EXPECT_EQ(put.error().code, "storage");
  EXPECT_NE(put.error().message.find(std::strerror(ENOTDIR)), std::string::npos)
      << put.error().message;
  EXPECT_NE(put.error().message.find((root_ / "x").string()), std::string::npos)
      << put.error().message;
  EXPECT_FALSE(store_->Get("x/map")->has_value());
  EXPECT_EQ(ReadFile(root_ / "x"), "someone else's file");
  EXPECT_TRUE(Keys().empty());
}

TEST_F(FileBlobStoreTest, APutOfTheStoredBytesWritesNothing) {
  ASSERT_TRUE(store_->Put("c/map", "same bytes").ok());
  const fs::path file = root_ / "c" / "map.blob";
  const auto inode = [&] {
    struct stat st;
    return ::stat(file.c_str(), &st) == 0 ? st.st_ino : 0;
  };
  const auto before = inode();
  ASSERT_TRUE(store_->Put("c/map", "same bytes").ok());
  EXPECT_EQ(inode(), before);
  ASSERT_TRUE(store_->Put("c/map", "other byte").ok());  // same size, other bytes
  EXPECT_NE(inode(), before);
  EXPECT_EQ(Get("c/map"), "other byte");
}

TEST(FileBlobStoreOpen, AMissingPathIsAnIoErrorNamingItAndWhatToDo) {
  TempDir dir;
  const std::string missing = (dir.path() / "missing").string();
  auto store = FileBlobStore::Open(missing);
  ASSERT_FALSE(store.ok());
  EXPECT_EQ(store.error().code, "io");
  EXPECT_NE(store.error().message.find("'" + missing + "'"), std::string::npos)
      << store.error().message;
  EXPECT_NE(store.error().message.find("create it"), std::string::npos) << store.error().message;
  EXPECT_FALSE(fs::exists(missing));
}

TEST(FileBlobStoreOpen, AFileIsAnIoErrorSayingItIsNoDirectory) {
  TempDir dir;
  const std::string file = (dir.path() / "file").string();
  WriteFile(file, "x");
  auto store = FileBlobStore::Open(file);
  ASSERT_FALSE(store.ok());
  EXPECT_EQ(store.error().code, "io");
  EXPECT_NE(store.error().message.find("'" + file + "' is not a directory"), std::string::npos)
      << store.error().message;
}

TEST(FileBlobStoreOpen, AReadOnlyDirectoryIsAnIoErrorSayingItIsNotWritable) {
  if (geteuid() == 0) GTEST_SKIP() << "root writes into read-only directories";
  TempDir dir;
  fs::permissions(dir.path(), fs::perms::owner_read | fs::perms::owner_exec);
  auto store = FileBlobStore::Open(dir.path().string());
  fs::permissions(dir.path(), fs::perms::owner_all);
  ASSERT_FALSE(store.ok());
  EXPECT_EQ(store.error().code, "io");
  EXPECT_NE(store.error().message.find("is not writable"), std::string::npos)
      << store.error().message;
}

TEST(FileBlobStoreOpen, AnUnusableBlobDirCreatesNoDatabase) {
  TempDir dir;
  const std::string db = (dir.path() / "db.sqlite").string();
  StorageOptions options;
  options.blob_dir = (dir.path() / "missing").string();
  auto storage = OpenSqliteStorage(db, options);
  ASSERT_FALSE(storage.ok());
  EXPECT_EQ(storage.error().code, "io");
  EXPECT_FALSE(fs::exists(db));
}

TEST(FileBlobStoreOpen, PostgresMetadataWithTheBlobsAsFiles) {
  auto url = testing::NewPostgresTestDatabase();
  if (!url && url.error().code == "unavailable") GTEST_SKIP() << url.error().message;
  ASSERT_TRUE(url.ok()) << url.error().message;
  TempDir dir;
  StorageOptions options;
  options.blob_dir = dir.path().string();
  auto storage = OpenPostgresStorage(*url, options);
  ASSERT_TRUE(storage.ok()) << storage.error().message;
  ASSERT_TRUE(storage->blobs->Put("c/map", "on a file").ok());
  EXPECT_EQ(ReadFile(dir.path() / "c" / "map.blob"), "on a file");
  auto db = pg::Connection::Open(*url);
  ASSERT_TRUE(db.ok()) << db.error().message;
  auto rows = db->Query("SELECT count(*) FROM blobs");
  ASSERT_TRUE(rows.ok()) << rows.error().message;
  EXPECT_EQ(rows->Int(0, 0), 0);
}

TEST_F(FileBlobStoreTest, TwoStoresOnOneDirectorySeeEachOthersPayloads) {
  auto other = Open();  // as a second server process would
  ASSERT_NE(other, nullptr);
  ASSERT_TRUE(store_->Put("c/frames/0", "from one").ok());
  auto reader = other->OpenReader("c/frames/0");
  ASSERT_TRUE(reader.ok() && *reader);
  ASSERT_TRUE(other->Put("c/frames/0", "from two, longer").ok());
  EXPECT_EQ(Get("c/frames/0"), "from two, longer");
  std::vector<char> buffer(4);
  auto n = (*reader)->Read(0, buffer);
  ASSERT_FALSE(n.ok());
  EXPECT_EQ(n.error().code, "changed");
  ASSERT_TRUE(store_->DeletePrefix("c/").ok());
  EXPECT_FALSE(other->Get("c/frames/0")->has_value());
}

TEST_F(FileBlobStoreTest, ThreadsPutGetAndDeleteInOneDirectoryAtOnce) {
  // Each DeletePrefix can leave "clip/frames" and "clip" empty and remove them while the other
  // threads are about to write there.
  constexpr int kThreads = 4, kRounds = 150;
  std::atomic<int> failures{0};
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t) {
    threads.emplace_back([&, t] {
      for (int i = 0; i < kRounds; ++i) {
        std::string key = "clip/frames/";
        key += std::to_string(t);
        key += "-";
        key += std::to_string(i);
        const std::string payload = key + std::string(100 + i, 'p');
        if (!store_->Put(key, payload).ok()) ++failures;
        auto got = store_->Get(key);
        if (!got.ok() || !got->has_value() || **got != payload) ++failures;
        if (!store_->DeletePrefix(key + "/").ok() || !store_->DeletePrefix(key).ok()) ++failures;
        auto gone = store_->Get(key);
        if (!gone.ok() || gone->has_value()) ++failures;
      }
    });
  }
  for (std::thread& t : threads) t.join();
  EXPECT_EQ(failures.load(), 0);
  EXPECT_TRUE(Keys().empty());
  EXPECT_TRUE(fs::is_empty(root_));
}

// The routes on SQLite metadata with the blobs as files.
class FileBlobRoutesTest : public testing::ServiceFixture {
 protected:
  testing::Engine engine() const override { return testing::Engine::kSqliteFiles; }
};

TEST_F(FileBlobRoutesTest, AClipIsUploadedPublishedAndDownloadedWithItsPartsAsFiles) {
  const testing::TestClip clip = testing::MakeTestClip(47.37, 8.54, 3, "files");
  const std::string id = Publish(clip, alice_);
  const fs::path blobs = testing::TestBlobDir(dir_);
  for (int n = 0; n < 3; ++n) {
    EXPECT_EQ(ReadFile(blobs / id / "frames" / (std::to_string(n) + ".blob")), clip.frames[n]);
    Response got = Call("GET", "/v1/clips/" + id + "/frames/" + std::to_string(n));
    EXPECT_EQ(got.status, 200);
    EXPECT_EQ(got.body, clip.frames[n]);
  }
  EXPECT_EQ(ReadFile(blobs / id / "map.blob"), clip.map);
  Response map = Call("GET", "/v1/clips/" + id + "/map");
  EXPECT_EQ(map.status, 200);
  EXPECT_EQ(map.body, clip.map);
  // The database holds no payload.
  auto db = sqlite::Database::Open((dir_.path() / "db.sqlite").string());
  ASSERT_TRUE(db.ok()) << db.error().message;
  auto count = db->Prepare("SELECT count(*) FROM blobs");
  ASSERT_TRUE(count.ok());
  ASSERT_TRUE(*count->Step());
  EXPECT_EQ(count->ColumnInt(0), 0);

  EXPECT_EQ(Call("DELETE", "/v1/clips/" + id, alice_).status, 204);
  EXPECT_FALSE(fs::exists(blobs / id));
  EXPECT_TRUE(fs::is_empty(blobs));
}

}  // namespace
}  // namespace reenact::server
