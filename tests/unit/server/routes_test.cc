// Route handlers without sockets, on real storage of each engine: SQLite in a temp dir (blobs
// in the database or as files), and PostgreSQL in the tests' throwaway cluster (skipped with a
// message where none is installed).
#include "server/http/routes.h"

#include <gtest/gtest.h>

#include "tests/unit/server/server_test_util.h"

namespace reenact::server {
namespace {

using nlohmann::json;
using testing::MakeTestClip;
using testing::TestClip;

class RoutesTest : public testing::EngineServiceFixture {};
INSTANTIATE_TEST_SUITE_P(Engines, RoutesTest,
                         ::testing::Values(testing::Engine::kSqlite, testing::Engine::kPostgres,
                                           testing::Engine::kSqliteFiles),
                         testing::EngineName);

std::optional<std::string> HeaderOf(const Response& r, const std::string& name) {
  return proto::FindHeader(r.headers, name);
}

TEST_P(RoutesTest, CreateWithoutTokenIs401) {
  const TestClip clip = MakeTestClip(1, 2);
  Response r = Call("POST", "/v1/clips", "", clip.manifest_json, "application/json");
  EXPECT_EQ(r.status, 401);
  EXPECT_EQ(ErrorCode(r), "unauthorized");
  EXPECT_TRUE(HeaderOf(r, "WWW-Authenticate").has_value());
}

TEST_P(RoutesTest, CreateWithUnknownTokenIs401) {
  const TestClip clip = MakeTestClip(1, 2);
  Response r =
      Call("POST", "/v1/clips", "rnk_not-a-real-token", clip.manifest_json, "application/json");
  EXPECT_EQ(r.status, 401);
  Request basic;
  basic.method = "POST";
  basic.target = "/v1/clips";
  basic.headers = {{"Authorization", "Basic YWxpY2U6eA=="}, {"Content-Type", "application/json"}};
  basic.body = clip.manifest_json;
  EXPECT_EQ(Handle(basic, *context_).status, 401);
}

TEST_P(RoutesTest, CreateRejectsWrongContentType) {
  Response r = Call("POST", "/v1/clips", alice_, MakeTestClip(1, 2).manifest_json, "text/plain");
  EXPECT_EQ(r.status, 415);
  EXPECT_EQ(ErrorCode(r), "unsupported_media_type");
}

TEST_P(RoutesTest, CreateRejectsMalformedJson) {
  Response r = Call("POST", "/v1/clips", alice_, "{\"title\": ", "application/json");
  EXPECT_EQ(r.status, 400);
  EXPECT_EQ(ErrorCode(r), "bad_request");
}

TEST_P(RoutesTest, CreateRejectsInvalidManifestWith422) {
  json manifest = json::parse(MakeTestClip(1, 2).manifest_json);
  manifest["location"]["lat_deg"] = 95.0;
  Response r = Call("POST", "/v1/clips", alice_, manifest.dump(), "application/json");
  EXPECT_EQ(r.status, 422);
  EXPECT_EQ(ErrorCode(r), "invalid_manifest");
  EXPECT_NE(ErrorMessage(r).find("lat_deg"), std::string::npos);
}

TEST_P(RoutesTest, CreateRejectsAManifestWithARepeatedKeyWith422) {
  const std::string manifest = MakeTestClip(1, 2).manifest_json;
  ASSERT_EQ(manifest.find('{'), 0u);
  // A second "title" first in the object; the parser would otherwise keep the last one.
  const std::string repeated = "{\"title\": \"shadow\"," + manifest.substr(1);
  Response r = Call("POST", "/v1/clips", alice_, repeated, "application/json");
  EXPECT_EQ(r.status, 422) << r.body;
  EXPECT_EQ(ErrorCode(r), "invalid_manifest");
  EXPECT_NE(ErrorMessage(r).find("key title appears more than once"), std::string::npos)
      << ErrorMessage(r);
  EXPECT_EQ(Call("POST", "/v1/clips", alice_, manifest, "application/json").status, 201);
}

TEST_P(RoutesTest, CreateRejectsOversizedManifestWith413) {
  context_->limits.max_manifest_bytes = 100;
  Response r =
      Call("POST", "/v1/clips", alice_, MakeTestClip(1, 2).manifest_json, "application/json");
  EXPECT_EQ(r.status, 413);
}

TEST_P(RoutesTest, CreateRejectsFrameDeclaredBeyondLimit) {
  context_->limits.max_frame_bytes = 5;
  Response r =
      Call("POST", "/v1/clips", alice_, MakeTestClip(1, 2).manifest_json, "application/json");
  EXPECT_EQ(r.status, 422);
  EXPECT_NE(ErrorMessage(r).find("frame 0"), std::string::npos);
}

TEST_P(RoutesTest, PutChecksSizeAndHashAgainstManifest) {
  const TestClip clip = MakeTestClip(1, 2);
  const std::string id = Create(clip, alice_);
  const std::string target = "/v1/clips/" + id + "/frames/0";
  Response shorter = Call("PUT", target, alice_, clip.frames[0] + "!", "application/octet-stream");
  EXPECT_EQ(shorter.status, 422);
  EXPECT_EQ(ErrorCode(shorter), "size_mismatch");
  std::string flipped = clip.frames[0];
  flipped[0] ^= 1;
  Response corrupt = Call("PUT", target, alice_, flipped, "application/octet-stream");
  EXPECT_EQ(corrupt.status, 422);
  EXPECT_EQ(ErrorCode(corrupt), "hash_mismatch");
  EXPECT_EQ(Call("PUT", target, alice_, clip.frames[0], "text/plain").status, 415);
}

TEST_P(RoutesTest, PutRejectsBadFrameNumbers) {
  const TestClip clip = MakeTestClip(1, 2, 3);
  const std::string id = Create(clip, alice_);
  EXPECT_EQ(Call("PUT", "/v1/clips/" + id + "/frames/3", alice_, clip.frames[0],
                 "application/octet-stream")
                .status,
            404);
  EXPECT_EQ(Call("PUT", "/v1/clips/" + id + "/frames/-1", alice_, clip.frames[0],
                 "application/octet-stream")
                .status,
            400);
  EXPECT_EQ(Call("PUT", "/v1/clips/" + id + "/frames/x", alice_, clip.frames[0],
                 "application/octet-stream")
                .status,
            400);
}

TEST_P(RoutesTest, PutIsIdempotent) {
  const TestClip clip = MakeTestClip(1, 2);
  const std::string id = Create(clip, alice_);
  const std::string target = "/v1/clips/" + id + "/frames/1";
  EXPECT_EQ(Call("PUT", target, alice_, clip.frames[1], "application/octet-stream").status, 204);
  EXPECT_EQ(Call("PUT", target, alice_, clip.frames[1], "application/octet-stream").status, 204);
  Response got = Call("GET", target, alice_);
  EXPECT_EQ(got.status, 200);
  EXPECT_EQ(got.body, clip.frames[1]);
}

TEST_P(RoutesTest, OtherUsersCannotWriteOrSeeADraft) {
  const TestClip clip = MakeTestClip(1, 2);
  const std::string id = Create(clip, alice_);
  EXPECT_EQ(
      Call("PUT", "/v1/clips/" + id + "/map", bob_, clip.map, "application/octet-stream").status,
      404);
  EXPECT_EQ(Call("GET", "/v1/clips/" + id, bob_).status, 404);
  EXPECT_EQ(Call("GET", "/v1/clips/" + id).status, 404);
  EXPECT_EQ(Call("GET", "/v1/clips/" + id, alice_).status, 200);
}

TEST_P(RoutesTest, PublishNamesMissingPartsThenSucceeds) {
  const TestClip clip = MakeTestClip(1, 2, 3);
  const std::string id = Create(clip, alice_);
  ASSERT_EQ(Call("PUT", "/v1/clips/" + id + "/frames/0", alice_, clip.frames[0],
                 "application/octet-stream")
                .status,
            204);
  Response early = Call("POST", "/v1/clips/" + id + "/publish", alice_);
  EXPECT_EQ(early.status, 409);
  EXPECT_EQ(ErrorCode(early), "incomplete");
  EXPECT_NE(ErrorMessage(early).find("frames 1, 2 and the map"), std::string::npos)
      << ErrorMessage(early);
  // Still a draft: nobody else sees it, it is not listed.
  EXPECT_EQ(Call("GET", "/v1/clips/" + id, bob_).status, 404);
  Response list = Call("GET", "/v1/clips?near=1,2&radius_m=10");
  EXPECT_TRUE(json::parse(list.body)["clips"].empty());

  for (int n = 1; n < 3; ++n) {
    ASSERT_EQ(Call("PUT", "/v1/clips/" + id + "/frames/" + std::to_string(n), alice_,
                   clip.frames[n], "application/octet-stream")
                  .status,
              204);
  }
  ASSERT_EQ(
      Call("PUT", "/v1/clips/" + id + "/map", alice_, clip.map, "application/octet-stream").status,
      204);
  EXPECT_EQ(Call("POST", "/v1/clips/" + id + "/publish", bob_).status, 404);
  EXPECT_EQ(Call("POST", "/v1/clips/" + id + "/publish", alice_).status, 200);
  EXPECT_EQ(Call("GET", "/v1/clips/" + id).status, 200);
  list = Call("GET", "/v1/clips?near=1,2&radius_m=10");
  ASSERT_EQ(json::parse(list.body)["clips"].size(), 1u);
}

TEST_P(RoutesTest, ManifestIsReturnedExactlyWithEtagAnd304) {
  const TestClip clip = MakeTestClip(1, 2);
  const std::string id = Publish(clip, alice_);
  Response r = Call("GET", "/v1/clips/" + id);
  ASSERT_EQ(r.status, 200);
  EXPECT_EQ(r.body, clip.manifest_json);
  const std::string etag = "\"" + proto::Sha256Hex(clip.manifest_json) + "\"";
  EXPECT_EQ(HeaderOf(r, "ETag"), etag);
  Request conditional;
  conditional.method = "GET";
  conditional.target = "/v1/clips/" + id;
  conditional.headers = {{"If-None-Match", etag}};
  Response not_modified = Handle(conditional, *context_);
  EXPECT_EQ(not_modified.status, 304);
  EXPECT_TRUE(not_modified.body.empty());
}

TEST_P(RoutesTest, PartsCarryManifestHashAsEtag) {
  const TestClip clip = MakeTestClip(1, 2);
  const std::string id = Publish(clip, alice_);
  Response map = Call("GET", "/v1/clips/" + id + "/map");
  EXPECT_EQ(map.status, 200);
  EXPECT_EQ(map.body, clip.map);
  EXPECT_EQ(map.content_type, "application/octet-stream");
  EXPECT_EQ(HeaderOf(map, "ETag"), "\"" + proto::Sha256Hex(clip.map) + "\"");
  Request conditional;
  conditional.method = "GET";
  conditional.target = "/v1/clips/" + id + "/frames/2";
  conditional.headers = {{"If-None-Match", "\"" + proto::Sha256Hex(clip.frames[2]) + "\""}};
  EXPECT_EQ(Handle(conditional, *context_).status, 304);
}

TEST_P(RoutesTest, OnlyOwnerDeletesAndDeleteRemovesEveryPart) {
  const TestClip clip = MakeTestClip(1, 2);
  const std::string id = Publish(clip, alice_);
  EXPECT_EQ(Call("DELETE", "/v1/clips/" + id, bob_).status, 403);
  EXPECT_EQ(
      Call("PUT", "/v1/clips/" + id + "/map", bob_, clip.map, "application/octet-stream").status,
      403);
  EXPECT_EQ(Call("DELETE", "/v1/clips/" + id).status, 401);
  EXPECT_EQ(Call("DELETE", "/v1/clips/" + id, alice_).status, 204);
  EXPECT_EQ(Call("GET", "/v1/clips/" + id, alice_).status, 404);
  EXPECT_EQ(Call("GET", "/v1/clips/" + id + "/frames/0", alice_).status, 404);
  for (int n = 0; n < 3; ++n) {
    auto blob = storage_.blobs->Get(BlobKey(id, n));
    ASSERT_TRUE(blob.ok());
    EXPECT_FALSE(blob->has_value());
  }
  auto map_blob = storage_.blobs->Get(BlobKey(id, kMapPart));
  ASSERT_TRUE(map_blob.ok());
  EXPECT_FALSE(map_blob->has_value());
}

// Distances below are arc lengths R * angle with R = 6371008.8 m along the equator or a
// meridian through the pole, computed by hand: 0.05 deg -> 5559.754 m, 0.15 deg ->
// 16679.262 m, 0.1 deg -> 11119.508 m, 0.45 deg -> 50037.786 m.
TEST_P(RoutesTest, QuickPathAnswersSmallNearbySearchesAsHandleDoesAndDefersTheRest) {
  for (const char* title : {"c0", "c1", "c2", "c3"}) {
    Publish(MakeTestClip(48.0 + 0.001 * (title[1] - '0'), 11.0, 1, title), alice_);
  }
  Request nearby;
  nearby.method = "GET";
  nearby.target = "/v1/clips?near=48,11&radius_m=2000&limit=3";
  const Response full = Handle(nearby, *context_);
  ASSERT_EQ(full.status, 200);
  // A box of 4 rows within a bound of 4: the same answer, byte for byte (cursor included).
  const std::optional<Response> quick = HandleQuick(nearby, *context_, 4);
  ASSERT_TRUE(quick.has_value());
  EXPECT_EQ(quick->status, 200);
  EXPECT_EQ(quick->body, full.body);
  // A bound below the box's rows: left to the pool, never a partial or wrong answer.
  EXPECT_FALSE(HandleQuick(nearby, *context_, 3).has_value());
  // A malformed query is answered at once (no rows read).
  nearby.target = "/v1/clips?near=91,0";
  const std::optional<Response> bad = HandleQuick(nearby, *context_, 4);
  ASSERT_TRUE(bad.has_value());
  EXPECT_EQ(bad->status, 400);
  // Other routes and methods always go to the pool.
  nearby.target = "/healthz";
  EXPECT_FALSE(HandleQuick(nearby, *context_).has_value());
  Request create;
  create.method = "POST";
  create.target = "/v1/clips?near=48,11";
  EXPECT_FALSE(HandleQuick(create, *context_).has_value());
}

TEST_P(RoutesTest, NearbyAcrossTheAntimeridian) {
  const std::string east = Publish(MakeTestClip(0, 179.9, 1, "east"), alice_);
  const std::string west = Publish(MakeTestClip(0, -179.9, 1, "west"), alice_);
  Publish(MakeTestClip(0, 179.0, 1, "far"), alice_);
  Response r = Call("GET", "/v1/clips?near=0,179.95&radius_m=20000");
  ASSERT_EQ(r.status, 200) << r.body;
  const json clips = json::parse(r.body)["clips"];
  ASSERT_EQ(clips.size(), 2u);
  EXPECT_EQ(clips[0]["id"], east);
  EXPECT_NEAR(clips[0]["distance_m"].get<double>(), 5559.754, 0.01);
  EXPECT_EQ(clips[1]["id"], west);
  EXPECT_NEAR(clips[1]["distance_m"].get<double>(), 16679.262, 0.01);
  EXPECT_EQ(clips[1]["location"]["lon_deg"].get<double>(), -179.9);
}

TEST_P(RoutesTest, NearbyAroundThePole) {
  const std::string across = Publish(MakeTestClip(89.95, 180, 1, "across"), alice_);
  const std::string pole = Publish(MakeTestClip(90, 0, 1, "pole"), alice_);
  Publish(MakeTestClip(89.5, 0, 1, "far"), alice_);
  Response r = Call("GET", "/v1/clips?near=89.95,0&radius_m=20000");
  ASSERT_EQ(r.status, 200) << r.body;
  const json clips = json::parse(r.body)["clips"];
  ASSERT_EQ(clips.size(), 2u);
  EXPECT_EQ(clips[0]["id"], pole);
  EXPECT_NEAR(clips[0]["distance_m"].get<double>(), 5559.754, 0.01);
  EXPECT_EQ(clips[1]["id"], across);
  EXPECT_NEAR(clips[1]["distance_m"].get<double>(), 11119.508, 0.01);
  // The far clip is 0.45 deg = 50037.786 m away: in at 50100 m, out at 50000 m.
  EXPECT_EQ(json::parse(Call("GET", "/v1/clips?near=89.95,0&radius_m=50100").body)["clips"].size(),
            3u);
  EXPECT_EQ(json::parse(Call("GET", "/v1/clips?near=89.95,0&radius_m=50000").body)["clips"].size(),
            2u);
}

TEST_P(RoutesTest, NearbyWithRadiusZeroFindsOnlyTheExactPoint) {
  const std::string here = Publish(MakeTestClip(-33.8568, 151.2153, 1, "here"), alice_);
  Publish(MakeTestClip(-33.8568, 151.2154, 1, "next door"), alice_);
  const json clips =
      json::parse(Call("GET", "/v1/clips?near=-33.8568,151.2153&radius_m=0").body)["clips"];
  ASSERT_EQ(clips.size(), 1u);
  EXPECT_EQ(clips[0]["id"], here);
  EXPECT_EQ(clips[0]["distance_m"].get<double>(), 0.0);
}

TEST_P(RoutesTest, NearbyPagesInDistanceOrder) {
  std::vector<std::string> ids;
  for (int k = 0; k < 5; ++k) {
    std::string title = "c";
    title += std::to_string(k);
    ids.push_back(Publish(MakeTestClip(0, 0.001 * k, 1, title), alice_));
  }
  std::vector<std::string> seen;
  std::string cursor;
  for (int page = 0; page < 10; ++page) {
    std::string target = "/v1/clips?near=0,0&radius_m=10000&limit=2";
    if (!cursor.empty()) target += "&cursor=" + cursor;
    const json body = json::parse(Call("GET", target).body);
    EXPECT_LE(body["clips"].size(), 2u);
    for (const auto& c : body["clips"]) seen.push_back(c["id"]);
    if (body["next_cursor"].is_null()) break;
    cursor = body["next_cursor"].get<std::string>();
  }
  EXPECT_EQ(seen, ids);
}

TEST_P(RoutesTest, NearbyRejectsBadQueries) {
  EXPECT_EQ(Call("GET", "/v1/clips").status, 400);
  EXPECT_EQ(Call("GET", "/v1/clips?near=91,0").status, 400);
  EXPECT_EQ(Call("GET", "/v1/clips?near=abc").status, 400);
  EXPECT_EQ(Call("GET", "/v1/clips?near=0,0&radius_m=2000001").status, 400);
  EXPECT_EQ(Call("GET", "/v1/clips?near=0,0&radius_m=-1").status, 400);
  EXPECT_EQ(Call("GET", "/v1/clips?near=0,0&limit=0").status, 400);
  EXPECT_EQ(Call("GET", "/v1/clips?near=0,0&limit=101").status, 400);
  EXPECT_EQ(Call("GET", "/v1/clips?near=0,0&cursor=zz").status, 400);
  EXPECT_EQ(Call("GET", "/v1/clips?near=0,0&radius_m=2000000").status, 200);
}

TEST_P(RoutesTest, UnknownRouteAndWrongMethod) {
  EXPECT_EQ(Call("GET", "/v2/things").status, 404);
  Response r = Call("PATCH", "/v1/clips");
  EXPECT_EQ(r.status, 405);
  EXPECT_EQ(HeaderOf(r, "Allow"), "GET, POST");
}

TEST_P(RoutesTest, MyClipsListsDraftsOfTheCallerOnly) {
  Create(MakeTestClip(1, 2, 1, "draft"), alice_);
  Publish(MakeTestClip(1, 2, 1, "published"), bob_);
  Response r = Call("GET", "/v1/me/clips", alice_);
  ASSERT_EQ(r.status, 200);
  const json clips = json::parse(r.body)["clips"];
  ASSERT_EQ(clips.size(), 1u);
  EXPECT_EQ(clips[0]["title"], "draft");
  EXPECT_EQ(clips[0]["state"], "draft");
  EXPECT_EQ(Call("GET", "/v1/me/clips").status, 401);
}

TEST_P(RoutesTest, HealthAndMetrics) {
  EXPECT_EQ(Call("GET", "/healthz").status, 200);
  Publish(MakeTestClip(1, 2, 1), alice_);
  Create(MakeTestClip(1, 2, 1, "d"), alice_);
  Response m = Call("GET", "/metrics");
  EXPECT_EQ(m.status, 200);
  EXPECT_NE(m.body.find("reenact_clips{state=\"published\"} 1\n"), std::string::npos);
  EXPECT_NE(m.body.find("reenact_clips{state=\"draft\"} 1\n"), std::string::npos);
}

TEST(RouteLabelTest, UsesPatternsNotRawPaths) {
  EXPECT_EQ(RouteLabel("PUT", "/v1/clips/abc/frames/7"), "PUT /v1/clips/{id}/frames/{n}");
  EXPECT_EQ(RouteLabel("GET", "/v1/clips?near=1,2"), "GET /v1/clips");
  EXPECT_EQ(RouteLabel("GET", "/nope"), "unmatched");
  ServiceLimits limits;
  EXPECT_EQ(BodyLimit("PUT", "/v1/clips/abc/frames/7", limits), limits.max_frame_bytes);
  EXPECT_EQ(BodyLimit("POST", "/v1/clips", limits), limits.max_manifest_bytes);
  EXPECT_EQ(BodyLimit("GET", "/v1/clips/abc", limits), 0u);
}

}  // namespace
}  // namespace reenact::server
