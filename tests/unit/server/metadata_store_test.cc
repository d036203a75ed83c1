// MetadataStore on both engines, with the same expectations: SQLite in a temp dir always, and
// PostgreSQL/PostGIS in the tests' throwaway cluster (postgres_test_cluster.h), skipped with a
// message where no PostgreSQL is installed. Distances are checked against great circles whose
// length is known in closed form (along a meridian, across the antimeridian, over a pole).
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "server/geo/geodesic.h"
#include "server/storage/embedded_migrations.h"
#include "server/storage/migrations.h"
#include "server/storage/open_storage.h"
#include "server/storage/postgres.h"
#include "server/storage/postgres_metadata_store.h"
#include "server/storage/postgres_migrations.h"
#include "tests/unit/server/postgres_test_cluster.h"
#include "tests/unit/server/server_test_util.h"

namespace reenact::server {
namespace {

using testing::Engine;
using testing::EngineName;
using testing::TempDir;

// Metres along a great circle of `degrees` of arc on the store's sphere.
double ArcM(double degrees) { return kEarthMeanRadiusM * degrees * std::numbers::pi / 180.0; }

std::string Hash(char c) { return std::string(64, c); }

class MetadataStoreTest : public ::testing::TestWithParam<Engine> {
 protected:
  void SetUp() override {
    if (GetParam() == Engine::kSqlite) {
      auto storage = OpenSqliteStorage((dir_.path() / "db.sqlite").string());
      ASSERT_TRUE(storage.ok()) << storage.error().message;
      store_ = std::move(storage->metadata);
    } else {
      auto url = testing::NewPostgresTestDatabase();
      if (!url && url.error().code == "unavailable") GTEST_SKIP() << url.error().message;
      ASSERT_TRUE(url.ok()) << url.error().message;
      auto store = PostgresMetadataStore::Open(*url);
      ASSERT_TRUE(store.ok()) << store.error().message;
      store_ = std::move(*store);
    }
    auto owner = store_->AddUser("owner", Hash('0'));
    ASSERT_TRUE(owner.ok()) << owner.error().message;
    owner_ = owner->id;
  }

  // A clip of `frames` frames and a map at (lat, lon); published when asked.
  void AddClip(const std::string& id, double lat, double lon, bool publish = true,
               int frames = 2) {
    NewClip clip;
    clip.record.id = id;
    clip.record.owner_id = owner_;
    clip.record.title = "title of " + id;
    clip.record.author = "author";
    clip.record.lat_deg = lat;
    clip.record.lon_deg = lon;
    clip.record.alt_m = 12.5;
    clip.record.duration_s = 3.25;
    clip.record.frame_count = frames;
    clip.record.manifest_sha256 = Hash('m');
    clip.manifest_json = "{\"id\":\"" + id + "\"}";
    for (int i = 0; i < frames; ++i) clip.parts.push_back({i, 10 + i, Hash('f')});
    clip.parts.push_back({kMapPart, 100, Hash('p')});
    ASSERT_TRUE(store_->CreateClip(clip).ok()) << id;
    if (!publish) return;
    for (const PartSpec& part : clip.parts) {
      ASSERT_TRUE(store_->MarkPartPresent(id, part.index).ok());
    }
    auto published = store_->Publish(id);
    ASSERT_TRUE(published.ok() && published->published) << id;
  }

  std::vector<NearbyHit> Nearby(double lat, double lon, double radius_m, int limit = 100) {
    NearbyQuery query;
    query.lat_deg = lat;
    query.lon_deg = lon;
    query.radius_m = radius_m;
    query.limit = limit;
    auto hits = store_->Nearby(query);
    EXPECT_TRUE(hits.ok()) << hits.error().message;
    return hits.ok() ? *hits : std::vector<NearbyHit>{};
  }

  static std::vector<std::string> Ids(const std::vector<NearbyHit>& hits) {
    std::vector<std::string> ids;
    for (const NearbyHit& h : hits) ids.push_back(h.clip.id);
    return ids;
  }

  TempDir dir_;
  std::unique_ptr<MetadataStore> store_;
  int64_t owner_ = 0;
};

INSTANTIATE_TEST_SUITE_P(Engines, MetadataStoreTest,
                         ::testing::Values(Engine::kSqlite, Engine::kPostgres), EngineName);

TEST_P(MetadataStoreTest, UsersAndTokens) {
  auto dup = store_->AddUser("owner", Hash('1'));
  ASSERT_FALSE(dup.ok());
  EXPECT_EQ(dup.error().code, "conflict");
  auto found = store_->FindUserByTokenHash(Hash('0'));
  ASSERT_TRUE(found.ok() && found->has_value());
  EXPECT_EQ((*found)->user.id, owner_);
  EXPECT_EQ((*found)->user.name, "owner");
  EXPECT_EQ((*found)->stored_sha256, Hash('0'));
  EXPECT_FALSE(store_->FindUserByTokenHash(Hash('9'))->has_value());

  auto missing = store_->AddToken("nobody", Hash('2'));
  ASSERT_FALSE(missing.ok());
  EXPECT_EQ(missing.error().code, "not_found");
  auto second = store_->AddToken("owner", Hash('2'));
  ASSERT_TRUE(second.ok());
  EXPECT_EQ(second->id, owner_);
  EXPECT_EQ((*store_->FindUserByTokenHash(Hash('2')))->user.id, owner_);

  EXPECT_TRUE(*store_->RevokeToken(Hash('2')));
  EXPECT_FALSE(*store_->RevokeToken(Hash('2')));
  EXPECT_FALSE(store_->FindUserByTokenHash(Hash('2'))->has_value());
  ASSERT_TRUE(store_->AddToken("owner", Hash('3')).ok());
  EXPECT_EQ(*store_->RevokeUserTokens("owner"), 2);
  EXPECT_FALSE(store_->FindUserByTokenHash(Hash('0'))->has_value());
  EXPECT_EQ(store_->RevokeUserTokens("nobody").error().code, "not_found");
}

TEST_P(MetadataStoreTest, ListUsersAndTheirTokenHashes) {
  ASSERT_TRUE(store_->AddUser("zed", Hash('5')).ok());
  auto amy = store_->AddUser("amy", Hash('1'));
  ASSERT_TRUE(amy.ok());
  ASSERT_TRUE(store_->AddToken("amy", Hash('4')).ok());
  ASSERT_TRUE(store_->AddToken("amy", Hash('2')).ok());
  ASSERT_TRUE(store_->AddToken("owner", Hash('3')).ok());
  ASSERT_TRUE(*store_->RevokeToken(Hash('4')));
  auto users = store_->ListUsers();
  ASSERT_TRUE(users.ok()) << users.error().message;
  std::vector<std::string> names;
  for (const UserRecord& u : *users) names.push_back(u.name);
  EXPECT_EQ(names, (std::vector<std::string>{"owner", "zed", "amy"}));  // by id: as added
  EXPECT_EQ(users->back().id, amy->id);
  // Oldest first, without the revoked one.
  EXPECT_EQ(*store_->TokenHashesOfUser(amy->id), (std::vector<std::string>{Hash('1'), Hash('2')}));
  EXPECT_EQ(*store_->TokenHashesOfUser(owner_), (std::vector<std::string>{Hash('0'), Hash('3')}));
  ASSERT_EQ(*store_->RevokeUserTokens("zed"), 1);
  EXPECT_TRUE(store_->TokenHashesOfUser((*users)[1].id)->empty());
  EXPECT_TRUE(store_->TokenHashesOfUser(amy->id + 1000)->empty());
}

TEST_P(MetadataStoreTest, ClipRecordManifestAndPartsRoundTrip) {
  NewClip clip;
  clip.record.id = "clip-1";
  clip.record.owner_id = owner_;
  clip.record.title = "Plaça Major";
  clip.record.author = "Ana";
  clip.record.lat_deg = 39.569600123456789;
  clip.record.lon_deg = -0.10000000000000001;
  clip.record.alt_m = 1e-300;
  clip.record.duration_s = 1.0 / 3.0;
  clip.record.frame_count = 2;
  clip.record.manifest_sha256 = Hash('a');
  clip.manifest_json = std::string("{\"x\":\"\0\xff\\\"\"}", 12);
  clip.parts = {{kMapPart, 7, Hash('c')}, {1, 6, Hash('b')}, {0, 5, Hash('a')}};
  ASSERT_TRUE(store_->CreateClip(clip).ok());
  EXPECT_EQ(store_->CreateClip(clip).error().code, "conflict");

  auto got = store_->GetClip("clip-1");
  ASSERT_TRUE(got.ok() && got->has_value());
  const ClipRecord& r = **got;
  EXPECT_EQ(r.id, "clip-1");
  EXPECT_EQ(r.owner_id, owner_);
  EXPECT_EQ(r.state, ClipState::kDraft);
  EXPECT_EQ(r.title, "Plaça Major");
  EXPECT_EQ(r.author, "Ana");
  EXPECT_EQ(r.lat_deg, clip.record.lat_deg);  // exact: doubles round-trip
  EXPECT_EQ(r.lon_deg, clip.record.lon_deg);
  EXPECT_EQ(r.alt_m, clip.record.alt_m);
  EXPECT_EQ(r.duration_s, clip.record.duration_s);
  EXPECT_EQ(r.frame_count, 2);
  EXPECT_EQ(r.manifest_sha256, Hash('a'));
  EXPECT_EQ(*store_->GetManifest("clip-1"), clip.manifest_json);
  EXPECT_EQ(store_->GetManifest("none").error().code, "not_found");
  EXPECT_FALSE(store_->GetClip("none")->has_value());

  auto parts = store_->ListParts("clip-1");
  ASSERT_TRUE(parts.ok());
  ASSERT_EQ(parts->size(), 3u);  // frames in order, then the map
  EXPECT_EQ((*parts)[0].spec.index, 0);
  EXPECT_EQ((*parts)[0].spec.bytes, 5);
  EXPECT_EQ((*parts)[1].spec.index, 1);
  EXPECT_EQ((*parts)[2].spec.index, kMapPart);
  EXPECT_EQ((*parts)[2].spec.sha256, Hash('c'));
  for (const PartRecord& p : *parts) EXPECT_FALSE(p.present);
  EXPECT_EQ(store_->ListParts("none").error().code, "not_found");

  auto publish = store_->Publish("clip-1");
  ASSERT_TRUE(publish.ok());
  EXPECT_FALSE(publish->published);
  EXPECT_EQ(publish->missing_parts, (std::vector<int>{kMapPart, 0, 1}));
  ASSERT_TRUE(store_->MarkPartPresent("clip-1", 1).ok());
  ASSERT_TRUE(store_->MarkPartPresent("clip-1", 1).ok());  // idempotent
  EXPECT_EQ(store_->MarkPartPresent("clip-1", 2).error().code, "not_found");
  EXPECT_EQ(store_->MarkPartPresent("none", 0).error().code, "not_found");
  auto part = store_->GetPart("clip-1", 1);
  ASSERT_TRUE(part.ok() && part->has_value());
  EXPECT_TRUE((*part)->present);
  EXPECT_EQ((*part)->spec.bytes, 6);
  EXPECT_FALSE(store_->GetPart("clip-1", 5)->has_value());
  EXPECT_EQ(store_->Publish("clip-1")->missing_parts, (std::vector<int>{kMapPart, 0}));
  EXPECT_EQ(*store_->CountClips(ClipState::kDraft), 1);

  ASSERT_TRUE(store_->MarkPartPresent("clip-1", 0).ok());
  ASSERT_TRUE(store_->MarkPartPresent("clip-1", kMapPart).ok());
  EXPECT_TRUE(store_->Publish("clip-1")->published);
  EXPECT_TRUE(store_->Publish("clip-1")->published);  // again: still published
  EXPECT_EQ(store_->Publish("none").error().code, "not_found");
  EXPECT_EQ((*store_->GetClip("clip-1"))->state, ClipState::kPublished);
  EXPECT_EQ(*store_->CountClips(ClipState::kPublished), 1);
  EXPECT_EQ(*store_->CountClips(ClipState::kDraft), 0);

  EXPECT_EQ(store_->ClipsOfOwner(owner_)->size(), 1u);
  EXPECT_TRUE(store_->ClipsOfOwner(owner_ + 1)->empty());
  EXPECT_TRUE(*store_->DeleteClip("clip-1"));
  EXPECT_FALSE(*store_->DeleteClip("clip-1"));
  EXPECT_FALSE(store_->GetPart("clip-1", 0)->has_value());
  EXPECT_EQ(*store_->CountClips(ClipState::kPublished), 0);
}

TEST_P(MetadataStoreTest, ClipCreationIsAllOrNothing) {
  NewClip clip;
  clip.record.id = "c1";
  clip.record.owner_id = owner_;
  clip.manifest_json = "{}";
  // Two parts with the same index violate the primary key after the clip row was inserted.
  clip.parts = {{0, 1, Hash('b')}, {0, 1, Hash('c')}};
  EXPECT_FALSE(store_->CreateClip(clip).ok());
  EXPECT_FALSE(store_->GetClip("c1")->has_value());
  clip.parts.pop_back();
  EXPECT_TRUE(store_->CreateClip(clip).ok());
}

TEST_P(MetadataStoreTest, NearbyMeasuresGreatCirclesAndKeepsPublishedWithinRadius) {
  AddClip("north-1", 0.01, 0.0);
  AddClip("north-3", 0.03, 0.0);
  AddClip("south-2", -0.02, 0.0);
  AddClip("draft", 0.0, 0.001, /*publish=*/false);
  const auto hits = Nearby(0.0, 0.0, ArcM(0.025));
  ASSERT_EQ(Ids(hits), (std::vector<std::string>{"north-1", "south-2"}));
  EXPECT_NEAR(hits[0].distance_m, ArcM(0.01), 1e-6);
  EXPECT_NEAR(hits[1].distance_m, ArcM(0.02), 1e-6);
  EXPECT_EQ(hits[0].clip.title, "title of north-1");
  EXPECT_EQ(hits[0].clip.state, ClipState::kPublished);
  EXPECT_EQ(Ids(Nearby(0.0, 0.0, ArcM(0.035))).size(), 3u);
  EXPECT_TRUE(Nearby(0.0, 0.0, ArcM(0.005)).empty());
}

TEST_P(MetadataStoreTest, NearbyReachesAcrossTheAntimeridianAndOverThePoles) {
  AddClip("east", 0.0, 179.99);
  AddClip("west", 0.0, -179.995);
  AddClip("pole-far-side", 89.99, 180.0);
  AddClip("south-pole", -90.0, 0.0);
  const auto across = Nearby(0.0, -179.99, 5000.0);
  ASSERT_EQ(Ids(across), (std::vector<std::string>{"west", "east"}));
  EXPECT_NEAR(across[0].distance_m, ArcM(0.005), 1e-6);
  EXPECT_NEAR(across[1].distance_m, ArcM(0.02), 1e-6);
  // Over the north pole: from 89.99 N 0 E to 89.99 N 180 E is 0.02 degrees of a meridian.
  const auto over = Nearby(89.99, 0.0, 5000.0);
  ASSERT_EQ(Ids(over), (std::vector<std::string>{"pole-far-side"}));
  EXPECT_NEAR(over[0].distance_m, ArcM(0.02), 1e-6);
  const auto south = Nearby(-89.995, 123.0, 1000.0);
  ASSERT_EQ(Ids(south), (std::vector<std::string>{"south-pole"}));
  EXPECT_NEAR(south[0].distance_m, ArcM(0.005), 1e-6);
}

TEST_P(MetadataStoreTest, NearbyPagesByDistanceThenIdWithoutGapsOrRepeats) {
  // Ties: "b" and "a" at one point, "d" and "c" at another; pages of 2 split both ties.
  AddClip("b", 0.01, 0.0);
  AddClip("a", 0.01, 0.0);
  AddClip("e", 0.0, 0.015);
  AddClip("d", -0.02, 0.0);
  AddClip("c", -0.02, 0.0);
  const std::vector<std::string> expected = {"a", "b", "e", "c", "d"};
  EXPECT_EQ(Ids(Nearby(0.0, 0.0, 10000.0)), expected);
  std::vector<std::string> paged;
  NearbyQuery query;
  query.radius_m = 10000.0;
  query.limit = 2;
  for (int page = 0; page < 4; ++page) {
    auto hits = store_->Nearby(query);
    ASSERT_TRUE(hits.ok()) << hits.error().message;
    for (const NearbyHit& h : *hits) paged.push_back(h.clip.id);
    if (hits->empty()) break;
    query.after = NearbyQuery::Key{hits->back().distance_m, hits->back().clip.id};
  }
  EXPECT_EQ(paged, expected);
}

TEST_P(MetadataStoreTest, NearbyStopsPastTheScanBound) {
  for (int i = 0; i < 5; ++i) {
    std::string id = "clip-";
    id += std::to_string(i);
    AddClip(id, 0.001 * i, 0.0);
  }
  NearbyQuery query;
  query.radius_m = 10000.0;
  query.max_scanned = 3;
  auto bounded = store_->Nearby(query);
  ASSERT_FALSE(bounded.ok());
  EXPECT_EQ(bounded.error().code, "too_costly");
  query.max_scanned = 5;
  ASSERT_TRUE(store_->Nearby(query).ok());
  EXPECT_EQ(store_->Nearby(query)->size(), 5u);
}

// Both engines' migrations declare the same versions, so a schema version means one thing.
TEST(PostgresMigrations, SameVersionsAsSqlite) {
  const auto& sqlite_files = EmbeddedMigrations();
  const auto& pg_files = EmbeddedPostgresMigrations();
  ASSERT_EQ(pg_files.size(), sqlite_files.size());
  ASSERT_TRUE(CheckMigrationSequence(pg_files).ok());
  for (size_t i = 0; i < pg_files.size(); ++i) {
    EXPECT_STREQ(pg_files[i].name, sqlite_files[i].name);
  }
}

// A fresh database's connection string, or skips the test.
#define REENACT_POSTGRES_DATABASE_OR_SKIP(url)                                          \
  auto url = testing::NewPostgresTestDatabase();                                        \
  if (!url && url.error().code == "unavailable") GTEST_SKIP() << url.error().message; \
  ASSERT_TRUE(url.ok()) << url.error().message

TEST(PostgresMigrations, AppliedOnceFailingFileRollsBackNewerRefused) {
  REENACT_POSTGRES_DATABASE_OR_SKIP(url);
  {
    auto store = PostgresMetadataStore::Open(*url);
    ASSERT_TRUE(store.ok()) << store.error().message;
  }
  auto db = pg::Connection::Open(*url);
  ASSERT_TRUE(db.ok());
  const int newest = static_cast<int>(EmbeddedPostgresMigrations().size());
  EXPECT_EQ(*PostgresSchemaVersion(*db), newest);
  ASSERT_TRUE(PostgresMetadataStore::Open(*url).ok());  // reopening applies nothing
  EXPECT_EQ(*PostgresSchemaVersion(*db), newest);

  std::vector<MigrationFile> files = EmbeddedPostgresMigrations();
  const std::string bad_name = "000" + std::to_string(newest + 1) + "_bad.sql";
  files.push_back({bad_name.c_str(), "CREATE TABLE u(x int); INSERT INTO missing_table VALUES (1);"});
  Status failed = ApplyPostgresMigrations(*db, files);
  ASSERT_FALSE(failed.ok());
  EXPECT_EQ(failed.error().code, "migration_failed");
  EXPECT_NE(failed.error().message.find(bad_name), std::string::npos);
  EXPECT_EQ(*PostgresSchemaVersion(*db), newest);
  EXPECT_EQ(db->Query("SELECT to_regclass('u') IS NULL")->Int(0, 0), 1);

  ASSERT_TRUE(db->Exec("UPDATE reenact_schema_version SET version = 99").ok());
  auto refused = PostgresMetadataStore::Open(*url);
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.error().code, "schema_too_new");
  EXPECT_NE(refused.error().message.find("99"), std::string::npos);
  EXPECT_NE(refused.error().message.find("newer reenact-server"), std::string::npos);
  EXPECT_EQ(*PostgresSchemaVersion(*db), 99);
}

TEST(PostgresConnection, WrongPasswordIsOneClearLineWithoutThePassword) {
  auto login = testing::PostgresTestPasswordLogin("postgres", "right-secret");
  if (!login && login.error().code == "unavailable") GTEST_SKIP() << login.error().message;
  ASSERT_TRUE(login.ok()) << login.error().message;
  ASSERT_TRUE(pg::Connection::Open(*login + " password=right-secret").ok());
  auto wrong = PostgresMetadataStore::Open(*login + " password=wrong-secret");
  ASSERT_FALSE(wrong.ok());
  EXPECT_EQ(wrong.error().code, "io");
  const std::string& message = wrong.error().message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  EXPECT_NE(message.find("password authentication failed"), std::string::npos) << message;
  EXPECT_NE(message.find("reenact_password_test"), std::string::npos) << message;
  EXPECT_EQ(message.find("wrong-secret"), std::string::npos) << message;
}

TEST(PostgresConnection, UnreachableServerAndMalformedUrlAreClearErrors) {
  auto absent = PostgresMetadataStore::Open(
      "postgresql://someone:topsecret@/reenact?host=/nonexistent-reenact-socket-dir");
  ASSERT_FALSE(absent.ok());
  EXPECT_EQ(absent.error().code, "io");
  EXPECT_EQ(absent.error().message.find('\n'), std::string::npos) << absent.error().message;
  EXPECT_NE(absent.error().message.find("database 'reenact' as user 'someone'"),
            std::string::npos)
      << absent.error().message;
  EXPECT_EQ(absent.error().message.find("topsecret"), std::string::npos);
  auto malformed = PostgresMetadataStore::Open("postgresql://reenact@host/db?no_such_option=1");
  ASSERT_FALSE(malformed.ok());
  EXPECT_EQ(malformed.error().code, "invalid_argument") << malformed.error().message;
  EXPECT_NE(malformed.error().message.find("no_such_option"), std::string::npos);
}

TEST(PostgresConnection, AsUrlKeepsEverySettingAndEncodesThem) {
  const std::string conninfo =
      "host='/tmp/a dir' port=5433 user=someone dbname='d b' password='p&q=r%'";
  auto url = pg::AsUrl(conninfo);
  ASSERT_TRUE(url.ok()) << url.error().message;
  EXPECT_EQ(url->rfind("postgresql:///?", 0), 0u) << *url;
  EXPECT_NE(url->find("host=/tmp/a%20dir"), std::string::npos) << *url;
  EXPECT_NE(url->find("password=p%26q%3Dr%25"), std::string::npos) << *url;
  EXPECT_EQ(*pg::DescribeTarget(*url), *pg::DescribeTarget(conninfo));
  EXPECT_EQ(*pg::AsUrl(*url), *url);  // a URL comes back as it went in
  EXPECT_EQ(pg::AsUrl("host=x no_such_option=1").error().code, "invalid_argument");

  REENACT_POSTGRES_DATABASE_OR_SKIP(database);
  auto reached = pg::AsUrl(*database);
  ASSERT_TRUE(reached.ok());
  auto db = pg::Connection::Open(*reached);
  ASSERT_TRUE(db.ok()) << db.error().message;
  EXPECT_EQ(db->target(), *pg::DescribeTarget(*database));  // the same database, user and host
}

}  // namespace
}  // namespace reenact::server
