#pragma once
// Shared helpers of the server tests: a temporary directory, valid clips built through
// proto's manifest writer, storage on each engine, and a service over real storage (SQLite,
// SQLite with the blobs as files, or PostgreSQL in the tests' throwaway cluster) with two
// users.

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "proto/clip/content_hash.h"
#include "proto/clip/manifest.h"
#include "server/auth/token.h"
#include "server/http/routes.h"
#include "server/storage/blob_store.h"
#include "server/storage/open_storage.h"
#include "tests/support/temp_dir.h"
#include "tests/unit/server/postgres_test_cluster.h"

namespace reenact::server::testing {

using reenact::test_support::TempDir;

struct TestClip {
  std::string manifest_json;
  std::vector<std::string> frames;
  std::string map;
};

// A valid manifest at (lat, lon) whose parts are exactly `frames` and `map`.
inline std::string TestManifestJson(double lat, double lon, const std::string& title,
                                    const std::string& author,
                                    const std::vector<std::string>& frames,
                                    const std::string& map) {
  proto::ClipManifest m;
  m.title = title;
  m.author = author;
  m.capture_time = "2024-05-01T12:00:00Z";
  m.location = {lat, lon, 10.0, 3.0, std::nullopt};
  m.color_camera = {640, 480, 525.0, 525.0, 319.5, 239.5, {}};
  m.depth_camera = {640, 480, 525.0, 525.0, 319.5, 239.5, {}};
  for (int i = 0; i < kBodyPartCount; ++i) m.radius_ratio[i] = 0.2;
  m.frame_count = static_cast<int64_t>(frames.size());
  m.representative_frame = 0;
  m.frame_rate_hz = 10;
  for (const std::string& f : frames) m.frame_parts.push_back({f.size(), proto::Sha256Hex(f)});
  m.map_part = {map.size(), proto::Sha256Hex(map)};
  return proto::SerializeManifest(m);
}

// A clip at (lat, lon) with `frames` frames whose payloads are distinct, known byte strings.
inline TestClip MakeTestClip(double lat, double lon, int frames = 3,
                             const std::string& title = "clip") {
  TestClip clip;
  for (int i = 0; i < frames; ++i) {
    std::string frame = "frame-";  // built step by step: GCC 12 misreports a one-line concat
    frame += std::to_string(i);
    frame += "-";
    frame += title;
    frame.append(10 + i, 'x');
    clip.frames.push_back(std::move(frame));
  }
  clip.map = "map-of-" + title + std::string(100, 'm');
  clip.manifest_json = TestManifestJson(lat, lon, title, "tester", clip.frames, clip.map);
  return clip;
}

// The storage engines tests run on, as a test parameter: kSqliteFiles is SQLite metadata with
// the blobs as files (FileBlobStore).
enum class Engine { kSqlite, kPostgres, kSqliteFiles };

inline std::string EngineName(const ::testing::TestParamInfo<Engine>& info) {
  switch (info.param) {
    case Engine::kSqlite: return "Sqlite";
    case Engine::kPostgres: return "Postgres";
    case Engine::kSqliteFiles: return "SqliteFiles";
  }
  return "Unknown";
}

// The blob directory of kSqliteFiles storage in `dir`.
inline std::filesystem::path TestBlobDir(const TempDir& dir) { return dir.path() / "blobs"; }

// New empty storage on `engine`: a SQLite file in `dir` (with the blobs in TestBlobDir(dir)
// for kSqliteFiles), or a fresh database of the PostgreSQL test cluster `which`
// (postgres_test_cluster.h; code "unavailable" where none can be started).
inline Expected<Storage> OpenTestStorage(Engine engine, const TempDir& dir,
                                         TestCluster which = TestCluster::kShared) {
  const std::string db = (dir.path() / "db.sqlite").string();
  if (engine == Engine::kSqlite) return OpenSqliteStorage(db);
  if (engine == Engine::kSqliteFiles) {
    std::filesystem::create_directories(TestBlobDir(dir));
    StorageOptions options;
    options.blob_dir = TestBlobDir(dir).string();
    return OpenSqliteStorage(db, options);
  }
  auto url = NewPostgresTestDatabase(which);
  if (!url) return url.error();
  return OpenPostgresStorage(*url);
}

// Real storage on engine() (SQLite unless a parameterized fixture says otherwise), a metrics
// sink, and two users with their tokens. Skips where the engine's server is not installed.
class ServiceFixture : public ::testing::Test {
 protected:
  virtual Engine engine() const { return Engine::kSqlite; }
  // The PostgreSQL cluster of Engine::kPostgres: kOwn for tests that stop it.
  virtual TestCluster postgres_cluster() const { return TestCluster::kShared; }

  void SetUp() override {
    auto opened = OpenTestStorage(engine(), dir_, postgres_cluster());
    if (!opened && opened.error().code == "unavailable") GTEST_SKIP() << opened.error().message;
    ASSERT_TRUE(opened.ok()) << opened.error().message;
    storage_ = std::move(*opened);
    context_ = std::make_unique<ServiceContext>(
        ServiceContext{*storage_.metadata, *storage_.blobs, metrics_, ServiceLimits{}});
    auto a = AddUserWithToken(*storage_.metadata, "alice");
    auto b = AddUserWithToken(*storage_.metadata, "bob");
    ASSERT_TRUE(a.ok() && b.ok());
    alice_ = *a;
    bob_ = *b;
  }

  Response Call(const std::string& method, const std::string& target, const std::string& token = "",
                const std::string& body = "", const std::string& content_type = "") {
    Request request;
    request.method = method;
    request.target = target;
    if (!token.empty()) request.headers.emplace_back("Authorization", "Bearer " + token);
    if (!content_type.empty()) request.headers.emplace_back("Content-Type", content_type);
    request.body = body;
    return Received(Handle(request, *context_));
  }

  // The response as a client receives it: a streamed payload read into body.
  static Response Received(Response response) {
    if (!response.stream) return response;
    std::string bytes(static_cast<size_t>(response.stream->size()), '\0');
    uint64_t done = 0;
    while (done < bytes.size()) {
      auto n = response.stream->Read(done, std::span<char>(bytes.data() + done, bytes.size() - done));
      if (!n.ok() || *n == 0) {
        ADD_FAILURE() << "stream ended at " << done << " of " << bytes.size() << " bytes";
        break;
      }
      done += *n;
    }
    response.body = std::move(bytes);
    response.stream.reset();
    return response;
  }

  // Creates the clip as `token`'s user and returns its id.
  std::string Create(const TestClip& clip, const std::string& token) {
    Response r = Call("POST", "/v1/clips", token, clip.manifest_json, "application/json");
    EXPECT_EQ(r.status, 201) << r.body;
    return nlohmann::json::parse(r.body).at("id").get<std::string>();
  }

  // Creates, uploads every part and publishes.
  std::string Publish(const TestClip& clip, const std::string& token) {
    const std::string id = Create(clip, token);
    for (size_t n = 0; n < clip.frames.size(); ++n) {
      EXPECT_EQ(Call("PUT", "/v1/clips/" + id + "/frames/" + std::to_string(n), token,
                     clip.frames[n], "application/octet-stream")
                    .status,
                204);
    }
    EXPECT_EQ(
        Call("PUT", "/v1/clips/" + id + "/map", token, clip.map, "application/octet-stream").status,
        204);
    EXPECT_EQ(Call("POST", "/v1/clips/" + id + "/publish", token).status, 200);
    return id;
  }

  static std::string ErrorCode(const Response& r) {
    return nlohmann::json::parse(r.body).at("error").at("code").get<std::string>();
  }
  static std::string ErrorMessage(const Response& r) {
    return nlohmann::json::parse(r.body).at("error").at("message").get<std::string>();
  }

  TempDir dir_;
  Storage storage_;
  Metrics metrics_;
  std::unique_ptr<ServiceContext> context_;
  std::string alice_;
  std::string bob_;
};

// ServiceFixture on the engine of the test parameter:
//   class RoutesTest : public EngineServiceFixture {};
//   INSTANTIATE_TEST_SUITE_P(Engines, RoutesTest,
//                            ::testing::Values(Engine::kSqlite, Engine::kPostgres,
//                                              Engine::kSqliteFiles),
//                            EngineName);
class EngineServiceFixture : public ServiceFixture, public ::testing::WithParamInterface<Engine> {
 protected:
  Engine engine() const override { return GetParam(); }
};

}  // namespace reenact::server::testing
