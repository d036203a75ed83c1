#pragma once
// The reenact-server command line (main.cc only forwards to it):
//   reenact-server serve --db FILE [--listen HOST:PORT] [--threads N]
//       Serves the API. Prints exactly one line "listening on http://HOST:PORT" to stdout once
//       ready (port 0 = a free port, printed as the real one). SIGINT/SIGTERM stop gracefully.
//   reenact-server user add NAME --db FILE
//       Creates a user and prints their new token once.
//   reenact-server --help
// Exit codes: 0 success, 1 runtime failure (database, I/O), 2 bad arguments or a listen
// address already in use. Every failure is one line on stderr.

#include <iosfwd>

namespace reenact::server {

int RunServerCli(int argc, const char* const* argv, std::ostream& out, std::ostream& err);

}  // namespace reenact::server
