// A lock keeps a second master (or animat evolve) off a store a master is
// running: the second exits non-zero naming the store and its lock, and
// the first runs on as if nothing happened.
#include <memory>
#include <string>
#include <vector>

#include "tests/master/master_harness.h"

namespace animat::testing {
namespace {

// `second` must exit non-zero, saying the store `db` is in use.
void ExpectRefusedForTheLock(ChildProcess& second, const std::string& db) {
  ASSERT_TRUE(second.WaitExit(kStepWait)) << "the second one kept running";
  EXPECT_NE(second.exit_code(), 0) << second.Describe();
  const std::string error = second.standard_error();
  EXPECT_NE(error.find(db + ": in use by another master"), std::string::npos)
      << error;
  EXPECT_NE(error.find(db + ".lock"), std::string::npos) << error;
}

TEST_F(MasterTest, ASecondMasterOnAStoreInUseIsRefused) {
  TestRun run;
  run.seed = 21;
  run.generations = 3;
  const std::string config = WriteConfig("run.txtpb", run);
  const std::string db = Path("run.db");
  // Without workers yet, the first master waits with its candidates out.
  std::unique_ptr<ChildProcess> first = StartRun(config, db);
  ASSERT_TRUE(AwaitStore(
      db, [](const Progress& p) { return p.individuals >= 1024; }, *first))
      << first->Describe() << "\n"
      << first->output();
  const std::string contents_before = RowText(ReadStoreContents(db).runs.at(0));

  // The same command again, a resume, and animat evolve, on the same
  // endpoint: all refused before they touch the store or the socket.
  std::unique_ptr<ChildProcess> again = StartRun(config, db);
  ExpectRefusedForTheLock(*again, db);
  std::unique_ptr<ChildProcess> resume = Resume(db);
  ExpectRefusedForTheLock(*resume, db);
  std::unique_ptr<ChildProcess> evolve =
      StartAnimat({"evolve", "--db", db, "--workers", "1"});
  ExpectRefusedForTheLock(*evolve, db);

  // The first is unaffected: workers join it and it finishes the run.
  ASSERT_TRUE(first->Running()) << first->Describe() << "\n" << first->output();
  EXPECT_EQ(RowText(ReadStoreContents(db).runs.at(0)), contents_before);
  std::vector<std::unique_ptr<WorkerProcess>> workers = StartWorkers(2);
  ASSERT_TRUE(AwaitExit(*first, kRunWait, "the first master"));
  EXPECT_EQ(first->exit_code(), 0) << first->output();
  const Progress done = ReadProgress(db);
  EXPECT_TRUE(done.finished) << done.ToString();
  EXPECT_EQ(done.complete_generations, run.generations);

  // Its exit released the lock: a resume now opens the store (and finds
  // nothing left to do).
  std::unique_ptr<ChildProcess> later = Resume(db);
  ASSERT_TRUE(AwaitExit(*later, kStepWait, "a resume of a finished run"));
  EXPECT_EQ(later->exit_code(), 0) << later->output();
  EXPECT_NE(later->output().find("finished"), std::string::npos)
      << later->output();
}

}  // namespace
}  // namespace animat::testing
