// The ends of a run as workers see them: a dispatcher without workers says
// so periodically, with its endpoint (on simulated time); its farewell
// reaches every connected worker; a real worker with --exit-when-done then
// exits 0, one without it waits for a next master, and one with
// --idle-timeout exits 0 when no master comes.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/dispatch/dispatch_harness.h"
#include "tests/dispatch/fake_peers.h"
#include "tests/dispatch/worker_process.h"

namespace animat::testing {
namespace {

TEST_F(DispatchTest, WithoutWorkersTheDispatcherSaysSoPeriodically) {
  DispatcherOptions options = SimulatedOptions();
  options.idle_notice_ms = 1000;
  ASSERT_TRUE(StartDispatcher(options));
  Submit(Population({DataGenome("seed-1198")}, 7));
  const std::string endpoint = dispatcher_->endpoint();
  const auto notices = [&](const std::string& what) {
    return log_.Count(
        {what, "; listening on " + endpoint, "(1 individuals waiting)"});
  };
  AdvanceAndPoll(milliseconds(999));
  EXPECT_EQ(notices("no worker"), 0) << log_.Dump();
  AdvanceAndPoll(milliseconds(1));
  EXPECT_EQ(notices("no worker has joined in 1 s"), 1) << log_.Dump();
  AdvanceAndPoll(milliseconds(999));
  EXPECT_EQ(notices("no worker"), 1) << log_.Dump();
  AdvanceAndPoll(milliseconds(1));
  EXPECT_EQ(notices("no worker has joined in 2 s"), 1) << log_.Dump();

  // A worker: no notice while it is there.
  FakeWorker fake(context_, endpoint, clock_);
  fake.Hello(1, 4242);
  ASSERT_TRUE(
      Serve([&] { return fake.welcomed(); }, kShortWait, [&] { fake.Pump(); }));
  ServeFor(milliseconds(3000), [&] { fake.Pump(); });
  EXPECT_EQ(notices("no worker"), 2) << log_.Dump();

  // Gone: the count starts again from its leaving.
  v1::Envelope goodbye;
  goodbye.mutable_goodbye()->set_reason("test");
  fake.Send(goodbye);
  ASSERT_TRUE(Serve([&] { return dispatcher_->workers() == 0; }, kShortWait));
  ServeFor(milliseconds(995));
  EXPECT_EQ(notices("no worker"), 2) << log_.Dump();
  ServeFor(milliseconds(10));
  EXPECT_EQ(notices("no worker connected for 1 s"), 1) << log_.Dump();
}

TEST_F(DispatchTest, NoticesGoWhereTheOptionsSay) {
  DispatcherOptions options = SimulatedOptions();
  options.idle_notice_ms = 1000;
  LogLines notices;
  options.notices = notices.Sink();
  ASSERT_TRUE(StartDispatcher(options));
  AdvanceAndPoll(milliseconds(1000));
  EXPECT_EQ(notices.Count({"no worker has joined in 1 s"}), 1)
      << notices.Dump();
  EXPECT_EQ(log_.Count({"no worker"}), 0) << log_.Dump();

  options = SimulatedOptions();
  options.idle_notice_ms = 0;  // Never.
  dispatcher_.reset();
  ASSERT_TRUE(StartDispatcher(options));
  AdvanceAndPoll(milliseconds(100000));
  EXPECT_EQ(log_.Count({"no worker"}), 0) << log_.Dump();
}

TEST_F(DispatchTest, TheFarewellReachesEveryConnectedWorker) {
  ASSERT_TRUE(StartDispatcher(SimulatedOptions()));
  FakeWorker first(context_, dispatcher_->endpoint(), clock_);
  FakeWorker second(context_, dispatcher_->endpoint(), clock_);
  const auto pump = [&] {
    first.Pump();
    second.Pump();
  };
  first.Hello(1, 1001);
  second.Hello(1, 1002);
  ASSERT_TRUE(Serve([&] { return first.welcomed() && second.welcomed(); },
                    kShortWait, pump));
  dispatcher_->Farewell("the run is finished");
  const auto said_goodbye = [](const FakeWorker& fake) {
    for (const v1::Envelope& e : fake.received()) {
      if (e.has_goodbye()) {
        return e.goodbye().reason() == "the run is finished" &&
               e.goodbye().returned_size() == 0;
      }
    }
    return false;
  };
  ASSERT_TRUE(Serve([&] { return said_goodbye(first) && said_goodbye(second); },
                    kShortWait, pump));
}

TEST_F(DispatchTest, AWorkerThatExitsWhenDoneExitsAtTheFarewell) {
  ASSERT_TRUE(StartDispatcher());
  WorkerArgs args = Worker(1);
  args.exit_when_done = true;
  WorkerProcess leaving(args);
  WorkerProcess staying(Worker(1));
  ASSERT_TRUE(Serve([&] { return dispatcher_->workers() == 2; }, kShortWait));
  dispatcher_->Farewell("the run is finished");
  dispatcher_.reset();  // The farewell is delivered as the socket closes.
  ASSERT_TRUE(leaving.WaitExit(kShortWait)) << leaving.output();
  EXPECT_EQ(leaving.exit_code(), 0) << leaving.Describe();
  EXPECT_NE(leaving.output().find("the master's run is over (the run is "
                                  "finished)"),
            std::string::npos)
      << leaving.output();
  EXPECT_NE(leaving.output().find("exiting (--exit-when-done)"),
            std::string::npos)
      << leaving.output();
  // Without the flag it waits for a next master (ChildProcess fails the
  // test if it exits by itself).
  for (int i = 0;
       i < 1000 && staying.output().find("waiting for a next "
                                         "master") == std::string::npos;
       ++i) {
    std::this_thread::sleep_for(milliseconds(10));
  }
  EXPECT_NE(staying.output().find("the master's run is over; waiting for a "
                                  "next master"),
            std::string::npos)
      << staying.output();
  EXPECT_TRUE(staying.Running());
}

TEST(WorkerIdleTimeoutTest, AWorkerWithoutAMasterExitsAfterItsIdleTimeout) {
  WorkerArgs args;
  args.endpoint = "ipc://" + ::testing::TempDir() + "/no-master-" +
                  std::to_string(getpid()) + ".ipc";
  std::vector<std::string> argv = WorkerArgv(args);
  argv.insert(argv.end(), {"--idle-timeout", "1"});
  ChildProcess idle("animat-worker", argv,
                    ChildProcess::Lifetime::kExitsByItself);
  ASSERT_TRUE(idle.WaitExit(kShortWait)) << idle.output();
  EXPECT_EQ(idle.exit_code(), 0) << idle.Describe();
  EXPECT_NE(idle.output().find("no master for 1 s; exiting (--idle-timeout)"),
            std::string::npos)
      << idle.output();
}

}  // namespace
}  // namespace animat::testing
