// 16 concurrent synthetic clients against the real reenact-server: uploading (with resent
// parts), publishing, browsing and downloading at once. Afterwards every clip is whole and
// every nearby answer equals the one computed here from the clips' known places.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <map>
#include <mutex>
#include <set>

#include "proto/api/api_client.h"
#include "server/auth/token.h"
#include "server/storage/open_storage.h"
#include "tests/integration/server_harness.h"

namespace reenact {
namespace {

using testing::MakeSyntheticClip;
using testing::SyntheticClip;

constexpr int kClients = 16;
constexpr int kClipsPerClient = 3;
constexpr int kFrames = 6;
constexpr size_t kFrameBytes = 24 * 1024;
constexpr double kLat0 = 48.0, kLon0 = 11.0;

// Clip (client c, k) sits on a grid with 0.01 deg steps (about 1.1 km north, 0.74 km east).
SyntheticClip ClipOf(int client, int k) {
  const double lat = kLat0 + 0.01 * client, lon = kLon0 + 0.01 * k;
  return MakeSyntheticClip(lat, lon, kFrames, kFrameBytes, 1000 * client + k,
                           "c" + std::to_string(client) + "k" + std::to_string(k));
}

TEST(ServerLoad, SixteenConcurrentClientsLeaveEveryClipWholeAndNearbyRight) {
  testing::TempDir tmp;
  const std::string db = tmp.path() + "/load.db";
  std::vector<std::string> tokens;
  {
    auto storage = server::OpenSqliteStorage(db);
    ASSERT_TRUE(storage.ok()) << storage.error().message;
    for (int c = 0; c < kClients; ++c) {
      auto token = server::AddUserWithToken(*storage->metadata, "user" + std::to_string(c));
      ASSERT_TRUE(token.ok());
      tokens.push_back(*token);
    }
  }
  testing::ServerProcess server;
  auto url = server.Start(db, {"--threads", "4"});
  ASSERT_TRUE(url.has_value());

  std::vector<std::vector<SyntheticClip>> clips(kClients);
  for (int c = 0; c < kClients; ++c)
    for (int k = 0; k < kClipsPerClient; ++k) clips[c].push_back(ClipOf(c, k));

  std::mutex mutex;
  std::map<std::string, const SyntheticClip*> published;  // id -> clip
  std::vector<std::string> failures;
  std::atomic<int> browsed{0};
  auto fail = [&](std::string what) {
    std::lock_guard lock(mutex);
    failures.push_back(std::move(what));
  };

  std::vector<std::thread> threads;
  for (int c = 0; c < kClients; ++c) {
    threads.emplace_back([&, c] {
      proto::ApiClient api(*url, tokens[c]);
      proto::ApiClient anonymous(*url, "");
      std::mt19937 rng(c);
      for (int k = 0; k < kClipsPerClient; ++k) {
        const SyntheticClip& clip = clips[c][k];
        auto id = api.CreateClip(clip.manifest_json);
        if (!id) return fail("create: " + id.error().message);
        std::vector<int> order(kFrames);
        for (int i = 0; i < kFrames; ++i) order[i] = i;
        std::shuffle(order.begin(), order.end(), rng);
        order.push_back(order[0]);  // a resumed upload sends a part twice
        for (int n : order) {
          if (auto s = api.PutFrame(*id, n, clip.frames[n]); !s) {
            return fail("put frame: " + s.error().message);
          }
        }
        if (auto s = api.PutMap(*id, clip.map); !s) return fail("put map: " + s.error().message);
        if (auto s = api.Publish(*id); !s) return fail("publish: " + s.error().message);
        {
          std::lock_guard lock(mutex);
          published[*id] = &clip;
        }
        // Browse somewhere and download one clip found: published means whole, always.
        std::uniform_int_distribution<int> row(0, kClients - 1);
        auto found = anonymous.Nearby(kLat0 + 0.01 * row(rng), kLon0, 3000, 50);
        if (!found) return fail("nearby: " + found.error().message);
        ++browsed;
        if (found->empty()) continue;
        const proto::ClipSummary& pick = (*found)[rng() % found->size()];
        const SyntheticClip* expected = nullptr;
        {
          std::lock_guard lock(mutex);
          auto it = published.find(pick.id);
          if (it != published.end()) expected = it->second;
        }
        if (expected == nullptr) {
          // Published by a client that has not recorded it yet: check what we can.
          auto manifest = anonymous.GetManifest(pick.id);
          if (!manifest) fail("manifest of a listed clip: " + manifest.error().message);
          continue;
        }
        auto frame = anonymous.GetFrame(pick.id, kFrames - 1);
        if (!frame || *frame != expected->frames[kFrames - 1]) fail("frame differs: " + pick.id);
      }
    });
  }
  for (auto& t : threads) t.join();
  ASSERT_TRUE(failures.empty()) << failures.size() << " failures, first: " << failures[0];
  EXPECT_EQ(browsed.load(), kClients * kClipsPerClient);
  ASSERT_EQ(published.size(), static_cast<size_t>(kClients * kClipsPerClient));

  proto::ApiClient anonymous(*url, "");
  for (const auto& [id, clip] : published) {
    auto manifest = anonymous.GetManifest(id);
    ASSERT_TRUE(manifest.ok()) << manifest.error().message;
    EXPECT_EQ(*manifest, clip->manifest_json);
    for (int n = 0; n < kFrames; ++n) {
      auto frame = anonymous.GetFrame(id, n);
      ASSERT_TRUE(frame.ok()) << frame.error().message;
      EXPECT_EQ(*frame, clip->frames[n]) << id << " frame " << n;
    }
    auto map = anonymous.GetMap(id);
    ASSERT_TRUE(map.ok());
    EXPECT_EQ(*map, clip->map);
  }

  // Nearby from query points between grid nodes (no clip near the radius' edge): the answer
  // is exactly the clips within the radius by the reference formula, nearest first.
  for (const auto& [qlat, qlon, radius] : std::vector<std::tuple<double, double, double>>{
           {48.053, 11.004, 2500}, {48.0, 11.0, 5}, {48.151, 11.016, 5000}, {47.9, 11.0, 900}}) {
    std::vector<std::pair<double, std::string>> expected;
    for (const auto& [id, clip] : published) {
      const double d = testing::ReferenceDistanceM(qlat, qlon, clip->lat, clip->lon);
      ASSERT_GT(std::abs(d - radius), 1.0) << "test geometry puts a clip on the radius";
      if (d <= radius) expected.emplace_back(d, id);
    }
    std::sort(expected.begin(), expected.end());
    std::vector<std::pair<double, std::string>> got;
    std::string cursor;
    for (int page = 0; page < 20; ++page) {
      auto answer = anonymous.NearbyPageAt(qlat, qlon, radius, 4, cursor);
      ASSERT_TRUE(answer.ok()) << answer.error().message;
      for (const auto& s : answer->clips) got.emplace_back(s.distance_m, s.id);
      if (!answer->next_cursor) break;
      cursor = *answer->next_cursor;
    }
    ASSERT_EQ(got.size(), expected.size()) << qlat << "," << qlon << " r=" << radius;
    for (size_t i = 0; i < got.size(); ++i) {
      EXPECT_EQ(got[i].second, expected[i].second);
      EXPECT_NEAR(got[i].first, expected[i].first, 0.01);
    }
  }
  EXPECT_EQ(server.Kill(SIGTERM), 0);
  EXPECT_EQ(testing::IntegrityCheck(db), "ok");
}

}  // namespace
}  // namespace reenact
