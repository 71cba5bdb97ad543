#include "bench/worker_processes.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>

#include "bench/timing.h"

extern char** environ;

namespace animat::bench {

WorkerProcesses::WorkerProcesses(std::string binary, std::string log,
                                 Dispatcher* dispatcher)
    : binary_(std::move(binary)),
      log_(std::move(log)),
      dispatcher_(dispatcher) {}

bool WorkerProcesses::Spawn(int count, int threads, bool null_evaluation) {
  for (int i = 0; i < count; ++i) {
    std::vector<std::string> args = {binary_, "--connect",
                                     dispatcher_->endpoint(), "--threads",
                                     std::to_string(threads)};
    if (null_evaluation) args.push_back("--null-evaluation");
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, log_.c_str(),
                                     O_WRONLY | O_CREAT | O_APPEND, 0644);
    pid_t pid = 0;
    const int error = posix_spawn(&pid, binary_.c_str(), &actions, nullptr,
                                  argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (error != 0) {
      std::fprintf(stderr, "cannot start %s: %s\n", binary_.c_str(),
                   std::strerror(error));
      return false;
    }
    pids_.push_back(pid);
  }
  // Serve until every worker has said hello.
  const Clock::time_point start = Clock::now();
  while (dispatcher_->workers() < pids_.size()) {
    dispatcher_->Poll(10);
    for (pid_t pid : pids_) {
      int status = 0;
      if (waitpid(pid, &status, WNOHANG) == pid) {
        std::fprintf(stderr,
                     "a worker exited (status %d; 3: refused) before "
                     "joining; see its log (%s)\n",
                     WIFEXITED(status) ? WEXITSTATUS(status) : -1,
                     log_.c_str());
        pids_.erase(std::find(pids_.begin(), pids_.end(), pid));
        return false;
      }
    }
    if (SecondsSince(start) > 10) {
      std::fprintf(stderr, "workers did not join within 10 s\n");
      return false;
    }
  }
  return true;
}

void WorkerProcesses::Stop() {
  for (pid_t pid : pids_) kill(pid, SIGTERM);
  const Clock::time_point start = Clock::now();
  while (!pids_.empty()) {
    dispatcher_->Poll(5);
    for (size_t i = 0; i < pids_.size();) {
      int status = 0;
      if (waitpid(pids_[i], &status, WNOHANG) == pids_[i]) {
        pids_.erase(pids_.begin() + static_cast<long>(i));
      } else {
        ++i;
      }
    }
    if (SecondsSince(start) > 5) {
      for (pid_t pid : pids_) {
        kill(pid, SIGKILL);
        waitpid(pid, nullptr, 0);
      }
      pids_.clear();
    }
  }
}

}  // namespace animat::bench
