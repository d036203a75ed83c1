#pragma once
// The process's limit on open files against the connections it is asked to serve.

#include "common/error/expected.h"

namespace reenact::server {

// Raises the soft limit on open files (RLIMIT_NOFILE) toward the hard limit so that
// max_connections connections, plus the database and a margin, fit. Code "invalid_argument"
// naming both numbers when even the hard limit is too small (lower --max-connections or raise
// LimitNOFILE / ulimit -n).
Status RaiseOpenFileLimit(int max_connections);

}  // namespace reenact::server
