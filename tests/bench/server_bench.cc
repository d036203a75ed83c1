// reenact-bench server: the sharing service under load on loopback.
//   1. Seeds N published clips' metadata at uniformly random places in a 10 x 20 degree box
//      (southern Europe) straight through the storage layer (one transaction).
//   2. Nearby search through the store alone (us_per_query), then over HTTP with `clients`
//      keep-alive client threads for `seconds`: qps, p50_ms, p99_ms.
//   3. Uploads: `clients` threads PUT 1 MiB frames for `seconds` (bounded in bytes): mb_per_s,
//      with every commit synced to disk (the default) and again without (upload_http_unsynced,
//      synchronous=NORMAL): what the durability of a 204 costs.
// N is 10^5 and 10^6 (only 10^5 with --quick; --clips N picks one). Loopback only.
// With --db DIR the seeded databases stay in DIR as bench-N.db, and a later run with the same
// N reuses one that holds N published clips (the uploads add only drafts).
// With --db postgresql://... each N runs on SQLite (a temporary file) and then on that
// PostgreSQL database, in one table (column engine); the database is the bench's own: its
// "seed" user's clips are replaced unless it already holds N of them. PostgreSQL uploads are
// synced as its server is configured, so they have no unsynced row but one with the parts as
// files (upload_http_files, --blobs in a temporary directory). Then the kill run
// (server_kill_bench.h): two `reenact-server` processes (--server PATH, default the build
// tree's) on that database and --kills K random SIGKILLs (default 50).
// --attacks runs only the adversarial section instead (server_attack_bench.h): 10^4 clips
// (--clips N), C normal clients, S seconds per measurement (default 8), about 3 minutes.
#include "tests/bench/server_bench.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <boost/beast/http.hpp>
#include <filesystem>
#include <functional>
#include <iostream>
#include <mutex>
#include <random>
#include <thread>

#include "proto/api/api_client.h"
#include "proto/clip/content_hash.h"
#include "proto/clip/manifest.h"
#include "proto/report/report_table.h"
#include "server/auth/token.h"
#include "server/http/http_server.h"
#include "server/storage/open_storage.h"
#include "server/storage/sqlite.h"
#include "tests/bench/bench_support.h"
#include "tests/bench/server_attack_bench.h"
#include "tests/bench/server_bench_support.h"
#include "tests/bench/server_kill_bench.h"

namespace reenact::bench {
namespace {

namespace http = boost::beast::http;

constexpr size_t kUploadFrameBytes = size_t{1} << 20;
constexpr size_t kMaxUploadBytes = size_t{1} << 30;  // bound on what one run writes

struct Settings {
  std::vector<long long> clip_counts;
  int clients = 4;
  double seconds = 3;
  std::string db_dir;   // where the SQLite databases go (a temp dir unless --db DIR)
  bool keep_db = false;  // --db DIR: seeded databases stay there and later runs reuse them
  std::string postgres_url;  // --db URL: PostgreSQL beside SQLite, and the kill run
  std::string server_binary;  // reenact-server, for the kill run's server processes
  int kills = 50;
};

// Nearby through the metadata store alone: microseconds per query, after as many untimed
// queries (which warm the caches: a PostgreSQL session's first PostGIS query takes ~30 ms).
double StoreMicrosPerQuery(server::MetadataStore& store, int queries) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> lat(kMinLat + 0.1, kMaxLat - 0.1),
      lon(kMinLon + 0.1, kMaxLon - 0.1);
  auto t0 = Clock::now();
  for (int i = 0; i < 2 * queries; ++i) {
    if (i == queries) t0 = Clock::now();
    server::NearbyQuery q;
    q.lat_deg = lat(rng);
    q.lon_deg = lon(rng);
    q.radius_m = kQueryRadiusM;
    q.limit = kQueryLimit + 1;
    if (!store.Nearby(q)) return -1;
  }
  return std::chrono::duration<double, std::micro>(Clock::now() - t0).count() / queries;
}

struct LoadResult {
  double qps = 0, p50_ms = 0, p99_ms = 0, mean_hits = 0, mb_per_s = 0;
  long long errors = 0, requests = 0;
};

LoadResult NearbyLoad(uint16_t port, const Settings& settings) {
  std::mutex mutex;
  std::vector<double> latencies_ms;
  std::atomic<long long> errors{0}, hits_total{0};
  const auto until = Clock::now() + std::chrono::duration<double>(settings.seconds);
  const auto t0 = Clock::now();
  std::vector<std::thread> threads;
  for (int c = 0; c < settings.clients; ++c) {
    threads.emplace_back([&, c] {
      std::mt19937_64 rng(1000 + c);
      std::vector<double> mine;
      try {
        KeepAliveClient client(port);
        while (Clock::now() < until) {
          const std::string target = NearbyTarget(rng);
          size_t hits = 0;
          const auto start = Clock::now();
          const int status = client.Send(http::verb::get, target, "", "", &hits);
          mine.push_back(std::chrono::duration<double, std::milli>(Clock::now() - start).count());
          if (status != 200) ++errors;
          hits_total += static_cast<long long>(hits);
        }
      } catch (const std::exception&) {
        ++errors;
      }
      std::lock_guard lock(mutex);
      latencies_ms.insert(latencies_ms.end(), mine.begin(), mine.end());
    });
  }
  for (auto& t : threads) t.join();
  const double elapsed = std::chrono::duration<double>(Clock::now() - t0).count();
  LoadResult r;
  r.requests = static_cast<long long>(latencies_ms.size());
  r.qps = static_cast<double>(r.requests) / elapsed;
  r.p50_ms = Percentile(latencies_ms, 0.50);
  r.p99_ms = Percentile(latencies_ms, 0.99);
  r.mean_hits = r.requests ? static_cast<double>(hits_total) / static_cast<double>(r.requests) : 0;
  r.errors = errors;
  return r;
}

// Each client uploads 1 MiB frames of its own clip until `seconds` pass or the byte budget
// is spent.
Expected<LoadResult> UploadLoad(uint16_t port, const std::string& url, const std::string& token,
                                const Settings& settings) {
  const int frames_per_clip =
      static_cast<int>(std::max<size_t>(1, kMaxUploadBytes / kUploadFrameBytes / settings.clients));
  std::mt19937 rng(5);
  std::string frame(kUploadFrameBytes, '\0');
  for (char& ch : frame) ch = static_cast<char>(rng() & 0xff);
  // Frames differ by their first 4 bytes (the frame number), so each has its own hash.
  auto frame_bytes = [&](int n) {
    std::string f = frame;
    std::memcpy(f.data(), &n, sizeof n);
    return f;
  };
  std::vector<proto::PartInfo> frames;
  for (int n = 0; n < frames_per_clip; ++n) {
    frames.push_back({kUploadFrameBytes, proto::Sha256Hex(frame_bytes(n))});
  }
  const std::string manifest = BenchManifest("upload", frames, {3, proto::Sha256Hex("map")});
  proto::ApiClient api(url, token);
  std::vector<std::string> ids;
  for (int c = 0; c < settings.clients; ++c) {
    auto id = api.CreateClip(manifest);
    if (!id) return id.error();
    ids.push_back(*id);
  }
  std::mutex mutex;
  std::vector<double> latencies_ms;
  std::atomic<long long> errors{0}, bytes{0};
  const auto until = Clock::now() + std::chrono::duration<double>(settings.seconds);
  const auto t0 = Clock::now();
  std::vector<std::thread> threads;
  for (int c = 0; c < settings.clients; ++c) {
    threads.emplace_back([&, c] {
      std::vector<double> mine;
      try {
        KeepAliveClient client(port);
        for (int n = 0; n < frames_per_clip && Clock::now() < until; ++n) {
          const std::string body = frame_bytes(n);
          const auto start = Clock::now();
          const int status = client.Send(
              http::verb::put, "/v1/clips/" + ids[c] + "/frames/" + std::to_string(n), token, body);
          mine.push_back(std::chrono::duration<double, std::milli>(Clock::now() - start).count());
          if (status == 204) {
            bytes += static_cast<long long>(body.size());
          } else {
            ++errors;
          }
        }
      } catch (const std::exception&) {
        ++errors;
      }
      std::lock_guard lock(mutex);
      latencies_ms.insert(latencies_ms.end(), mine.begin(), mine.end());
    });
  }
  for (auto& t : threads) t.join();
  const double elapsed = std::chrono::duration<double>(Clock::now() - t0).count();
  LoadResult r;
  r.requests = static_cast<long long>(latencies_ms.size());
  r.mb_per_s = static_cast<double>(bytes) / (1 << 20) / elapsed;
  r.p50_ms = Percentile(latencies_ms, 0.50);
  r.p99_ms = Percentile(latencies_ms, 0.99);
  r.errors = errors;
  // The drafts go again, so that a kept database does not grow from run to run.
  for (const std::string& id : ids) {
    if (Status s = api.DeleteClip(id); !s) return s.error();
  }
  return r;
}

Status UploadRow(const std::string& name, const std::string& engine, uint16_t port,
                 const std::string& url, const std::string& token, long long count,
                 const Settings& settings, proto::Report& report) {
  auto upload = UploadLoad(port, url, token, settings);
  if (!upload) return upload.error();
  report.rows.push_back(proto::ReportRow()
                            .Add("test", name)
                            .Add("engine", engine)
                            .Add("n", count)
                            .Add("clients", static_cast<long long>(settings.clients))
                            .Add("mb_per_s", upload->mb_per_s)
                            .Add("p50_ms", upload->p50_ms)
                            .Add("p99_ms", upload->p99_ms)
                            .Add("errors", upload->errors));
  return {};
}

// The database of `count` seeded clips on `engine` ("sqlite": a file in db_dir, reused when
// kept; "postgresql": settings.postgres_url, reused when it holds exactly `count`).
Expected<std::string> SeededDatabase(const std::string& engine, long long count,
                                     const Settings& settings) {
  std::string db = settings.postgres_url;
  if (engine == "sqlite") {
    // A kept database (--db DIR) is named by its clip count alone, so the next run finds it.
    db = settings.db_dir + "/bench-" + std::to_string(count) +
         (settings.keep_db ? std::string() : "-" + std::to_string(getpid())) + ".db";
  }
  if ((settings.keep_db || engine == "postgresql") && SeededClips(db) == count) {
    std::cerr << "reenact-bench: reusing " << count << " seeded clips on " << engine << std::endl;
    return db;
  }
  const auto seed_start = Clock::now();
  if (engine == "sqlite") {
    for (const char* suffix : {"", "-wal", "-shm"}) std::filesystem::remove(db + suffix);
    if (Status s = Seed(db, count); !s) return s.error();
  } else if (Status s = SeedPostgres(db, count); !s) {
    return s.error();
  }
  const double seed_s = std::chrono::duration<double>(Clock::now() - seed_start).count();
  std::cerr << "reenact-bench: seeded " << count << " clips on " << engine << " in " << seed_s
            << " s" << std::endl;
  return db;
}

Status RunOne(const std::string& engine, long long count, const Settings& settings,
              proto::Report& report) {
  auto db = SeededDatabase(engine, count, settings);
  if (!db) return db.error();
  auto storage = server::OpenStorage(*db);
  if (!storage) return storage.error();
  // A kept database already has the users of earlier runs (and PostgreSQL those of other N).
  std::string uploader = "uploader-" + std::to_string(getpid());
  uploader += "-" + std::to_string(count);
  auto token = server::AddUserWithToken(*storage->metadata, uploader);
  if (!token) return token.error();
  const double us = StoreMicrosPerQuery(*storage->metadata, 1000);
  report.rows.push_back(proto::ReportRow()
                            .Add("test", std::string("nearby_store"))
                            .Add("engine", engine)
                            .Add("n", count)
                            .Add("clients", 1LL)
                            .Add("us_per_query", us));

  // No rate limit: the bench measures the server, not the limiter.
  server::ServerOptions options;
  options.rate_limit.per_second = 0;
  Status served = WithServer(*storage, options, [&](uint16_t port, const std::string& url) -> Status {
    const LoadResult nearby = NearbyLoad(port, settings);
    report.rows.push_back(proto::ReportRow()
                              .Add("test", std::string("nearby_http"))
                              .Add("engine", engine)
                              .Add("n", count)
                              .Add("clients", static_cast<long long>(settings.clients))
                              .Add("qps", nearby.qps)
                              .Add("p50_ms", nearby.p50_ms)
                              .Add("p99_ms", nearby.p99_ms)
                              .Add("mean_hits", nearby.mean_hits)
                              .Add("errors", nearby.errors));
    return UploadRow("upload_http", engine, port, url, *token, count, settings, report);
  });
  if (!served) return served;
  storage->metadata.reset();
  storage->blobs.reset();
  if (engine == "postgresql") {
    // PostgreSQL commits as its server is configured; the same uploads with the parts as
    // files (--blobs) instead, in a directory beside the SQLite databases.
    server::StorageOptions files;
    files.blob_dir = settings.db_dir + "/blobs-" + std::to_string(getpid());
    std::filesystem::create_directories(files.blob_dir);
    storage = server::OpenStorage(*db, files);
    if (!storage) return storage.error();
    served = WithServer(*storage, options, [&](uint16_t port, const std::string& url) {
      return UploadRow("upload_http_files", engine, port, url, *token, count, settings, report);
    });
    storage->metadata.reset();
    storage->blobs.reset();
    std::error_code ec;
    std::filesystem::remove_all(files.blob_dir, ec);
    return served;
  }
  // The same uploads with commits that are not synced to disk (synchronous=NORMAL): what the
  // durability of a 204 costs.
  server::StorageOptions unsynced;
  unsynced.fsync_each_commit = false;
  storage = server::OpenSqliteStorage(*db, unsynced);
  if (!storage) return storage.error();
  served = WithServer(*storage, options, [&](uint16_t port, const std::string& url) {
    return UploadRow("upload_http_unsynced", engine, port, url, *token, count, settings, report);
  });
  if (!served) return served;
  storage->metadata.reset();
  storage->blobs.reset();
  if (!settings.keep_db) {
    for (const char* suffix : {"", "-wal", "-shm"}) std::filesystem::remove(*db + suffix);
  }
  return {};
}

// Two server processes on settings.postgres_url and settings.kills random SIGKILLs.
Status KillRow(const Settings& settings, proto::Report& report) {
  KillBenchOptions options;
  options.server_binary = settings.server_binary;
  options.db = settings.postgres_url;
  options.kills = settings.kills;
  auto run = RunKillBench(options);
  if (!run) return run.error();
  report.rows.push_back(proto::ReportRow()
                            .Add("test", std::string("kills"))
                            .Add("engine", std::string("postgresql"))
                            .Add("kills", static_cast<long long>(run->kills))
                            .Add("mid_upload", static_cast<long long>(run->mid_upload))
                            .Add("published", static_cast<long long>(run->published))
                            .Add("lost", static_cast<long long>(run->lost))
                            .Add("half_visible", static_cast<long long>(run->half_visible))
                            .Add("observed", run->observed)
                            .Add("seconds", run->seconds));
  return {};
}

}  // namespace

int RunServerBench(const CommandLine& cl) {
  auto fail = [](const Error& e) { return ReportFailure("reenact-bench", e); };
  Settings settings;
  const auto clips = cl.GetInt("clips", 0);
  const auto clients = cl.GetInt("clients", 4);
  const auto seconds = cl.GetDouble("seconds", 3);
  if (!clips.ok()) return fail(clips.error());
  if (!clients.ok()) return fail(clients.error());
  if (!seconds.ok()) return fail(seconds.error());
  if (*clips < 0 || *clips > 10'000'000) {
    return fail(MakeError("usage", "--clips must be in [1, 10000000]"));
  }
  if (*clients < 1 || *clients > 256)
    return fail(MakeError("usage", "--clients must be in [1, 256]"));
  if (!(*seconds > 0 && *seconds <= 600)) {
    return fail(MakeError("usage", "--seconds must be in (0, 600]"));
  }
  settings.clients = static_cast<int>(*clients);
  settings.seconds = *seconds;
  if (*clips > 0) {
    settings.clip_counts = {*clips};
  } else if (cl.Has("quick")) {
    settings.clip_counts = {100'000};
  } else {
    settings.clip_counts = {100'000, 1'000'000};
  }
  const bool attacks = cl.Has("attacks");
  const auto kills = cl.GetInt("kills", 50);
  if (!kills.ok()) return fail(kills.error());
  if (*kills < 0 || *kills > 10'000) return fail(MakeError("usage", "--kills must be in [0, 10000]"));
  settings.kills = static_cast<int>(*kills);
  settings.server_binary = cl.GetOr("server", DefaultServerBinary());
  std::filesystem::path temp_dir;
  const std::optional<std::string> db = cl.Get("db");
  if (db && server::IsPostgresUrl(*db)) {
    if (attacks) return fail(MakeError("usage", "--attacks runs on SQLite: --db wants a directory"));
    settings.postgres_url = *db;
  } else if (db) {
    if (!std::filesystem::is_directory(*db)) {
      return fail(MakeError("usage", "--db wants an existing directory for the bench databases "
                                     "or a postgresql:// URL"));
    }
    settings.db_dir = *db;
    settings.keep_db = !attacks;  // the attack database is removed after the run
  }
  if (settings.db_dir.empty()) {
    std::string pattern =
        (std::filesystem::temp_directory_path() / "reenact-bench-XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr) {
      return fail(MakeError("io", "cannot create a temporary directory"));
    }
    temp_dir = pattern;
    settings.db_dir = pattern;
  }
  proto::Report report{"server", {}};
  Status status;
  if (attacks) {
    AttackBenchOptions options;
    options.db_dir = settings.db_dir;
    if (*clips > 0) options.clips = *clips;
    options.clients = settings.clients;
    if (cl.Has("seconds")) options.seconds = settings.seconds;
    options.only = cl.GetOr("only", "");
    status = RunAttackBench(options, report);
  } else {
    std::vector<std::string> engines = {"sqlite"};
    if (!settings.postgres_url.empty()) engines.push_back("postgresql");
    for (long long count : settings.clip_counts) {
      for (const std::string& engine : engines) {
        status = RunOne(engine, count, settings, report);
        if (!status) break;
      }
      if (!status) break;
    }
    if (status && !settings.postgres_url.empty() && settings.kills > 0) {
      status = KillRow(settings, report);
    }
  }
  if (!temp_dir.empty()) {
    std::error_code ec;
    std::filesystem::remove_all(temp_dir, ec);
  }
  if (!status) return fail(status.error());
  std::cout << report.FormatTable(attacks ? 2 : 3);
  if (auto json = cl.Get("json")) {
    if (Status s = report.WriteJson(*json); !s.ok()) return fail(s.error());
  }
  return 0;
}

}  // namespace reenact::bench
