// The child processes that evaluate a suspect alone
// (master/run/child_isolation.h), with real children (/bin/sh and small
// scripts standing in for an evaluation that ends each way): only a crash
// signal is a crash; another signal, another exit code, no result, or a
// child past its time limit decide nothing; a child's request holds the
// work item, and a cancelled child is gone.
#include "master/run/child_isolation.h"

#include <unistd.h>

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "animat/v1/isolation.pb.h"
#include "common/base/clock.h"
#include "common/protocol/protocol.h"

namespace animat {
namespace {

using Kind = IsolatedOutcome::Kind;

// A serialised work item for individual `id`.
std::string Item(uint64_t id) {
  v1::WorkItem item;
  item.set_individual(id);
  item.set_genome_hash(0xabcdef);
  return item.SerializeAsString();
}

std::unique_ptr<ChildIsolation> Make(const std::string& script,
                                     const Clock* clock = &RealClock(),
                                     int time_limit_ms = 60000) {
  Result<std::unique_ptr<ChildIsolation>> made =
      ChildIsolation::Create({{"/bin/sh", "-c", script}, time_limit_ms, clock});
  EXPECT_TRUE(made.ok()) << made.status().ToString();
  return made.ok() ? std::move(made).value() : nullptr;
}

// The outcomes of the children started, once all have ended (they are
// real processes: waited for, a millisecond at a time).
std::vector<IsolatedOutcome> AwaitAll(ChildIsolation& isolation) {
  std::vector<IsolatedOutcome> all;
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (isolation.running() > 0 && std::chrono::steady_clock::now() < end) {
    for (IsolatedOutcome& o : isolation.Finished()) all.push_back(std::move(o));
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  EXPECT_EQ(isolation.running(), 0u);
  return all;
}

TEST(ChildIsolationTest, OnlyACrashSignalIsACrash) {
  const std::vector<std::pair<std::string, std::string>> endings = {
      {"kill -SEGV $$", "signal Segmentation fault"},
      {"kill -ABRT $$", "signal Aborted"},
      {"kill -FPE $$", "signal Floating point exception"},
      {"kill -KILL $$", "signal Killed"},
      {"kill -TERM $$", "signal Terminated"},
      {"exit 2", "exit code 2"},
      {"exit 0", "exit code 0 without a readable result"},
  };
  for (const auto& [script, how] : endings) {
    SCOPED_TRACE(script);
    std::unique_ptr<ChildIsolation> isolation = Make(script);
    ASSERT_NE(isolation, nullptr);
    ASSERT_TRUE(isolation->Start(7, Item(7), v1::Config(), 1).ok());
    const std::vector<IsolatedOutcome> outcomes = AwaitAll(*isolation);
    ASSERT_EQ(outcomes.size(), 1u);
    const IsolatedOutcome& o = outcomes[0];
    EXPECT_EQ(o.individual, 7u);
    EXPECT_EQ(o.how, how);
    const bool crash = how == "signal Segmentation fault" ||
                       how == "signal Aborted" ||
                       how == "signal Floating point exception";
    EXPECT_EQ(o.kind, crash ? Kind::kCrashed : Kind::kUndecided);
    EXPECT_NE(o.evaluator.find("(isolated)"), std::string::npos) << o.evaluator;
  }
}

// The child finds its request where its command line says, and what it
// writes where the command line says is the result.
TEST(ChildIsolationTest, AChildReadsItsRequestAndItsResultIsRead) {
  const std::string copy =
      ::testing::TempDir() + "/isolation-request-" + std::to_string(getpid());
  // The script's arguments: $0 = --evaluate-one, $1 = REQUEST,
  // $2 = --result, $3 = RESULT. It keeps a copy of the request and
  // answers with a WorkResult of individual 42 and genome hash
  // 0x0807060504030201 (fields 1 and 2), byte by byte.
  std::unique_ptr<ChildIsolation> isolation = Make(
      "test \"$0\" = --evaluate-one && test \"$2\" = --result && "
      "cp \"$1\" " +
      copy +
      " && printf '\\010\\052\\021\\001\\002"
      "\\003\\004\\005\\006\\007\\010' > \"$3\"");
  ASSERT_NE(isolation, nullptr);
  v1::Config config;
  config.mutable_evaluation()->set_motion_steps(123);
  ASSERT_TRUE(isolation->Start(42, Item(42), config, 99).ok());
  const std::vector<IsolatedOutcome> outcomes = AwaitAll(*isolation);
  ASSERT_EQ(outcomes.size(), 1u);
  EXPECT_EQ(outcomes[0].kind, Kind::kResult) << outcomes[0].how;
  EXPECT_EQ(outcomes[0].result.individual(), 42u);
  EXPECT_EQ(outcomes[0].result.genome_hash(), 0x0807060504030201u);

  v1::IsolatedEvaluation request;
  std::ifstream in(copy, std::ios::binary);
  ASSERT_TRUE(request.ParseFromIstream(&in));
  EXPECT_EQ(request.build_id(), protocol::BuildId());
  EXPECT_EQ(request.config().evaluation().motion_steps(), 123);
  EXPECT_EQ(request.config_hash(), 99u);
  EXPECT_EQ(request.item().SerializeAsString(), Item(42));
  std::remove(copy.c_str());
}

TEST(ChildIsolationTest, AChildPastItsTimeLimitIsStoppedAndDecidesNothing) {
  ManualClock clock;
  std::unique_ptr<ChildIsolation> isolation =
      Make("exec sleep 60", &clock, /*time_limit_ms=*/1000);
  ASSERT_NE(isolation, nullptr);
  ASSERT_TRUE(isolation->Start(3, Item(3), v1::Config(), 1).ok());
  clock.Advance(std::chrono::milliseconds(1000));
  EXPECT_TRUE(isolation->Finished().empty());  // At the limit, not past.
  EXPECT_EQ(isolation->running(), 1u);
  clock.Advance(std::chrono::milliseconds(1));
  const std::vector<IsolatedOutcome> outcomes = isolation->Finished();
  ASSERT_EQ(outcomes.size(), 1u);
  EXPECT_EQ(outcomes[0].kind, Kind::kUndecided);
  EXPECT_EQ(outcomes[0].how, "still running after 1000 ms; stopped");
  EXPECT_EQ(isolation->running(), 0u);
}

TEST(ChildIsolationTest, ACancelledChildIsGoneAndNotReported) {
  std::unique_ptr<ChildIsolation> isolation = Make("exec sleep 60");
  ASSERT_NE(isolation, nullptr);
  ASSERT_TRUE(isolation->Start(5, Item(5), v1::Config(), 1).ok());
  ASSERT_TRUE(isolation->Start(6, Item(6), v1::Config(), 1).ok());
  EXPECT_EQ(isolation->running(), 2u);
  isolation->Cancel(5);
  EXPECT_EQ(isolation->running(), 1u);
  EXPECT_TRUE(isolation->Finished().empty());
}

TEST(ChildIsolationTest, AProgramThatCannotStartIsAnError) {
  Result<std::unique_ptr<ChildIsolation>> isolation = ChildIsolation::Create(
      {{"/nonexistent/animat-worker"}, 1000, &RealClock()});
  ASSERT_TRUE(isolation.ok());
  const Status started = (*isolation)->Start(1, Item(1), v1::Config(), 1);
  EXPECT_FALSE(started.ok());
  EXPECT_NE(started.message().find("/nonexistent/animat-worker"),
            std::string::npos)
      << started.message();
  EXPECT_EQ((*isolation)->running(), 0u);
  EXPECT_FALSE(ChildIsolation::Create({{}, 1000, &RealClock()}).ok());
}

}  // namespace
}  // namespace animat
