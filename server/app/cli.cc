#include "server/app/cli.h"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include "server/app/open_file_limit.h"
#include "server/auth/token.h"
#include "server/http/http_server.h"
#include "server/storage/copy_storage.h"
#include "server/storage/open_storage.h"

namespace reenact::server {

namespace {

constexpr const char* kUsage =
    "usage: reenact-server serve --db FILE|URL [--blobs DIR] [--listen HOST:PORT]\n"
    "                            [--threads N] [--max-connections N]\n"
    "                            [--rate-limit PER_S] [--rate-burst N]\n"
    "                            [--header-timeout-s S] [--handler-threads N]\n"
    "                            [--max-connections-per-address N] [--max-body-mb N]\n"
    "                            [--min-transfer-rate BYTES_PER_S] [--min-rate-grace-s S]\n"
    "       reenact-server user add NAME --db FILE|URL\n"
    "       reenact-server token add NAME --db FILE|URL\n"
    "       reenact-server token revoke NAME --db FILE|URL\n"
    "       reenact-server migrate-db --from FILE|URL --to URL|FILE\n"
    "                                 [--from-blobs DIR] [--to-blobs DIR]\n"
    "--db: a SQLite database file (created if absent), or a PostgreSQL URL\n"
    "      postgresql://USER:PASSWORD@HOST:PORT/DATABASE (PostGIS installed there)\n"
    "--blobs: keep frames and maps as files in this existing directory instead of in the\n"
    "      database (every server of one database must see the same directory)\n";

struct Args {
  std::vector<std::string> positional;
  std::map<std::string, std::string> flags;
};

// Splits "--name value" pairs from positional words; nullopt-like false for a flag without
// its value or an unknown flag.
bool ParseArgs(const std::vector<std::string>& words, const std::vector<std::string>& known,
               Args& args, std::string& problem) {
  for (size_t i = 0; i < words.size(); ++i) {
    const std::string& w = words[i];
    if (w.rfind("--", 0) != 0) {
      args.positional.push_back(w);
      continue;
    }
    if (std::find(known.begin(), known.end(), w) == known.end()) {
      problem = "unknown option " + w;
      return false;
    }
    if (i + 1 >= words.size()) {
      problem = w + " needs a value";
      return false;
    }
    args.flags[w] = words[++i];
  }
  return true;
}

int Usage(std::ostream& err, const std::string& problem) {
  err << "reenact-server: " << problem << "\n" << kUsage;
  return 2;
}

// The flag's value as a number in [lo, hi]; false with a usage problem otherwise.
bool NumberFlag(const Args& args, const std::string& flag, double lo, double hi, double& value,
                std::string& problem) {
  auto it = args.flags.find(flag);
  if (it == args.flags.end()) return true;
  const std::string& t = it->second;
  double parsed = 0;
  auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), parsed);
  if (ec != std::errc() || end != t.data() + t.size() || !(parsed >= lo && parsed <= hi)) {
    problem = flag + " wants a number in [" + std::to_string(static_cast<long long>(lo)) + ", " +
              std::to_string(static_cast<long long>(hi)) + "], got '" + t + "'";
    return false;
  }
  value = parsed;
  return true;
}

// As NumberFlag, for a flag whose value must be a whole number.
bool IntegerFlag(const Args& args, const std::string& flag, double lo, double hi, double& value,
                 std::string& problem) {
  if (!NumberFlag(args, flag, lo, hi, value, problem)) return false;
  if (value == static_cast<double>(static_cast<long long>(value))) return true;
  problem = flag + " wants a whole number, got '" + args.flags.at(flag) + "'";
  return false;
}

int Serve(const Args& args, std::ostream& out, std::ostream& err) {
  if (!args.positional.empty()) return Usage(err, "unexpected argument " + args.positional[0]);
  auto db = args.flags.find("--db");
  if (db == args.flags.end()) return Usage(err, "serve needs --db FILE|URL");
  ServerOptions options;
  if (auto listen = args.flags.find("--listen"); listen != args.flags.end()) {
    auto address = ParseListenAddress(listen->second);
    if (!address) return Usage(err, address.error().message);
    options.host = address->first;
    options.port = address->second;
  }
  double threads = options.threads, handler_threads = options.handler_threads;
  double max_connections = options.max_connections;
  double per_address = options.max_connections_per_address;
  double body_mb = static_cast<double>(options.max_body_memory >> 20);
  double header_timeout_s = std::chrono::duration<double>(options.idle_timeout).count();
  double grace_s = std::chrono::duration<double>(options.min_transfer_rate.grace).count();
  std::string problem;
  if (!IntegerFlag(args, "--threads", 0, 256, threads, problem) ||
      !IntegerFlag(args, "--handler-threads", 0, 1024, handler_threads, problem) ||
      !IntegerFlag(args, "--max-connections", 1, 1'000'000, max_connections, problem) ||
      !IntegerFlag(args, "--max-connections-per-address", 0, 1'000'000, per_address, problem) ||
      !IntegerFlag(args, "--max-body-mb", 64, 1'000'000, body_mb, problem) ||
      !NumberFlag(args, "--min-transfer-rate", 0, 1e12, options.min_transfer_rate.bytes_per_s,
                  problem) ||
      !NumberFlag(args, "--min-rate-grace-s", 0, 3600, grace_s, problem) ||
      !NumberFlag(args, "--rate-limit", 0, 1e9, options.rate_limit.per_second, problem) ||
      !NumberFlag(args, "--rate-burst", 1, 1e9, options.rate_limit.burst, problem) ||
      !NumberFlag(args, "--header-timeout-s", 0.01, 3600, header_timeout_s, problem)) {
    return Usage(err, problem);
  }
  options.threads = static_cast<int>(threads);
  options.handler_threads = static_cast<int>(handler_threads);
  options.max_connections = static_cast<int>(max_connections);
  options.max_connections_per_address = static_cast<int>(per_address);
  options.max_body_memory = static_cast<size_t>(body_mb) << 20;
  options.idle_timeout = std::chrono::milliseconds(static_cast<int64_t>(header_timeout_s * 1000));
  options.min_transfer_rate.grace = std::chrono::milliseconds(static_cast<int64_t>(grace_s * 1000));
  if (Status limit = RaiseOpenFileLimit(options.max_connections); !limit) {
    err << "reenact-server: " << limit.error().message << std::endl;
    return 2;
  }
  StorageOptions storage_options;
  if (auto blobs = args.flags.find("--blobs"); blobs != args.flags.end()) {
    storage_options.blob_dir = blobs->second;
  }
  auto storage = OpenStorage(db->second, storage_options);
  if (!storage) {
    err << "reenact-server: " << storage.error().message << std::endl;
    return 1;
  }
  Metrics metrics;
  ServiceContext context{*storage->metadata, *storage->blobs, metrics, ServiceLimits{}};
  HttpServer server(context, options);
  auto port = server.Listen();
  if (!port) {
    err << "reenact-server: " << port.error().message << std::endl;
    return port.error().code == "address_in_use" || port.error().code == "invalid_argument" ? 2 : 1;
  }
  const bool ipv6 = options.host.find(':') != std::string::npos;
  out << "listening on http://" << (ipv6 ? "[" + options.host + "]" : options.host) << ":" << *port
      << std::endl;
  server.Run(/*stop_on_signals=*/true);
  err << "reenact-server: stopped" << std::endl;
  return 0;
}

int UserAdd(const Args& args, std::ostream& out, std::ostream& err) {
  if (args.positional.size() != 1) return Usage(err, "user add needs exactly one NAME");
  auto db = args.flags.find("--db");
  if (db == args.flags.end()) return Usage(err, "user add needs --db FILE|URL");
  auto storage = OpenStorage(db->second);
  if (!storage) {
    err << "reenact-server: " << storage.error().message << std::endl;
    return 1;
  }
  auto token = AddUserWithToken(*storage->metadata, args.positional[0]);
  if (!token) {
    err << "reenact-server: " << token.error().message << std::endl;
    return token.error().code == "storage" || token.error().code == "unavailable" ? 1 : 2;
  }
  out << *token << std::endl;
  err << "reenact-server: created user '" << args.positional[0]
      << "'; the token above is shown only once" << std::endl;
  return 0;
}

// token add|revoke NAME --db FILE|URL
int Token(const std::string& action, const Args& args, std::ostream& out, std::ostream& err) {
  if (args.positional.size() != 1) return Usage(err, "token " + action + " needs exactly one NAME");
  auto db = args.flags.find("--db");
  if (db == args.flags.end()) return Usage(err, "token " + action + " needs --db FILE|URL");
  auto storage = OpenStorage(db->second);
  if (!storage) {
    err << "reenact-server: " << storage.error().message << std::endl;
    return 1;
  }
  const std::string& name = args.positional[0];
  if (action == "add") {
    auto token = AddTokenForUser(*storage->metadata, name);
    if (!token) {
      err << "reenact-server: " << token.error().message << std::endl;
      return token.error().code == "not_found" ? 2 : 1;
    }
    out << *token << std::endl;
    err << "reenact-server: new token for '" << name << "'; it is shown only once" << std::endl;
    return 0;
  }
  auto revoked = storage->metadata->RevokeUserTokens(name);
  if (!revoked) {
    err << "reenact-server: " << revoked.error().message << std::endl;
    return revoked.error().code == "not_found" ? 2 : 1;
  }
  out << "revoked " << *revoked << " token(s) of '" << name << "'" << std::endl;
  return 0;
}

// The blob directory of `flag`, if given, as StorageOptions.
StorageOptions BlobOptions(const Args& args, const std::string& flag) {
  StorageOptions options;
  if (auto dir = args.flags.find(flag); dir != args.flags.end()) options.blob_dir = dir->second;
  return options;
}

// migrate-db --from FILE|URL --to URL|FILE [--from-blobs DIR] [--to-blobs DIR]
int MigrateDb(const Args& args, std::ostream& out, std::ostream& err) {
  if (!args.positional.empty()) return Usage(err, "unexpected argument " + args.positional[0]);
  auto from = args.flags.find("--from");
  auto to = args.flags.find("--to");
  if (from == args.flags.end() || to == args.flags.end()) {
    return Usage(err, "migrate-db needs --from FILE|URL and --to URL|FILE");
  }
  std::error_code ec;
  if (!IsPostgresUrl(from->second) && !std::filesystem::is_regular_file(from->second, ec)) {
    err << "reenact-server: no database file at '" << from->second
        << "'; --from must name an existing reenact-server database" << std::endl;
    return 2;
  }
  auto source = OpenStorage(from->second, BlobOptions(args, "--from-blobs"));
  if (!source) {
    err << "reenact-server: source: " << source.error().message << std::endl;
    return 1;
  }
  auto target = OpenStorage(to->second, BlobOptions(args, "--to-blobs"));
  if (!target) {
    err << "reenact-server: target: " << target.error().message << std::endl;
    return 1;
  }
  auto copied = CopyStorage(*source, *target);
  if (!copied) {
    err << "reenact-server: " << copied.error().message << std::endl;
    return 1;
  }
  char seconds[32];
  std::snprintf(seconds, sizeof(seconds), "%.2f", copied->seconds);
  out << "copied " << copied->users << " users, " << copied->tokens << " tokens, "
      << copied->clips << " clips (" << copied->published_clips << " published), "
      << copied->parts << " parts, " << copied->blobs << " blobs, " << copied->blob_bytes
      << " bytes in " << seconds << " s; verified by SHA-256" << std::endl;
  return 0;
}

}  // namespace

int RunServerCli(int argc, const char* const* argv, std::ostream& out, std::ostream& err) {
  std::vector<std::string> words(argv + 1, argv + argc);
  if (words.empty()) return Usage(err, "missing command");
  if (std::find(words.begin(), words.end(), "--help") != words.end() || words[0] == "-h" ||
      words[0] == "help") {
    out << kUsage;
    return 0;
  }
  Args args;
  std::string problem;
  if (words[0] == "serve") {
    if (!ParseArgs({words.begin() + 1, words.end()},
                   {"--db", "--blobs", "--listen", "--threads", "--handler-threads",
                    "--max-connections", "--max-connections-per-address", "--max-body-mb",
                    "--min-transfer-rate", "--min-rate-grace-s", "--rate-limit", "--rate-burst",
                    "--header-timeout-s"},
                   args, problem)) {
      return Usage(err, problem);
    }
    return Serve(args, out, err);
  }
  if (words[0] == "user" && words.size() >= 2 && words[1] == "add") {
    if (!ParseArgs({words.begin() + 2, words.end()}, {"--db"}, args, problem)) {
      return Usage(err, problem);
    }
    return UserAdd(args, out, err);
  }
  if (words[0] == "token" && words.size() >= 2 && (words[1] == "add" || words[1] == "revoke")) {
    if (!ParseArgs({words.begin() + 2, words.end()}, {"--db"}, args, problem)) {
      return Usage(err, problem);
    }
    return Token(words[1], args, out, err);
  }
  if (words[0] == "migrate-db") {
    if (!ParseArgs({words.begin() + 1, words.end()},
                   {"--from", "--to", "--from-blobs", "--to-blobs"}, args, problem)) {
      return Usage(err, problem);
    }
    return MigrateDb(args, out, err);
  }
  return Usage(err, "unknown command '" + words[0] + "'");
}

}  // namespace reenact::server
