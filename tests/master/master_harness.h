// The fixture of the master's end-to-end tests: a temporary directory per
// test, run configurations small enough to evolve in seconds, and real
// animat-master, animat-worker and animat processes (from ANIMAT_BIN_DIR)
// on an ipc:// endpoint of that directory (no port to find or share; a
// restarted master binds the same endpoint and its workers come back).
#ifndef ANIMAT_TESTS_MASTER_MASTER_HARNESS_H_
#define ANIMAT_TESTS_MASTER_MASTER_HARNESS_H_

#include <unistd.h>

#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "common/io/proto_file.h"
#include "tests/child_process.h"
#include "tests/dispatch/worker_process.h"
#include "tests/master/store_reader.h"

namespace animat::testing {

using Clock = std::chrono::steady_clock;
using std::chrono::milliseconds;

// The masters' heartbeat: a worker silent for 3 intervals is dead, and a
// worker finds a dead master as fast. Long enough that a master busy
// writing its store under a sanitizer, on a loaded machine, is not taken
// for dead (its workers' leases would then count as failed attempts).
inline constexpr int kMasterHeartbeatMs = 500;
// Bounds on waits that normally end far sooner (each ends as soon as its
// condition holds): a whole test run, and a master starting or stopping.
// Generous for sanitizer builds on a busy machine.
inline constexpr milliseconds kRunWait{300000};
inline constexpr milliseconds kStepWait{60000};

// Motion steps that make a generation of a test run last some 50 ms in an
// optimised build (about 10 ms an evaluation), so that a test watching the
// store can act within a few; a sanitizer build is that slow with 200.
#ifdef NDEBUG
inline constexpr int kMotionStepsForSlowGenerations = 10000;
#else
inline constexpr int kMotionStepsForSlowGenerations = 200;
#endif

// A run configuration for tests: the model with small bodies (at most 8
// cells) and a short evaluation (50 equilibration and, by default, 200
// motion steps), and a small population. The initial population takes
// the first genomes with any fitness, about one random genome in 100, so
// two or three blocks of 1024 candidates (most failing early in
// development) hold it: the costliest part of a test run, hence seeds
// whose first two blocks do.
struct TestRun {
  uint64_t seed = 3;
  int population = 20;
  int generations = 6;
  int motion_steps = 200;
  std::string evolution_extra;  // More fields of the evolution block.

  std::string Text() const {
    return "model {\n"
           "  development { max_cells: 8 }\n"
           "  evaluation { equilibration_steps: 50 motion_steps: " +
           std::to_string(motion_steps) +
           " }\n"
           "}\n"
           "evolution {\n"
           "  seed: " +
           std::to_string(seed) +
           "\n  population: " + std::to_string(population) +
           "\n  generations: " + std::to_string(generations) +
           "\n  elite: 2\n"
           "  initial_min_fitness: 0\n  " +
           evolution_extra + "\n}\n";
  }
};

class MasterTest : public ::testing::Test {
 protected:
  void SetUp() override {
    static int counter = 0;
    dir_ = ::testing::TempDir() + "/animat-master-" + std::to_string(getpid()) +
           "-" + std::to_string(++counter);
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::string Path(const std::string& name) const { return dir_ + "/" + name; }

  // Writes `run` as a run configuration file in the test's directory.
  std::string WriteConfig(const std::string& name, const TestRun& run) {
    const std::string path = Path(name);
    const Status status = WriteFile(path, run.Text());
    EXPECT_TRUE(status.ok()) << status.ToString();
    return path;
  }

  std::string Endpoint() const { return "ipc://" + dir_ + "/master.ipc"; }

  // animat-master with `args`, bound to `bind` (by default Endpoint())
  // with a short heartbeat.
  std::unique_ptr<ChildProcess> StartMaster(std::vector<std::string> args,
                                            std::string bind = "") {
    std::vector<std::string> argv = {
        std::string(ANIMAT_BIN_DIR) + "/animat-master", "--bind",
        bind.empty() ? Endpoint() : bind, "--heartbeat-ms",
        std::to_string(kMasterHeartbeatMs)};
    argv.insert(argv.end(), args.begin(), args.end());
    auto master =
        std::make_unique<ChildProcess>("animat-master", std::move(argv),
                                       ChildProcess::Lifetime::kExitsByItself);
    EXPECT_TRUE(master->started());
    return master;
  }
  std::unique_ptr<ChildProcess> StartRun(const std::string& config,
                                         const std::string& db) {
    return StartMaster({"--config", config, "--db", db});
  }
  std::unique_ptr<ChildProcess> Resume(const std::string& db,
                                       std::vector<std::string> more = {}) {
    std::vector<std::string> args = {"--resume", "--db", db};
    args.insert(args.end(), more.begin(), more.end());
    return StartMaster(std::move(args));
  }

  // `count` workers of one thread each, connecting to Endpoint().
  std::vector<std::unique_ptr<WorkerProcess>> StartWorkers(int count) {
    std::vector<std::unique_ptr<WorkerProcess>> workers;
    for (int i = 0; i < count; ++i) {
      WorkerArgs args;
      args.endpoint = Endpoint();
      args.threads = 1;
      args.heartbeat_ms = kMasterHeartbeatMs;
      workers.push_back(std::make_unique<WorkerProcess>(args));
      EXPECT_TRUE(workers.back()->started());
    }
    return workers;
  }

  // The animat tool with `args`.
  std::unique_ptr<ChildProcess> StartAnimat(std::vector<std::string> args) {
    args.insert(args.begin(), std::string(ANIMAT_BIN_DIR) + "/animat");
    auto animat = std::make_unique<ChildProcess>(
        "animat", std::move(args), ChildProcess::Lifetime::kExitsByItself);
    EXPECT_TRUE(animat->started());
    return animat;
  }

  // Waits until `process` exits, up to `timeout`; false (and a failure
  // naming `what`) if it does not.
  static bool AwaitExit(ChildProcess& process, milliseconds timeout,
                        const std::string& what) {
    if (process.WaitExit(timeout)) return true;
    ADD_FAILURE() << what << ": " << process.label() << " still running after "
                  << timeout.count() << " ms";
    return false;
  }

  // Polls the store at `db` every 10 ms until `condition` holds (true),
  // `master` exits (false) or `timeout` passes (false).
  static bool AwaitStore(const std::string& db,
                         const std::function<bool(const Progress&)>& condition,
                         ChildProcess& master,
                         milliseconds timeout = kRunWait) {
    const auto end = Clock::now() + timeout;
    for (;;) {
      if (condition(ReadProgress(db))) return true;
      if (!master.Running() || Clock::now() >= end) return false;
      std::this_thread::sleep_for(milliseconds(10));
    }
  }

  // Waits until `process` has written `text` to its standard error or
  // output; false if it exits first or `timeout` passes.
  static bool AwaitOutput(ChildProcess& process, const std::string& text,
                          milliseconds timeout = kStepWait) {
    const auto end = Clock::now() + timeout;
    for (;;) {
      if (process.output().find(text) != std::string::npos) return true;
      if (!process.Running() || Clock::now() >= end) {
        return process.output().find(text) != std::string::npos;
      }
      std::this_thread::sleep_for(milliseconds(10));
    }
  }

  // Runs `config` from start to finish into `db` with `workers` workers;
  // expects a clean exit and a finished run.
  void RunToEnd(const std::string& config, const std::string& db, int workers) {
    std::unique_ptr<ChildProcess> master = StartRun(config, db);
    const auto started = StartWorkers(workers);
    ASSERT_TRUE(AwaitExit(*master, kRunWait, "an uninterrupted run"));
    ASSERT_EQ(master->exit_code(), 0) << master->output();
    ASSERT_TRUE(ReadProgress(db).finished) << ReadProgress(db).ToString();
  }

  std::string dir_;
};

}  // namespace animat::testing

#endif  // ANIMAT_TESTS_MASTER_MASTER_HARNESS_H_
