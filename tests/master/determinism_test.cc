// The master's promise: one seed gives one store (the same individuals,
// parents, genomes, evaluations to the bit, generations and ranks) whatever
// the number of workers, and however often the master or a worker is
// killed mid-run and the master resumed.
#include <csignal>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "common/base/rng.h"
#include "tests/master/master_harness.h"

namespace animat::testing {
namespace {

// A moment to kill the master: once the store shows `reached`, after a
// further pause.
struct Kill {
  std::string when;
  std::function<bool(const Progress&)> reached;
  milliseconds pause{0};
};

TEST_F(MasterTest, RunKilledAndResumedGivesTheStoreOfAnUninterruptedRun) {
  TestRun run;
  run.seed = 10;
  run.generations = 10;
  run.motion_steps = kMotionStepsForSlowGenerations;
  const std::string config = WriteConfig("run.txtpb", run);
  const std::string reference_db = Path("reference.db");
  RunToEnd(config, reference_db, /*workers=*/1);
  if (HasFatalFailure()) return;
  const int64_t candidates = QueryInt(
      reference_db, "SELECT count(*) FROM individuals WHERE generation = 0");
  ASSERT_GE(candidates, 2048);  // Two blocks at least.

  // The kill moments: when the store shows a point of the run (among the
  // initial candidates, after the initial population, after a later
  // generation, soon after a resume), then after a pause. Each but the
  // first waits for progress beyond the kill before it. The generation and the
  // pauses are drawn from a stream of a fixed seed: every run of the test aims
  // at the same points (where exactly a kill lands depends on timing).
  RandomStream draws(20240611, 0, StreamPurpose::kSelection);
  const auto pause = [&] {
    return milliseconds(static_cast<int64_t>(draws.Below(30)));
  };
  const int64_t later_generation =
      2 + static_cast<int64_t>(draws.Below(run.generations - 6));
  std::vector<Kill> kills = {
      {"among the initial candidates",
       [](const Progress& p) { return p.generations == 0; }, pause()},
      {"after the initial population",
       [](const Progress& p) { return p.complete_generations >= 1; }, pause()},
      {"after generation " + std::to_string(later_generation),
       [&](const Progress& p) {
         return p.complete_generations >= later_generation;
       },
       pause()},
      {"soon after a resume", [](const Progress&) { return true; }, pause()},
  };

  const std::string db = Path("killed.db");
  std::unique_ptr<ChildProcess> master = StartRun(config, db);
  std::vector<std::unique_ptr<WorkerProcess>> workers = StartWorkers(3);
  int64_t evaluated_at_last_kill = 0;
  for (size_t k = 0; k < kills.size(); ++k) {
    SCOPED_TRACE("kill " + std::to_string(k) + ", " + kills[k].when);
    ASSERT_TRUE(AwaitStore(
        db,
        [&](const Progress& p) {
          // The first kill waits for candidates in the store, not for a
          // recorded result: the initial candidates may all be evaluated
          // before the first commit of results (0.2 s), which also chooses
          // the population.
          const bool progress =
              k == 0 ? p.individuals > 0 : p.evaluated > evaluated_at_last_kill;
          return progress && kills[k].reached(p);
        },
        *master))
        << "the master ended first: " << master->Describe() << "; store "
        << ReadProgress(db).ToString();
    std::this_thread::sleep_for(kills[k].pause);
    ASSERT_TRUE(master->Running())
        << "the run ended before the kill: " << ReadProgress(db).ToString();
    ASSERT_TRUE(master->Signal(SIGKILL));
    ASSERT_TRUE(AwaitExit(*master, kStepWait, "SIGKILL"));
    EXPECT_EQ(master->term_signal(), SIGKILL) << master->Describe();
    const Progress killed = ReadProgress(db);
    ASSERT_FALSE(killed.finished) << "the kill landed after the end";
    evaluated_at_last_kill = killed.evaluated;

    master = Resume(db);
    if (k == 0) {
      // A worker dies too, while the master serves: its leases come back
      // when the master finds it silent (or when the master next dies).
      ASSERT_TRUE(AwaitOutput(*master, workers[0]->name() + " joined"));
      ASSERT_TRUE(AwaitStore(
          db,
          [&](const Progress& p) {
            return p.evaluated > evaluated_at_last_kill;
          },
          *master));
      ASSERT_TRUE(workers[0]->Signal(SIGKILL));
      ASSERT_TRUE(AwaitExit(*workers[0], kStepWait, "SIGKILL"));
      ASSERT_TRUE(master->Running());
      ASSERT_FALSE(ReadProgress(db).finished) << "the worker died too late";
    }
  }
  ASSERT_TRUE(AwaitExit(*master, kRunWait, "the resumed run"));
  ASSERT_EQ(master->exit_code(), 0) << master->output();
  ASSERT_TRUE(ReadProgress(db).finished) << ReadProgress(db).ToString();

  ExpectSameContents(ReadStoreContents(reference_db), ReadStoreContents(db));
}

}  // namespace
}  // namespace animat::testing
