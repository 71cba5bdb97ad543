// A real program run by an end-to-end test: started with posix_spawn in a
// process group of its own, signalled with kill(2), reaped with waitpid.
//
// The destructor kills (SIGKILL) the group of a process still running and
// reaps it, so no test leaks a process (nor the processes it started) even
// when it fails half-way. Standard output and error go to temporary files
// (standard_output(), output()); when the test has failed, the destructor
// prints them. Output holding a sanitizer report fails the test, and so
// does, for a process started as Lifetime::kStaysUp, an exit the test
// neither waited for nor caused. Not thread-safe: one test thread uses it.
#ifndef ANIMAT_TESTS_CHILD_PROCESS_H_
#define ANIMAT_TESTS_CHILD_PROCESS_H_

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
#include <utility>
#include <vector>

extern char** environ;

namespace animat::testing {

class ChildProcess {
 public:
  enum class Lifetime {
    kExitsByItself,  // E.g. a command that does its job and ends.
    kStaysUp,        // E.g. a worker: it ends only when told to.
  };

  // Starts argv[0] with `argv`; started() says whether it worked. `label`
  // names the process in failures and in its output files' names.
  ChildProcess(std::string label, std::vector<std::string> argv,
               Lifetime lifetime)
      : label_(std::move(label)), lifetime_(lifetime) {
    static int counter = 0;
    const std::string stem = ::testing::TempDir() + "/" + label_ + "-" +
                             std::to_string(getpid()) + "-" +
                             std::to_string(++counter);
    stdout_path_ = stem + ".out";
    stderr_path_ = stem + ".err";
    std::vector<char*> pointers;
    for (std::string& a : argv) pointers.push_back(a.data());
    pointers.push_back(nullptr);

    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO,
                                     stdout_path_.c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&actions, STDERR_FILENO,
                                     stderr_path_.c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawnattr_t attributes;
    posix_spawnattr_init(&attributes);
    posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP);
    posix_spawnattr_setpgroup(&attributes, 0);  // A group of its own.
    const int error = posix_spawn(&pid_, argv[0].c_str(), &actions, &attributes,
                                  pointers.data(), environ);
    posix_spawnattr_destroy(&attributes);
    posix_spawn_file_actions_destroy(&actions);
    if (error != 0) {
      ADD_FAILURE() << "posix_spawn " << argv[0] << ": " << strerror(error);
      pid_ = -1;
    }
  }

  virtual ~ChildProcess() {
    if (pid_ > 0 && !reaped_) {
      if (Reap(WNOHANG) && !signalled_ && lifetime_ == Lifetime::kStaysUp) {
        ADD_FAILURE() << label_ << " " << pid_
                      << " exited by itself: " << Describe() << "\n"
                      << output();
      }
      if (!reaped_) {
        kill(-pid_, SIGKILL);  // It and whatever it started.
        Reap(0);
      }
    }
    const std::string text = output();
    if (text.find("Sanitizer") != std::string::npos ||
        text.find("runtime error:") != std::string::npos) {
      ADD_FAILURE() << label_ << " " << pid_ << " reported a sanitizer error:\n"
                    << text;
    } else if (::testing::Test::HasFailure()) {
      std::cerr << "--- " << label_ << " " << pid_ << " output ---\n"
                << text << "--- end of " << label_ << " " << pid_ << " ---\n";
    }
    std::remove(stdout_path_.c_str());
    std::remove(stderr_path_.c_str());
  }

  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  bool started() const { return pid_ > 0; }
  pid_t pid() const { return pid_; }
  const std::string& label() const { return label_; }

  // Sends `signal` to the process (not its group); the test then expects
  // whatever it does (no failure if the process exits).
  bool Signal(int signal) {
    if (pid_ <= 0 || reaped_) return false;
    signalled_ = true;
    return kill(pid_, signal) == 0;
  }

  // True while the process has not exited (reaps it if it has).
  bool Running() { return pid_ > 0 && !reaped_ && !Reap(WNOHANG); }

  // Waits up to `timeout` for the process to exit, calling `between`
  // about every 10 ms (or sleeping). True if it exited; then exit_code()
  // or term_signal() say how.
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

  // What it wrote to standard output so far.
  std::string standard_output() const { return ReadAll(stdout_path_); }
  // What it wrote to standard error so far.
  std::string standard_error() const { return ReadAll(stderr_path_); }
  // Both: standard output, then standard error.
  std::string output() const { return standard_output() + standard_error(); }

 private:
  static std::string ReadAll(const std::string& path) {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
  }

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

  std::string label_;
  Lifetime lifetime_;
  pid_t pid_ = -1;
  std::string stdout_path_;
  std::string stderr_path_;
  int status_ = 0;
  bool reaped_ = false;
  bool signalled_ = false;
};

}  // namespace animat::testing

#endif  // ANIMAT_TESTS_CHILD_PROCESS_H_
