#include "tests/unit/server/postgres_test_cluster.h"

#include <fcntl.h>
#include <grp.h>
#include <pwd.h>
#include <signal.h>
#include <stdlib.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <mutex>
#include <sstream>
#include <thread>
#include <vector>

#include "server/storage/postgres.h"

namespace reenact::server::testing {

namespace {

namespace fs = std::filesystem;

// The role of the local cluster that authenticates by password.
constexpr const char* kPasswordRole = "reenact_password_test";

constexpr const char* kInstallHint =
    "install the postgresql and postgis packages (deploy/install-deps.sh) or set "
    "REENACT_TEST_POSTGRES_URL to a server whose role may CREATE DATABASE";

// The bin directory of the newest installed server, or "".
fs::path NewestServerBinDir() {
  fs::path best;
  int best_version = -1;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator("/usr/lib/postgresql", ec)) {
    const std::string name = entry.path().filename().string();
    char* end = nullptr;
    const long version = std::strtol(name.c_str(), &end, 10);
    if (end == name.c_str() || *end != '\0') continue;
    if (!fs::exists(entry.path() / "bin" / "initdb") ||
        !fs::exists(entry.path() / "bin" / "postgres")) {
      continue;
    }
    if (version > best_version) {
      best_version = static_cast<int>(version);
      best = entry.path() / "bin";
    }
  }
  return best;
}

std::string Tail(const fs::path& log) {
  std::ifstream in(log);
  std::stringstream text;
  text << in.rdbuf();
  std::string s = text.str();
  if (s.size() > 2000) s = s.substr(s.size() - 2000);
  return s;
}

// Who runs the server: the current user, or `postgres` when running as root.
struct RunAs {
  bool switch_user = false;
  uid_t uid = 0;
  gid_t gid = 0;
};

// Forks and execs `args` as `who`, stdout and stderr to `log`. In the child only
// async-signal-safe calls. `die_with_parent`: SIGQUIT when this thread ends.
Expected<pid_t> Spawn(const std::vector<std::string>& args, const RunAs& who, const fs::path& log,
                      bool die_with_parent) {
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const int log_fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0600);
  if (log_fd < 0) return MakeError("io", "cannot create " + log.string());
  if (who.switch_user && ::fchown(log_fd, who.uid, who.gid) != 0) {
    ::close(log_fd);
    return MakeError("io", "cannot hand " + log.string() + " to the postgres user");
  }
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(log_fd);
    return MakeError("io", "fork failed");
  }
  if (pid == 0) {
    ::dup2(log_fd, STDOUT_FILENO);
    ::dup2(log_fd, STDERR_FILENO);
    const int null_fd = ::open("/dev/null", O_RDONLY);
    if (null_fd >= 0) ::dup2(null_fd, STDIN_FILENO);
    if (who.switch_user) {
      if (::setgroups(0, nullptr) != 0 || ::setgid(who.gid) != 0 || ::setuid(who.uid) != 0) {
        ::_exit(126);
      }
    }
    // After the user switch, which clears it.
    if (die_with_parent) {
      ::prctl(PR_SET_PDEATHSIG, SIGQUIT);
      if (::getppid() != parent) ::_exit(125);
    }
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  ::close(log_fd);
  return pid;
}

class Cluster {
 public:
  // The server at `url` (REENACT_TEST_POSTGRES_URL), where databases are created and dropped.
  static Expected<std::unique_ptr<Cluster>> Connect(const std::string& url) {
    std::unique_ptr<Cluster> cluster(new Cluster);
    cluster->admin_url_ = url;
    cluster->external_ = true;
    auto admin = pg::Connection::Open(cluster->admin_url_);
    if (!admin) return MakeError("io", "REENACT_TEST_POSTGRES_URL: " + admin.error().message);
    return cluster;
  }

  // A cluster of this process under a new temporary directory.
  static Expected<std::unique_ptr<Cluster>> StartLocal() {
    std::unique_ptr<Cluster> cluster(new Cluster);
    if (Status s = cluster->InitAndLaunch(); !s) return s.error();
    return cluster;
  }

  ~Cluster() {
    if (external_) {
      if (auto admin = pg::Connection::Open(admin_url_)) {
        for (const std::string& name : created_) {
          (void)admin->Exec("DROP DATABASE IF EXISTS " + name + " WITH (FORCE)");
        }
      }
      return;
    }
    if (server_ > 0) {
      ::kill(server_, SIGINT);  // fast shutdown
      int status = 0;
      for (int i = 0; i < 200 && ::waitpid(server_, &status, WNOHANG) == 0; ++i) {
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
      }
      ::kill(server_, SIGKILL);
      ::waitpid(server_, &status, 0);
    }
    std::error_code ec;
    if (!dir_.empty()) fs::remove_all(dir_, ec);
  }

  Expected<std::string> NewDatabase() {
    std::string name = "reenact_test_";
    name += std::to_string(::getpid());
    name += "_";
    name += std::to_string(created_.size());
    auto admin = pg::Connection::Open(admin_url_);
    if (!admin) return admin.error();
    if (Status s = admin->Exec("CREATE DATABASE " + name); !s) return s.error();
    created_.push_back(name);
    return pg::WithDatabase(admin_url_, name);
  }

  Expected<std::string> PasswordLogin(const std::string& database, const std::string& password) {
    auto admin = pg::Connection::Open(admin_url_);
    if (!admin) return admin.error();
    // The password is a test constant; quoted as a literal, doubling quotes.
    std::string literal = "'";
    for (char c : password) literal += c == '\'' ? std::string("''") : std::string(1, c);
    literal += "'";
    const std::string role = kPasswordRole;
    if (Status s = admin->Exec("DROP ROLE IF EXISTS " + role + "; CREATE ROLE " + role +
                               " LOGIN PASSWORD " + literal);
        !s) {
      return s.error();
    }
    return "host=" + dir_.string() + " port=5432 user=" + role + " dbname=" + database;
  }

 private:
  Cluster() = default;

  Status InitAndLaunch() {
    const fs::path bin = NewestServerBinDir();
    if (bin.empty()) {
      return MakeError("unavailable",
                       std::string("no PostgreSQL server in /usr/lib/postgresql: ") + kInstallHint);
    }
    const fs::path share = fs::path("/usr/share/postgresql") / bin.parent_path().filename();
    if (!fs::exists(share / "extension" / "postgis.control")) {
      return MakeError("unavailable", "PostgreSQL " + bin.parent_path().filename().string() +
                                          " has no PostGIS extension: " + kInstallHint);
    }
    RunAs who;
    if (::geteuid() == 0) {
      const struct passwd* pw = ::getpwnam("postgres");
      if (!pw) {
        return MakeError("unavailable",
                         "running as root (PostgreSQL refuses to) and there is no 'postgres' "
                         "user to run the test cluster as");
      }
      who = RunAs{true, pw->pw_uid, pw->pw_gid};
    }
    // Under /tmp: a unix socket path must stay short, and the postgres user must reach it.
    std::string pattern = "/tmp/reenact-pg-XXXXXX";
    if (!::mkdtemp(pattern.data())) return MakeError("io", "mkdtemp failed for " + pattern);
    dir_ = pattern;
    if (who.switch_user && ::chown(dir_.c_str(), who.uid, who.gid) != 0) {
      return MakeError("io", "cannot hand " + dir_.string() + " to the postgres user");
    }
    const fs::path data = dir_ / "data";
    const fs::path log = dir_ / "server.log";
    auto initdb = Spawn({(bin / "initdb").string(), "-D", data.string(), "-A", "trust", "-U",
                         "reenact", "-E", "UTF8", "--locale=C", "--no-sync"},
                        who, log, /*die_with_parent=*/false);
    if (!initdb) return initdb.error();
    int status = 0;
    ::waitpid(*initdb, &status, 0);
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
      return MakeError("io", "initdb of the test cluster failed: " + Tail(log));
    }
    {
      std::ofstream hba(data / "pg_hba.conf", std::ios::trunc);
      hba << "local all " << kPasswordRole << " scram-sha-256\nlocal all all trust\n";
      if (!hba) return MakeError("io", "cannot write the test cluster's pg_hba.conf");
    }
    bin_ = bin;
    who_ = who;
    admin_url_ = "host=" + dir_.string() + " port=5432 user=reenact dbname=postgres";
    return Launch();
  }

  // Starts postgres on the cluster's data directory and waits until it accepts connections.
  Status Launch() {
    const fs::path data = dir_ / "data";
    const fs::path log = dir_ / "server.log";
    auto server = Spawn({(bin_ / "postgres").string(), "-D", data.string(), "-k", dir_.string(),
                         "-p", "5432", "-c", "listen_addresses=", "-c", "fsync=off"},
                        who_, log, /*die_with_parent=*/true);
    if (!server) return server.error();
    server_ = *server;
    int status = 0;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    for (;;) {
      if (pg::Connection::Open(admin_url_).ok()) return {};
      if (::waitpid(server_, &status, WNOHANG) == server_) {
        server_ = 0;
        return MakeError("io", "the test cluster's postgres exited at start: " + Tail(log));
      }
      if (std::chrono::steady_clock::now() > deadline) {
        return MakeError("io", "the test cluster did not accept connections in 30 s: " +
                                   Tail(log));
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
  }

 public:
  Status Stop(bool immediate) {
    if (server_ <= 0) return MakeError("io", "the test cluster is not running");
    ::kill(server_, immediate ? SIGQUIT : SIGINT);
    int status = 0;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    while (::waitpid(server_, &status, WNOHANG) == 0) {
      if (std::chrono::steady_clock::now() > deadline) {
        ::kill(server_, SIGKILL);
        ::waitpid(server_, &status, 0);
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    server_ = 0;
    return {};
  }

  Status Restart() {
    if (server_ > 0) return MakeError("io", "the test cluster is already running");
    return Launch();
  }

 private:
  fs::path dir_;
  fs::path bin_;
  RunAs who_;
  pid_t server_ = 0;
  std::string admin_url_;
  bool external_ = false;
  std::vector<std::string> created_;
};

// The cluster this process starts itself (once, at first use).
Expected<std::unique_ptr<Cluster>>& OwnCluster() {
  static Expected<std::unique_ptr<Cluster>> cluster = Cluster::StartLocal();
  return cluster;
}

// REENACT_TEST_POSTGRES_URL's server where it is set, else the own cluster.
Expected<std::unique_ptr<Cluster>>& SharedCluster() {
  const char* url = std::getenv("REENACT_TEST_POSTGRES_URL");
  if (!url || !*url) return OwnCluster();
  static Expected<std::unique_ptr<Cluster>> cluster = Cluster::Connect(url);
  return cluster;
}

std::mutex cluster_mutex;

}  // namespace

Expected<std::string> NewPostgresTestDatabase(TestCluster which) {
  std::lock_guard lock(cluster_mutex);
  auto& cluster = which == TestCluster::kShared ? SharedCluster() : OwnCluster();
  if (!cluster) return cluster.error();
  return (*cluster)->NewDatabase();
}

Expected<std::string> PostgresTestPasswordLogin(const std::string& database,
                                                const std::string& password) {
  std::lock_guard lock(cluster_mutex);
  auto& cluster = OwnCluster();
  if (!cluster) return cluster.error();
  return (*cluster)->PasswordLogin(database, password);
}

Status StopPostgresTestCluster(bool immediate) {
  std::lock_guard lock(cluster_mutex);
  auto& cluster = OwnCluster();
  if (!cluster) return cluster.error();
  return (*cluster)->Stop(immediate);
}

Status StartPostgresTestCluster() {
  std::lock_guard lock(cluster_mutex);
  auto& cluster = OwnCluster();
  if (!cluster) return cluster.error();
  return (*cluster)->Restart();
}

}  // namespace reenact::server::testing
