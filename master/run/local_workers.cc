#include "master/run/local_workers.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstring>
#include <thread>

extern char** environ;

namespace animat {
namespace {

// posix_spawn's file actions and attributes, released on destruction.
class SpawnSetup {
 public:
  explicit SpawnSetup(const ProcessOptions& options) {
    posix_spawn_file_actions_init(&actions_);
    posix_spawnattr_init(&attributes_);
    const int flags =
        O_WRONLY | O_CREAT | (options.truncate ? O_TRUNC : O_APPEND);
    if (!options.stdout_path.empty()) {
      posix_spawn_file_actions_addopen(
          &actions_, STDOUT_FILENO, options.stdout_path.c_str(), flags, 0644);
    }
    if (!options.stderr_path.empty()) {
      if (options.stderr_path == options.stdout_path) {
        posix_spawn_file_actions_adddup2(&actions_, STDOUT_FILENO,
                                         STDERR_FILENO);
      } else {
        posix_spawn_file_actions_addopen(
            &actions_, STDERR_FILENO, options.stderr_path.c_str(), flags, 0644);
      }
    }
    if (options.own_process_group) {
      posix_spawnattr_setflags(&attributes_, POSIX_SPAWN_SETPGROUP);
      posix_spawnattr_setpgroup(&attributes_, 0);
    }
  }
  ~SpawnSetup() {
    posix_spawnattr_destroy(&attributes_);
    posix_spawn_file_actions_destroy(&actions_);
  }
  SpawnSetup(const SpawnSetup&) = delete;
  SpawnSetup& operator=(const SpawnSetup&) = delete;

  const posix_spawn_file_actions_t* actions() const { return &actions_; }
  const posix_spawnattr_t* attributes() const { return &attributes_; }

 private:
  posix_spawn_file_actions_t actions_;
  posix_spawnattr_t attributes_;
};

}  // namespace

Result<std::unique_ptr<LocalProcess>> LocalProcess::Start(
    const ProcessOptions& options) {
  if (options.argv.empty()) {
    return Status::InvalidArgument("no program to start");
  }
  std::vector<std::string> args = options.argv;
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  const SpawnSetup setup(options);
  pid_t pid = 0;
  const int error = posix_spawn(&pid, args[0].c_str(), setup.actions(),
                                setup.attributes(), argv.data(), environ);
  if (error != 0) {
    return Status::IoError("cannot start " + args[0] + ": " +
                           std::strerror(error));
  }
  return std::unique_ptr<LocalProcess>(
      new LocalProcess(pid, options.own_process_group));
}

LocalProcess::~LocalProcess() {
  if (Exited()) return;
  if (group_) {
    kill(-pid_, SIGKILL);  // It and whatever it started.
  } else {
    kill(pid_, SIGKILL);
  }
  Wait();
}

bool LocalProcess::Signal(int signal) {
  return !reaped_ && kill(pid_, signal) == 0;
}

bool LocalProcess::SignalGroup(int signal) {
  return !reaped_ && kill(group_ ? -pid_ : pid_, signal) == 0;
}

bool LocalProcess::Reap(int flags) {
  if (reaped_) return true;
  pid_t got;
  do {
    got = waitpid(pid_, &status_, flags);
  } while (got < 0 && errno == EINTR);
  // ECHILD: someone else reaped it (it is gone all the same).
  if (got == pid_ || (got < 0 && errno == ECHILD)) reaped_ = true;
  return reaped_;
}

bool LocalProcess::Exited() { return Reap(WNOHANG); }

void LocalProcess::Wait() { Reap(0); }

int LocalProcess::exit_code() const {
  return reaped_ && WIFEXITED(status_) ? WEXITSTATUS(status_) : -1;
}

int LocalProcess::term_signal() const {
  return reaped_ && WIFSIGNALED(status_) ? WTERMSIG(status_) : 0;
}

std::string LocalProcess::Describe() const {
  if (!reaped_) return "running";
  if (WIFEXITED(status_)) return "exit code " + std::to_string(exit_code());
  return std::string("signal ") + strsignal(term_signal());
}

std::string WorkerBesideThisProgram() {
  char self[PATH_MAX];
  const ssize_t n = readlink("/proc/self/exe", self, sizeof(self) - 1);
  if (n <= 0) return "animat-worker";
  const std::string path(self, static_cast<size_t>(n));
  return path.substr(0, path.rfind('/') + 1) + "animat-worker";
}

namespace {

// `value` as text that reads back as the same double.
std::string ExactText(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.17g", value);
  return text;
}

}  // namespace

std::vector<std::string> WorkerArgv(const LocalWorkerOptions& options) {
  std::vector<std::string> argv = {options.binary, "--connect",
                                   options.endpoint, "--threads",
                                   std::to_string(options.threads)};
  if (options.heartbeat_ms > 0) {
    argv.push_back("--heartbeat-ms");
    argv.push_back(std::to_string(options.heartbeat_ms));
  }
  if (options.null_evaluation) argv.push_back("--null-evaluation");
  if (options.null_delay_ms > 0) {
    argv.push_back("--null-delay-ms");
    argv.push_back(ExactText(options.null_delay_ms));
    argv.push_back("--null-delay-cv");
    argv.push_back(ExactText(options.null_delay_cv));
  }
  if (options.exit_when_done) argv.push_back("--exit-when-done");
  if (options.idle_timeout_s > 0) {
    argv.push_back("--idle-timeout");
    argv.push_back(std::to_string(options.idle_timeout_s));
  }
  if (options.log_items) argv.push_back("--log-items");
  return argv;
}

Status LocalWorkers::Start(int count, const LocalWorkerOptions& options) {
  ProcessOptions process;
  process.argv = WorkerArgv(options);
  process.stdout_path = options.log_path;
  process.stderr_path = options.log_path;
  for (int i = 0; i < count; ++i) {
    Result<std::unique_ptr<LocalProcess>> worker = LocalProcess::Start(process);
    if (!worker.ok()) return worker.status();
    workers_.push_back(std::move(worker).value());
  }
  return Status::Ok();
}

std::string LocalWorkers::Exited() {
  for (auto it = workers_.begin(); it != workers_.end(); ++it) {
    if ((*it)->Exited()) {
      const std::string how = (*it)->Describe();
      workers_.erase(it);
      return how;
    }
  }
  return "";
}

void LocalWorkers::Stop(std::chrono::milliseconds grace,
                        const std::function<void()>& between) {
  for (const auto& worker : workers_) worker->Signal(SIGTERM);
  const auto end = std::chrono::steady_clock::now() + grace;
  while (!workers_.empty() && std::chrono::steady_clock::now() < end) {
    std::erase_if(workers_, [](const std::unique_ptr<LocalProcess>& worker) {
      return worker->Exited();
    });
    if (workers_.empty()) break;
    if (between) {
      between();
    } else {
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  }
  workers_.clear();  // SIGKILL to the rest (~LocalProcess).
}

}  // namespace animat
