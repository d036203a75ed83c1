#pragma once
// Background WAL checkpoints for one SQLite database file.
//
// In WAL mode a commit appends pages to the -wal file (and fsyncs it with synchronous=FULL,
// Database::Open's default; with NORMAL it does not); the checkpoint (copy the WAL back into the
// database file) is where SQLite syncs the database file, after the WAL. By default every
// connection runs that checkpoint itself after any commit that leaves the WAL above 1000 pages, on
// the request thread, holding its store's mutex through both fsyncs. A WalCheckpointer takes the
// job over: the writing connections attached to it only report the WAL's size after each commit; a
// thread with its own connection runs the checkpoints. Durability is unchanged: committed
// transactions are in the WAL, which SQLite replays after a crash or kill -9 whether or not it was
// checkpointed.
//
// Checkpoints are PASSIVE (they never block readers or writers) once the WAL holds
// start_frames pages. Readers can pin old frames and keep a passive checkpoint from finishing,
// so the WAL would keep growing; past restart_frames pages a RESTART checkpoint waits (up to
// the connection's busy timeout) for those readers and lets the WAL start over.

#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "common/error/expected.h"
#include "server/storage/sqlite.h"

namespace reenact::server::sqlite {

struct WalCheckpointOptions {
  // WAL size (pages) at which a passive checkpoint starts; >= 1. Default 4096 (16 MiB of
  // 4 KiB pages): fewer, larger checkpoints than SQLite's 1000.
  int start_frames = 4096;
  // WAL size (pages) past which the checkpoint waits for readers; >= start_frames.
  // Default 65536 (256 MiB).
  int restart_frames = 65536;

  void Check() const;
};

class WalCheckpointer {
 public:
  // The checkpointer of the database file at `path`, shared by all its users in this process;
  // started (with `options`) by the first call for that file. Fails like Database::Open.
  static Expected<std::shared_ptr<WalCheckpointer>> ForFile(
      const std::string& path, const WalCheckpointOptions& options = {});

  // Stops the thread after the checkpoint in progress, if any.
  ~WalCheckpointer();
  WalCheckpointer(const WalCheckpointer&) = delete;
  WalCheckpointer& operator=(const WalCheckpointer&) = delete;

  // From now on `db`'s commits leave checkpoints to this object. `db` must be a connection
  // to the same file and must close before this object is destroyed (hold the shared_ptr).
  void Attach(Database& db);

  // Checkpoints run so far (passive or restart, finished or not).
  int64_t checkpoints() const;

  // Called by SQLite after each commit of an attached connection (the WAL holds `frames`).
  void OnCommit(int frames);

 private:
  WalCheckpointer(Database db, const WalCheckpointOptions& options);
  void Loop();

  Database db_;
  const WalCheckpointOptions options_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  int frames_ = 0;  // WAL size at the last commit; 0 once a checkpoint is under way
  int64_t checkpoints_ = 0;
  std::thread thread_;  // last: starts once the members above exist
};

}  // namespace reenact::server::sqlite
