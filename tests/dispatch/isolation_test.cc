// A suspect evaluated alone (master/dispatch/isolation.h with the child
// processes of master/run/child_isolation.h): after kMaxAttempts leases
// ended without a result, a genome is recorded as crashed only when its
// evaluation alone crashes too; an evaluation alone that decides nothing,
// or no isolation at all, leaves it to the workers, for as long as it
// takes. And the child's side, animat-worker --evaluate-one.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "animat/v1/isolation.pb.h"
#include "tests/dispatch/dispatch_harness.h"
#include "tests/dispatch/fake_peers.h"
#include "worker/evaluate_one.h"

namespace animat::testing {
namespace {

class IsolationTest : public DispatchTest {
 protected:
  // A worker played by the test asks for one item, gets `id` (the queue
  // holds nothing else it could get) and vanishes with it; returns once
  // the dispatcher has found it silent.
  void VanishHolding(uint64_t id, uint64_t pid) {
    {
      FakeWorker fake(context_, dispatcher_->endpoint(), clock_);
      fake.Hello(1, pid);
      ASSERT_TRUE(Serve([&] { return fake.welcomed(); }, kShortWait,
                        [&] { fake.Pump(); }));
      fake.Credit(1);
      ASSERT_TRUE(Serve([&] { return !fake.work_items().empty(); }, kShortWait,
                        [&] { fake.Pump(); }));
      ASSERT_EQ(fake.work_items()[0].individual(), id);
    }
    ASSERT_TRUE(Serve(
        [&] {
          return log_.Count({"worker fake-worker:" + std::to_string(pid) +
                             " silent"}) == 1;
        },
        kShortWait));
  }

  // A worker that answers everything it gets, until all is done.
  void AnswerTheRest(uint64_t pid) {
    FakeWorker worker(context_, dispatcher_->endpoint(), clock_);
    worker.Hello(1, pid);
    worker.Credit(2);
    size_t answered = 0;
    ASSERT_TRUE(ServeUntilAllDone(kLongWait, [&] {
      Answer(worker, &answered);
      LetChildrenRun();
    })) << log_.Dump();
  }
};

TEST_F(IsolationTest, SuspectThatCrashesAloneTooIsRecordedAsCrashed) {
  // A genome of this simulator never crashes its process; a child that
  // dies of SIGSEGV is what such a genome would make of its evaluation.
  const Individual suspect = Population({DataGenome("seed-139")}, 20)[0];
  ASSERT_TRUE(StartDispatcher(
      WithIsolation(SimulatedOptions(), {"/bin/sh", "-c", "kill -SEGV $$"})));
  Submit({suspect});
  for (int round = 1; round <= protocol::kMaxAttempts; ++round) {
    SCOPED_TRACE("round " + std::to_string(round));
    VanishHolding(suspect.id, 8100 + round);
  }
  ASSERT_TRUE(Serve([&] { return CompletionsOf(suspect.id) == 1; }, kLongWait,
                    LetChildrenRun))
      << log_.Dump();
  const Completion& crashed = completions_[0];
  EXPECT_EQ(crashed.result.status(), v1::EvaluationResult::CRASHED);
  EXPECT_NE(crashed.result.reason().find("signal Segmentation fault"),
            std::string::npos)
      << crashed.result.reason();
  EXPECT_NE(crashed.result.reason().find("after 3 leases"), std::string::npos)
      << crashed.result.reason();
  EXPECT_FALSE(crashed.result.has_fitness());
  EXPECT_TRUE(protocol::ValidateResult(crashed.result).ok());
  EXPECT_EQ(crashed.attempts, 3);
  EXPECT_NE(crashed.worker.find("(isolated)"), std::string::npos);
  EXPECT_EQ(dispatcher_->stats().crashed, 1);
  EXPECT_EQ(log_.Count({"individual 20 crashed alone too"}), 1) << log_.Dump();
  EXPECT_EQ(dispatcher_->pending(), 0u);
}

TEST_F(IsolationTest, EvaluationAloneThatDecidesNothingLeavesItToWorkers) {
  // A child that exits 1 without a result: neither a result nor a crash.
  const Individual suspect = Population({DataGenome("seed-1198")}, 30)[0];
  ASSERT_TRUE(
      StartDispatcher(WithIsolation(SimulatedOptions(), {"/bin/false"})));
  Submit({suspect});
  for (int round = 1; round <= protocol::kMaxAttempts; ++round) {
    SCOPED_TRACE("round " + std::to_string(round));
    VanishHolding(suspect.id, 8200 + round);
  }
  ASSERT_TRUE(Serve(
      [&] {
        return log_.Count({"the evaluation of individual 30 alone decided "
                           "nothing (exit code 1)"}) == 1;
      },
      kLongWait, LetChildrenRun))
      << log_.Dump();
  EXPECT_EQ(CompletionsOf(suspect.id), 0);
  // A fourth worker vanishes too: alone again, nothing decided again.
  VanishHolding(suspect.id, 8204);
  ASSERT_TRUE(Serve(
      [&] {
        return log_.Count({"the evaluation of individual 30 alone"}) == 2;
      },
      kLongWait, LetChildrenRun));
  EXPECT_EQ(dispatcher_->stats().isolated, 2);
  // A worker that answers gets it at last.
  AnswerTheRest(8299);
  ASSERT_EQ(CompletionsOf(suspect.id), 1);
  ExpectSameResult(completions_[0].result, suspect.expected, suspect.id);
  EXPECT_EQ(completions_[0].attempts, 4);
  EXPECT_EQ(completions_[0].worker, "fake-worker:8299");
}

TEST_F(IsolationTest, WithoutAnIsolationASuspectIsRetriedOnWorkersForEver) {
  const Individual suspect = Population({DataGenome("seed-1203")}, 40)[0];
  ASSERT_TRUE(StartDispatcher(SimulatedOptions()));
  Submit({suspect});
  for (int round = 1; round <= protocol::kMaxAttempts + 2; ++round) {
    SCOPED_TRACE("round " + std::to_string(round));
    VanishHolding(suspect.id, 8300 + round);
  }
  EXPECT_EQ(CompletionsOf(suspect.id), 0);
  EXPECT_EQ(log_.Count({"individual 40: ",
                        "retried on workers (no isolation "
                        "here)"}),
            3)
      << log_.Dump();
  AnswerTheRest(8399);
  ASSERT_EQ(CompletionsOf(suspect.id), 1);
  ExpectSameResult(completions_[0].result, suspect.expected, suspect.id);
  EXPECT_EQ(completions_[0].attempts, protocol::kMaxAttempts + 2);
}

// The worker whose leases expired answers after all, while the genome is
// being evaluated alone: the first result wins and the child is stopped.
TEST_F(IsolationTest, LateResultFromAWorkerCompletesASuspectBeingIsolated) {
  const Individual stuck = Population({DataGenome("seed-139")}, 50)[0];
  DispatcherOptions options = SimulatedOptions();
  options.lease_ms = 200;
  // A child that takes its time.
  ASSERT_TRUE(StartDispatcher(
      WithIsolation(options, {"/bin/sh", "-c", "exec sleep 60"})));
  Submit({stuck});
  FakeWorker fake(context_, dispatcher_->endpoint(), clock_);
  auto pump = [&] { fake.Pump(); };
  fake.Hello(1, 8400);
  ASSERT_TRUE(Serve([&] { return fake.welcomed(); }, kShortWait, pump));
  for (int lease = 1; lease <= protocol::kMaxAttempts; ++lease) {
    fake.Credit(1);
    ASSERT_TRUE(Serve(
        [&] {
          return log_.Count({"lease of individual 50", "expired"}) == lease;
        },
        kShortWait, pump));
  }
  ASSERT_EQ(isolation_->running(), 1u);
  v1::Envelope results;
  v1::WorkResult* r = results.mutable_results()->add_results();
  r->set_individual(stuck.id);
  r->set_genome_hash(protocol::GenomeHash(stuck.genome));
  *r->mutable_result() = stuck.expected;
  fake.Send(results);
  ASSERT_TRUE(
      Serve([&] { return CompletionsOf(stuck.id) == 1; }, kShortWait, pump));
  ExpectSameResult(completions_[0].result, stuck.expected, stuck.id);
  EXPECT_EQ(completions_[0].worker, "fake-worker:8400");
  EXPECT_EQ(isolation_->running(), 0u);
  ServeFor(milliseconds(50), pump);
  EXPECT_EQ(CompletionsOf(stuck.id), 1);
}

// animat-worker --evaluate-one, called as the child would call it.
class EvaluateOneTest : public DispatchTest {
 protected:
  void SetUp() override {
    dir_ = ::testing::TempDir() + "/evaluate-one-" + std::to_string(getpid());
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override {
    std::filesystem::remove_all(dir_);
    DispatchTest::TearDown();
  }
  v1::IsolatedEvaluation Request(const v1::Genome& genome) const {
    v1::IsolatedEvaluation request;
    request.set_build_id(protocol::BuildId());
    *request.mutable_config() = ConfigToProto(config_);
    request.set_config_hash(protocol::ConfigHash(request.config()));
    request.mutable_item()->set_individual(7);
    *request.mutable_item()->mutable_genome() = genome;
    request.mutable_item()->set_genome_hash(protocol::GenomeHash(genome));
    return request;
  }
  // Writes `request`, evaluates it; the exit code and the lines logged.
  int Run(const v1::IsolatedEvaluation& request, std::string* logged) {
    std::ofstream(dir_ + "/request", std::ios::binary)
        << request.SerializeAsString();
    return EvaluateOne(
        dir_ + "/request", dir_ + "/result",
        [&](std::string_view line) { *logged += std::string(line) + "\n"; });
  }
  std::string dir_;
};

TEST_F(EvaluateOneTest, WritesTheResultOfADirectEvaluation) {
  const v1::Genome genome = DataGenome("seed-1198");
  std::string logged;
  ASSERT_EQ(Run(Request(genome), &logged), kEvaluatedOne) << logged;
  v1::WorkResult result;
  std::ifstream in(dir_ + "/result", std::ios::binary);
  ASSERT_TRUE(result.ParseFromIstream(&in));
  EXPECT_EQ(result.individual(), 7u);
  EXPECT_EQ(result.genome_hash(), protocol::GenomeHash(genome));
  ExpectSameResult(result.result(), DirectResult(genome, config_), 7);
  EXPECT_TRUE(protocol::CheckWorkResult(result).ok());
}

TEST_F(EvaluateOneTest, RefusesARequestItCannotTrust) {
  const v1::Genome genome = DataGenome("seed-1198");
  v1::IsolatedEvaluation other_build = Request(genome);
  other_build.set_build_id("animat 0.0.0 elsewhere");
  v1::IsolatedEvaluation wrong_hash = Request(genome);
  wrong_hash.set_config_hash(wrong_hash.config_hash() + 1);
  for (const auto& [request, says] :
       std::vector<std::pair<v1::IsolatedEvaluation, std::string>>{
           {other_build, "made by build \"animat 0.0.0 elsewhere\""},
           {wrong_hash, "hash differs"}}) {
    std::string logged;
    EXPECT_EQ(Run(request, &logged), kCannotEvaluateOne);
    EXPECT_NE(logged.find(says), std::string::npos) << logged;
    EXPECT_FALSE(std::filesystem::exists(dir_ + "/result"));
  }
  std::string logged;
  EXPECT_EQ(EvaluateOne(dir_ + "/missing", dir_ + "/result",
                        [&](std::string_view line) { logged += line; }),
            kCannotEvaluateOne);
  EXPECT_NE(logged.find("not an animat.v1.IsolatedEvaluation"),
            std::string::npos)
      << logged;
}

}  // namespace
}  // namespace animat::testing
