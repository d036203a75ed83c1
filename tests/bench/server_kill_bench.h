#pragma once
// The kill run of `reenact-bench server --db postgresql://...`: two `reenact-server serve`
// processes on one database, and `kills` rounds of:
//   1. upload a clip (kFrames frames of kFrameBytes random bytes and a map) through one server,
//   2. SIGKILL that server at a random moment of the upload (uniform in [0, 1.5 x the time an
//      undisturbed upload took], so some kills land after the publish),
//   3. finish through the other server as the capture client does: find the draft by its
//      manifest's SHA-256, send the parts it lacks, publish,
//   4. start the killed server again.
// An observer browses both servers all the while (anonymous nearby search at the clips'
// place) and downloads every clip it sees, checking each part against its manifest's SHA-256.
// At the end every published clip is downloaded from both servers and compared with the bytes
// sent. The clips are at (60, 25), outside the seeded box, and are deleted after the run.

#include <cstdint>
#include <string>

#include "common/error/expected.h"

namespace reenact::bench {

struct KillBenchOptions {
  std::string server_binary;  // reenact-server
  std::string db;             // the servers' --db (a PostgreSQL URL)
  int kills = 50;
  uint32_t seed = 1;
};

struct KillBenchResult {
  int kills = 0;         // SIGKILLs sent
  int mid_upload = 0;    // of them, before the clip was published
  int published = 0;     // clips published
  int lost = 0;          // published but not whole or not visible on both servers at the end
  int half_visible = 0;  // seen by the observer with a part missing or other bytes
  long long observed = 0;  // clips the observer downloaded whole
  double seconds = 0;
};

// The binary beside this one's build tree: <build>/server/reenact-server.
std::string DefaultServerBinary();

// Errors: a server that does not start, a failure outside the kills (the database, a user).
Expected<KillBenchResult> RunKillBench(const KillBenchOptions& options);

}  // namespace reenact::bench
