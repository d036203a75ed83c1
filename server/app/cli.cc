#include "server/app/cli.h"

#include <algorithm>
#include <charconv>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include "server/auth/token.h"
#include "server/http/http_server.h"
#include "server/storage/open_storage.h"

namespace reenact::server {

namespace {

constexpr const char* kUsage =
    "usage: reenact-server serve --db FILE [--listen HOST:PORT] [--threads N]\n"
    "       reenact-server user add NAME --db FILE\n";

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

int Serve(const Args& args, std::ostream& out, std::ostream& err) {
  if (!args.positional.empty()) return Usage(err, "unexpected argument " + args.positional[0]);
  auto db = args.flags.find("--db");
  if (db == args.flags.end()) return Usage(err, "serve needs --db FILE");
  ServerOptions options;
  if (auto listen = args.flags.find("--listen"); listen != args.flags.end()) {
    auto address = ParseListenAddress(listen->second);
    if (!address) return Usage(err, address.error().message);
    options.host = address->first;
    options.port = address->second;
  }
  if (auto threads = args.flags.find("--threads"); threads != args.flags.end()) {
    const std::string& t = threads->second;
    int n = 0;
    auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), n);
    if (ec != std::errc() || end != t.data() + t.size() || n < 1 || n > 256) {
      return Usage(err, "--threads wants an integer in [1, 256]");
    }
    options.threads = n;
  }
  auto storage = OpenSqliteStorage(db->second);
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
    return port.error().code == "address_in_use" || port.error().code == "invalid_argument" ? 2
                                                                                             : 1;
  }
  const bool ipv6 = options.host.find(':') != std::string::npos;
  out << "listening on http://" << (ipv6 ? "[" + options.host + "]" : options.host) << ":"
      << *port << std::endl;
  server.Run(/*stop_on_signals=*/true);
  err << "reenact-server: stopped" << std::endl;
  return 0;
}

int UserAdd(const Args& args, std::ostream& out, std::ostream& err) {
  if (args.positional.size() != 1) return Usage(err, "user add needs exactly one NAME");
  auto db = args.flags.find("--db");
  if (db == args.flags.end()) return Usage(err, "user add needs --db FILE");
  auto storage = OpenSqliteStorage(db->second);
  if (!storage) {
    err << "reenact-server: " << storage.error().message << std::endl;
    return 1;
  }
  auto token = AddUserWithToken(*storage->metadata, args.positional[0]);
  if (!token) {
    err << "reenact-server: " << token.error().message << std::endl;
    return token.error().code == "storage" ? 1 : 2;
  }
  out << *token << std::endl;
  err << "reenact-server: created user '" << args.positional[0]
      << "'; the token above is shown only once" << std::endl;
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
    if (!ParseArgs({words.begin() + 1, words.end()}, {"--db", "--listen", "--threads"}, args,
                   problem)) {
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
  return Usage(err, "unknown command '" + words[0] + "'");
}

}  // namespace reenact::server
