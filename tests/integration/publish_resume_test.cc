// `reenact-capture publish` against the real reenact-server on an ephemeral port: an upload
// cut off by a server crash resumes and sends only what is missing; a server unreachable from
// the start fails clearly and leaves nothing; parts damaged in the server's storage are sent
// again; plain progress lines when stdout is not a terminal. Published clips are downloaded
// and compared, part by part, with the SHA-256 of the clip files on disk.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <thread>

#include "proto/api/api_client.h"
#include "proto/clip/content_hash.h"
#include "server/auth/token.h"
#include "server/storage/blob_store.h"
#include "server/storage/open_storage.h"
#include "tests/integration/server_harness.h"

namespace reenact {
namespace {

using testing::ExpectClipWholeOn;
using testing::kCapture;
using testing::PartOnDisk;
using testing::RunProcess;
using testing::ServerProcess;

constexpr int kFrames = 40;
constexpr int kParts = kFrames + 1;

// A user and two tokens of theirs: one for the client under test, one for the test's own
// requests (so that they never spend the client's rate-limit credit).
struct Account {
  std::string token;
  std::string observer_token;
};
Account AddAccount(const std::string& db) {
  auto storage = server::OpenSqliteStorage(db);
  EXPECT_TRUE(storage.ok()) << storage.error().message;
  auto token = server::AddUserWithToken(*storage->metadata, "uploader");
  auto observer = server::AddTokenForUser(*storage->metadata, "uploader");
  EXPECT_TRUE(token.ok() && observer.ok());
  return {*token, *observer};
}

testing::ProcessResult Publish(const std::string& clip, const std::string& url,
                               const std::string& token,
                               const std::vector<std::string>& extra = {}) {
  std::vector<std::string> argv = {kCapture, "publish", clip,      "--server", url,       "--token",
                                   token,    "--lat",   "34.7325", "--lon",    "135.7336"};
  argv.insert(argv.end(), extra.begin(), extra.end());
  return RunProcess(argv, std::chrono::seconds(120));
}

// The value of key=N on the summary line.
long long SummaryValue(const std::string& out, const std::string& key) {
  std::smatch m;
  if (!std::regex_search(out, m, std::regex("(^|\\s)" + key + "=(\\d+)"))) return -1;
  return std::stoll(m[2].str());
}

std::string ClipId(const std::string& out) {
  std::smatch m;
  return std::regex_search(out, m, std::regex(R"(clip_id=(\S+))")) ? m[1].str() : "";
}

void ExpectOneLine(const std::string& err) {
  std::string text = err;
  while (!text.empty() && text.back() == '\n') text.pop_back();
  EXPECT_EQ(text.find('\n'), std::string::npos) << "more than one line:\n" << err;
}

size_t VisibleNearby(const std::string& url) {
  auto clips = proto::ApiClient(url, "").Nearby(34.7325, 135.7336, 1000);
  EXPECT_TRUE(clips.ok()) << clips.error().message;
  return clips.ok() ? clips->size() : 0;
}

class PublishResume : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new testing::TempDir();
    const auto record = RunProcess({kCapture, "record", "--source", "synthetic:turn-and-kick",
                                    "--out", clip(), "--frames", std::to_string(kFrames)},
                                   std::chrono::seconds(300));
    ASSERT_EQ(record.exit_code, 0) << record.err;
  }
  static void TearDownTestSuite() {
    delete dir_;
    dir_ = nullptr;
  }
  static std::string clip() { return dir_->path() + "/clip"; }

  testing::TempDir tmp_;
  std::string db_ = tmp_.path() + "/publish.db";

 private:
  static testing::TempDir* dir_;
};
testing::TempDir* PublishResume::dir_ = nullptr;

TEST_F(PublishResume, ServerKilledMidUploadThenRerunSendsOnlyTheMissingParts) {
  const Account account = AddAccount(db_);
  ServerProcess server;
  // A slow upload (8 requests per second for the client's token) so that the crash lands
  // in the middle of it; the client waits out each 429 as its Retry-After says.
  auto url = server.Start(db_, {"--rate-limit", "8", "--rate-burst", "4"});
  ASSERT_TRUE(url);
  testing::ProcessResult first;
  std::thread client([&] { first = Publish(clip(), *url, account.token, {"--retries", "2"}); });

  const proto::ApiClient observer(*url, account.observer_token);
  int held_at_kill = 0;
  for (int i = 0; i < 600 && held_at_kill < 8; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    auto mine = observer.MyClips();
    if (!mine.ok() || mine->empty()) continue;
    auto parts = observer.ListParts(mine->front().id);
    if (!parts.ok()) continue;
    held_at_kill = 0;
    for (const auto& part : parts->parts) held_at_kill += part.Complete() ? 1 : 0;
  }
  ASSERT_GE(held_at_kill, 8) << "the upload never got going";
  server.Kill(SIGKILL);
  client.join();

  EXPECT_FALSE(first.timed_out);
  EXPECT_EQ(first.exit_code, 1) << first.out << first.err;
  ExpectOneLine(first.err);
  EXPECT_NE(first.err.find("cannot reach server"), std::string::npos) << first.err;
  EXPECT_NE(first.err.find("run the same command again to resume"), std::string::npos) << first.err;
  EXPECT_NE(first.out.find("retrying PUT"), std::string::npos) << first.out;

  url = server.Start(db_, {"--rate-limit", "0"});
  ASSERT_TRUE(url);
  EXPECT_EQ(VisibleNearby(*url), 0u) << "a partial clip is visible";
  // What the server holds now decides what the re-run must send.
  const proto::ApiClient restarted(*url, account.observer_token);
  auto mine = restarted.MyClips();
  ASSERT_TRUE(mine.ok() && mine->size() == 1u);
  const std::string draft = mine->front().id;
  auto parts = restarted.ListParts(draft);
  ASSERT_TRUE(parts.ok()) << parts.error().message;
  int held = 0;
  uint64_t missing_bytes = 0;
  for (const auto& part : parts->parts) {
    if (part.Complete()) {
      ++held;
    } else {
      missing_bytes += PartOnDisk(clip(), part.index).size();
    }
  }
  EXPECT_GE(held, held_at_kill);
  ASSERT_LT(held, kParts) << "the crash came too late to test resuming";

  const auto second = Publish(clip(), *url, account.token);
  ASSERT_EQ(second.exit_code, 0) << second.out << second.err;
  EXPECT_EQ(ClipId(second.out), draft);
  EXPECT_EQ(SummaryValue(second.out, "resumed"), 1);
  EXPECT_EQ(SummaryValue(second.out, "parts_skipped"), held);
  EXPECT_EQ(SummaryValue(second.out, "parts_sent"), kParts - held);
  EXPECT_EQ(SummaryValue(second.out, "bytes_sent"), static_cast<long long>(missing_bytes));
  EXPECT_EQ(VisibleNearby(*url), 1u);
  ExpectClipWholeOn(*url, draft, clip(), kFrames);
  server.Kill(SIGTERM);
  EXPECT_EQ(testing::IntegrityCheck(db_), "ok");
}

TEST_F(PublishResume, UnreachableServerFromTheStartFailsClearlyAndLeavesNothing) {
  const Account account = AddAccount(db_);
  ServerProcess server;
  auto url = server.Start(db_);
  ASSERT_TRUE(url);
  server.Kill(SIGTERM);  // the port is known and now nobody listens on it

  const auto r = Publish(clip(), *url, account.token, {"--retries", "2"});
  EXPECT_FALSE(r.timed_out);
  EXPECT_EQ(r.exit_code, 1);
  ExpectOneLine(r.err);
  EXPECT_NE(r.err.find("cannot reach server"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("gave up after 3 attempts"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("nothing was uploaded"), std::string::npos) << r.err;
  EXPECT_EQ(ClipId(r.out), "");
  // Two retries announced on stdout, with their waits.
  const std::regex retry_line(R"(retrying GET /v1/me/clips\S* in \d+\.\d s \(attempt \d of 3)");
  EXPECT_EQ(std::distance(std::sregex_iterator(r.out.begin(), r.out.end(), retry_line),
                          std::sregex_iterator()),
            2)
      << r.out;

  url = server.Start(db_);
  ASSERT_TRUE(url);
  EXPECT_EQ(VisibleNearby(*url), 0u);
  auto mine = proto::ApiClient(*url, account.observer_token).MyClips();
  ASSERT_TRUE(mine.ok());
  EXPECT_TRUE(mine->empty()) << "a draft was created";
}

TEST_F(PublishResume, PartsDamagedInTheServersStorageAreSentAgain) {
  const Account account = AddAccount(db_);
  ServerProcess server;
  // A token bucket of 12 requests that never refills and no retries: the first run stops
  // after finding no draft (1), creating one (1) and uploading frames 0..9 (10).
  auto url = server.Start(db_, {"--rate-limit", "0.0001", "--rate-burst", "12"});
  ASSERT_TRUE(url);
  const auto first = Publish(clip(), *url, account.token, {"--retries", "0"});
  EXPECT_EQ(first.exit_code, 1) << first.out;
  EXPECT_NE(first.err.find("run the same command again to resume"), std::string::npos) << first.err;
  server.Kill(SIGTERM);

  // Damage two stored frames behind the server's back: one flipped byte (same size) and one
  // truncated. Both are marked present in the metadata.
  std::string draft;
  {
    auto db = server::sqlite::Database::Open(db_);
    ASSERT_TRUE(db.ok());
    auto id = db->Prepare("SELECT public_id FROM clips");
    ASSERT_TRUE(id.ok());
    auto row = id->Step();
    ASSERT_TRUE(row.ok() && *row);
    draft = id->ColumnText(0);
    auto held = db->Prepare(
        "SELECT COUNT(*) FROM clip_parts WHERE present = 1 AND part_index BETWEEN 0 AND 9");
    ASSERT_TRUE(held.ok());
    ASSERT_TRUE(held->Step().ok());
    ASSERT_EQ(held->ColumnInt(0), 10) << "the first run should have stored frames 0..9";
    std::string flipped = PartOnDisk(clip(), 3);
    flipped[flipped.size() / 2] ^= 0x01;
    const std::string truncated = PartOnDisk(clip(), 7).substr(0, 100);
    for (const auto& [index, bytes] : {std::pair<int, std::string>{3, flipped}, {7, truncated}}) {
      auto update = db->Prepare("UPDATE blobs SET data = ?2 WHERE key = ?1");
      ASSERT_TRUE(update.ok());
      update->BindText(1, server::BlobKey(draft, index)).BindBlob(2, bytes);
      ASSERT_TRUE(update->Run().ok());
    }
  }

  url = server.Start(db_, {"--rate-limit", "0"});
  ASSERT_TRUE(url);
  const auto second = Publish(clip(), *url, account.token);
  ASSERT_EQ(second.exit_code, 0) << second.out << second.err;
  EXPECT_EQ(ClipId(second.out), draft);
  EXPECT_EQ(SummaryValue(second.out, "parts_repaired"), 2);
  EXPECT_EQ(SummaryValue(second.out, "parts_skipped"), 8);
  EXPECT_EQ(SummaryValue(second.out, "parts_sent"), kParts - 8);
  EXPECT_NE(second.out.find("copy of frame 3 differs"), std::string::npos) << second.out;
  EXPECT_NE(second.out.find("copy of frame 7 differs"), std::string::npos) << second.out;
  ExpectClipWholeOn(*url, draft, clip(), kFrames);

  // Running it once more finds the clip published and sends nothing.
  const auto third = Publish(clip(), *url, account.token);
  ASSERT_EQ(third.exit_code, 0) << third.err;
  EXPECT_EQ(ClipId(third.out), draft);
  EXPECT_EQ(SummaryValue(third.out, "already_published"), 1);
  EXPECT_EQ(SummaryValue(third.out, "parts_sent"), 0);
  EXPECT_EQ(SummaryValue(third.out, "bytes_sent"), 0);
  server.Kill(SIGTERM);
}

TEST_F(PublishResume, PlainProgressLinesWhenStdoutIsNotATerminal) {
  const Account account = AddAccount(db_);
  ServerProcess server;
  auto url = server.Start(db_);
  ASSERT_TRUE(url);
  const auto r = Publish(clip(), *url, account.token);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.find('\r'), std::string::npos) << "a terminal bar in a pipe";
  const std::regex line_form(R"(^progress +(\d+)% \((\d+)/41 parts, [0-9.]+/[0-9.]+ [kMG]?B\) )"
                             R"((-- B/s|[0-9.]+ [kMG]?B/s) ETA (--|\d+ s|\d+ min \d+ s)$)");
  std::vector<int> percents;
  std::istringstream lines(r.out);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("progress", 0) != 0) continue;
    std::smatch m;
    ASSERT_TRUE(std::regex_match(line, m, line_form)) << line;
    percents.push_back(std::stoi(m[1].str()));
  }
  ASSERT_FALSE(percents.empty()) << r.out;
  EXPECT_EQ(percents.front(), 0);
  EXPECT_EQ(percents.back(), 100);
  EXPECT_TRUE(std::is_sorted(percents.begin(), percents.end()));
  // A line in every tenth: 41 parts of similar size cross each tenth on its own part.
  for (int tenth = 1; tenth <= 9; ++tenth) {
    EXPECT_TRUE(
        std::any_of(percents.begin(), percents.end(), [&](int p) { return p / 10 == tenth; }))
        << "no line in " << tenth * 10 << "%..: " << r.out;
  }
  EXPECT_NE(r.out.find("progress 100% (41/41 parts"), std::string::npos) << r.out;
  EXPECT_LE(percents.size(), 20u) << "plain mode should not print a line per part";
  server.Kill(SIGTERM);
}

}  // namespace
}  // namespace reenact
