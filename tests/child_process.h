// A real program run by an end-to-end test: started by the project's
// spawner (master/run/local_workers.h) in a process group of its own,
// signalled with kill(2), reaped with waitpid.
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

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <functional>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "master/run/local_workers.h"

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
    ProcessOptions options;
    options.argv = std::move(argv);
    options.stdout_path = stdout_path_;
    options.stderr_path = stderr_path_;
    options.truncate = true;
    options.own_process_group = true;
    Result<std::unique_ptr<LocalProcess>> process =
        LocalProcess::Start(options);
    if (process.ok()) {
      process_ = std::move(process).value();
      pid_ = process_->pid();
    } else {
      ADD_FAILURE() << process.status().message();
    }
  }

  virtual ~ChildProcess() {
    if (process_ != nullptr && process_->Exited() && !signalled_ &&
        lifetime_ == Lifetime::kStaysUp) {
      ADD_FAILURE() << label_ << " " << pid_
                    << " exited by itself: " << Describe() << "\n"
                    << output();
    }
    process_.reset();  // Killed (with its group) and reaped if running.
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

  bool started() const { return process_ != nullptr; }
  pid_t pid() const { return pid_; }
  const std::string& label() const { return label_; }

  // Sends `signal` to the process (not its group); the test then expects
  // whatever it does (no failure if the process exits).
  bool Signal(int signal) {
    if (process_ == nullptr) return false;
    signalled_ = true;
    return process_->Signal(signal);
  }

  // True while the process has not exited (reaps it if it has).
  bool Running() { return process_ != nullptr && !process_->Exited(); }

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
    return process_ != nullptr;
  }

  // After an exit: the code it exited with, or -1 if a signal ended it.
  int exit_code() const { return process_ ? process_->exit_code() : -1; }
  // After an exit: the signal that ended it, or 0.
  int term_signal() const { return process_ ? process_->term_signal() : 0; }
  std::string Describe() const {
    return process_ ? process_->Describe() : "not started";
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

  std::string label_;
  Lifetime lifetime_;
  std::unique_ptr<LocalProcess> process_;
  pid_t pid_ = -1;
  std::string stdout_path_;
  std::string stderr_path_;
  bool signalled_ = false;
};

}  // namespace animat::testing

#endif  // ANIMAT_TESTS_CHILD_PROCESS_H_
