#pragma once
// Runs the project's programs as real child processes for integration tests: output captured,
// a deadline on every run (a hang is a failure, never a stuck test).

#include <chrono>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace reenact::testing {

// The programs under test, in the build tree.
inline const std::string kBin = REENACT_BINARY_DIR;
inline const std::string kServer = kBin + "/server/reenact-server";
inline const std::string kCapture = kBin + "/capture-client/reenact-capture";
inline const std::string kViewer = kBin + "/viewer-client/reenact-viewer";

struct ProcessResult {
  int exit_code = -1;     // -1 if killed at the deadline or by a signal
  bool timed_out = false;
  std::string out;        // stdout
  std::string err;        // stderr
  double seconds = 0;
};

// Runs argv[0] with arguments, waits at most `deadline`, with extra environment entries.
ProcessResult RunProcess(const std::vector<std::string>& argv,
                         std::chrono::milliseconds deadline = std::chrono::seconds(120),
                         const std::vector<std::string>& extra_env = {});

// A long-running child (the server): started, its stdout read line by line until a line
// starting with `ready_prefix` appears; terminated with SIGTERM on Stop or destruction.
class BackgroundProcess {
 public:
  BackgroundProcess() = default;
  BackgroundProcess(const BackgroundProcess&) = delete;
  BackgroundProcess& operator=(const BackgroundProcess&) = delete;
  ~BackgroundProcess();

  // The ready line, or nullopt if the process exited or the deadline passed first (then
  // stderr_text() says why).
  std::optional<std::string> Start(const std::vector<std::string>& argv,
                                   const std::string& ready_prefix,
                                   std::chrono::milliseconds deadline);
  // SIGTERM, then waits up to `deadline`; returns the exit code (-1 if it had to be killed).
  int Stop(std::chrono::milliseconds deadline = std::chrono::seconds(10));
  bool running() const { return pid_ > 0; }
  std::string stderr_text() const;

 private:
  int pid_ = -1;
  int out_fd_ = -1;
  std::thread drain_;  // keeps reading stdout after the ready line so the child never blocks
  std::string err_path_;
};

// A fresh temporary directory, removed by the destructor.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

// A loopback TCP port that nothing listens on at the moment of the call.
int UnusedLoopbackPort();

}  // namespace reenact::testing
