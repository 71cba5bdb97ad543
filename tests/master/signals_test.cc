// SIGTERM and SIGINT stop a master cleanly: it commits what came in, exits
// 0 and leaves a store that resumes to the same individuals as a run never
// stopped.
#include <csignal>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "tests/master/master_harness.h"

namespace animat::testing {
namespace {

// Sends `signal` to `master`, which must then exit 0 saying how to resume,
// leaving an unfinished, intact store.
void ExpectCleanStop(ChildProcess& master, int signal, const std::string& db) {
  ASSERT_TRUE(master.Running()) << "the run ended before the signal";
  ASSERT_TRUE(master.Signal(signal));
  ASSERT_TRUE(master.WaitExit(kStepWait)) << "no exit after the signal";
  EXPECT_EQ(master.exit_code(), 0) << master.Describe() << "\n"
                                   << master.output();
  EXPECT_NE(master.output().find("resume with: " + std::string(ANIMAT_BIN_DIR) +
                                 "/animat-master --resume --db " + db),
            std::string::npos)
      << master.output();
  EXPECT_EQ(QueryCell(db, "PRAGMA integrity_check"), "ok");
  const Progress stopped = ReadProgress(db);
  EXPECT_TRUE(stopped.has_run);
  EXPECT_FALSE(stopped.finished) << stopped.ToString();
}

TEST_F(MasterTest, SigtermAndSigintLeaveAStoreThatResumesToTheSameRun) {
  TestRun run;
  run.seed = 6;
  run.generations = 5;
  run.motion_steps = kMotionStepsForSlowGenerations;
  const std::string config = WriteConfig("run.txtpb", run);
  const std::string reference_db = Path("reference.db");
  RunToEnd(config, reference_db, /*workers=*/2);
  if (HasFatalFailure()) return;

  const std::string db = Path("stopped.db");
  std::unique_ptr<ChildProcess> master = StartRun(config, db);
  std::vector<std::unique_ptr<WorkerProcess>> workers = StartWorkers(2);
  // SIGTERM among the initial candidates.
  ASSERT_TRUE(AwaitStore(
      db, [](const Progress& p) { return p.evaluated >= 500; }, *master));
  ExpectCleanStop(*master, SIGTERM, db);
  if (HasFatalFailure()) return;
  const int64_t after_sigterm = ReadProgress(db).evaluated;

  // SIGINT once the resumed master has completed a generation.
  master = Resume(db);
  ASSERT_TRUE(AwaitStore(
      db,
      [&](const Progress& p) {
        return p.evaluated > after_sigterm && p.complete_generations >= 1;
      },
      *master))
      << master->Describe() << "\n"
      << master->output();
  ExpectCleanStop(*master, SIGINT, db);
  if (HasFatalFailure()) return;

  master = Resume(db);
  ASSERT_TRUE(AwaitExit(*master, kRunWait, "the resumed run"));
  ASSERT_EQ(master->exit_code(), 0) << master->output();
  ASSERT_TRUE(ReadProgress(db).finished) << ReadProgress(db).ToString();
  ExpectSameContents(ReadStoreContents(reference_db), ReadStoreContents(db));
}

}  // namespace
}  // namespace animat::testing
