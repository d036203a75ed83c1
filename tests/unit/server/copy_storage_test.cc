// CopyStorage from a real SQLite file into a fresh store on each engine (SQLite with blobs in
// the database or as files; PostgreSQL: the tests' throwaway cluster, skipped with a message
// where none is installed): every record and payload read back through the target equals what
// was built into the source.
#include "server/storage/copy_storage.h"

#include <gtest/gtest.h>

#include <map>
#include <string>
#include <vector>

#include "proto/clip/content_hash.h"
#include "tests/unit/server/server_test_util.h"

namespace reenact::server {
namespace {

using testing::Engine;
using testing::TempDir;
using testing::TestClip;

std::string TokenHash(const std::string& name) { return proto::Sha256Hex("rnk_" + name); }

// One clip of the source as built: its record, payloads and which parts arrived.
struct BuiltClip {
  std::string owner;
  ClipRecord record;
  TestClip payloads;
  std::vector<PartRecord> parts;  // frames in order, then the map
};

BuiltClip Build(const std::string& owner, const std::string& id, double lat, double lon,
                int frames, ClipState state) {
  BuiltClip c;
  c.owner = owner;
  c.payloads = testing::MakeTestClip(lat, lon, frames, id);
  c.record.id = id;
  c.record.state = state;
  c.record.title = "title of " + id;
  c.record.author = "author of " + id;
  c.record.lat_deg = lat;
  c.record.lon_deg = lon;
  c.record.alt_m = -12.345678901234567;
  c.record.duration_s = 0.1 * frames;
  c.record.frame_count = frames;
  c.record.manifest_sha256 = proto::Sha256Hex(c.payloads.manifest_json);
  for (int i = 0; i < frames; ++i) {
    const std::string& f = c.payloads.frames[i];
    c.parts.push_back({{i, static_cast<int64_t>(f.size()), proto::Sha256Hex(f)}, false});
  }
  const std::string& map = c.payloads.map;
  c.parts.push_back({{kMapPart, static_cast<int64_t>(map.size()), proto::Sha256Hex(map)}, false});
  return c;
}

const std::string& Payload(const BuiltClip& c, int index) {
  return index == kMapPart ? c.payloads.map : c.payloads.frames[index];
}

// Users alice (two tokens), bob (one), carol (all revoked), dave (no clips); two published
// clips, a draft with one part arrived and another stored but not yet verified, and a payload
// that belongs to no clip.
struct SourceData {
  std::vector<BuiltClip> clips;
  std::map<std::string, std::string> blobs;  // every payload stored, by key
  int64_t parts = 0;
};

SourceData Populate(Storage& s) {
  SourceData d;
  MetadataStore& m = *s.metadata;
  EXPECT_TRUE(m.AddUser("alice", TokenHash("alice-1")).ok());
  EXPECT_TRUE(m.AddToken("alice", TokenHash("alice-2")).ok());
  EXPECT_TRUE(m.AddUser("bob", TokenHash("bob-1")).ok());
  EXPECT_TRUE(m.AddUser("carol", TokenHash("carol-1")).ok());
  EXPECT_EQ(*m.RevokeUserTokens("carol"), 1);
  EXPECT_TRUE(m.AddUser("dave", TokenHash("dave-1")).ok());
  d.clips.push_back(Build("alice", "tower", 48.858370123456789, 2.294481, 3, ClipState::kPublished));
  d.clips.push_back(Build("alice", "opera", -33.8567844, 151.2152967, 2, ClipState::kDraft));
  d.clips.push_back(Build("bob", "tokyo", 35.6585805, 139.7454329, 1, ClipState::kPublished));
  std::map<std::string, int64_t> ids;
  const auto users = m.ListUsers();  // kept: the loop must not range over a temporary
  EXPECT_TRUE(users.ok());
  if (users.ok()) {
    for (const UserRecord& u : *users) ids[u.name] = u.id;
  }
  for (BuiltClip& c : d.clips) {
    NewClip draft{c.record, c.payloads.manifest_json, {}};
    draft.record.owner_id = ids[c.owner];
    for (const PartRecord& p : c.parts) draft.parts.push_back(p.spec);
    EXPECT_TRUE(m.CreateClip(draft).ok()) << c.record.id;
    for (PartRecord& p : c.parts) {
      // The draft: frame 0 arrived, frame 1 is stored but unverified, the map is missing.
      const bool draft_stored = p.spec.index >= 0;
      if (c.record.state == ClipState::kDraft && !draft_stored) continue;
      const std::string key = BlobKey(c.record.id, p.spec.index);
      EXPECT_TRUE(s.blobs->Put(key, Payload(c, p.spec.index)).ok());
      d.blobs[key] = Payload(c, p.spec.index);
      if (c.record.state == ClipState::kDraft && p.spec.index != 0) continue;
      EXPECT_TRUE(m.MarkPartPresent(c.record.id, p.spec.index).ok());
      p.present = true;
    }
    d.parts += static_cast<int64_t>(c.parts.size());
    if (c.record.state == ClipState::kPublished) {
      EXPECT_TRUE(m.Publish(c.record.id)->published);
    }
  }
  const std::string orphan("\0\x01\xff orphan", 10);
  EXPECT_TRUE(s.blobs->Put("gone/frames/0", orphan).ok());
  d.blobs["gone/frames/0"] = orphan;
  return d;
}

class CopyStorageTest : public ::testing::TestWithParam<Engine> {
 protected:
  void SetUp() override {
    auto source = OpenSqliteStorage((source_dir_.path() / "source.sqlite").string());
    ASSERT_TRUE(source.ok()) << source.error().message;
    source_ = std::move(*source);
    auto target = testing::OpenTestStorage(GetParam(), target_dir_);
    if (!target && target.error().code == "unavailable") GTEST_SKIP() << target.error().message;
    ASSERT_TRUE(target.ok()) << target.error().message;
    target_ = std::move(*target);
  }

  TempDir source_dir_, target_dir_;
  Storage source_, target_;
};

INSTANTIATE_TEST_SUITE_P(Engines, CopyStorageTest,
                         ::testing::Values(Engine::kSqlite, Engine::kPostgres,
                                           Engine::kSqliteFiles),
                         testing::EngineName);

TEST_P(CopyStorageTest, EveryRecordAndPayloadReadsBackFromTheTargetAsBuilt) {
  const SourceData d = Populate(source_);
  auto summary = CopyStorage(source_, target_);
  ASSERT_TRUE(summary.ok()) << summary.error().message;
  EXPECT_EQ(summary->users, 4);
  EXPECT_EQ(summary->tokens, 4);
  EXPECT_EQ(summary->clips, 3);
  EXPECT_EQ(summary->published_clips, 2);
  EXPECT_EQ(summary->parts, d.parts);
  EXPECT_EQ(summary->blobs, static_cast<int64_t>(d.blobs.size()));
  int64_t bytes = 0;
  for (const auto& [key, payload] : d.blobs) bytes += static_cast<int64_t>(payload.size());
  EXPECT_EQ(summary->blob_bytes, bytes);
  EXPECT_GE(summary->seconds, 0.0);

  MetadataStore& t = *target_.metadata;
  std::map<std::string, int64_t> ids;
  std::vector<std::string> names;
  const auto users = t.ListUsers();
  ASSERT_TRUE(users.ok()) << users.error().message;
  for (const UserRecord& u : *users) {
    ids[u.name] = u.id;
    names.push_back(u.name);
  }
  EXPECT_EQ(names, (std::vector<std::string>{"alice", "bob", "carol", "dave"}));
  // Issued tokens keep working; revoked ones stay revoked.
  for (const char* token : {"alice-1", "alice-2", "bob-1", "dave-1"}) {
    auto owner = t.FindUserByTokenHash(TokenHash(token));
    ASSERT_TRUE(owner.ok() && owner->has_value()) << token;
  }
  EXPECT_EQ((*t.FindUserByTokenHash(TokenHash("alice-2")))->user.id, ids["alice"]);
  EXPECT_FALSE(t.FindUserByTokenHash(TokenHash("carol-1"))->has_value());
  EXPECT_TRUE(t.TokenHashesOfUser(ids["carol"])->empty());

  for (const BuiltClip& c : d.clips) {
    auto got = t.GetClip(c.record.id);
    ASSERT_TRUE(got.ok() && got->has_value()) << c.record.id;
    const ClipRecord& r = **got;
    EXPECT_EQ(r.owner_id, ids[c.owner]);
    EXPECT_EQ(r.state, c.record.state);
    EXPECT_EQ(r.title, c.record.title);
    EXPECT_EQ(r.author, c.record.author);
    EXPECT_EQ(r.lat_deg, c.record.lat_deg);
    EXPECT_EQ(r.lon_deg, c.record.lon_deg);
    EXPECT_EQ(r.alt_m, c.record.alt_m);
    EXPECT_EQ(r.duration_s, c.record.duration_s);
    EXPECT_EQ(r.frame_count, c.record.frame_count);
    EXPECT_EQ(r.manifest_sha256, c.record.manifest_sha256);
    EXPECT_EQ(*t.GetManifest(c.record.id), c.payloads.manifest_json);
    auto parts = t.ListParts(c.record.id);
    ASSERT_TRUE(parts.ok());
    ASSERT_EQ(parts->size(), c.parts.size());
    for (size_t i = 0; i < parts->size(); ++i) {
      EXPECT_EQ((*parts)[i].spec.index, c.parts[i].spec.index);
      EXPECT_EQ((*parts)[i].spec.bytes, c.parts[i].spec.bytes);
      EXPECT_EQ((*parts)[i].spec.sha256, c.parts[i].spec.sha256);
      EXPECT_EQ((*parts)[i].present, c.parts[i].present) << c.record.id << " part " << i;
    }
  }
  EXPECT_EQ(*t.CountClips(ClipState::kPublished), 2);
  EXPECT_EQ(*t.CountClips(ClipState::kDraft), 1);
  std::vector<std::string> keys;
  for (const auto& [key, payload] : d.blobs) {
    keys.push_back(key);
    auto got = target_.blobs->Get(key);
    ASSERT_TRUE(got.ok() && got->has_value()) << key;
    EXPECT_EQ(**got, payload) << key;
  }
  EXPECT_EQ(*target_.blobs->ListKeys(), keys);  // std::map: bytewise order, and nothing else
  // Published clips are found nearby on the target, the draft is not.
  NearbyQuery near_tower{48.8584, 2.2945, 1000.0, 10, std::nullopt, 0};
  auto hits = t.Nearby(near_tower);
  ASSERT_TRUE(hits.ok());
  ASSERT_EQ(hits->size(), 1u);
  EXPECT_EQ((*hits)[0].clip.id, "tower");
  NearbyQuery near_opera{-33.8568, 151.2153, 1000.0, 10, std::nullopt, 0};
  EXPECT_TRUE(t.Nearby(near_opera)->empty());
  // The source still holds everything.
  EXPECT_EQ(*source_.blobs->ListKeys(), keys);
  EXPECT_EQ(source_.metadata->ListUsers()->size(), 4u);
}

TEST_P(CopyStorageTest, ATargetHoldingAUserIsRefusedUntouched) {
  Populate(source_);
  ASSERT_TRUE(target_.metadata->AddUser("someone", TokenHash("someone")).ok());
  auto summary = CopyStorage(source_, target_);
  ASSERT_FALSE(summary.ok());
  EXPECT_EQ(summary.error().code, "not_empty");
  EXPECT_NE(summary.error().message.find("1 user(s)"), std::string::npos)
      << summary.error().message;
  EXPECT_NE(summary.error().message.find("empty database"), std::string::npos);
  EXPECT_EQ(target_.metadata->ListUsers()->size(), 1u);
  EXPECT_TRUE(target_.blobs->ListKeys()->empty());
}

TEST_P(CopyStorageTest, ASecondCopyIntoTheSameTargetIsRefused) {
  Populate(source_);
  ASSERT_TRUE(CopyStorage(source_, target_).ok());
  auto again = CopyStorage(source_, target_);
  ASSERT_FALSE(again.ok());
  EXPECT_EQ(again.error().code, "not_empty");
}

TEST_P(CopyStorageTest, ATargetHoldingOnlyABlobIsRefused) {
  Populate(source_);
  ASSERT_TRUE(target_.blobs->Put("x/map", "left over").ok());
  auto summary = CopyStorage(source_, target_);
  ASSERT_FALSE(summary.ok());
  EXPECT_EQ(summary.error().code, "not_empty");
  EXPECT_TRUE(target_.metadata->ListUsers()->empty());
}

TEST_P(CopyStorageTest, APresentPartWithOtherBytesStopsTheCopyBeforeItsClipIsVisible) {
  Populate(source_);
  // The published clip "tower" now has a frame whose stored bytes no longer match its hash.
  ASSERT_TRUE(source_.blobs->Put(BlobKey("tower", 1), "bit rot").ok());
  auto summary = CopyStorage(source_, target_);
  ASSERT_FALSE(summary.ok());
  EXPECT_EQ(summary.error().code, "damaged_source");
  EXPECT_NE(summary.error().message.find("tower/frames/1"), std::string::npos)
      << summary.error().message;
  EXPECT_NE(summary.error().message.find("drop it"), std::string::npos);
  // Nothing half-copied is visible: the clip stays a draft on the target.
  auto tower = target_.metadata->GetClip("tower");
  ASSERT_TRUE(tower.ok());
  if (tower->has_value()) {
    EXPECT_EQ((*tower)->state, ClipState::kDraft);
  }
  EXPECT_EQ(*target_.metadata->CountClips(ClipState::kPublished), 0);
}

// Forwards to a real store but flips a byte of the payload stored under one key.
class CorruptingBlobStore : public BlobStore {
 public:
  CorruptingBlobStore(std::unique_ptr<BlobStore> store, std::string key)
      : store_(std::move(store)), key_(std::move(key)) {}
  Status Put(const std::string& key, std::string_view bytes) override {
    if (key != key_ || bytes.empty()) return store_->Put(key, bytes);
    std::string changed(bytes);
    changed.back() ^= 1;
    return store_->Put(key, changed);
  }
  Expected<std::optional<std::string>> Get(const std::string& key) override {
    return store_->Get(key);
  }
  Expected<std::unique_ptr<BlobReader>> OpenReader(const std::string& key) override {
    return store_->OpenReader(key);
  }
  Status DeletePrefix(const std::string& prefix) override { return store_->DeletePrefix(prefix); }
  Expected<std::vector<std::string>> ListKeys() override { return store_->ListKeys(); }

 private:
  std::unique_ptr<BlobStore> store_;
  std::string key_;
};

TEST_P(CopyStorageTest, APayloadStoredWrongOnTheTargetFailsVerification) {
  Populate(source_);
  target_.blobs = std::make_unique<CorruptingBlobStore>(std::move(target_.blobs), "gone/frames/0");
  auto summary = CopyStorage(source_, target_);
  ASSERT_FALSE(summary.ok());
  EXPECT_EQ(summary.error().code, "mismatch");
  EXPECT_NE(summary.error().message.find("blob gone/frames/0"), std::string::npos)
      << summary.error().message;
  EXPECT_NE(summary.error().message.find("run migrate-db again"), std::string::npos);
}

TEST_P(CopyStorageTest, AnEmptySourceCopiesNothingAndVerifies) {
  auto summary = CopyStorage(source_, target_);
  ASSERT_TRUE(summary.ok()) << summary.error().message;
  EXPECT_EQ(summary->users, 0);
  EXPECT_EQ(summary->clips, 0);
  EXPECT_EQ(summary->blobs, 0);
}

}  // namespace
}  // namespace reenact::server
