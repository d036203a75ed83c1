#include "capture-client/publish/clip_publisher.h"

#include <chrono>
#include <cstdio>
#include <vector>

#include "common/error/check.h"
#include "proto/api/api_client.h"
#include "proto/clip/clip_directory.h"
#include "proto/clip/content_hash.h"

namespace reenact::capture {
namespace {

using Clock = std::chrono::steady_clock;

std::string AsString(const std::vector<uint8_t>& bytes) {
  return std::string(bytes.begin(), bytes.end());
}

std::string PartName(int index) {
  return index == proto::kMapPartIndex ? std::string("the map") : "frame " + std::to_string(index);
}

// A part to send: its index and size (the bytes are read again when it is sent).
struct PendingPart {
  int index = 0;
  uint64_t bytes = 0;
};

class Uploader {
 public:
  Uploader(const proto::ClipDirectory& clip, const PublishOptions& options)
      : clip_(clip),
        api_(options.server_url, options.token, {}, options.retry),
        printer_(stdout, options.progress) {
    api_.set_retry_observer([this](const proto::RetryNotice& notice) {
      ++summary_.retries;
      char text[96];
      std::snprintf(text, sizeof(text), " in %.1f s (attempt %d of %d failed): ", notice.delay_s,
                    notice.attempt, notice.max_attempts);
      printer_.Note("retrying " + notice.request + text + notice.cause.message);
    });
  }

  Expected<PublishSummary> Run(const std::string& manifest_json) {
    const proto::ClipManifest& manifest = clip_.manifest();
    summary_.frames = static_cast<int>(manifest.frame_count);
    summary_.parts_total = summary_.frames + 1;
    for (int n = 0; n < summary_.frames; ++n) total_bytes_ += manifest.frame_parts[n].bytes;
    total_bytes_ += manifest.map_part.bytes;

    if (Status s = FindOrCreateDraft(manifest_json); !s) return s.error();
    if (summary_.already_published) return summary_;
    auto pending = PendingParts();
    if (!pending) return Resumable(pending.error());
    if (Status s = Upload(*pending); !s) return Resumable(s.error());
    Status published = api_.Publish(summary_.clip_id);
    if (!published && published.error().code == "incomplete") {
      // The server found a stored part damaged after it was acknowledged: one more round.
      std::printf("the server reports: %s; sending those parts again\n",
                  published.error().message.c_str());
      pending = PendingParts();
      if (!pending) return Resumable(pending.error());
      if (Status s = Upload(*pending); !s) return Resumable(s.error());
      published = api_.Publish(summary_.clip_id);
    }
    if (!published) return Resumable(published.error());
    return summary_;
  }

 private:
  Status FindOrCreateDraft(const std::string& manifest_json) {
    auto mine = api_.MyClipsWithManifest(proto::Sha256Hex(manifest_json));
    if (!mine) return NothingSent(mine.error());
    for (const proto::OwnClip& clip : *mine) {
      if (clip.published) {
        summary_.clip_id = clip.summary.id;
        summary_.already_published = true;
        summary_.parts_skipped = summary_.parts_total;
        std::printf("this clip is already published as %s; nothing to send\n",
                    clip.summary.id.c_str());
        return {};
      }
    }
    if (!mine->empty()) {
      summary_.clip_id = mine->front().summary.id;
      summary_.resumed = true;
      std::printf("resuming draft %s\n", summary_.clip_id.c_str());
      return {};
    }
    auto id = api_.CreateClip(manifest_json);
    if (!id) return NothingSent(id.error());
    summary_.clip_id = *id;
    summary_.bytes_sent += manifest_json.size();
    std::printf("created draft %s\n", id->c_str());
    return {};
  }

  // Parts the server does not hold intact, frames in order then the map.
  Expected<std::vector<PendingPart>> PendingParts() {
    const proto::ClipManifest& manifest = clip_.manifest();
    std::vector<PendingPart> pending;
    done_bytes_ = 0;
    done_parts_ = 0;
    if (!summary_.resumed && !listed_once_) {
      // A draft created by this run holds nothing yet.
      listed_once_ = true;
      for (int n = 0; n < summary_.frames; ++n) {
        pending.push_back({n, manifest.frame_parts[n].bytes});
      }
      pending.push_back({proto::kMapPartIndex, manifest.map_part.bytes});
      parts_known_ = true;
      return pending;
    }
    listed_once_ = true;
    parts_known_ = false;
    auto parts = api_.ListParts(summary_.clip_id);
    if (!parts) return parts.error();
    if (static_cast<int>(parts->parts.size()) != summary_.parts_total) {
      return MakeError("conflict", "draft " + summary_.clip_id + " on the server has " +
                                       std::to_string(parts->parts.size()) +
                                       " parts but the clip has " +
                                       std::to_string(summary_.parts_total));
    }
    int skipped = 0;
    for (const proto::PartStatus& part : parts->parts) {
      if (part.Complete()) {
        ++skipped;
        ++done_parts_;
        done_bytes_ += part.bytes;
        continue;
      }
      if (part.held) {
        ++summary_.parts_repaired;
        std::printf("the server's copy of %s differs from the clip; sending it again\n",
                    PartName(part.index).c_str());
      }
      pending.push_back({part.index, part.bytes});
    }
    // The first listing of a resumed draft says what was already there.
    if (!counted_skipped_) {
      summary_.parts_skipped = skipped;
      counted_skipped_ = true;
      std::printf("%d of %d parts are already on the server; %zu to send\n", skipped,
                  summary_.parts_total, pending.size());
    }
    parts_known_ = true;
    return pending;
  }

  Status Upload(const std::vector<PendingPart>& pending) {
    const auto start = Clock::now();
    auto snapshot = [&] {
      UploadSnapshot s;
      s.total_bytes = total_bytes_;
      s.done_bytes = done_bytes_;
      s.sent_bytes = sent_bytes_;
      s.total_parts = summary_.parts_total;
      s.done_parts = done_parts_;
      s.elapsed_s = std::chrono::duration<double>(Clock::now() - start).count();
      return s;
    };
    printer_.Update(snapshot());
    for (const PendingPart& part : pending) {
      const bool map = part.index == proto::kMapPartIndex;
      auto bytes = map ? clip_.ReadMapBytes() : clip_.ReadFrameBytes(part.index);
      if (!bytes) return bytes.error();
      const std::string body = AsString(*bytes);
      Status sent = map ? api_.PutMap(summary_.clip_id, body)
                        : api_.PutFrame(summary_.clip_id, part.index, body);
      if (!sent) {
        printer_.Finish(snapshot());
        return MakeError(sent.error().code,
                         "uploading " + PartName(part.index) + " failed: " + sent.error().message);
      }
      ++summary_.parts_sent;
      summary_.bytes_sent += body.size();
      sent_bytes_ += body.size();
      done_bytes_ += body.size();
      ++done_parts_;
      printer_.Update(snapshot());
    }
    printer_.Finish(snapshot());
    return {};
  }

  // Nothing was created on the server: a plain re-run starts over.
  Error NothingSent(const Error& error) const {
    return MakeError(error.code, error.message +
                                     "; nothing was uploaded; run the same command again when "
                                     "the server is reachable");
  }

  // The draft stays on the server, invisible to others: a re-run resumes it.
  Error Resumable(const Error& error) const {
    const std::string held = parts_known_
                                 ? " keeps the " + std::to_string(done_parts_) + " of " +
                                       std::to_string(summary_.parts_total) + " parts it holds and"
                                 : "";
    return MakeError(error.code, error.message + "; draft " + summary_.clip_id + held +
                                     " is not visible to others: run the same command again "
                                     "to resume the upload");
  }

  const proto::ClipDirectory& clip_;
  proto::ApiClient api_;
  ProgressPrinter printer_;
  PublishSummary summary_;
  uint64_t total_bytes_ = 0;
  uint64_t done_bytes_ = 0;
  uint64_t sent_bytes_ = 0;
  int done_parts_ = 0;
  bool listed_once_ = false;
  bool counted_skipped_ = false;
  bool parts_known_ = false;
};

}  // namespace

void PublishOptions::Check() const {
  REENACT_CHECK(!server_url.empty(), "server_url must be set");
  REENACT_CHECK(!token.empty(), "token must be set");
  retry.Check();
}

Expected<PublishSummary> PublishClip(const std::filesystem::path& clip_dir,
                                     const PublishOptions& options) {
  options.Check();
  const auto start = Clock::now();
  auto clip = proto::ReadClipDirectory(clip_dir);
  if (!clip.ok()) return clip.error();
  proto::ClipManifest manifest = clip->manifest();
  manifest.location = options.location;
  if (options.title) manifest.title = *options.title;
  const std::string manifest_json = proto::SerializeManifest(manifest);
  if (auto valid = proto::ParseManifest(manifest_json); !valid.ok()) return valid.error();

  // Every part is read and verified before the first byte goes out: a damaged clip is
  // refused without leaving a draft behind. (Parts are read again, one at a time, to send.)
  for (int64_t n = 0; n < manifest.frame_count; ++n) {
    if (auto bytes = clip->ReadFrameBytes(n); !bytes.ok()) return bytes.error();
  }
  if (auto map = clip->ReadMapBytes(); !map.ok()) return map.error();

  Uploader uploader(*clip, options);
  auto summary = uploader.Run(manifest_json);
  if (!summary) return summary.error();
  summary->seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return summary;
}

}  // namespace reenact::capture
