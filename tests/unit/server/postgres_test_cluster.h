#pragma once
// PostgreSQL for tests: a fresh, empty database per call, in a throwaway cluster that the test
// process starts under a temporary directory (initdb and postgres from
// /usr/lib/postgresql/<newest>/bin, a unix socket in that directory and no TCP port, trust
// authentication, fsync off) and stops at exit. Run as root, the server runs as the `postgres`
// user (PostgreSQL refuses root); if the test process dies without stopping it, the server gets
// SIGQUIT (immediate shutdown) from the kernel.
//
// With REENACT_TEST_POSTGRES_URL set, databases are created on that server instead (its role
// needs CREATEDB, and PostGIS must be installed there) and dropped at exit.
//
// Where neither is possible (no PostgreSQL server or PostGIS installed, or root without a
// `postgres` user) the error has code "unavailable", and a test skips:
//   auto url = NewPostgresTestDatabase();
//   if (!url && url.error().code == "unavailable") GTEST_SKIP() << url.error().message;
// Any other error (a cluster that was installed but failed to start) is a test failure.

#include <string>

#include "common/error/expected.h"

namespace reenact::server::testing {

// The connection string of a new empty database (named uniquely within the process).
Expected<std::string> NewPostgresTestDatabase();

// A role of the local test cluster that must log in with `password` (scram-sha-256; every
// other role is trusted): the connection string of `database` as that role, without the
// password. "unavailable" with REENACT_TEST_POSTGRES_URL, whose authentication is not ours.
Expected<std::string> PostgresTestPasswordLogin(const std::string& database,
                                                const std::string& password);

// Stops the local test cluster and waits for its exit: immediate (SIGQUIT, as a crash:
// sessions cut without a word) or fast (SIGINT: sessions told "terminating connection due to
// administrator command" first). Its databases survive for StartPostgresTestCluster, which
// starts it again on the same socket and waits until it accepts connections. Both
// "unavailable" with REENACT_TEST_POSTGRES_URL, which the tests do not stop.
Status StopPostgresTestCluster(bool immediate);
Status StartPostgresTestCluster();

}  // namespace reenact::server::testing
