// Issue 14's fault case: three peers in a row take the same individual and
// vanish with it. A vanished worker is no evidence against a genome, so
// the master evaluates that genome alone, in a child process, and records
// its true result: the store equals an undisturbed run's.
#include <chrono>
#include <memory>
#include <string>
#include <thread>
#include <zmq.hpp>

#include "tests/dispatch/fake_peers.h"
#include "tests/master/master_harness.h"

namespace animat::testing {
namespace {

// Pumps `peer` every 10 ms until `done` holds or `timeout` passes.
bool PumpUntil(FakeWorker& peer, const std::function<bool()>& done,
               milliseconds timeout = kStepWait) {
  const auto end = Clock::now() + timeout;
  while (!done()) {
    if (Clock::now() >= end) return false;
    peer.Pump();
    std::this_thread::sleep_for(milliseconds(10));
  }
  return true;
}

TEST_F(MasterTest, ThreeVanishedPeersHoldingOneIndividualLeaveTheStoreAsIs) {
  TestRun run;
  run.seed = 5;
  const std::string config = WriteConfig("run.txtpb", run);
  const std::string reference_db = Path("reference.db");
  RunToEnd(config, reference_db, /*workers=*/1);
  if (HasFatalFailure()) return;

  const std::string db = Path("vanished.db");
  std::unique_ptr<ChildProcess> master = StartRun(config, db);
  zmq::context_t context(1);
  uint64_t held = 0;
  for (int peer = 1; peer <= 3; ++peer) {
    SCOPED_TRACE("peer " + std::to_string(peer));
    const uint64_t pid = 91000 + peer;
    {
      // Any local process can play a worker; this one takes one item and
      // is gone.
      FakeWorker fake(context, Endpoint());
      fake.Hello(1, pid);
      ASSERT_TRUE(PumpUntil(fake, [&] { return fake.welcomed(); }))
          << master->output();
      fake.Credit(1);
      ASSERT_TRUE(PumpUntil(fake, [&] { return !fake.work_items().empty(); }))
          << master->output();
      ASSERT_EQ(fake.work_items().size(), 1u);
      if (peer == 1) held = fake.work_items()[0].individual();
      EXPECT_EQ(fake.work_items()[0].individual(), held);
    }
    ASSERT_TRUE(AwaitOutput(
        *master, "worker fake-worker:" + std::to_string(pid) + " silent"))
        << master->output();
  }
  const std::string which = "individual " + std::to_string(held);
  ASSERT_TRUE(AwaitOutput(*master, which + " evaluated alone: "))
      << master->output();
  EXPECT_NE(master->output().find(which + ": 3 leases ended without a result"),
            std::string::npos)
      << master->output();

  // A real worker does the rest.
  const auto workers = StartWorkers(1);
  ASSERT_TRUE(AwaitExit(*master, kRunWait, "the run after the vanishings"));
  ASSERT_EQ(master->exit_code(), 0) << master->output();
  ASSERT_TRUE(ReadProgress(db).finished) << ReadProgress(db).ToString();

  ExpectSameContents(ReadStoreContents(reference_db), ReadStoreContents(db));
  const std::string evaluator = QueryCell(
      db, "SELECT worker FROM individuals WHERE id = " + std::to_string(held));
  EXPECT_NE(evaluator.find("(isolated)"), std::string::npos) << evaluator;
}

}  // namespace
}  // namespace animat::testing
