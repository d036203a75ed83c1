#include "tests/integration/process.h"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

extern char** environ;

namespace reenact::testing {
namespace {

using Clock = std::chrono::steady_clock;

std::vector<char*> CStrings(std::vector<std::string>& strings) {
  std::vector<char*> out;
  for (auto& s : strings) out.push_back(s.data());
  out.push_back(nullptr);
  return out;
}

// fork + exec with stdout/stderr redirected to the given fds.
int Spawn(const std::vector<std::string>& argv, int out_fd, int err_fd,
          const std::vector<std::string>& extra_env) {
  std::vector<std::string> args = argv;
  std::vector<std::string> env;
  for (char** e = environ; *e; ++e) env.emplace_back(*e);
  env.insert(env.end(), extra_env.begin(), extra_env.end());
  std::vector<char*> cargs = CStrings(args), cenv = CStrings(env);
  const pid_t pid = fork();
  if (pid == 0) {
    setpgid(0, 0);
    const int devnull = open("/dev/null", O_RDONLY);
    dup2(devnull, 0);
    dup2(out_fd, 1);
    dup2(err_fd, 2);
    execve(cargs[0], cargs.data(), cenv.data());
    std::fprintf(stderr, "exec %s failed: %s\n", cargs[0], std::strerror(errno));
    _exit(127);
  }
  return pid;
}

std::string ReadWhole(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

int WaitWithDeadline(int pid, Clock::time_point until, bool& timed_out) {
  int status = 0;
  while (true) {
    const int r = waitpid(pid, &status, WNOHANG);
    if (r == pid) break;
    if (Clock::now() >= until) {
      timed_out = true;
      kill(-pid, SIGKILL);
      waitpid(pid, &status, 0);
      return -1;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace

ProcessResult RunProcess(const std::vector<std::string>& argv, std::chrono::milliseconds deadline,
                         const std::vector<std::string>& extra_env) {
  TempDir tmp;
  const std::string out_path = tmp.path() + "/out", err_path = tmp.path() + "/err";
  const int out_fd = open(out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  const int err_fd = open(err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  const auto start = Clock::now();
  const int pid = Spawn(argv, out_fd, err_fd, extra_env);
  close(out_fd);
  close(err_fd);
  ProcessResult result;
  result.exit_code = WaitWithDeadline(pid, start + deadline, result.timed_out);
  result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  result.out = ReadWhole(out_path);
  result.err = ReadWhole(err_path);
  return result;
}

BackgroundProcess::~BackgroundProcess() { Stop(std::chrono::seconds(5)); }

std::optional<std::string> BackgroundProcess::Start(const std::vector<std::string>& argv,
                                                    const std::string& ready_prefix,
                                                    std::chrono::milliseconds deadline) {
  int pipe_fds[2];
  if (pipe(pipe_fds) != 0) return std::nullopt;
  err_path_ = (std::filesystem::temp_directory_path() /
               ("reenact-bg-" + std::to_string(getpid()) + "-" + std::to_string(rand()) + ".err"))
                  .string();
  const int err_fd = open(err_path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  pid_ = Spawn(argv, pipe_fds[1], err_fd, {});
  close(pipe_fds[1]);
  close(err_fd);
  out_fd_ = pipe_fds[0];
  const auto until = Clock::now() + deadline;
  std::string buffer;
  while (Clock::now() < until) {
    pollfd pfd{out_fd_, POLLIN, 0};
    if (poll(&pfd, 1, 50) > 0) {
      char chunk[256];
      const ssize_t n = read(out_fd_, chunk, sizeof chunk);
      if (n <= 0) return std::nullopt;  // closed: the process exited
      buffer.append(chunk, static_cast<size_t>(n));
      size_t pos;
      while ((pos = buffer.find('\n')) != std::string::npos) {
        std::string line = buffer.substr(0, pos);
        buffer.erase(0, pos + 1);
        if (line.rfind(ready_prefix, 0) == 0) {
          drain_ = std::thread([fd = out_fd_] {
            char sink[4096];
            while (read(fd, sink, sizeof sink) > 0) {
            }
          });
          return line;
        }
      }
    }
  }
  return std::nullopt;
}

int BackgroundProcess::Stop(std::chrono::milliseconds deadline) {
  if (pid_ <= 0) return -1;
  kill(pid_, SIGTERM);
  bool timed_out = false;
  const int code = WaitWithDeadline(pid_, Clock::now() + deadline, timed_out);
  pid_ = -1;
  if (drain_.joinable()) drain_.join();  // the pipe closed when the child exited
  if (out_fd_ >= 0) close(out_fd_);
  out_fd_ = -1;
  return code;
}

std::string BackgroundProcess::stderr_text() const { return ReadWhole(err_path_); }

TempDir::TempDir() {
  std::string templ = (std::filesystem::temp_directory_path() / "reenact-test-XXXXXX").string();
  path_ = mkdtemp(templ.data());
}

TempDir::~TempDir() {
  std::error_code ec;
  std::filesystem::remove_all(path_, ec);
}

int UnusedLoopbackPort() {
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  addr.sin_port = 0;
  bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr);
  socklen_t len = sizeof addr;
  getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len);
  close(fd);
  return ntohs(addr.sin_port);
}

}  // namespace reenact::testing
