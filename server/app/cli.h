#pragma once
// The reenact-server command line (main.cc only forwards to it):
//   reenact-server serve --db FILE|URL [--listen HOST:PORT] [--threads N] [--max-connections N]
//                        [--rate-limit PER_S] [--rate-burst N] [--header-timeout-s S]
//       Serves the API. Prints exactly one line "listening on http://HOST:PORT" to stdout once
//       ready (port 0 = a free port, printed as the real one). SIGINT/SIGTERM stop gracefully.
//       --threads 0 (default) = one per hardware thread; --rate-limit 0 = no per-token limit.
//   reenact-server user add NAME --db FILE|URL
//       Creates a user and prints their new token once.
//   reenact-server token add NAME --db FILE|URL
//       Issues another token for an existing user and prints it once.
//   reenact-server token revoke NAME --db FILE|URL
//       Revokes every token of the user (effective at once, also for a running server).
//   reenact-server migrate-db --from FILE|URL --to URL|FILE
//       Copies a whole database into an empty one (typically a SQLite file into PostgreSQL),
//       verifies it by SHA-256 (server/storage/copy_storage.h) and prints one summary line
//       "copied U users, T tokens, C clips (P published), N parts, B blobs, X bytes in S s;
//       verified by SHA-256". A missing --from file exits 2; a target holding data, a failed
//       copy or a verification mismatch exits 1 with one line (after a partial copy: drop the
//       target and run again). The source is only read.
//   reenact-server --help
// --db FILE is the embedded SQLite database (metadata and payloads in one file); --db URL with
// postgresql:// or postgres:// keeps both in that PostgreSQL/PostGIS database. A wrong URL,
// password or unreachable server is one line on stderr at start (never the password), exit 1.
// Exit codes: 0 success, 1 runtime failure (database, I/O), 2 bad arguments or a listen
// address already in use. Every failure is one line on stderr.

#include <iosfwd>

namespace reenact::server {

int RunServerCli(int argc, const char* const* argv, std::ostream& out, std::ostream& err);

}  // namespace reenact::server
