// A real animat-worker process for the dispatch tests: started with
// posix_spawn, signalled with kill(2), reaped with waitpid.
//
// The destructor kills (SIGKILL) and reaps a process still running, so no
// test leaks a worker even when it fails half-way. Standard output and
// error go to a temporary file (output()); when the test has failed, the
// destructor prints it. A worker that exited by itself without a test
// waiting for it, or whose output holds a sanitizer report, fails the test.
// Not thread-safe: one test thread uses it.
#ifndef ANIMAT_TESTS_DISPATCH_WORKER_PROCESS_H_
#define ANIMAT_TESTS_DISPATCH_WORKER_PROCESS_H_

#include <fcntl.h>
#include <spawn.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <iostream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

extern char** environ;

namespace animat::testing {

struct WorkerArgs {
  std::string endpoint;  // The master's.
  int threads = 1;
  int heartbeat_ms = 100;  // Until the master's welcome sets its own.
  bool null_evaluation = false;
};

class WorkerProcess {
 public:
  // Starts ANIMAT_BIN_DIR/animat-worker; started() says whether it worked.
  explicit WorkerProcess(const WorkerArgs& args) {
    static int counter = 0;
    output_path_ = ::testing::TempDir() + "/animat-worker-" +
                   std::to_string(getpid()) + "-" + std::to_string(++counter) +
                   ".log";
    const std::string binary = std::string(ANIMAT_BIN_DIR) + "/animat-worker";
    std::vector<std::string> argv = {binary,
                                     "--connect",
                                     args.endpoint,
                                     "--threads",
                                     std::to_string(args.threads),
                                     "--heartbeat-ms",
                                     std::to_string(args.heartbeat_ms)};
    if (args.null_evaluation) argv.push_back("--null-evaluation");
    std::vector<char*> pointers;
    for (std::string& a : argv) pointers.push_back(a.data());
    pointers.push_back(nullptr);

    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO,
                                     output_path_.c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
    const int error = posix_spawn(&pid_, binary.c_str(), &actions, nullptr,
                                  pointers.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (error != 0) {
      ADD_FAILURE() << "posix_spawn " << binary << ": " << strerror(error);
      pid_ = -1;
    }
  }

  ~WorkerProcess() {
    if (pid_ > 0 && !reaped_) {
      if (Reap(WNOHANG) && !signalled_) {
        ADD_FAILURE() << "animat-worker " << pid_
                      << " exited by itself: " << Describe() << "\n"
                      << output();
      }
      if (!reaped_) {
        kill(pid_, SIGKILL);
        Reap(0);
      }
    }
    const std::string text = output();
    if (text.find("Sanitizer") != std::string::npos ||
        text.find("runtime error:") != std::string::npos) {
      ADD_FAILURE() << "animat-worker " << pid_
                    << " reported a sanitizer error:\n"
                    << text;
    } else if (::testing::Test::HasFailure()) {
      std::cerr << "--- animat-worker " << pid_ << " output ---\n"
                << text << "--- end of animat-worker " << pid_ << " ---\n";
    }
    std::remove(output_path_.c_str());
  }

  WorkerProcess(const WorkerProcess&) = delete;
  WorkerProcess& operator=(const WorkerProcess&) = delete;

  bool started() const { return pid_ > 0; }
  pid_t pid() const { return pid_; }

  // "host:pid", as the dispatcher names the worker.
  std::string name() const {
    char host[256] = {};
    gethostname(host, sizeof(host) - 1);
    return std::string(host) + ":" + std::to_string(pid_);
  }

  // Sends `signal`; the test then expects whatever it does (no failure if
  // the process exits).
  bool Signal(int signal) {
    if (pid_ <= 0 || reaped_) return false;
    signalled_ = true;
    return kill(pid_, signal) == 0;
  }

  // True while the process has not exited (reaps it if it has).
  bool Running() { return pid_ > 0 && !reaped_ && !Reap(WNOHANG); }

  // Waits up to `timeout` for the process to exit, calling `between`
  // (e.g. to keep a dispatcher serving) about every 10 ms. True if it
  // exited; then exit_code() or term_signal() say how.
  bool WaitExit(std::chrono::milliseconds timeout,
                const std::function<void()>& between = {}) {
    signalled_ = true;  // The test expects the exit.
    const auto end = std::chrono::steady_clock::now() + timeout;
    while (Running()) {
      if (std::chrono::steady_clock::now() >= end) return false;
      if (between) {
        between();
      } else {
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
      }
    }
    return reaped_;
  }

  // After an exit: the code it exited with, or -1 if a signal ended it.
  int exit_code() const {
    return reaped_ && WIFEXITED(status_) ? WEXITSTATUS(status_) : -1;
  }
  // After an exit: the signal that ended it, or 0.
  int term_signal() const {
    return reaped_ && WIFSIGNALED(status_) ? WTERMSIG(status_) : 0;
  }
  std::string Describe() const {
    if (!reaped_) return "running";
    if (WIFEXITED(status_)) return "exit code " + std::to_string(exit_code());
    return std::string("signal ") + strsignal(term_signal());
  }

  // Everything it wrote to standard output and error so far.
  std::string output() const {
    std::ifstream in(output_path_);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
  }

 private:
  // True if the process has exited (and is now reaped).
  bool Reap(int flags) {
    if (reaped_) return true;
    pid_t got;
    do {
      got = waitpid(pid_, &status_, flags);
    } while (got < 0 && errno == EINTR);
    if (got == pid_) reaped_ = true;
    return reaped_;
  }

  pid_t pid_ = -1;
  std::string output_path_;
  int status_ = 0;
  bool reaped_ = false;
  bool signalled_ = false;
};

}  // namespace animat::testing

#endif  // ANIMAT_TESTS_DISPATCH_WORKER_PROCESS_H_
