#pragma once
// MetadataStore: users and tokens, clips (drafts and published), their parts, nearby search.
// Storage-agnostic; SqliteMetadataStore is the embedded implementation, and a deployment that
// outgrows one machine can implement this on PostgreSQL/PostGIS without touching the routes.
// Every method is safe to call from several threads. Failures of the store itself come back
// with code "storage", or "unavailable" when the database server cannot be reached (the store
// works again once it can: retry); they never carry user input back out.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "common/error/expected.h"

namespace reenact::server {

struct UserRecord {
  int64_t id = 0;
  std::string name;
};

// A token lookup's result: the owner and the hash as stored (for a constant-time check).
struct TokenOwner {
  UserRecord user;
  std::string stored_sha256;
};

// A part promised by the manifest: a frame (index >= 0) or the map (index kMapPart).
inline constexpr int kMapPart = -1;

struct PartSpec {
  int index = 0;       // frame number, or kMapPart
  int64_t bytes = 0;   // exact payload size
  std::string sha256;  // 64 lowercase hex digits of the payload's SHA-256
};

struct PartRecord {
  PartSpec spec;
  bool present = false;  // the payload has arrived and matched size and hash
};

enum class ClipState { kDraft, kPublished };

// What the routes need to know about a clip (the manifest itself is fetched separately).
struct ClipRecord {
  std::string id;  // opaque public id
  int64_t owner_id = 0;
  ClipState state = ClipState::kDraft;
  std::string title;
  std::string author;
  double lat_deg = 0.0;
  double lon_deg = 0.0;
  double alt_m = 0.0;
  double duration_s = 0.0;
  int frame_count = 0;
  std::string manifest_sha256;  // hex SHA-256 of the manifest bytes as uploaded
};

// A new draft with every part it must receive before it may be published.
struct NewClip {
  ClipRecord record;          // state is ignored: a new clip is a draft
  std::string manifest_json;  // stored byte for byte
  std::vector<PartSpec> parts;
};

// Published clips within radius_m of (lat_deg, lon_deg), sorted by (distance, id), starting
// strictly after `after` when set, at most `limit` of them.
struct NearbyQuery {
  double lat_deg = 0.0;     // [-90, 90]
  double lon_deg = 0.0;     // [-180, 180]
  double radius_m = 0.0;    // [0, kMaxNearbyRadiusM]
  int limit = 20;           // >= 1
  struct Key {
    double distance_m = 0.0;
    std::string id;
  };
  std::optional<Key> after;  // keyset pagination cursor
  // Rows of the search box examined at most; 0 = no bound. Past it the search stops with code
  // "too_costly" (the caller may run it again without a bound, elsewhere).
  size_t max_scanned = 0;
};

// Largest radius nearby search accepts: 2000 km (a "near me" query, not a world dump).
inline constexpr double kMaxNearbyRadiusM = 2'000'000.0;

struct NearbyHit {
  ClipRecord clip;
  double distance_m = 0.0;  // haversine great-circle distance from the query point
};

// The keyset order every store pages nearby search by, so that a cursor means the same on any
// engine: whether a hit at (distance_m, id) comes strictly after the query's cursor.
inline bool AfterNearbyCursor(const NearbyQuery& query, double distance_m, const std::string& id) {
  return !query.after || std::tie(distance_m, id) > std::tie(query.after->distance_m,
                                                             query.after->id);
}

// Sorts hits by (distance, id) and keeps the first `limit`.
inline void SortAndTrimNearby(std::vector<NearbyHit>& hits, int limit) {
  std::sort(hits.begin(), hits.end(), [](const NearbyHit& a, const NearbyHit& b) {
    return std::tie(a.distance_m, a.clip.id) < std::tie(b.distance_m, b.clip.id);
  });
  if (hits.size() > static_cast<size_t>(limit)) hits.resize(static_cast<size_t>(limit));
}

struct PublishResult {
  bool published = false;            // true: the clip is now (or already was) visible
  std::vector<int> missing_parts;    // when not published: indices still absent (kMapPart = map)
};

class MetadataStore {
 public:
  virtual ~MetadataStore() = default;

  // Adds a user with one token; code "conflict" when the name exists.
  virtual Expected<UserRecord> AddUser(const std::string& name,
                                       const std::string& token_sha256) = 0;
  // The user owning a token hash, or nullopt.
  virtual Expected<std::optional<TokenOwner>> FindUserByTokenHash(
      const std::string& token_sha256) = 0;
  // Adds another token to an existing user; code "not_found" when there is no such user.
  virtual Expected<UserRecord> AddToken(const std::string& user_name,
                                        const std::string& token_sha256) = 0;
  // Revokes one token (it stops authenticating at once); false when it was unknown.
  virtual Expected<bool> RevokeToken(const std::string& token_sha256) = 0;
  // Revokes every token of a user; returns how many; code "not_found" for no such user.
  virtual Expected<int> RevokeUserTokens(const std::string& user_name) = 0;
  // Every user, by id (to copy a whole store: reenact-server migrate-db).
  virtual Expected<std::vector<UserRecord>> ListUsers() = 0;
  // The token hashes of a user, oldest first; empty when it has none or there is no such user.
  virtual Expected<std::vector<std::string>> TokenHashesOfUser(int64_t user_id) = 0;

  // Creates a draft; code "conflict" when the id exists.
  virtual Status CreateClip(const NewClip& clip) = 0;
  virtual Expected<std::optional<ClipRecord>> GetClip(const std::string& id) = 0;
  // The manifest bytes exactly as uploaded; code "not_found" when the clip does not exist.
  virtual Expected<std::string> GetManifest(const std::string& id) = 0;
  virtual Expected<std::optional<PartRecord>> GetPart(const std::string& id, int index) = 0;
  // Every part the clip's manifest promises, frames in order then the map (kMapPart last);
  // code "not_found" when the clip does not exist.
  virtual Expected<std::vector<PartRecord>> ListParts(const std::string& id) = 0;
  virtual Status MarkPartPresent(const std::string& id, int index) = 0;
  // In one transaction: if every part is present the clip becomes published.
  virtual Expected<PublishResult> Publish(const std::string& id) = 0;
  // Removes the clip and its part records; false when it did not exist.
  virtual Expected<bool> DeleteClip(const std::string& id) = 0;
  virtual Expected<std::vector<ClipRecord>> ClipsOfOwner(int64_t owner_id) = 0;
  virtual Expected<std::vector<NearbyHit>> Nearby(const NearbyQuery& query) = 0;
  virtual Expected<int64_t> CountClips(ClipState state) = 0;
};

}  // namespace reenact::server
