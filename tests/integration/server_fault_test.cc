// Crashes: the real reenact-server killed with SIGKILL in the middle of uploads and of
// publishes, then restarted on the same database. Afterwards PRAGMA integrity_check is ok,
// every acknowledged write is there, published clips are whole, and drafts resume.
#include <gtest/gtest.h>

#include <atomic>
#include <mutex>

#include "proto/api/api_client.h"
#include "server/auth/token.h"
#include "server/storage/open_storage.h"
#include "tests/integration/server_harness.h"

namespace reenact {
namespace {

using testing::MakeSyntheticClip;
using testing::SyntheticClip;

std::string AddUser(const std::string& db, const std::string& name) {
  auto storage = server::OpenSqliteStorage(db);
  EXPECT_TRUE(storage.ok()) << storage.error().message;
  auto token = server::AddUserWithToken(*storage->metadata, name);
  EXPECT_TRUE(token.ok());
  return *token;
}

// Every part of a published clip downloads and equals what was uploaded.
void ExpectWhole(const proto::ApiClient& api, const std::string& id, const SyntheticClip& clip) {
  auto manifest = api.GetManifest(id);
  ASSERT_TRUE(manifest.ok()) << manifest.error().message;
  EXPECT_EQ(*manifest, clip.manifest_json);
  for (size_t n = 0; n < clip.frames.size(); ++n) {
    auto frame = api.GetFrame(id, static_cast<int64_t>(n));
    ASSERT_TRUE(frame.ok()) << id << " frame " << n << ": " << frame.error().message;
    EXPECT_EQ(*frame, clip.frames[n]);
  }
  auto map = api.GetMap(id);
  ASSERT_TRUE(map.ok()) << map.error().message;
  EXPECT_EQ(*map, clip.map);
}

TEST(ServerFault, KillDuringUploadThenRestartAndResume) {
  testing::TempDir tmp;
  const std::string db = tmp.path() + "/fault.db";
  const std::string token = AddUser(db, "uploader");
  const SyntheticClip clip = MakeSyntheticClip(35.0, 135.0, 60, 256 * 1024, 7, "crash");
  std::string id;
  std::vector<int> acknowledged;
  {
    testing::ServerProcess server;
    auto url = server.Start(db, {"--rate-limit", "0"});
    ASSERT_TRUE(url.has_value());
    proto::ApiClient api(*url, token);
    auto created = api.CreateClip(clip.manifest_json);
    ASSERT_TRUE(created.ok()) << created.error().message;
    id = *created;
    std::mutex mutex;
    std::atomic<int> next{0};
    std::vector<std::thread> uploaders;
    for (int t = 0; t < 4; ++t) {
      uploaders.emplace_back([&] {
        for (int n; (n = next++) < static_cast<int>(clip.frames.size());) {
          if (!api.PutFrame(id, n, clip.frames[n])) return;  // the server died
          std::lock_guard lock(mutex);
          acknowledged.push_back(n);
        }
      });
    }
    // Kill once a few frames are acknowledged, while the others are in flight.
    while (true) {
      {
        std::lock_guard lock(mutex);
        if (acknowledged.size() >= 8) break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    server.Kill(SIGKILL);
    for (auto& u : uploaders) u.join();
  }
  ASSERT_LT(acknowledged.size(), clip.frames.size()) << "the kill came too late to test much";
  EXPECT_EQ(testing::IntegrityCheck(db), "ok");

  testing::ServerProcess server;
  auto url = server.Start(db);
  ASSERT_TRUE(url.has_value()) << "restart failed";
  proto::ApiClient api(*url, token);
  // The draft survived, invisible to others, and every acknowledged frame is intact.
  auto mine = api.MyClips();
  ASSERT_TRUE(mine.ok());
  ASSERT_EQ(mine->size(), 1u);
  EXPECT_EQ((*mine)[0].id, id);
  EXPECT_FALSE(proto::ApiClient(*url, "").GetManifest(id).ok());
  for (int n : acknowledged) {
    auto frame = api.GetFrame(id, n);
    ASSERT_TRUE(frame.ok()) << "acknowledged frame " << n << " lost: " << frame.error().message;
    EXPECT_EQ(*frame, clip.frames[n]);
  }
  auto early = api.Publish(id);
  ASSERT_FALSE(early.ok());
  EXPECT_EQ(early.error().code, "incomplete");
  // Resume: send everything again (idempotent), then publish.
  for (size_t n = 0; n < clip.frames.size(); ++n) {
    ASSERT_TRUE(api.PutFrame(id, static_cast<int64_t>(n), clip.frames[n]).ok());
  }
  ASSERT_TRUE(api.PutMap(id, clip.map).ok());
  ASSERT_TRUE(api.Publish(id).ok());
  ExpectWhole(proto::ApiClient(*url, ""), id, clip);
}

TEST(ServerFault, KillDuringPublishesLeavesEachClipPublishedWholeOrAResumableDraft) {
  testing::TempDir tmp;
  const std::string db = tmp.path() + "/fault.db";
  const std::string token = AddUser(db, "publisher");
  constexpr int kClips = 40;
  std::vector<SyntheticClip> clips;
  for (int i = 0; i < kClips; ++i) {
    const std::string title = std::string("p").append(std::to_string(i));  // GCC 12 -Wrestrict
    clips.push_back(MakeSyntheticClip(10.0 + 0.001 * i, 20.0, 2, 4096, 100 + i, title));
  }
  std::vector<std::string> ids;
  std::vector<int> acknowledged;
  {
    testing::ServerProcess server;
    auto url = server.Start(db, {"--rate-limit", "0"});
    ASSERT_TRUE(url.has_value());
    proto::ApiClient api(*url, token);
    for (const SyntheticClip& clip : clips) {
      auto id = api.CreateClip(clip.manifest_json);
      ASSERT_TRUE(id.ok());
      for (size_t n = 0; n < clip.frames.size(); ++n) {
        ASSERT_TRUE(api.PutFrame(*id, static_cast<int64_t>(n), clip.frames[n]).ok());
      }
      ASSERT_TRUE(api.PutMap(*id, clip.map).ok());
      ids.push_back(*id);
    }
    std::mutex mutex;
    std::atomic<int> next{0};
    std::vector<std::thread> publishers;
    for (int t = 0; t < 4; ++t) {
      publishers.emplace_back([&] {
        for (int i; (i = next++) < kClips;) {
          if (!api.Publish(ids[i])) return;
          std::lock_guard lock(mutex);
          acknowledged.push_back(i);
        }
      });
    }
    while (next < 6) std::this_thread::yield();
    server.Kill(SIGKILL);
    for (auto& p : publishers) p.join();
  }
  EXPECT_EQ(testing::IntegrityCheck(db), "ok");

  testing::ServerProcess server;
  auto url = server.Start(db);
  ASSERT_TRUE(url.has_value()) << "restart failed";
  proto::ApiClient api(*url, token);
  proto::ApiClient anonymous(*url, "");
  auto listed = anonymous.Nearby(10.02, 20.0, 50000, 100);
  ASSERT_TRUE(listed.ok());
  std::set<std::string> visible;
  for (const auto& s : *listed) visible.insert(s.id);
  for (int i : acknowledged) EXPECT_TRUE(visible.count(ids[i])) << "acknowledged publish lost";
  for (int i = 0; i < kClips; ++i) {
    if (visible.count(ids[i])) {
      ExpectWhole(anonymous, ids[i], clips[i]);
    } else {
      // Still a draft with every part: publishing now succeeds.
      ASSERT_TRUE(api.Publish(ids[i]).ok()) << "draft " << i << " is not resumable";
      ExpectWhole(anonymous, ids[i], clips[i]);
    }
  }
}

}  // namespace
}  // namespace reenact
