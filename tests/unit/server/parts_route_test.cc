// GET /v1/clips/{id}/parts, GET /v1/me/clips?manifest_sha256=, and how PUT and publish treat
// a part whose stored copy was damaged: the routes a resumable upload relies on. On each
// storage engine (SQLite with blobs in the database or as files; PostgreSQL where the tests'
// cluster can be started).
#include <gtest/gtest.h>

#include "proto/api/api_types.h"
#include "tests/unit/server/server_test_util.h"

namespace reenact::server {
namespace {

using nlohmann::json;
using testing::MakeTestClip;
using testing::TestClip;

class PartsRouteTest : public testing::EngineServiceFixture {};
INSTANTIATE_TEST_SUITE_P(Engines, PartsRouteTest,
                         ::testing::Values(testing::Engine::kSqlite, testing::Engine::kPostgres,
                                           testing::Engine::kSqliteFiles),
                         testing::EngineName);

proto::ClipParts Parts(const Response& r) {
  EXPECT_EQ(r.status, 200) << r.body;
  auto parsed = proto::ParseClipParts(r.body);
  EXPECT_TRUE(parsed.ok()) << (parsed.ok() ? "" : parsed.error().message);
  return parsed.ok() ? *parsed : proto::ClipParts{};
}

TEST_P(PartsRouteTest, ListsEveryPartWithWhatTheServerHolds) {
  const TestClip clip = MakeTestClip(1, 2, 3);
  const std::string id = Create(clip, alice_);
  proto::ClipParts parts = Parts(Call("GET", "/v1/clips/" + id + "/parts", alice_));
  EXPECT_EQ(parts.id, id);
  EXPECT_FALSE(parts.published);
  ASSERT_EQ(parts.parts.size(), 4u);  // frames 0, 1, 2 then the map
  for (int n = 0; n < 3; ++n) {
    EXPECT_EQ(parts.parts[n].index, n);
    EXPECT_EQ(parts.parts[n].bytes, clip.frames[n].size());
    EXPECT_EQ(parts.parts[n].sha256, proto::Sha256Hex(clip.frames[n]));
    EXPECT_FALSE(parts.parts[n].held);
  }
  EXPECT_EQ(parts.parts[3].index, proto::kMapPartIndex);
  EXPECT_EQ(parts.parts[3].sha256, proto::Sha256Hex(clip.map));

  ASSERT_EQ(Call("PUT", "/v1/clips/" + id + "/frames/1", alice_, clip.frames[1],
                 "application/octet-stream")
                .status,
            204);
  ASSERT_EQ(
      Call("PUT", "/v1/clips/" + id + "/map", alice_, clip.map, "application/octet-stream").status,
      204);
  parts = Parts(Call("GET", "/v1/clips/" + id + "/parts", alice_));
  ASSERT_EQ(parts.parts.size(), 4u);
  EXPECT_FALSE(parts.parts[0].held);
  ASSERT_TRUE(parts.parts[1].held);
  EXPECT_EQ(parts.parts[1].held->bytes, clip.frames[1].size());
  EXPECT_EQ(parts.parts[1].held->sha256, proto::Sha256Hex(clip.frames[1]));
  EXPECT_TRUE(parts.parts[1].Complete());
  EXPECT_TRUE(parts.parts[3].Complete());
  EXPECT_FALSE(parts.parts[2].Complete());
}

TEST_P(PartsRouteTest, DamagedStoredPartIsReportedRefusedAtPublishAndRepairedByPut) {
  const TestClip clip = MakeTestClip(1, 2, 2);
  const std::string id = Create(clip, alice_);
  for (int n = 0; n < 2; ++n) {
    ASSERT_EQ(Call("PUT", "/v1/clips/" + id + "/frames/" + std::to_string(n), alice_,
                   clip.frames[n], "application/octet-stream")
                  .status,
              204);
  }
  ASSERT_EQ(
      Call("PUT", "/v1/clips/" + id + "/map", alice_, clip.map, "application/octet-stream").status,
      204);
  // The stored copy of frame 1 goes bad behind the server's back (disk, operator, bug).
  std::string damaged = clip.frames[1];
  damaged[3] ^= 0x40;
  ASSERT_TRUE(storage_.blobs->Put(BlobKey(id, 1), damaged).ok());

  proto::ClipParts parts = Parts(Call("GET", "/v1/clips/" + id + "/parts", alice_));
  ASSERT_TRUE(parts.parts[1].held);
  EXPECT_EQ(parts.parts[1].held->sha256, proto::Sha256Hex(damaged));
  EXPECT_FALSE(parts.parts[1].Complete());
  EXPECT_TRUE(parts.parts[0].Complete());

  Response refused = Call("POST", "/v1/clips/" + id + "/publish", alice_);
  EXPECT_EQ(refused.status, 409);
  EXPECT_EQ(ErrorCode(refused), "incomplete");
  EXPECT_NE(ErrorMessage(refused).find("frame 1 differs"), std::string::npos)
      << ErrorMessage(refused);
  EXPECT_TRUE(json::parse(Call("GET", "/v1/clips?near=1,2&radius_m=10").body)["clips"].empty());

  // Sending the part again (already marked present) rewrites the stored copy.
  ASSERT_EQ(Call("PUT", "/v1/clips/" + id + "/frames/1", alice_, clip.frames[1],
                 "application/octet-stream")
                .status,
            204);
  parts = Parts(Call("GET", "/v1/clips/" + id + "/parts", alice_));
  EXPECT_TRUE(parts.parts[1].Complete());
  EXPECT_EQ(Call("POST", "/v1/clips/" + id + "/publish", alice_).status, 200);
  Response got = Call("GET", "/v1/clips/" + id + "/frames/1");
  EXPECT_EQ(got.body, clip.frames[1]);
  EXPECT_TRUE(Parts(Call("GET", "/v1/clips/" + id + "/parts", alice_)).published);
}

TEST_P(PartsRouteTest, PartsLargerThanOneReadAreHashedWhole) {
  TestClip clip;
  clip.frames = {std::string(size_t{5} << 19, 'a') + "tail", "short frame"};  // 2.5 MiB + 4
  clip.frames[0][size_t{1} << 20] = 'b';  // a byte at the start of the second 1 MiB piece
  clip.map = "map";
  clip.manifest_json = testing::TestManifestJson(1, 2, "large", "tester", clip.frames, clip.map);
  const std::string id = Create(clip, alice_);
  for (int n = 0; n < 2; ++n) {
    ASSERT_EQ(Call("PUT", "/v1/clips/" + id + "/frames/" + std::to_string(n), alice_,
                   clip.frames[n], "application/octet-stream")
                  .status,
              204);
  }
  proto::ClipParts parts = Parts(Call("GET", "/v1/clips/" + id + "/parts", alice_));
  ASSERT_EQ(parts.parts.size(), 3u);
  ASSERT_TRUE(parts.parts[0].held);
  EXPECT_EQ(parts.parts[0].held->bytes, clip.frames[0].size());
  EXPECT_EQ(parts.parts[0].held->sha256, proto::Sha256Hex(clip.frames[0]));
  EXPECT_TRUE(parts.parts[1].Complete());
  ASSERT_EQ(
      Call("PUT", "/v1/clips/" + id + "/map", alice_, clip.map, "application/octet-stream").status,
      204);
  EXPECT_EQ(Call("POST", "/v1/clips/" + id + "/publish", alice_).status, 200);
}

// A reader whose every Read fails as if the payload had been replaced since Open.
class ReplacedReader : public BlobReader {
 public:
  explicit ReplacedReader(uint64_t size) : size_(size) {}
  uint64_t size() const override { return size_; }
  Expected<size_t> Read(uint64_t, std::span<char>) override {
    return MakeError("changed", "replaced while being read");
  }

 private:
  uint64_t size_;
};

// Forwards to a real store, except that the first `replaced` OpenReader calls of a present key
// give a ReplacedReader.
class ReplacingBlobStore : public BlobStore {
 public:
  ReplacingBlobStore(BlobStore& store, int replaced) : store_(store), replaced_(replaced) {}
  Status Put(const std::string& key, std::string_view bytes) override {
    return store_.Put(key, bytes);
  }
  Expected<std::optional<std::string>> Get(const std::string& key) override {
    return store_.Get(key);
  }
  Expected<std::unique_ptr<BlobReader>> OpenReader(const std::string& key) override {
    auto reader = store_.OpenReader(key);
    if (!reader || !*reader || replaced_ == 0) return reader;
    --replaced_;
    return std::unique_ptr<BlobReader>(new ReplacedReader((*reader)->size()));
  }
  Status DeletePrefix(const std::string& prefix) override { return store_.DeletePrefix(prefix); }
  Expected<std::vector<std::string>> ListKeys() override { return store_.ListKeys(); }

 private:
  BlobStore& store_;
  int replaced_;
};

TEST_P(PartsRouteTest, PartReplacedWhileHashedIsHashedOnceMore) {
  const TestClip clip = MakeTestClip(1, 2, 1);
  const std::string id = Publish(clip, alice_);
  Request request;
  request.method = "GET";
  request.target = "/v1/clips/" + id + "/parts";
  request.headers.emplace_back("Authorization", "Bearer " + alice_);

  ReplacingBlobStore once(*storage_.blobs, 1);
  ServiceContext retried{*storage_.metadata, once, metrics_, ServiceLimits{}};
  proto::ClipParts parts = Parts(Handle(request, retried));
  ASSERT_EQ(parts.parts.size(), 2u);
  EXPECT_TRUE(parts.parts[0].Complete());
  EXPECT_TRUE(parts.parts[1].Complete());

  ReplacingBlobStore twice(*storage_.blobs, 2);  // replaced again during the second try
  ServiceContext failed{*storage_.metadata, twice, metrics_, ServiceLimits{}};
  EXPECT_EQ(Handle(request, failed).status, 500);
}

TEST_P(PartsRouteTest, PartsAreTheOwnersOnly) {
  const TestClip clip = MakeTestClip(1, 2, 1);
  const std::string draft = Create(clip, alice_);
  EXPECT_EQ(Call("GET", "/v1/clips/" + draft + "/parts").status, 401);
  EXPECT_EQ(Call("GET", "/v1/clips/" + draft + "/parts", bob_).status, 404);
  EXPECT_EQ(Call("GET", "/v1/clips/nosuchclip/parts", alice_).status, 404);
  Response wrong = Call("POST", "/v1/clips/" + draft + "/parts", alice_);
  EXPECT_EQ(wrong.status, 405);
  const std::string published = Publish(MakeTestClip(3, 4, 1, "pub"), alice_);
  EXPECT_EQ(Call("GET", "/v1/clips/" + published + "/parts", bob_).status, 403);
}

TEST_P(PartsRouteTest, MyClipsFindsTheDraftOfAManifest) {
  const TestClip a = MakeTestClip(1, 2, 1, "a");
  const TestClip b = MakeTestClip(1, 2, 1, "b");
  const std::string id_a = Create(a, alice_);
  Create(b, alice_);
  Create(a, bob_);  // the same manifest by someone else is not alice's
  const std::string hash_a = proto::Sha256Hex(a.manifest_json);
  Response r = Call("GET", "/v1/me/clips?manifest_sha256=" + hash_a, alice_);
  ASSERT_EQ(r.status, 200) << r.body;
  auto mine = proto::ParseOwnClips(r.body);
  ASSERT_TRUE(mine.ok()) << mine.error().message;
  ASSERT_EQ(mine->size(), 1u);
  EXPECT_EQ((*mine)[0].summary.id, id_a);
  EXPECT_FALSE((*mine)[0].published);
  EXPECT_EQ((*mine)[0].manifest_sha256, hash_a);

  const std::string unknown(64, '0');
  r = Call("GET", "/v1/me/clips?manifest_sha256=" + unknown, alice_);
  ASSERT_EQ(r.status, 200);
  EXPECT_TRUE(json::parse(r.body)["clips"].empty());
  // Without the filter: both of alice's clips.
  EXPECT_EQ(json::parse(Call("GET", "/v1/me/clips", alice_).body)["clips"].size(), 2u);
}

TEST_P(PartsRouteTest, MyClipsRejectsMalformedFilters) {
  Response r = Call("GET", "/v1/me/clips?manifest_sha256=ABC", alice_);
  EXPECT_EQ(r.status, 400);
  EXPECT_EQ(ErrorCode(r), "bad_request");
  EXPECT_NE(ErrorMessage(r).find("64 lowercase hex"), std::string::npos);
  r = Call("GET", "/v1/me/clips?owner=1", alice_);
  EXPECT_EQ(r.status, 400);
  EXPECT_NE(ErrorMessage(r).find("'owner'"), std::string::npos);
  r = Call("GET", "/v1/me/clips?manifest_sha256=%zz", alice_);
  EXPECT_EQ(r.status, 400);
}

TEST(ClipPartsJson, RoundTripsAndRejectsMalformedListings) {
  proto::ClipParts parts;
  parts.id = "abc";
  parts.parts.push_back({0, 10, std::string(64, 'a'), proto::HeldBytes{10, std::string(64, 'a')}});
  parts.parts.push_back({proto::kMapPartIndex, 5, std::string(64, 'b'), std::nullopt});
  auto back = proto::ParseClipParts(proto::ClipPartsToJson(parts).dump());
  ASSERT_TRUE(back.ok()) << back.error().message;
  ASSERT_EQ(back->parts.size(), 2u);
  EXPECT_EQ(back->parts[0].index, 0);
  EXPECT_TRUE(back->parts[0].Complete());
  EXPECT_EQ(back->parts[1].index, proto::kMapPartIndex);
  EXPECT_FALSE(back->parts[1].held);

  EXPECT_FALSE(proto::ParseClipParts("[1,2]").ok());
  EXPECT_FALSE(proto::ParseClipParts(R"({"id":"a","state":"draft"})").ok());
  auto bad_name = proto::ParseClipParts(
      R"({"id":"a","state":"draft","parts":[{"part":"frames/x","bytes":1,"sha256":"h","held":null}]})");
  ASSERT_FALSE(bad_name.ok());
  EXPECT_NE(bad_name.error().message.find("frames/x"), std::string::npos);
  auto bad_held = proto::ParseClipParts(
      R"({"id":"a","state":"draft","parts":[{"part":"map","bytes":1,"sha256":"h","held":3}]})");
  ASSERT_FALSE(bad_held.ok());
  EXPECT_NE(bad_held.error().message.find("held"), std::string::npos);
}

}  // namespace
}  // namespace reenact::server
