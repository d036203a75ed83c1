#include "server/storage/copy_storage.h"

#include <algorithm>
#include <chrono>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "proto/clip/content_hash.h"

namespace reenact::server {

namespace {

constexpr size_t kHashChunkBytes = size_t{1} << 20;

// An error after the target was first written: it says how to start again.
Error Incomplete(Error error) {
  error.message +=
      "; the target is incomplete: drop it (or create a new empty database) and run "
      "migrate-db again";
  return error;
}

Error Mismatch(const std::string& what) {
  return Incomplete(MakeError("mismatch", "verification failed: " + what));
}

Error Damaged(const std::string& what) {
  return Incomplete(MakeError("damaged_source", "the source is damaged: " + what));
}

// SHA-256 of a blob read in pieces; nullopt when the key is absent.
Expected<std::optional<std::string>> HashBlob(BlobStore& store, const std::string& key) {
  auto reader = store.OpenReader(key);
  if (!reader) return reader.error();
  if (!*reader) return std::optional<std::string>();
  proto::Sha256Hasher hasher;
  std::string chunk(kHashChunkBytes, '\0');
  for (uint64_t offset = 0; offset < (*reader)->size();) {
    auto got = (*reader)->Read(offset, std::span<char>(chunk.data(), chunk.size()));
    if (!got) return got.error();
    if (*got == 0) break;
    hasher.Update(std::string_view(chunk.data(), *got));
    offset += *got;
  }
  return std::optional<std::string>(hasher.FinalHex());
}

bool SameRecordButOwner(const ClipRecord& a, const ClipRecord& b) {
  return a.id == b.id && a.state == b.state && a.title == b.title && a.author == b.author &&
         a.lat_deg == b.lat_deg && a.lon_deg == b.lon_deg && a.alt_m == b.alt_m &&
         a.duration_s == b.duration_s && a.frame_count == b.frame_count &&
         a.manifest_sha256 == b.manifest_sha256;
}

bool SameParts(const std::vector<PartRecord>& a, const std::vector<PartRecord>& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i) {
    if (a[i].spec.index != b[i].spec.index || a[i].spec.bytes != b[i].spec.bytes ||
        a[i].spec.sha256 != b[i].spec.sha256 || a[i].present != b[i].present) {
      return false;
    }
  }
  return true;
}

std::vector<ClipRecord> SortedById(std::vector<ClipRecord> clips) {
  std::sort(clips.begin(), clips.end(),
            [](const ClipRecord& a, const ClipRecord& b) { return a.id < b.id; });
  return clips;
}

// What the copy read from the source, to verify the target against.
struct SourceUser {
  UserRecord user;
  std::vector<std::string> token_hashes;
  std::vector<ClipRecord> clips;  // sorted by id
};

struct Copier {
  Storage& source;
  Storage& target;
  std::vector<SourceUser> users;
  std::map<std::string, std::vector<PartRecord>> parts;  // by clip id
  std::vector<std::string> keys;                         // source blob keys, bytewise order
  std::map<std::string, std::string> blob_sha256;        // source blob key -> its hash
  std::map<std::string, std::string> part_sha256;        // key of a present part -> its hash
  CopySummary summary;

  Status RefuseNonEmptyTarget() {
    auto users = target.metadata->ListUsers();
    if (!users) return users.error();
    auto drafts = target.metadata->CountClips(ClipState::kDraft);
    if (!drafts) return drafts.error();
    auto published = target.metadata->CountClips(ClipState::kPublished);
    if (!published) return published.error();
    auto keys = target.blobs->ListKeys();
    if (!keys) return keys.error();
    if (users->empty() && *drafts + *published == 0 && keys->empty()) return {};
    return MakeError("not_empty",
                     "the target already holds " + std::to_string(users->size()) + " user(s), " +
                         std::to_string(*drafts + *published) + " clip(s) and " +
                         std::to_string(keys->size()) +
                         " blob(s); migrate-db copies only into an empty database: create a new "
                         "one (or drop this one) and run again");
  }

  // Copies the payload under key; its hash is remembered for verification.
  Expected<std::string> CopyBlob(const std::string& key) {
    auto bytes = source.blobs->Get(key);
    if (!bytes) return Incomplete(bytes.error());
    if (!*bytes) return Damaged("blob " + key + " disappeared while being copied");
    if (Status put = target.blobs->Put(key, **bytes); !put) return Incomplete(put.error());
    std::string sha = proto::Sha256Hex(**bytes);
    blob_sha256[key] = sha;
    summary.blob_bytes += static_cast<int64_t>((*bytes)->size());
    return sha;
  }

  Status CopyUsers() {
    auto listed = source.metadata->ListUsers();
    if (!listed) return listed.error();
    for (const UserRecord& user : *listed) {
      auto hashes = source.metadata->TokenHashesOfUser(user.id);
      if (!hashes) return Incomplete(hashes.error());
      auto clips = source.metadata->ClipsOfOwner(user.id);
      if (!clips) return Incomplete(clips.error());
      users.push_back(SourceUser{user, *hashes, SortedById(std::move(*clips))});
    }
    for (const SourceUser& u : users) {
      // A user without tokens is created with a placeholder no token hashes to (not hex),
      // revoked at once.
      std::string placeholder = "migrate-db-placeholder-";
      placeholder += std::to_string(u.user.id);
      const std::string& first = u.token_hashes.empty() ? placeholder : u.token_hashes[0];
      if (auto added = target.metadata->AddUser(u.user.name, first); !added) {
        return Incomplete(added.error());
      }
      if (u.token_hashes.empty()) {
        if (auto revoked = target.metadata->RevokeToken(placeholder); !revoked) {
          return Incomplete(revoked.error());
        }
      }
      for (size_t i = 1; i < u.token_hashes.size(); ++i) {
        if (auto added = target.metadata->AddToken(u.user.name, u.token_hashes[i]); !added) {
          return Incomplete(added.error());
        }
      }
      summary.tokens += static_cast<int64_t>(u.token_hashes.size());
    }
    summary.users = static_cast<int64_t>(users.size());
    return {};
  }

  // A clip as a draft, its payloads and present flags, then publication when published.
  Status CopyClip(const ClipRecord& clip, int64_t target_owner,
                  const std::set<std::string>& source_keys) {
    auto manifest = source.metadata->GetManifest(clip.id);
    if (!manifest) return Incomplete(manifest.error());
    if (proto::Sha256Hex(*manifest) != clip.manifest_sha256) {
      return Damaged("clip " + clip.id + "'s manifest does not hash to its manifest_sha256");
    }
    auto listed = source.metadata->ListParts(clip.id);
    if (!listed) return Incomplete(listed.error());
    NewClip draft;
    draft.record = clip;
    draft.record.owner_id = target_owner;
    draft.record.state = ClipState::kDraft;
    draft.manifest_json = *manifest;
    for (const PartRecord& part : *listed) draft.parts.push_back(part.spec);
    if (Status created = target.metadata->CreateClip(draft); !created) {
      return Incomplete(created.error());
    }
    for (const PartRecord& part : *listed) {
      const std::string key = BlobKey(clip.id, part.spec.index);
      const bool stored = source_keys.count(key) > 0;
      if (part.present && !stored) {
        return Damaged("part " + key + " is marked present but has no payload");
      }
      if (stored) {
        auto sha = CopyBlob(key);
        if (!sha) return sha.error();
        if (part.present && *sha != part.spec.sha256) {
          return Damaged("part " + key + " is marked present but its payload has another hash");
        }
      }
      if (part.present) {
        part_sha256[key] = part.spec.sha256;
        if (Status marked = target.metadata->MarkPartPresent(clip.id, part.spec.index); !marked) {
          return Incomplete(marked.error());
        }
      }
    }
    summary.parts += static_cast<int64_t>(listed->size());
    parts[clip.id] = std::move(*listed);
    if (clip.state == ClipState::kPublished) {
      auto published = target.metadata->Publish(clip.id);
      if (!published) return Incomplete(published.error());
      if (!published->published) return Mismatch("clip " + clip.id + " could not be published");
      ++summary.published_clips;
    }
    ++summary.clips;
    return {};
  }

  Status CopyAll() {
    auto listed_keys = source.blobs->ListKeys();
    if (!listed_keys) return listed_keys.error();
    keys = std::move(*listed_keys);
    const std::set<std::string> source_keys(keys.begin(), keys.end());
    if (Status s = CopyUsers(); !s) return s;
    auto target_users = target.metadata->ListUsers();
    if (!target_users) return Incomplete(target_users.error());
    std::map<std::string, int64_t> target_id;
    for (const UserRecord& u : *target_users) target_id[u.name] = u.id;
    for (const SourceUser& u : users) {
      for (const ClipRecord& clip : u.clips) {
        if (Status s = CopyClip(clip, target_id[u.user.name], source_keys); !s) return s;
      }
    }
    for (const std::string& key : keys) {  // payloads that belong to no part
      if (blob_sha256.count(key)) continue;
      if (auto sha = CopyBlob(key); !sha) return sha.error();
    }
    summary.blobs = static_cast<int64_t>(keys.size());
    return {};
  }

  Status Verify() {
    auto target_users = target.metadata->ListUsers();
    if (!target_users) return Incomplete(target_users.error());
    if (target_users->size() != users.size()) {
      return Mismatch("the target has " + std::to_string(target_users->size()) +
                      " users where the source has " + std::to_string(users.size()));
    }
    int64_t drafts = 0, published = 0, part_count = 0;
    for (size_t i = 0; i < users.size(); ++i) {
      const SourceUser& u = users[i];
      const UserRecord& t = (*target_users)[i];
      if (t.name != u.user.name) return Mismatch("user '" + u.user.name + "' is missing");
      auto hashes = target.metadata->TokenHashesOfUser(t.id);
      if (!hashes) return Incomplete(hashes.error());
      if (*hashes != u.token_hashes) return Mismatch("the tokens of '" + u.user.name + "' differ");
      auto clips = target.metadata->ClipsOfOwner(t.id);
      if (!clips) return Incomplete(clips.error());
      const std::vector<ClipRecord> sorted = SortedById(std::move(*clips));
      if (sorted.size() != u.clips.size()) {
        return Mismatch("user '" + u.user.name + "' owns " + std::to_string(sorted.size()) +
                        " clips on the target, " + std::to_string(u.clips.size()) +
                        " on the source");
      }
      for (size_t c = 0; c < sorted.size(); ++c) {
        const ClipRecord& clip = sorted[c];
        if (!SameRecordButOwner(clip, u.clips[c])) {
          return Mismatch("clip " + u.clips[c].id + " differs on the target");
        }
        auto manifest = target.metadata->GetManifest(clip.id);
        if (!manifest) return Incomplete(manifest.error());
        if (proto::Sha256Hex(*manifest) != clip.manifest_sha256) {
          return Mismatch("clip " + clip.id + "'s manifest does not hash to its manifest_sha256");
        }
        auto target_parts = target.metadata->ListParts(clip.id);
        if (!target_parts) return Incomplete(target_parts.error());
        if (!SameParts(*target_parts, parts[clip.id])) {
          return Mismatch("the parts of clip " + clip.id + " differ");
        }
        part_count += static_cast<int64_t>(target_parts->size());
        ++(clip.state == ClipState::kPublished ? published : drafts);
      }
    }
    auto target_drafts = target.metadata->CountClips(ClipState::kDraft);
    if (!target_drafts) return Incomplete(target_drafts.error());
    auto target_published = target.metadata->CountClips(ClipState::kPublished);
    if (!target_published) return Incomplete(target_published.error());
    if (*target_drafts != drafts || *target_published != published ||
        published != summary.published_clips || drafts + published != summary.clips ||
        part_count != summary.parts) {
      return Mismatch("the target counts " + std::to_string(*target_drafts) + " drafts and " +
                      std::to_string(*target_published) + " published clips, the source " +
                      std::to_string(summary.clips - summary.published_clips) + " and " +
                      std::to_string(summary.published_clips));
    }
    auto target_keys = target.blobs->ListKeys();
    if (!target_keys) return Incomplete(target_keys.error());
    if (*target_keys != keys) {
      return Mismatch("the target holds " + std::to_string(target_keys->size()) +
                      " blobs where the source holds " + std::to_string(keys.size()));
    }
    for (const std::string& key : keys) {
      auto sha = HashBlob(*target.blobs, key);
      if (!sha) return Incomplete(sha.error());
      if (!*sha || **sha != blob_sha256[key]) {
        return Mismatch("blob " + key + " on the target does not hash as on the source");
      }
      if (auto part = part_sha256.find(key); part != part_sha256.end() && **sha != part->second) {
        return Mismatch("blob " + key + " does not hash to its part's sha256");
      }
    }
    return {};
  }
};

}  // namespace

Expected<CopySummary> CopyStorage(Storage& source, Storage& target) {
  const auto start = std::chrono::steady_clock::now();
  Copier copier{source, target, {}, {}, {}, {}, {}, {}};
  if (Status s = copier.RefuseNonEmptyTarget(); !s) return s.error();
  if (Status s = copier.CopyAll(); !s) return s.error();
  if (Status s = copier.Verify(); !s) return s.error();
  copier.summary.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return copier.summary;
}

}  // namespace reenact::server
