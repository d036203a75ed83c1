#include "server/app/open_file_limit.h"

#include <sys/resource.h>

#include <algorithm>
#include <string>

namespace reenact::server {

namespace {
// Descriptors besides connections: the database and its WAL and shm (several connections),
// the listener, event loops, standard streams, and connections refused at the cap.
constexpr rlim_t kSpareFiles = 256;
}  // namespace

Status RaiseOpenFileLimit(int max_connections) {
  rlimit limit{};
  if (getrlimit(RLIMIT_NOFILE, &limit) != 0) return {};
  const rlim_t wanted = static_cast<rlim_t>(max_connections) + kSpareFiles;
  if (limit.rlim_cur >= wanted) return {};
  if (limit.rlim_max != RLIM_INFINITY && limit.rlim_max < wanted) {
    return MakeError("invalid_argument",
                     "--max-connections " + std::to_string(max_connections) + " needs " +
                         std::to_string(wanted) + " open files but this process may open at "
                         "most " + std::to_string(limit.rlim_max) +
                         "; lower --max-connections or raise the limit (ulimit -n, systemd "
                         "LimitNOFILE=)");
  }
  limit.rlim_cur = wanted;
  if (setrlimit(RLIMIT_NOFILE, &limit) != 0) {
    return MakeError("invalid_argument", "cannot raise the open-file limit to " +
                                             std::to_string(wanted) + " for --max-connections");
  }
  return {};
}

}  // namespace reenact::server
