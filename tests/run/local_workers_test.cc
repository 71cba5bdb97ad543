// The spawner of local processes (master/run/local_workers.h) with real
// children (/bin/sh and small scripts): output where the options say,
// exit statuses, process groups, a failed start as a value, no process
// left behind by a destroyed object, and workers' command lines and stop.
#include "master/run/local_workers.h"

#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <cerrno>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace animat {
namespace {

std::string ReadAll(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

class LocalWorkersTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = ::testing::TempDir() + "/local-workers-" + std::to_string(getpid());
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string Path(const std::string& name) const { return dir_ + "/" + name; }

  // An executable shell script in the test's directory.
  std::string Script(const std::string& name, const std::string& body) {
    const std::string path = Path(name);
    std::ofstream(path) << "#!/bin/sh\n" << body << "\n";
    chmod(path.c_str(), 0755);
    return path;
  }

  // Waits (up to 10 s) until `process` has exited.
  static bool AwaitExit(LocalProcess& process) {
    for (int i = 0; i < 10000 && !process.Exited(); ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    return process.Exited();
  }

  std::string dir_;
};

TEST_F(LocalWorkersTest, OutputGoesWhereTheOptionsSayAndTheExitIsReported) {
  ProcessOptions options;
  options.argv = {"/bin/sh", "-c", "echo out; echo err >&2; exit 3"};
  options.stdout_path = Path("out.txt");
  options.stderr_path = Path("err.txt");
  Result<std::unique_ptr<LocalProcess>> process = LocalProcess::Start(options);
  ASSERT_TRUE(process.ok()) << process.status().ToString();
  (*process)->Wait();
  EXPECT_EQ((*process)->exit_code(), 3);
  EXPECT_EQ((*process)->term_signal(), 0);
  EXPECT_EQ((*process)->Describe(), "exit code 3");
  EXPECT_EQ(ReadAll(Path("out.txt")), "out\n");
  EXPECT_EQ(ReadAll(Path("err.txt")), "err\n");
}

TEST_F(LocalWorkersTest, OneFileForBothStreamsKeepsTheirOrderAndAppends) {
  std::ofstream(Path("log.txt")) << "before\n";
  ProcessOptions options;
  options.argv = {"/bin/sh", "-c", "echo 1; echo 2 >&2; echo 3"};
  options.stdout_path = Path("log.txt");
  options.stderr_path = Path("log.txt");
  Result<std::unique_ptr<LocalProcess>> process = LocalProcess::Start(options);
  ASSERT_TRUE(process.ok()) << process.status().ToString();
  (*process)->Wait();
  EXPECT_EQ(ReadAll(Path("log.txt")), "before\n1\n2\n3\n");

  options.truncate = true;
  process = LocalProcess::Start(options);
  ASSERT_TRUE(process.ok()) << process.status().ToString();
  (*process)->Wait();
  EXPECT_EQ(ReadAll(Path("log.txt")), "1\n2\n3\n");
}

TEST_F(LocalWorkersTest, AProgramThatCannotStartIsAnError) {
  ProcessOptions options;
  options.argv = {Path("no-such-program")};
  Result<std::unique_ptr<LocalProcess>> process = LocalProcess::Start(options);
  ASSERT_FALSE(process.ok());
  EXPECT_EQ(process.status().code(), StatusCode::kIoError);
  EXPECT_NE(process.status().message().find("cannot start " +
                                            Path("no-such-program")),
            std::string::npos)
      << process.status().ToString();
  options.argv.clear();
  EXPECT_FALSE(LocalProcess::Start(options).ok());
}

TEST_F(LocalWorkersTest, ASignalEndsTheProcessAndIsReported) {
  ProcessOptions options;
  options.argv = {"/bin/sh", "-c", "while :; do sleep 1; done"};
  Result<std::unique_ptr<LocalProcess>> process = LocalProcess::Start(options);
  ASSERT_TRUE(process.ok()) << process.status().ToString();
  EXPECT_FALSE((*process)->Exited());
  ASSERT_TRUE((*process)->Signal(SIGKILL));
  ASSERT_TRUE(AwaitExit(**process));
  EXPECT_EQ((*process)->term_signal(), SIGKILL);
  EXPECT_EQ((*process)->exit_code(), -1);
  EXPECT_FALSE((*process)->Signal(SIGKILL)) << "reaped: nothing to signal";
}

TEST_F(LocalWorkersTest, AGroupSignalReachesWhatTheProcessStarted) {
  // The child starts a grandchild that writes its pid, then waits for it.
  ProcessOptions options;
  options.argv = {"/bin/sh", "-c",
                  "sleep 1000 & echo $! > " + Path("grandchild") + "; wait"};
  options.own_process_group = true;
  Result<std::unique_ptr<LocalProcess>> process = LocalProcess::Start(options);
  ASSERT_TRUE(process.ok()) << process.status().ToString();
  EXPECT_EQ(getpgid((*process)->pid()), (*process)->pid());
  std::string grandchild;
  for (int i = 0; i < 10000 && grandchild.find('\n') == std::string::npos;
       ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
    grandchild = ReadAll(Path("grandchild"));
  }
  const pid_t pid = static_cast<pid_t>(std::stol(grandchild));
  EXPECT_EQ(getpgid(pid), (*process)->pid());
  ASSERT_TRUE((*process)->SignalGroup(SIGTERM));
  ASSERT_TRUE(AwaitExit(**process));
  EXPECT_EQ((*process)->term_signal(), SIGTERM);
}

TEST_F(LocalWorkersTest, DestroyingARunningProcessKillsAndReapsIt) {
  ProcessOptions options;
  options.argv = {"/bin/sh", "-c", "while :; do sleep 1; done"};
  Result<std::unique_ptr<LocalProcess>> process = LocalProcess::Start(options);
  ASSERT_TRUE(process.ok()) << process.status().ToString();
  const pid_t pid = (*process)->pid();
  process->reset();
  // Reaped: no such process any more, not even a zombie of this one.
  errno = 0;
  EXPECT_EQ(kill(pid, 0), -1);
  EXPECT_EQ(errno, ESRCH);
}

TEST_F(LocalWorkersTest, AWorkersCommandLineSaysWhatItsOptionsSay) {
  LocalWorkerOptions options;
  options.binary = "/opt/animat-worker";
  options.endpoint = "tcp://10.0.0.1:5555";
  options.threads = 4;
  EXPECT_EQ(WorkerArgv(options), (std::vector<std::string>{
                                     "/opt/animat-worker", "--connect",
                                     "tcp://10.0.0.1:5555", "--threads", "4"}));
  options.heartbeat_ms = 100;
  options.null_evaluation = true;
  options.exit_when_done = true;
  options.idle_timeout_s = 60;
  EXPECT_EQ(WorkerArgv(options),
            (std::vector<std::string>{
                "/opt/animat-worker", "--connect", "tcp://10.0.0.1:5555",
                "--threads", "4", "--heartbeat-ms", "100", "--null-evaluation",
                "--exit-when-done", "--idle-timeout", "60"}));
  options.exit_when_done = false;
  options.idle_timeout_s = 0;
  options.heartbeat_ms = 0;
  options.null_delay_ms = 12.5;
  options.null_delay_cv = 0.1;
  EXPECT_EQ(WorkerArgv(options),
            (std::vector<std::string>{
                "/opt/animat-worker", "--connect", "tcp://10.0.0.1:5555",
                "--threads", "4", "--null-evaluation", "--null-delay-ms",
                "12.5", "--null-delay-cv", "0.10000000000000001"}));
  options.null_evaluation = false;
  options.null_delay_ms = 0;
  options.log_items = true;
  EXPECT_EQ(WorkerArgv(options),
            (std::vector<std::string>{"/opt/animat-worker", "--connect",
                                      "tcp://10.0.0.1:5555", "--threads", "4",
                                      "--log-items"}));
}

TEST_F(LocalWorkersTest, WorkersThatExitAreReportedAndDropped) {
  LocalWorkerOptions options;
  options.binary = Script("refused", "echo \"$@\"; exit 3");
  options.endpoint = "ipc://nowhere";
  options.log_path = Path("workers.log");
  LocalWorkers workers;
  ASSERT_TRUE(workers.Start(2, options).ok());
  EXPECT_EQ(workers.size(), 2u);
  std::vector<std::string> exits;
  for (int i = 0; i < 10000 && exits.size() < 2; ++i) {
    const std::string exited = workers.Exited();
    if (exited.empty()) {
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    } else {
      exits.push_back(exited);
    }
  }
  EXPECT_EQ(exits, (std::vector<std::string>{"exit code 3", "exit code 3"}));
  EXPECT_EQ(workers.size(), 0u);
  EXPECT_EQ(ReadAll(Path("workers.log")),
            "--connect ipc://nowhere --threads 1\n"
            "--connect ipc://nowhere --threads 1\n");
}

TEST_F(LocalWorkersTest, StopEndsWorkersThatIgnoreSigtermAfterTheGrace) {
  LocalWorkerOptions options;
  // One ends on SIGTERM; the other ignores it, and says so once it does.
  options.binary = Script("worker", "while :; do sleep 1; done");
  LocalWorkers workers;
  ASSERT_TRUE(workers.Start(1, options).ok());
  options.binary =
      Script("stubborn", "trap '' TERM\ntouch " + Path("ignoring") +
                             "\nwhile :; do sleep 1; done");
  ASSERT_TRUE(workers.Start(1, options).ok());
  for (int i = 0; i < 10000 && !std::filesystem::exists(Path("ignoring"));
       ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  ASSERT_TRUE(std::filesystem::exists(Path("ignoring")));
  int between = 0;
  const auto start = std::chrono::steady_clock::now();
  workers.Stop(std::chrono::milliseconds(200), [&] {
    ++between;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  });
  // The stubborn one outlived the grace, then was killed.
  EXPECT_GE(std::chrono::steady_clock::now() - start,
            std::chrono::milliseconds(200));
  EXPECT_GT(between, 0);
  EXPECT_EQ(workers.size(), 0u);
}

}  // namespace
}  // namespace animat
