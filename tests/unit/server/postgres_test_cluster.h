#pragma once
// PostgreSQL for tests: a fresh, empty database per call, in a throwaway cluster that the test
// process starts under a temporary directory (initdb and postgres from
// /usr/lib/postgresql/<newest>/bin, a unix socket in that directory and no TCP port, trust
// authentication, fsync off) and stops at exit. Run as root, the server runs as the `postgres`
// user (PostgreSQL refuses root); if the test process dies without stopping it, the server gets
// SIGQUIT (immediate shutdown) from the kernel.
//
// With REENACT_TEST_POSTGRES_URL set (.ci/run starts one cluster for the whole run, which
// saves starting one per test process), databases are created on that server instead (its
// role needs CREATEDB, and PostGIS must be installed there) and dropped at exit. Tests that
// stop the server or log in by password still use a cluster of their own (TestCluster::kOwn).
//
// Where neither is possible (no PostgreSQL server or PostGIS installed, or root without a
// `postgres` user) the error has code "unavailable", and a test skips:
//   auto url = NewPostgresTestDatabase();
//   if (!url && url.error().code == "unavailable") GTEST_SKIP() << url.error().message;
// Any other error (a cluster that was installed but failed to start) is a test failure.

#include <string>

#include "common/error/expected.h"

namespace reenact::server::testing {

enum class TestCluster {
  kShared,  // REENACT_TEST_POSTGRES_URL's server where it is set, else kOwn
  kOwn,     // the cluster this process starts (the one the functions below act on)
};

// The connection string of a new empty database (named uniquely within the process).
Expected<std::string> NewPostgresTestDatabase(TestCluster which = TestCluster::kShared);

// A role of the own test cluster that must log in with `password` (scram-sha-256; every
// other role is trusted): the connection string of `database` as that role, without the
// password.
Expected<std::string> PostgresTestPasswordLogin(const std::string& database,
                                                const std::string& password);

// Stops the own test cluster and waits for its exit: immediate (SIGQUIT, as a crash:
// sessions cut without a word) or fast (SIGINT: sessions told "terminating connection due to
// administrator command" first). Its databases survive for StartPostgresTestCluster, which
// starts it again on the same socket and waits until it accepts connections.
Status StopPostgresTestCluster(bool immediate);
Status StartPostgresTestCluster();

}  // namespace reenact::server::testing
