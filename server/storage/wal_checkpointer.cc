#include "server/storage/wal_checkpointer.h"

#include <sqlite3.h>

#include <filesystem>
#include <iostream>
#include <map>

namespace reenact::server::sqlite {

namespace {

int WalHook(void* checkpointer, sqlite3*, const char*, int frames) {
  static_cast<WalCheckpointer*>(checkpointer)->OnCommit(frames);
  return SQLITE_OK;
}

}  // namespace

void WalCheckpointOptions::Check() const {
  REENACT_CHECK(start_frames >= 1, "start_frames must be >= 1");
  REENACT_CHECK(restart_frames >= start_frames, "restart_frames must be >= start_frames");
}

Expected<std::shared_ptr<WalCheckpointer>> WalCheckpointer::ForFile(
    const std::string& path, const WalCheckpointOptions& options) {
  options.Check();
  static std::mutex registry_mutex;
  static std::map<std::string, std::weak_ptr<WalCheckpointer>> registry;
  std::error_code ec;
  std::string key = std::filesystem::weakly_canonical(path, ec).string();
  if (ec) key = path;
  std::lock_guard lock(registry_mutex);
  std::erase_if(registry, [](const auto& entry) { return entry.second.expired(); });
  if (auto existing = registry[key].lock()) return existing;
  auto db = Database::Open(path);
  if (!db) return db.error();
  std::shared_ptr<WalCheckpointer> checkpointer(new WalCheckpointer(std::move(*db), options));
  registry[key] = checkpointer;
  return checkpointer;
}

WalCheckpointer::WalCheckpointer(Database db, const WalCheckpointOptions& options)
    : db_(std::move(db)), options_(options), thread_([this] { Loop(); }) {}

WalCheckpointer::~WalCheckpointer() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

void WalCheckpointer::Attach(Database& db) {
  // Replaces SQLite's own auto-checkpoint, which is itself a WAL hook.
  sqlite3_wal_hook(db.raw(), &WalHook, this);
}

int64_t WalCheckpointer::checkpoints() const {
  std::lock_guard lock(mutex_);
  return checkpoints_;
}

void WalCheckpointer::OnCommit(int frames) {
  {
    std::lock_guard lock(mutex_);
    frames_ = frames;
    if (frames < options_.start_frames) return;
  }
  wake_.notify_one();
}

void WalCheckpointer::Loop() {
  std::unique_lock lock(mutex_);
  for (;;) {
    wake_.wait(lock, [this] { return stop_ || frames_ >= options_.start_frames; });
    if (stop_) return;
    const int mode =
        frames_ >= options_.restart_frames ? SQLITE_CHECKPOINT_RESTART : SQLITE_CHECKPOINT_PASSIVE;
    frames_ = 0;
    lock.unlock();
    const int rc = sqlite3_wal_checkpoint_v2(db_.raw(), nullptr, mode, nullptr, nullptr);
    if (rc != SQLITE_OK && rc != SQLITE_BUSY) {
      // The WAL keeps the data; the next commit asks again.
      std::cerr << "reenact-server: WAL checkpoint of " << db_.path()
                << " failed: " << sqlite3_errmsg(db_.raw()) << std::endl;
    }
    lock.lock();
    ++checkpoints_;
  }
}

}  // namespace reenact::server::sqlite
