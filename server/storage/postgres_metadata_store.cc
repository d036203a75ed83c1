#include "server/storage/postgres_metadata_store.h"

#include <algorithm>
#include <ctime>
#include <tuple>

#include "server/geo/geodesic.h"
#include "server/storage/postgres_migrations.h"

namespace reenact::server {

namespace {

constexpr const char* kClipColumns =
    "c.public_id, c.owner_id, c.state, c.title, c.author, c.lat_deg, c.lon_deg, c.alt_m, "
    "c.duration_s, c.frame_count, c.manifest_sha256";

ClipRecord ReadClip(const pg::Result& rows, int row) {
  ClipRecord clip;
  clip.id = rows.Text(row, 0);
  clip.owner_id = rows.Int(row, 1);
  clip.state = rows.Text(row, 2) == "published" ? ClipState::kPublished : ClipState::kDraft;
  clip.title = rows.Text(row, 3);
  clip.author = rows.Text(row, 4);
  clip.lat_deg = rows.Double(row, 5);
  clip.lon_deg = rows.Double(row, 6);
  clip.alt_m = rows.Double(row, 7);
  clip.duration_s = rows.Double(row, 8);
  clip.frame_count = static_cast<int>(rows.Int(row, 9));
  clip.manifest_sha256 = rows.Text(row, 10);
  return clip;
}

int64_t NowUnix() { return static_cast<int64_t>(std::time(nullptr)); }

// The internal key of a clip (code "not_found" when there is none); `lock` takes the clip's
// row lock until commit.
Expected<int64_t> ClipKey(pg::Connection& db, const std::string& id, bool lock = false) {
  auto rows = db.Query(std::string("SELECT clip_key FROM clips WHERE public_id = $1") +
                           (lock ? " FOR UPDATE" : ""),
                       {id});
  if (!rows) return rows.error();
  if (rows->rows() == 0) return MakeError("not_found", "no clip " + id);
  return rows->Int(0, 0);
}

Expected<std::optional<UserRecord>> UserByName(pg::Connection& db, const std::string& name) {
  auto rows = db.Query("SELECT id, name FROM users WHERE name = $1", {name});
  if (!rows) return rows.error();
  if (rows->rows() == 0) return std::optional<UserRecord>();
  return std::optional<UserRecord>(UserRecord{rows->Int(0, 0), rows->Text(0, 1)});
}

// How far PostGIS's sphere distance may be from the haversine distance d, with room to spare:
// its sphere's radius is within 1e-8 of kEarthMeanRadiusM and it computes the central angle by
// another formula. Pre-filters widened by it keep every clip the exact filters accept.
double PrefilterMarginM(double distance_m) { return distance_m * 1e-6 + 1.0; }

}  // namespace

Expected<std::unique_ptr<PostgresMetadataStore>> PostgresMetadataStore::Open(
    const std::string& url, int connections) {
  {
    auto db = pg::Connection::Open(url);
    if (!db) return db.error();
    if (Status s = ApplyPostgresMigrations(*db, EmbeddedPostgresMigrations()); !s) {
      return s.error();
    }
  }
  auto pool = pg::ConnectionPool::Open(url, connections);
  if (!pool) return pool.error();
  return std::unique_ptr<PostgresMetadataStore>(new PostgresMetadataStore(std::move(*pool)));
}

Expected<UserRecord> PostgresMetadataStore::AddUser(const std::string& name,
                                                    const std::string& token_sha256) {
  pg::ConnectionPool::Lease db = pool_->Acquire();
  auto tx = pg::Transaction::Begin(*db);
  if (!tx) return tx.error();
  auto user = db->Query("INSERT INTO users(name, created_at) VALUES ($1, $2) RETURNING id",
                        {name, NowUnix()});
  if (!user) {
    if (db->last_sqlstate() == pg::kUniqueViolation) {
      return MakeError("conflict", "a user named '" + name + "' already exists");
    }
    return user.error();
  }
  UserRecord record{user->Int(0, 0), name};
  if (auto token = db->Query(
          "INSERT INTO tokens(user_id, token_sha256, created_at) VALUES ($1, $2, $3)",
          {record.id, token_sha256, NowUnix()});
      !token) {
    return token.error();
  }
  if (Status s = tx->Commit(); !s) return s.error();
  return record;
}

Expected<std::optional<TokenOwner>> PostgresMetadataStore::FindUserByTokenHash(
    const std::string& token_sha256) {
  pg::ConnectionPool::Lease db = pool_->Acquire();
  auto rows = db->Query(
      "SELECT u.id, u.name, t.token_sha256 FROM tokens t JOIN users u ON u.id = t.user_id "
      "WHERE t.token_sha256 = $1",
      {token_sha256});
  if (!rows) return rows.error();
  if (rows->rows() == 0) return std::optional<TokenOwner>();
  return std::optional<TokenOwner>(
      TokenOwner{UserRecord{rows->Int(0, 0), rows->Text(0, 1)}, rows->Text(0, 2)});
}

Expected<UserRecord> PostgresMetadataStore::AddToken(const std::string& user_name,
                                                     const std::string& token_sha256) {
  pg::ConnectionPool::Lease db = pool_->Acquire();
  auto tx = pg::Transaction::Begin(*db);
  if (!tx) return tx.error();
  auto user = UserByName(*db, user_name);
  if (!user) return user.error();
  if (!*user) return MakeError("not_found", "no user named '" + user_name + "'");
  if (auto insert = db->Query(
          "INSERT INTO tokens(user_id, token_sha256, created_at) VALUES ($1, $2, $3)",
          {(*user)->id, token_sha256, NowUnix()});
      !insert) {
    return insert.error();
  }
  if (Status s = tx->Commit(); !s) return s.error();
  return **user;
}

Expected<bool> PostgresMetadataStore::RevokeToken(const std::string& token_sha256) {
  pg::ConnectionPool::Lease db = pool_->Acquire();
  auto deleted = db->Query("DELETE FROM tokens WHERE token_sha256 = $1", {token_sha256});
  if (!deleted) return deleted.error();
  return deleted->affected() > 0;
}

Expected<int> PostgresMetadataStore::RevokeUserTokens(const std::string& user_name) {
  pg::ConnectionPool::Lease db = pool_->Acquire();
  auto tx = pg::Transaction::Begin(*db);
  if (!tx) return tx.error();
  auto user = UserByName(*db, user_name);
  if (!user) return user.error();
  if (!*user) return MakeError("not_found", "no user named '" + user_name + "'");
  auto deleted = db->Query("DELETE FROM tokens WHERE user_id = $1", {(*user)->id});
  if (!deleted) return deleted.error();
  const int revoked = static_cast<int>(deleted->affected());
  if (Status s = tx->Commit(); !s) return s.error();
  return revoked;
}

Expected<std::vector<UserRecord>> PostgresMetadataStore::ListUsers() {
  pg::ConnectionPool::Lease db = pool_->Acquire();
  auto rows = db->Query("SELECT id, name FROM users ORDER BY id", {});
  if (!rows) return rows.error();
  std::vector<UserRecord> users;
  for (int i = 0; i < rows->rows(); ++i) {
    users.push_back(UserRecord{rows->Int(i, 0), rows->Text(i, 1)});
  }
  return users;
}

Expected<std::vector<std::string>> PostgresMetadataStore::TokenHashesOfUser(int64_t user_id) {
  pg::ConnectionPool::Lease db = pool_->Acquire();
  auto rows =
      db->Query("SELECT token_sha256 FROM tokens WHERE user_id = $1 ORDER BY id", {user_id});
  if (!rows) return rows.error();
  std::vector<std::string> hashes;
  for (int i = 0; i < rows->rows(); ++i) hashes.push_back(rows->Text(i, 0));
  return hashes;
}

Status PostgresMetadataStore::CreateClip(const NewClip& clip) {
  pg::ConnectionPool::Lease db = pool_->Acquire();
  auto tx = pg::Transaction::Begin(*db);
  if (!tx) return tx.error();
  const ClipRecord& r = clip.record;
  auto key = db->Query(
      "INSERT INTO clips(public_id, owner_id, state, title, author, lat_deg, lon_deg, alt_m, "
      "duration_s, frame_count, manifest, manifest_sha256, created_at) "
      "VALUES ($1, $2, 'draft', $3, $4, $5, $6, $7, $8, $9, $10, $11, $12) RETURNING clip_key",
      {r.id, r.owner_id, r.title, r.author, r.lat_deg, r.lon_deg, r.alt_m, r.duration_s,
       r.frame_count, pg::Param::Bytes(clip.manifest_json), r.manifest_sha256, NowUnix()});
  if (!key) {
    if (db->last_sqlstate() == pg::kUniqueViolation) {
      return MakeError("conflict", "clip id already exists");
    }
    return key.error();
  }
  const int64_t clip_key = key->Int(0, 0);
  for (const PartSpec& spec : clip.parts) {
    if (auto part = db->Query(
            "INSERT INTO clip_parts(clip_key, part_index, bytes, sha256) VALUES ($1, $2, $3, $4)",
            {clip_key, spec.index, spec.bytes, spec.sha256});
        !part) {
      return part.error();
    }
  }
  return tx->Commit();
}

Expected<std::optional<ClipRecord>> PostgresMetadataStore::GetClip(const std::string& id) {
  pg::ConnectionPool::Lease db = pool_->Acquire();
  auto rows = db->Query(
      std::string("SELECT ") + kClipColumns + " FROM clips c WHERE c.public_id = $1", {id});
  if (!rows) return rows.error();
  if (rows->rows() == 0) return std::optional<ClipRecord>();
  return std::optional<ClipRecord>(ReadClip(*rows, 0));
}

Expected<std::string> PostgresMetadataStore::GetManifest(const std::string& id) {
  pg::ConnectionPool::Lease db = pool_->Acquire();
  // Binary result: the BYTEA comes back as the bytes themselves.
  auto rows = db->Query("SELECT manifest FROM clips WHERE public_id = $1", {id},
                        /*binary_result=*/true);
  if (!rows) return rows.error();
  if (rows->rows() == 0) return MakeError("not_found", "no clip " + id);
  return rows->Text(0, 0);
}

Expected<std::optional<PartRecord>> PostgresMetadataStore::GetPart(const std::string& id,
                                                                   int index) {
  pg::ConnectionPool::Lease db = pool_->Acquire();
  auto rows = db->Query(
      "SELECT p.bytes, p.sha256, p.present FROM clip_parts p JOIN clips c "
      "ON c.clip_key = p.clip_key WHERE c.public_id = $1 AND p.part_index = $2",
      {id, index});
  if (!rows) return rows.error();
  if (rows->rows() == 0) return std::optional<PartRecord>();
  PartRecord part;
  part.spec = PartSpec{index, rows->Int(0, 0), rows->Text(0, 1)};
  part.present = rows->Int(0, 2) != 0;
  return std::optional<PartRecord>(part);
}

Expected<std::vector<PartRecord>> PostgresMetadataStore::ListParts(const std::string& id) {
  pg::ConnectionPool::Lease db = pool_->Acquire();
  auto key = ClipKey(*db, id);
  if (!key) return key.error();
  // Frames 0..n-1 first, then the map (index -1): false sorts before true.
  auto rows = db->Query(
      "SELECT part_index, bytes, sha256, present FROM clip_parts WHERE clip_key = $1 "
      "ORDER BY part_index < 0, part_index",
      {*key});
  if (!rows) return rows.error();
  std::vector<PartRecord> parts;
  for (int i = 0; i < rows->rows(); ++i) {
    PartRecord part;
    part.spec =
        PartSpec{static_cast<int>(rows->Int(i, 0)), rows->Int(i, 1), rows->Text(i, 2)};
    part.present = rows->Int(i, 3) != 0;
    parts.push_back(std::move(part));
  }
  return parts;
}

Status PostgresMetadataStore::MarkPartPresent(const std::string& id, int index) {
  pg::ConnectionPool::Lease db = pool_->Acquire();
  auto updated = db->Query(
      "UPDATE clip_parts SET present = TRUE WHERE part_index = $2 AND clip_key = "
      "(SELECT clip_key FROM clips WHERE public_id = $1)",
      {id, index});
  if (!updated) return updated.error();
  if (updated->affected() == 0) return MakeError("not_found", "no such part of clip " + id);
  return {};
}

Expected<PublishResult> PostgresMetadataStore::Publish(const std::string& id) {
  pg::ConnectionPool::Lease db = pool_->Acquire();
  auto tx = pg::Transaction::Begin(*db);
  if (!tx) return tx.error();
  auto key = ClipKey(*db, id, /*lock=*/true);
  if (!key) return key.error();
  auto missing = db->Query(
      "SELECT part_index FROM clip_parts WHERE clip_key = $1 AND NOT present "
      "ORDER BY part_index",
      {*key});
  if (!missing) return missing.error();
  PublishResult result;
  for (int i = 0; i < missing->rows(); ++i) {
    result.missing_parts.push_back(static_cast<int>(missing->Int(i, 0)));
  }
  if (!result.missing_parts.empty()) return result;
  if (auto update = db->Query(
          "UPDATE clips SET state = 'published', published_at = COALESCE(published_at, $2) "
          "WHERE clip_key = $1",
          {*key, NowUnix()});
      !update) {
    return update.error();
  }
  if (Status s = tx->Commit(); !s) return s.error();
  result.published = true;
  return result;
}

Expected<bool> PostgresMetadataStore::DeleteClip(const std::string& id) {
  pg::ConnectionPool::Lease db = pool_->Acquire();
  auto deleted = db->Query("DELETE FROM clips WHERE public_id = $1", {id});
  if (!deleted) return deleted.error();
  return deleted->affected() > 0;
}

Expected<std::vector<ClipRecord>> PostgresMetadataStore::ClipsOfOwner(int64_t owner_id) {
  pg::ConnectionPool::Lease db = pool_->Acquire();
  auto rows = db->Query(std::string("SELECT ") + kClipColumns +
                            " FROM clips c WHERE c.owner_id = $1 ORDER BY c.created_at, "
                            "c.public_id",
                        {owner_id});
  if (!rows) return rows.error();
  std::vector<ClipRecord> clips;
  for (int i = 0; i < rows->rows(); ++i) clips.push_back(ReadClip(*rows, i));
  return clips;
}

Expected<std::vector<NearbyHit>> PostgresMetadataStore::Nearby(const NearbyQuery& query) {
  REENACT_CHECK(query.limit >= 1, "nearby limit must be >= 1");
  REENACT_CHECK(query.radius_m >= 0.0 && query.radius_m <= kMaxNearbyRadiusM,
                "nearby radius out of range");
  // $4: rows closer than the cursor (less the pre-filter's margin) cannot follow it.
  // $5: NULL (no bound) or one row more than may be examined.
  static const std::string kNearbySql =
      std::string("SELECT ") + kClipColumns +
      " FROM clips c, (SELECT ST_SetSRID(ST_MakePoint($2::float8, $1::float8), 4326)::geography"
      " AS point) q WHERE c.state = 'published' AND ST_DWithin(c.location, q.point, $3::float8,"
      " false) AND ($4::float8 IS NULL OR ST_Distance(c.location, q.point, false) >= $4::float8)"
      " LIMIT $5::bigint";
  pg::Param after_bound = pg::Param::Null();
  if (query.after) {
    after_bound =
        pg::Param(query.after->distance_m - PrefilterMarginM(query.after->distance_m));
  }
  pg::Param row_bound = pg::Param::Null();
  if (query.max_scanned > 0) row_bound = pg::Param(static_cast<int64_t>(query.max_scanned) + 1);
  pg::ConnectionPool::Lease db = pool_->Acquire();
  auto rows = db->Query(kNearbySql, {query.lat_deg, query.lon_deg,
                                     query.radius_m + PrefilterMarginM(query.radius_m), after_bound, row_bound});
  if (!rows) return rows.error();
  if (query.max_scanned > 0 && static_cast<size_t>(rows->rows()) > query.max_scanned) {
    return MakeError("too_costly", "the search box holds more than " +
                                       std::to_string(query.max_scanned) + " rows");
  }
  std::vector<NearbyHit> hits;
  for (int i = 0; i < rows->rows(); ++i) {
    const double d = HaversineDistanceM(query.lat_deg, query.lon_deg, rows->Double(i, 5),
                                        rows->Double(i, 6));
    if (d > query.radius_m) continue;
    ClipRecord clip = ReadClip(*rows, i);
    if (!AfterNearbyCursor(query, d, clip.id)) continue;
    hits.push_back(NearbyHit{std::move(clip), d});
  }
  SortAndTrimNearby(hits, query.limit);
  return hits;
}

Expected<int64_t> PostgresMetadataStore::CountClips(ClipState state) {
  pg::ConnectionPool::Lease db = pool_->Acquire();
  auto rows = db->Query("SELECT COUNT(*) FROM clips WHERE state = $1",
                        {state == ClipState::kPublished ? "published" : "draft"});
  if (!rows) return rows.error();
  return rows->Int(0, 0);
}

}  // namespace reenact::server
