#pragma once
// MetadataStore on SQLite (schema: migrations/*.sql). Nearby search pre-filters with the
// clip_boxes R*Tree over the query's covering boxes (server/geo/geodesic.h), then filters and
// sorts by exact haversine distance. Writes and most reads go through one connection guarded
// by a mutex; nearby searches, the hot read path, run on a pool of read-only connections
// (sqlite::ReaderPool; WAL lets them read committed data concurrently).

#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "server/storage/metadata_store.h"
#include "server/storage/reader_pool.h"
#include "server/storage/sqlite.h"
#include "server/storage/wal_checkpointer.h"

namespace reenact::server {

class SqliteMetadataStore : public MetadataStore {
 public:
  // Opens (creating if needed) the database at path and applies pending migrations. Every
  // connection commits as `sync` says.
  static Expected<std::unique_ptr<SqliteMetadataStore>> Open(
      const std::string& path, sqlite::Sync sync = sqlite::Sync::kFull);

  Expected<UserRecord> AddUser(const std::string& name, const std::string& token_sha256) override;
  Expected<std::optional<TokenOwner>> FindUserByTokenHash(
      const std::string& token_sha256) override;
  Expected<UserRecord> AddToken(const std::string& user_name,
                                const std::string& token_sha256) override;
  Expected<bool> RevokeToken(const std::string& token_sha256) override;
  Expected<int> RevokeUserTokens(const std::string& user_name) override;
  Expected<std::vector<UserRecord>> ListUsers() override;
  Expected<std::vector<std::string>> TokenHashesOfUser(int64_t user_id) override;
  Status CreateClip(const NewClip& clip) override;
  Expected<std::optional<ClipRecord>> GetClip(const std::string& id) override;
  Expected<std::string> GetManifest(const std::string& id) override;
  Expected<std::optional<PartRecord>> GetPart(const std::string& id, int index) override;
  Expected<std::vector<PartRecord>> ListParts(const std::string& id) override;
  Status MarkPartPresent(const std::string& id, int index) override;
  Expected<PublishResult> Publish(const std::string& id) override;
  Expected<bool> DeleteClip(const std::string& id) override;
  Expected<std::vector<ClipRecord>> ClipsOfOwner(int64_t owner_id) override;
  Expected<std::vector<NearbyHit>> Nearby(const NearbyQuery& query) override;
  Expected<int64_t> CountClips(ClipState state) override;

 private:
  explicit SqliteMetadataStore(sqlite::Database db) : db_(std::move(db)) {}

  std::mutex mutex_;
  std::shared_ptr<sqlite::WalCheckpointer> checkpointer_;  // outlives db_
  sqlite::Database db_;
  std::unique_ptr<sqlite::ReaderPool> readers_;  // for Nearby
};

}  // namespace reenact::server
