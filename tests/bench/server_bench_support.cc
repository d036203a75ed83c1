#include "tests/bench/server_bench_support.h"

#include <thread>

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "common/skeleton/skeleton.h"
#include "proto/clip/content_hash.h"
#include "server/storage/open_storage.h"
#include "server/storage/postgres.h"
#include "server/storage/sqlite.h"

namespace reenact::bench {

namespace beast = boost::beast;
namespace http = beast::http;
using tcp = boost::asio::ip::tcp;

Status Seed(const std::string& db_path, long long count) {
  auto storage = server::OpenSqliteStorage(db_path);  // applies the migrations
  if (!storage) return storage.error();
  auto db = server::sqlite::Database::Open(db_path);
  if (!db) return db.error();
  if (Status s = db->Exec("INSERT INTO users(name, created_at) VALUES ('seed', 0)"); !s) return s;
  const int64_t owner = db->LastInsertRowId();
  auto tx = server::sqlite::Transaction::Begin(*db);
  if (!tx) return tx.error();
  auto clip = db->Prepare(
      "INSERT INTO clips(public_id, owner_id, state, title, author, lat_deg, lon_deg, alt_m, "
      "duration_s, frame_count, manifest, manifest_sha256, created_at, published_at) VALUES "
      "(?1, ?2, 'published', 'seeded', 'bench', ?3, ?4, 0, 4, 120, '{}', '', 0, 0)");
  auto box = db->Prepare(
      "INSERT INTO clip_boxes(id, min_lat, max_lat, min_lon, max_lon) VALUES (?1, ?2, ?2, ?3, ?3)");
  if (!clip) return clip.error();
  if (!box) return box.error();
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> lat(kMinLat, kMaxLat), lon(kMinLon, kMaxLon);
  char id[32];
  for (long long i = 0; i < count; ++i) {
    std::snprintf(id, sizeof id, "seed%020lld", i);
    const double la = lat(rng), lo = lon(rng);
    clip->Reset();
    clip->BindText(1, id).Bind(2, owner).Bind(3, la).Bind(4, lo);
    if (Status s = clip->Run(); !s) return s;
    box->Reset();
    box->Bind(1, db->LastInsertRowId()).Bind(2, la).Bind(3, lo);
    if (Status s = box->Run(); !s) return s;
  }
  return tx->Commit();
}

Status SeedPostgres(const std::string& url, long long count) {
  auto storage = server::OpenPostgresStorage(url);  // applies the migrations
  if (!storage) return storage.error();
  auto db = server::pg::Connection::Open(url);
  if (!db) return db.error();
  auto tx = server::pg::Transaction::Begin(*db);
  if (!tx) return tx.error();
  if (Status s = db->Exec(
          "INSERT INTO users(name, created_at) VALUES ('seed', 0) ON CONFLICT (name) DO NOTHING; "
          "DELETE FROM clips WHERE owner_id = (SELECT id FROM users WHERE name = 'seed'); "
          "SELECT setseed(0.42)");
      !s) {
    return s;
  }
  auto inserted = db->Query(
      "INSERT INTO clips(public_id, owner_id, state, title, author, lat_deg, lon_deg, alt_m, "
      "duration_s, frame_count, manifest, manifest_sha256, created_at, published_at) "
      "SELECT 'seed' || lpad(i::text, 20, '0'), (SELECT id FROM users WHERE name = 'seed'), "
      "'published', 'seeded', 'bench', $2::float8 + ($3::float8 - $2::float8) * random(), "
      "$4::float8 + ($5::float8 - $4::float8) * random(), 0, "
      "4, 120, '\\x7b7d', '', 0, 0 FROM generate_series(0, $1::bigint - 1) AS i",
      {static_cast<int64_t>(count), kMinLat, kMaxLat, kMinLon, kMaxLon});
  if (!inserted) return inserted.error();
  if (Status s = tx->Commit(); !s) return s;
  return db->Exec("VACUUM ANALYZE clips");  // the deleted rows gone, as in a database at rest
}

long long SeededClips(const std::string& db) {
  const std::string count_sql =
      "SELECT COUNT(*) FROM clips JOIN users ON users.id = clips.owner_id "
      "WHERE users.name = 'seed' AND clips.state = 'published'";
  if (server::IsPostgresUrl(db)) {
    auto connection = server::pg::Connection::Open(db);
    if (!connection) return -1;
    auto rows = connection->Query(count_sql);
    if (!rows || rows->rows() != 1) return -1;
    return rows->Int(0, 0);
  }
  if (!std::filesystem::exists(db)) return -1;
  auto connection = server::sqlite::Database::Open(db);
  if (!connection) return -1;
  auto count = connection->Prepare(count_sql);
  if (!count) return -1;
  auto row = count->Step();
  if (!row || !*row) return -1;
  return count->ColumnInt(0);
}

double Percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  const size_t k = std::min(v.size() - 1, static_cast<size_t>(p * static_cast<double>(v.size())));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

std::string NearbyTarget(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> lat(kMinLat + 0.1, kMaxLat - 0.1),
      lon(kMinLon + 0.1, kMaxLon - 0.1);
  char target[160];
  std::snprintf(target, sizeof target, "/v1/clips?near=%.6f,%.6f&radius_m=%.0f&limit=%d", lat(rng),
                lon(rng), kQueryRadiusM, kQueryLimit);
  return target;
}

std::string BenchManifest(const std::string& title, const std::vector<proto::PartInfo>& frames,
                          const proto::PartInfo& map, double lat_deg, double lon_deg) {
  proto::ClipManifest m;
  m.title = title;
  m.author = "bench";
  m.capture_time = "2024-05-01T12:00:00Z";
  m.location = {lat_deg, lon_deg, 0, 3, std::nullopt};
  m.color_camera = {640, 480, 525.0, 525.0, 319.5, 239.5, {}};
  m.depth_camera = {640, 480, 525.0, 525.0, 319.5, 239.5, {}};
  for (int i = 0; i < kBodyPartCount; ++i) m.radius_ratio[i] = 0.2;
  m.frame_count = static_cast<int64_t>(frames.size());
  m.frame_rate_hz = 30;
  m.frame_parts = frames;
  m.map_part = map;
  return proto::SerializeManifest(m);
}

KeepAliveClient::KeepAliveClient(uint16_t port, std::chrono::milliseconds timeout)
    : port_(port), timeout_(timeout) {}

void KeepAliveClient::RunAll() {
  ioc_.restart();
  ioc_.run();
}

bool KeepAliveClient::Connect() {
  stream_.emplace(ioc_);
  buffer_.clear();
  const tcp::endpoint server(boost::asio::ip::make_address("127.0.0.1"), port_);
  beast::error_code result;
  if (timeout_.count() > 0) {
    stream_->expires_after(timeout_);
    stream_->async_connect(server, [&](beast::error_code ec) { result = ec; });
    RunAll();
  } else {
    stream_->connect(server, result);
  }
  if (!result) stream_->socket().set_option(tcp::no_delay(true), result);
  if (result) stream_.reset();
  return !result;
}

int KeepAliveClient::Send(http::verb verb, const std::string& target, const std::string& token,
                          const std::string& body, size_t* hits) {
  // One deadline for the whole exchange, connecting included: a stream's expiry covers
  // every operation after it.
  if (stream_) {
    if (timeout_.count() > 0) stream_->expires_after(timeout_);
  } else if (!Connect()) {
    return -1;
  }
  http::request<http::string_body> request(verb, target, 11);
  request.set(http::field::host, "127.0.0.1");
  if (!token.empty()) request.set(http::field::authorization, "Bearer " + token);
  if (!body.empty()) request.set(http::field::content_type, "application/octet-stream");
  request.body() = body;
  request.prepare_payload();
  http::response<http::string_body> response;
  beast::error_code result;
  if (timeout_.count() > 0) {
    http::async_write(*stream_, request, [&](beast::error_code ec, size_t) {
      if (ec) {
        result = ec;
        return;
      }
      http::async_read(*stream_, buffer_, response,
                       [&](beast::error_code read_ec, size_t) { result = read_ec; });
    });
    RunAll();
  } else {
    http::write(*stream_, request, result);
    if (!result) http::read(*stream_, buffer_, response, result);
  }
  if (result) {
    stream_.reset();  // the next request connects again
    return -1;
  }
  if (!response.keep_alive()) stream_.reset();
  if (hits) {
    size_t n = 0;
    for (size_t at = response.body().find("\"id\""); at != std::string::npos;
         at = response.body().find("\"id\"", at + 1)) {
      ++n;
    }
    *hits = n;
  }
  return static_cast<int>(response.result_int());
}

Status WithServer(server::Storage& storage, server::ServerOptions options,
                  const std::function<Status(uint16_t, const std::string&)>& body) {
  server::Metrics metrics;
  server::ServiceContext context{*storage.metadata, *storage.blobs, metrics,
                                 server::ServiceLimits{}};
  options.host = "127.0.0.1";
  options.port = 0;
  server::HttpServer http_server(context, options);
  auto port = http_server.Listen();
  if (!port) return port.error();
  std::thread runner([&] { http_server.Run(false); });
  Status status = body(*port, "http://127.0.0.1:" + std::to_string(*port));
  http_server.Stop();
  runner.join();
  return status;
}

}  // namespace reenact::bench
