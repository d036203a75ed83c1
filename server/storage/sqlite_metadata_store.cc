#include "server/storage/sqlite_metadata_store.h"

#include <algorithm>
#include <ctime>
#include <set>
#include <tuple>

#include "server/geo/geodesic.h"
#include "server/storage/migrations.h"

namespace reenact::server {

namespace {

constexpr const char* kClipColumns =
    "c.public_id, c.owner_id, c.state, c.title, c.author, c.lat_deg, c.lon_deg, c.alt_m, "
    "c.duration_s, c.frame_count, c.manifest_sha256";

ClipRecord ReadClip(const sqlite::Statement& stmt) {
  ClipRecord clip;
  clip.id = stmt.ColumnText(0);
  clip.owner_id = stmt.ColumnInt(1);
  clip.state = stmt.ColumnText(2) == "published" ? ClipState::kPublished : ClipState::kDraft;
  clip.title = stmt.ColumnText(3);
  clip.author = stmt.ColumnText(4);
  clip.lat_deg = stmt.ColumnDouble(5);
  clip.lon_deg = stmt.ColumnDouble(6);
  clip.alt_m = stmt.ColumnDouble(7);
  clip.duration_s = stmt.ColumnDouble(8);
  clip.frame_count = static_cast<int>(stmt.ColumnInt(9));
  clip.manifest_sha256 = stmt.ColumnText(10);
  return clip;
}

int64_t NowUnix() { return static_cast<int64_t>(std::time(nullptr)); }

// The internal key of a clip, or nullopt.
Expected<std::optional<int64_t>> ClipKey(sqlite::Database& db, const std::string& id) {
  auto stmt = db.Prepare("SELECT rowid_key FROM clips WHERE public_id = ?1");
  if (!stmt) return stmt.error();
  stmt->BindText(1, id);
  auto row = stmt->Step();
  if (!row) return row.error();
  if (!*row) return std::optional<int64_t>();
  return std::optional<int64_t>(stmt->ColumnInt(0));
}

Expected<std::optional<UserRecord>> UserByName(sqlite::Database& db, const std::string& name) {
  auto stmt = db.Prepare("SELECT id, name FROM users WHERE name = ?1");
  if (!stmt) return stmt.error();
  stmt->BindText(1, name);
  auto row = stmt->Step();
  if (!row) return row.error();
  if (!*row) return std::optional<UserRecord>();
  return std::optional<UserRecord>(UserRecord{stmt->ColumnInt(0), stmt->ColumnText(1)});
}

bool IsConstraintError(const Error& error) {
  return error.message.find("UNIQUE constraint failed") != std::string::npos;
}

}  // namespace

Expected<std::unique_ptr<SqliteMetadataStore>> SqliteMetadataStore::Open(const std::string& path,
                                                                         sqlite::Sync sync) {
  auto db = sqlite::Database::Open(path, sync);
  if (!db) return db.error();
  if (Status s = ApplyMigrations(*db, EmbeddedMigrations()); !s) return s.error();
  auto checkpointer = sqlite::WalCheckpointer::ForFile(path);
  if (!checkpointer) return checkpointer.error();
  (*checkpointer)->Attach(*db);
  std::unique_ptr<SqliteMetadataStore> store(new SqliteMetadataStore(std::move(*db)));
  store->checkpointer_ = std::move(*checkpointer);
  auto readers = sqlite::ReaderPool::Open(path, sqlite::ReaderPool::DefaultCount(), sync);
  if (!readers) return readers.error();
  store->readers_ = std::move(*readers);
  return store;
}

Expected<UserRecord> SqliteMetadataStore::AddUser(const std::string& name,
                                                  const std::string& token_sha256) {
  std::lock_guard lock(mutex_);
  auto tx = sqlite::Transaction::Begin(db_);
  if (!tx) return tx.error();
  auto insert_user = db_.Prepare("INSERT INTO users(name, created_at) VALUES (?1, ?2)");
  if (!insert_user) return insert_user.error();
  insert_user->BindText(1, name).Bind(2, NowUnix());
  if (Status s = insert_user->Run(); !s) {
    if (IsConstraintError(s.error())) {
      return MakeError("conflict", "a user named '" + name + "' already exists");
    }
    return s.error();
  }
  UserRecord user{db_.LastInsertRowId(), name};
  auto insert_token =
      db_.Prepare("INSERT INTO tokens(user_id, token_sha256, created_at) VALUES (?1, ?2, ?3)");
  if (!insert_token) return insert_token.error();
  insert_token->Bind(1, user.id).BindText(2, token_sha256).Bind(3, NowUnix());
  if (Status s = insert_token->Run(); !s) return s.error();
  if (Status s = tx->Commit(); !s) return s.error();
  return user;
}

Expected<std::optional<TokenOwner>> SqliteMetadataStore::FindUserByTokenHash(
    const std::string& token_sha256) {
  std::lock_guard lock(mutex_);
  auto stmt = db_.Prepare(
      "SELECT u.id, u.name, t.token_sha256 FROM tokens t JOIN users u ON u.id = t.user_id "
      "WHERE t.token_sha256 = ?1");
  if (!stmt) return stmt.error();
  stmt->BindText(1, token_sha256);
  auto row = stmt->Step();
  if (!row) return row.error();
  if (!*row) return std::optional<TokenOwner>();
  return std::optional<TokenOwner>(
      TokenOwner{UserRecord{stmt->ColumnInt(0), stmt->ColumnText(1)}, stmt->ColumnText(2)});
}

Expected<UserRecord> SqliteMetadataStore::AddToken(const std::string& user_name,
                                                   const std::string& token_sha256) {
  std::lock_guard lock(mutex_);
  auto tx = sqlite::Transaction::Begin(db_);
  if (!tx) return tx.error();
  auto user = UserByName(db_, user_name);
  if (!user) return user.error();
  if (!*user) return MakeError("not_found", "no user named '" + user_name + "'");
  auto insert =
      db_.Prepare("INSERT INTO tokens(user_id, token_sha256, created_at) VALUES (?1, ?2, ?3)");
  if (!insert) return insert.error();
  insert->Bind(1, (*user)->id).BindText(2, token_sha256).Bind(3, NowUnix());
  if (Status s = insert->Run(); !s) return s.error();
  if (Status s = tx->Commit(); !s) return s.error();
  return **user;
}

Expected<bool> SqliteMetadataStore::RevokeToken(const std::string& token_sha256) {
  std::lock_guard lock(mutex_);
  auto stmt = db_.Prepare("DELETE FROM tokens WHERE token_sha256 = ?1");
  if (!stmt) return stmt.error();
  stmt->BindText(1, token_sha256);
  if (Status s = stmt->Run(); !s) return s.error();
  return db_.Changes() > 0;
}

Expected<int> SqliteMetadataStore::RevokeUserTokens(const std::string& user_name) {
  std::lock_guard lock(mutex_);
  auto tx = sqlite::Transaction::Begin(db_);
  if (!tx) return tx.error();
  auto user = UserByName(db_, user_name);
  if (!user) return user.error();
  if (!*user) return MakeError("not_found", "no user named '" + user_name + "'");
  auto stmt = db_.Prepare("DELETE FROM tokens WHERE user_id = ?1");
  if (!stmt) return stmt.error();
  stmt->Bind(1, (*user)->id);
  if (Status s = stmt->Run(); !s) return s.error();
  const int revoked = db_.Changes();
  if (Status s = tx->Commit(); !s) return s.error();
  return revoked;
}

Expected<std::vector<UserRecord>> SqliteMetadataStore::ListUsers() {
  std::lock_guard lock(mutex_);
  auto stmt = db_.Prepare("SELECT id, name FROM users ORDER BY id");
  if (!stmt) return stmt.error();
  std::vector<UserRecord> users;
  for (;;) {
    auto row = stmt->Step();
    if (!row) return row.error();
    if (!*row) break;
    users.push_back(UserRecord{stmt->ColumnInt(0), stmt->ColumnText(1)});
  }
  return users;
}

Expected<std::vector<std::string>> SqliteMetadataStore::TokenHashesOfUser(int64_t user_id) {
  std::lock_guard lock(mutex_);
  auto stmt = db_.Prepare("SELECT token_sha256 FROM tokens WHERE user_id = ?1 ORDER BY id");
  if (!stmt) return stmt.error();
  stmt->Bind(1, user_id);
  std::vector<std::string> hashes;
  for (;;) {
    auto row = stmt->Step();
    if (!row) return row.error();
    if (!*row) break;
    hashes.push_back(stmt->ColumnText(0));
  }
  return hashes;
}

Status SqliteMetadataStore::CreateClip(const NewClip& clip) {
  std::lock_guard lock(mutex_);
  auto tx = sqlite::Transaction::Begin(db_);
  if (!tx) return tx.error();
  const ClipRecord& r = clip.record;
  auto insert = db_.Prepare(
      "INSERT INTO clips(public_id, owner_id, state, title, author, lat_deg, lon_deg, alt_m, "
      "duration_s, frame_count, manifest, manifest_sha256, created_at) "
      "VALUES (?1, ?2, 'draft', ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11, ?12)");
  if (!insert) return insert.error();
  insert->BindText(1, r.id)
      .Bind(2, r.owner_id)
      .BindText(3, r.title)
      .BindText(4, r.author)
      .Bind(5, r.lat_deg)
      .Bind(6, r.lon_deg)
      .Bind(7, r.alt_m)
      .Bind(8, r.duration_s)
      .Bind(9, r.frame_count)
      .BindBlob(10, clip.manifest_json)
      .BindText(11, r.manifest_sha256)
      .Bind(12, NowUnix());
  if (Status s = insert->Run(); !s) {
    if (IsConstraintError(s.error())) return MakeError("conflict", "clip id already exists");
    return s;
  }
  const int64_t key = db_.LastInsertRowId();
  auto box = db_.Prepare(
      "INSERT INTO clip_boxes(id, min_lat, max_lat, min_lon, max_lon) VALUES (?1, ?2, ?2, ?3, ?3)");
  if (!box) return box.error();
  box->Bind(1, key).Bind(2, r.lat_deg).Bind(3, r.lon_deg);
  if (Status s = box->Run(); !s) return s;
  auto part = db_.Prepare(
      "INSERT INTO clip_parts(clip_key, part_index, bytes, sha256) VALUES (?1, ?2, ?3, ?4)");
  if (!part) return part.error();
  for (const PartSpec& spec : clip.parts) {
    part->Reset();
    part->Bind(1, key).Bind(2, spec.index).Bind(3, spec.bytes).BindText(4, spec.sha256);
    if (Status s = part->Run(); !s) return s;
  }
  return tx->Commit();
}

Expected<std::optional<ClipRecord>> SqliteMetadataStore::GetClip(const std::string& id) {
  std::lock_guard lock(mutex_);
  auto stmt =
      db_.Prepare(std::string("SELECT ") + kClipColumns + " FROM clips c WHERE c.public_id = ?1");
  if (!stmt) return stmt.error();
  stmt->BindText(1, id);
  auto row = stmt->Step();
  if (!row) return row.error();
  if (!*row) return std::optional<ClipRecord>();
  return std::optional<ClipRecord>(ReadClip(*stmt));
}

Expected<std::string> SqliteMetadataStore::GetManifest(const std::string& id) {
  std::lock_guard lock(mutex_);
  auto stmt = db_.Prepare("SELECT manifest FROM clips WHERE public_id = ?1");
  if (!stmt) return stmt.error();
  stmt->BindText(1, id);
  auto row = stmt->Step();
  if (!row) return row.error();
  if (!*row) return MakeError("not_found", "no clip " + id);
  return stmt->ColumnBlob(0);
}

Expected<std::optional<PartRecord>> SqliteMetadataStore::GetPart(const std::string& id, int index) {
  std::lock_guard lock(mutex_);
  auto stmt = db_.Prepare(
      "SELECT p.bytes, p.sha256, p.present FROM clip_parts p JOIN clips c "
      "ON c.rowid_key = p.clip_key WHERE c.public_id = ?1 AND p.part_index = ?2");
  if (!stmt) return stmt.error();
  stmt->BindText(1, id).Bind(2, index);
  auto row = stmt->Step();
  if (!row) return row.error();
  if (!*row) return std::optional<PartRecord>();
  PartRecord part;
  part.spec = PartSpec{index, stmt->ColumnInt(0), stmt->ColumnText(1)};
  part.present = stmt->ColumnInt(2) != 0;
  return std::optional<PartRecord>(part);
}

Expected<std::vector<PartRecord>> SqliteMetadataStore::ListParts(const std::string& id) {
  std::lock_guard lock(mutex_);
  auto key = ClipKey(db_, id);
  if (!key) return key.error();
  if (!*key) return MakeError("not_found", "no clip " + id);
  // Frames 0..n-1 first, then the map (index -1): ORDER BY part_index < 0, part_index.
  auto stmt = db_.Prepare(
      "SELECT part_index, bytes, sha256, present FROM clip_parts WHERE clip_key = ?1 "
      "ORDER BY part_index < 0, part_index");
  if (!stmt) return stmt.error();
  stmt->Bind(1, **key);
  std::vector<PartRecord> parts;
  for (;;) {
    auto row = stmt->Step();
    if (!row) return row.error();
    if (!*row) break;
    PartRecord part;
    part.spec = PartSpec{static_cast<int>(stmt->ColumnInt(0)), stmt->ColumnInt(1),
                         stmt->ColumnText(2)};
    part.present = stmt->ColumnInt(3) != 0;
    parts.push_back(std::move(part));
  }
  return parts;
}

Status SqliteMetadataStore::MarkPartPresent(const std::string& id, int index) {
  std::lock_guard lock(mutex_);
  auto stmt = db_.Prepare(
      "UPDATE clip_parts SET present = 1 WHERE part_index = ?2 AND clip_key = "
      "(SELECT rowid_key FROM clips WHERE public_id = ?1)");
  if (!stmt) return stmt.error();
  stmt->BindText(1, id).Bind(2, index);
  if (Status s = stmt->Run(); !s) return s;
  if (db_.Changes() == 0) return MakeError("not_found", "no such part of clip " + id);
  return {};
}

Expected<PublishResult> SqliteMetadataStore::Publish(const std::string& id) {
  std::lock_guard lock(mutex_);
  auto tx = sqlite::Transaction::Begin(db_);
  if (!tx) return tx.error();
  auto key = ClipKey(db_, id);
  if (!key) return key.error();
  if (!*key) return MakeError("not_found", "no clip " + id);
  auto missing = db_.Prepare(
      "SELECT part_index FROM clip_parts WHERE clip_key = ?1 AND present = 0 ORDER BY part_index");
  if (!missing) return missing.error();
  missing->Bind(1, **key);
  PublishResult result;
  for (;;) {
    auto row = missing->Step();
    if (!row) return row.error();
    if (!*row) break;
    result.missing_parts.push_back(static_cast<int>(missing->ColumnInt(0)));
  }
  if (!result.missing_parts.empty()) return result;
  auto update = db_.Prepare(
      "UPDATE clips SET state = 'published', published_at = COALESCE(published_at, ?2) "
      "WHERE rowid_key = ?1");
  if (!update) return update.error();
  update->Bind(1, **key).Bind(2, NowUnix());
  if (Status s = update->Run(); !s) return s.error();
  if (Status s = tx->Commit(); !s) return s.error();
  result.published = true;
  return result;
}

Expected<bool> SqliteMetadataStore::DeleteClip(const std::string& id) {
  std::lock_guard lock(mutex_);
  auto stmt = db_.Prepare("DELETE FROM clips WHERE public_id = ?1");
  if (!stmt) return stmt.error();
  stmt->BindText(1, id);
  if (Status s = stmt->Run(); !s) return s.error();
  return db_.Changes() > 0;
}

Expected<std::vector<ClipRecord>> SqliteMetadataStore::ClipsOfOwner(int64_t owner_id) {
  std::lock_guard lock(mutex_);
  auto stmt = db_.Prepare(std::string("SELECT ") + kClipColumns +
                          " FROM clips c WHERE c.owner_id = ?1 ORDER BY c.created_at, c.public_id");
  if (!stmt) return stmt.error();
  stmt->Bind(1, owner_id);
  std::vector<ClipRecord> clips;
  for (;;) {
    auto row = stmt->Step();
    if (!row) return row.error();
    if (!*row) break;
    clips.push_back(ReadClip(*stmt));
  }
  return clips;
}

Expected<std::vector<NearbyHit>> SqliteMetadataStore::Nearby(const NearbyQuery& query) {
  REENACT_CHECK(query.limit >= 1, "nearby limit must be >= 1");
  REENACT_CHECK(query.radius_m >= 0.0 && query.radius_m <= kMaxNearbyRadiusM,
                "nearby radius out of range");
  // CROSS JOIN pins the R*Tree as the outer loop: otherwise SQLite may walk every published
  // clip through clips_by_state and probe the tree per row (linear in the clip count).
  static const std::string kNearbySql =
      std::string("SELECT ") + kClipColumns +
      " FROM clip_boxes b CROSS JOIN clips c ON c.rowid_key = b.id "
      "WHERE b.max_lat >= ?1 AND b.min_lat <= ?2 AND b.max_lon >= ?3 "
      "AND b.min_lon <= ?4 AND c.state = 'published'";
  // The lease resets the statement however this returns, ending the read transaction.
  sqlite::ReaderPool::Lease reader = readers_->Acquire();
  auto prepared = reader.Prepared(kNearbySql);
  if (!prepared) return prepared.error();
  sqlite::Statement* stmt = *prepared;
  std::vector<NearbyHit> hits;
  // Boxes overlap only when a query spans the antimeridian or a pole: then a clip can come
  // back twice, and only then are ids remembered.
  const std::vector<LatLonBox> boxes = BoundingBoxes(query.lat_deg, query.lon_deg, query.radius_m);
  std::set<std::string> seen;
  size_t scanned = 0;
  for (const LatLonBox& box : boxes) {
    stmt->Reset();
    stmt->Bind(1, box.min_lat_deg)
        .Bind(2, box.max_lat_deg)
        .Bind(3, box.min_lon_deg)
        .Bind(4, box.max_lon_deg);
    for (;;) {
      auto row = stmt->Step();
      if (!row) return row.error();
      if (!*row) break;
      if (query.max_scanned > 0 && ++scanned > query.max_scanned) {
        return MakeError("too_costly", "the search box holds more than " +
                                           std::to_string(query.max_scanned) + " rows");
      }
      // The distance first (columns 5, 6: lat, lon): most of a box's corners lie outside.
      const double d = HaversineDistanceM(query.lat_deg, query.lon_deg, stmt->ColumnDouble(5),
                                          stmt->ColumnDouble(6));
      if (d > query.radius_m) continue;
      ClipRecord clip = ReadClip(*stmt);
      if (boxes.size() > 1 && !seen.insert(clip.id).second) continue;
      if (!AfterNearbyCursor(query, d, clip.id)) continue;
      hits.push_back(NearbyHit{std::move(clip), d});
    }
  }
  SortAndTrimNearby(hits, query.limit);
  return hits;
}

Expected<int64_t> SqliteMetadataStore::CountClips(ClipState state) {
  std::lock_guard lock(mutex_);
  auto stmt = db_.Prepare("SELECT COUNT(*) FROM clips WHERE state = ?1");
  if (!stmt) return stmt.error();
  stmt->BindText(1, state == ClipState::kPublished ? "published" : "draft");
  auto row = stmt->Step();
  if (!row) return row.error();
  return stmt->ColumnInt(0);
}

}  // namespace reenact::server
