#pragma once
// MetadataStore on PostgreSQL with PostGIS (schema: migrations/postgresql/*.sql), with the
// semantics of SqliteMetadataStore: the same error codes, one transaction per multi-row
// change, and the same keyset order for nearby search.
//
// Nearby search pre-filters in the database with ST_DWithin on the clips' geography points
// (GiST index over published clips; right across the antimeridian and at the poles) on the
// sphere, with a radius a little larger than asked; the exact filter and the reported
// distance are the haversine distance of server/geo/geodesic.h computed here, as the SQLite
// store computes it. Both engines therefore report bit-identical distances and page through
// the same (distance, id) keys, so a cursor means the same on either.
//
// A pool of connections, one lent to each call for its duration, so that several handler
// threads query at once; every method is safe to call from several threads. A connection the
// server dropped is reopened before the next statement (outside a transaction).

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "server/storage/metadata_store.h"
#include "server/storage/postgres_pool.h"

namespace reenact::server {

class PostgresMetadataStore : public MetadataStore {
 public:
  // Connects to `url` (postgresql://user:password@host:port/database) and applies pending
  // migrations. Codes: "invalid_argument" for a malformed URL, "io" when the server cannot be
  // reached or refuses the login (one line, never the password), "schema_too_new",
  // "migration_failed".
  static Expected<std::unique_ptr<PostgresMetadataStore>> Open(
      const std::string& url, int connections = kDefaultConnections);

  // Default number of connections: as many as the server's default handler threads use.
  static constexpr int kDefaultConnections = 4;

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
  explicit PostgresMetadataStore(std::shared_ptr<pg::ConnectionPool> pool)
      : pool_(std::move(pool)) {}

  std::shared_ptr<pg::ConnectionPool> pool_;
};

}  // namespace reenact::server
