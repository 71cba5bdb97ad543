// The run loop with null-evaluation workers: their results are never
// recorded as evaluations, and a run served through the benchmark's
// scoring (bench/null_scoring.h) goes through every generation with each
// stand-in fitness recorded as the individual's own.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>
#include <zmq.hpp>

#include "bench/null_scoring.h"
#include "master/dispatch/dispatcher.h"
#include "master/lineage/store.h"
#include "master/run/evolution_run.h"
#include "tests/dispatch/worker_process.h"

namespace animat {
namespace {

using bench::NullEvaluationFitness;
using bench::NullScoring;
using testing::WorkerArgs;
using testing::WorkerProcess;

// Sets `stop` after `limit` unless destroyed first, so a run that never
// ends fails the test instead of hanging it.
class Watchdog {
 public:
  Watchdog(std::atomic<bool>* stop, std::chrono::seconds limit)
      : thread_([this, stop, limit] {
          std::unique_lock<std::mutex> lock(mutex_);
          if (!done_.wait_for(lock, limit, [this] { return over_; })) {
            stop->store(true);
          }
        }) {}
  ~Watchdog() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      over_ = true;
    }
    done_.notify_one();
    thread_.join();
  }

 private:
  std::mutex mutex_;
  std::condition_variable done_;
  bool over_ = false;
  std::thread thread_;
};

class NullEvaluationRunTest : public ::testing::Test {
 protected:
  void SetUp() override {
    Result<std::unique_ptr<lineage::Store>> store = lineage::Store::Open("");
    ASSERT_TRUE(store.ok()) << store.status().ToString();
    store_ = std::move(store).value();
    settings_.evolution.seed = 77;
    settings_.evolution.population = 6;
    settings_.evolution.generations = 3;
    settings_.evolution.elite = 1;
    Result<std::unique_ptr<EvolutionRun>> run =
        EvolutionRun::Start(store_.get(), settings_, [](std::string_view) {});
    ASSERT_TRUE(run.ok()) << run.status().ToString();
    run_ = std::move(run).value();
    DispatcherOptions options;
    options.endpoint = "tcp://127.0.0.1:*";
    options.heartbeat_ms = 100;
    options.accept_null_workers = true;
    options.log = [](std::string_view) {};
    Result<std::unique_ptr<Dispatcher>> dispatcher = Dispatcher::Create(
        &context_, options, ConfigToProto(run_->model_config()));
    ASSERT_TRUE(dispatcher.ok()) << dispatcher.status().ToString();
    dispatcher_ = std::move(dispatcher).value();
    WorkerArgs args;
    args.endpoint = dispatcher_->endpoint();
    args.threads = 4;
    args.null_evaluation = true;
    worker_ = std::make_unique<WorkerProcess>(args);
    ASSERT_TRUE(worker_->started());
  }

  // Serves the run with `evaluators` (by default the dispatcher itself).
  Status RunToEnd(EvaluationService* evaluators = nullptr) {
    std::atomic<bool> stop{false};
    Watchdog watchdog(&stop, std::chrono::seconds(60));
    Status status =
        run_->Run(evaluators != nullptr ? evaluators : dispatcher_.get(), stop);
    EXPECT_FALSE(stop.load()) << "the run did not end within 60 s";
    return status;
  }

  zmq::context_t context_{1};
  RunSettings settings_;
  std::unique_ptr<lineage::Store> store_;
  std::unique_ptr<EvolutionRun> run_;
  std::unique_ptr<Dispatcher> dispatcher_;
  std::unique_ptr<WorkerProcess> worker_;
};

TEST_F(NullEvaluationRunTest, NullResultsStopTheRunUnrecorded) {
  const Status status = RunToEnd();
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.message().find("null-evaluation worker"), std::string::npos)
      << status.ToString();
  EXPECT_FALSE(run_->finished());
  Result<std::vector<lineage::Score>> candidates =
      store_->ScoresOf(run_->run_id(), 0);
  ASSERT_TRUE(candidates.ok()) << candidates.status().ToString();
  EXPECT_EQ(candidates->size(), 2u * kCandidateBlock);  // Made and sent.
  for (const lineage::Score& s : *candidates) {
    EXPECT_FALSE(s.evaluated) << "individual " << s.id;
  }
  Result<std::optional<lineage::GenerationRow>> latest =
      store_->LatestGeneration(run_->run_id());
  ASSERT_TRUE(latest.ok());
  EXPECT_FALSE(latest->has_value());
}

TEST_F(NullEvaluationRunTest, ScoredNullResultsCompleteEveryGeneration) {
  NullScoring scoring(dispatcher_.get(), settings_.evolution.seed);
  const Status status = RunToEnd(&scoring);
  ASSERT_TRUE(status.ok()) << status.ToString();
  EXPECT_TRUE(run_->finished());
  const int64_t run = run_->run_id();
  for (int g = 0; g < settings_.evolution.generations; ++g) {
    Result<lineage::GenerationRow> generation = store_->Generation(run, g);
    ASSERT_TRUE(generation.ok()) << generation.status().ToString();
    EXPECT_TRUE(generation->complete) << "generation " << g;
    EXPECT_EQ(generation->members.size(), 6u) << "generation " << g;
    Result<std::vector<lineage::IndividualRow>> made =
        store_->IndividualsOf(run, g);
    ASSERT_TRUE(made.ok()) << made.status().ToString();
    // Generation 0: every candidate made; later ones: the offspring.
    EXPECT_EQ(made->size(), g == 0 ? 2u * kCandidateBlock : 5u);
    for (const lineage::IndividualRow& row : *made) {
      EXPECT_EQ(row.parents.empty(), g == 0) << "individual " << row.id;
      // A candidate not chosen may still be on its way when the run ends.
      if (g == 0 && !row.evaluated) continue;
      EXPECT_EQ(row.status, "ok") << "individual " << row.id;
      ASSERT_TRUE(row.fitness.has_value()) << "individual " << row.id;
      EXPECT_EQ(*row.fitness, NullEvaluationFitness(77, row.id))
          << "individual " << row.id;
    }
    Result<std::vector<lineage::Score>> members = store_->MemberScores(run, g);
    ASSERT_TRUE(members.ok()) << members.status().ToString();
    for (const lineage::Score& s : *members) {
      EXPECT_TRUE(s.evaluated) << "individual " << s.id;
    }
  }
  // The initial population: the first candidates, every stand-in fitness
  // being above the threshold.
  Result<lineage::GenerationRow> first = store_->Generation(run, 0);
  ASSERT_TRUE(first.ok());
  std::vector<uint64_t> members = first->members;
  std::sort(members.begin(), members.end());
  EXPECT_EQ(members, (std::vector<uint64_t>{0, 1, 2, 3, 4, 5}));
}

TEST(NullEvaluationFitnessTest, LiesInTheUnitIntervalAndDependsOnSeedAndId) {
  for (uint64_t id = 0; id < 1000; ++id) {
    const double f = NullEvaluationFitness(5, id);
    EXPECT_GE(f, 0.0);
    EXPECT_LT(f, 1.0);
  }
  EXPECT_NE(NullEvaluationFitness(5, 1), NullEvaluationFitness(6, 1));
  EXPECT_NE(NullEvaluationFitness(5, 1), NullEvaluationFitness(5, 2));
}

}  // namespace
}  // namespace animat
