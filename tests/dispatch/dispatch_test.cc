// Fault tolerance of the master-worker dispatch: with real sockets and real
// animat-worker processes, workers killed, frozen, terminated, joining
// late, and the master restarting; with workers played by the test, on
// simulated time, leases expiring, silent workers dropped, heartbeats, and
// a genome whose workers die with it (then evaluated alone:
// isolation_test.cc). Whatever happens, every individual completes
// exactly once, with the bits of a direct evaluation of its genome.
#include <algorithm>
#include <csignal>
#include <cstdio>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "tests/dispatch/dispatch_harness.h"
#include "tests/dispatch/fake_peers.h"
#include "tests/dispatch/worker_process.h"

namespace animat::testing {
namespace {

// `count` individuals cycling through the viable genomes: each runs the
// whole motion phase (some 50 ms with kSlowMotionSteps / 4 steps).
std::vector<v1::Genome> SlowGenomes(int count) {
  const std::vector<v1::Genome> viable = ViableGenomes();
  std::vector<v1::Genome> genomes;
  for (int i = 0; i < count; ++i) genomes.push_back(viable[i % viable.size()]);
  return genomes;
}

std::set<uint64_t> Ids(const std::vector<v1::WorkItem>& items) {
  std::set<uint64_t> ids;
  for (const v1::WorkItem& item : items) ids.insert(item.individual());
  return ids;
}

TEST_F(DispatchTest, EveryIndividualCompletesOnceAsEvaluatedDirectly) {
  const std::vector<Individual> population = Population(MixedGenomes(40), 1);
  ASSERT_TRUE(StartDispatcher(PatientOptions()));
  WorkerProcess a(PatientWorker(2));
  WorkerProcess b(PatientWorker(2));
  ASSERT_TRUE(a.started() && b.started());
  ASSERT_TRUE(Serve([&] { return dispatcher_->workers() == 2; }, kShortWait));
  ServeFor(milliseconds(300));  // Their credit arrives.
  Submit(population);
  ASSERT_TRUE(ServeUntilAllDone());

  ExpectEachCompletedOnceAsEvaluatedDirectly(population);
  EXPECT_EQ(CompletingWorkers(), (std::set<std::string>{a.name(), b.name()}));
  for (const Completion& c : completions_) EXPECT_FALSE(c.null_evaluation);
  const DispatcherStats& stats = dispatcher_->stats();
  EXPECT_EQ(stats.completed, 40);
  EXPECT_EQ(stats.dispatched, 40);  // Nothing sent twice.
  EXPECT_EQ(stats.requeued, 0);
  EXPECT_EQ(stats.isolated, 0);
  EXPECT_EQ(stats.ignored, 0);
  EXPECT_EQ(log_.Count({"joined"}), 2) << log_.Dump();
}

TEST_F(DispatchTest, KilledWorkersLeasesAreEvaluatedElsewhereExactlyOnce) {
  config_.evaluation.motion_steps = kSlowMotionSteps / 4;
  const std::vector<Individual> population = Population(SlowGenomes(6), 100);
  ASSERT_TRUE(StartDispatcher());
  Submit(population);
  WorkerProcess a(Worker(1));
  ASSERT_TRUE(a.started());
  // A has evaluated one and holds the next ones (one running, one queued).
  ASSERT_TRUE(Serve([&] { return !completions_.empty(); }, kLongWait));
  EXPECT_EQ(completions_.front().worker, a.name());
  ASSERT_TRUE(a.Signal(SIGKILL));
  WorkerProcess b(Worker(2));
  ASSERT_TRUE(a.WaitExit(kShortWait, [&] { ServeFor(milliseconds(10)); }));
  EXPECT_EQ(a.term_signal(), SIGKILL) << a.Describe();
  ASSERT_TRUE(ServeUntilAllDone());

  ExpectEachCompletedOnceAsEvaluatedDirectly(population);
  const std::string death =
      log_.Find({"worker " + a.name() + " silent for 300 ms"});
  ASSERT_FALSE(death.empty()) << log_.Dump();
  EXPECT_EQ(death.find("; 0 leases"), std::string::npos) << death;
  // What A held went back to the queue and was evaluated by B, one
  // attempt counted.
  int retried = 0;
  for (const Completion& c : completions_) {
    if (c.attempts == 0) continue;
    ++retried;
    EXPECT_EQ(c.attempts, 1) << "individual " << c.individual;
    EXPECT_EQ(c.worker, b.name()) << "individual " << c.individual;
  }
  EXPECT_GE(retried, 1);
  EXPECT_EQ(dispatcher_->stats().isolated, 0);
}

TEST_F(DispatchTest, WorkerJoiningLateGetsTheQueuedWork) {
  const std::vector<Individual> population = Population(MixedGenomes(12), 200);
  ASSERT_TRUE(StartDispatcher(PatientOptions()));
  Submit(population);
  ServeFor(milliseconds(500));
  EXPECT_TRUE(completions_.empty());
  EXPECT_EQ(dispatcher_->pending(), population.size());
  EXPECT_EQ(dispatcher_->stats().dispatched, 0);

  WorkerProcess late(PatientWorker(2));
  ASSERT_TRUE(late.started());
  ASSERT_TRUE(ServeUntilAllDone());
  ExpectEachCompletedOnceAsEvaluatedDirectly(population);
  EXPECT_EQ(CompletingWorkers(), std::set<std::string>{late.name()});
}

TEST_F(DispatchTest, FrozenWorkersLeasesExpireAndAreDoneElsewhereOnce) {
  config_.evaluation.motion_steps = kSlowMotionSteps / 4;
  const std::vector<Individual> population = Population(SlowGenomes(6), 300);
  const std::vector<Individual> afterwards = Population(MixedGenomes(8), 350);
  ASSERT_TRUE(StartDispatcher());
  Submit(population);
  WorkerProcess a(Worker(1));
  ASSERT_TRUE(a.started());
  ASSERT_TRUE(Serve([&] { return !completions_.empty(); }, kLongWait));
  ASSERT_TRUE(a.Signal(SIGSTOP));  // Mid-evaluation, holding leases.
  WorkerProcess b(Worker(2));
  ASSERT_TRUE(b.started());

  // Silent for 3 heartbeats: A is presumed dead, its leases go back. A
  // result A sent just before the freeze may still arrive and count (its
  // lease was live); none may after its death.
  ASSERT_TRUE(Serve(
      [&] { return !log_.Find({"worker " + a.name() + " silent"}).empty(); },
      kShortWait));
  const size_t completed_before_death = completions_.size();
  const std::string death = log_.Find({"worker " + a.name() + " silent"});
  EXPECT_EQ(death.find("; 0 leases"), std::string::npos) << death;
  ASSERT_TRUE(ServeUntilAllDone());

  // Thawed, A finishes what it was evaluating and answers on its old
  // session (ignored: that session is over), notices the master no longer
  // talks to it, and says hello again by itself.
  ASSERT_TRUE(a.Signal(SIGCONT));
  ASSERT_TRUE(
      Serve([&] { return log_.Count({"worker " + a.name() + " joined"}) == 2; },
            kShortWait))
      << log_.Dump();
  ServeFor(milliseconds(3 * kHeartbeatMs));
  EXPECT_TRUE(a.Running());
  ExpectEachCompletedOnceAsEvaluatedDirectly(population);
  for (size_t i = completed_before_death; i < completions_.size(); ++i) {
    EXPECT_EQ(completions_[i].worker, b.name())
        << "individual " << completions_[i].individual;
  }
  RecordProperty("ignored_after_thaw",
                 static_cast<int>(dispatcher_->stats().ignored));

  // A is a worker like any other again: with B gone, it does new work.
  ASSERT_TRUE(b.Signal(SIGTERM));
  ASSERT_TRUE(b.WaitExit(kShortWait, [&] { ServeFor(milliseconds(10)); }));
  EXPECT_EQ(b.exit_code(), 0) << b.Describe();
  completions_.clear();
  Submit(afterwards);
  ASSERT_TRUE(ServeUntilAllDone());
  ExpectEachCompletedOnceAsEvaluatedDirectly(afterwards);
  EXPECT_EQ(CompletingWorkers(), std::set<std::string>{a.name()});
}

TEST_F(DispatchTest, WorkersReconnectByThemselvesWhenTheMasterRestarts) {
  const std::vector<v1::Genome> genomes = MixedGenomes(24);
  const std::vector<Individual> first =
      Population({genomes.begin(), genomes.begin() + 12}, 400);
  const std::vector<Individual> second =
      Population({genomes.begin() + 12, genomes.end()}, 500);
  ASSERT_TRUE(StartDispatcher());
  const std::string endpoint = dispatcher_->endpoint();
  WorkerProcess worker(Worker(2));
  ASSERT_TRUE(worker.started());
  Submit(first);
  ASSERT_TRUE(ServeUntilAllDone());
  ExpectEachCompletedOnceAsEvaluatedDirectly(first);

  // The master goes away with work in flight and comes back on the same
  // endpoint knowing nothing; it submits what it still needs.
  Submit(second);
  ASSERT_TRUE(
      Serve([&] { return completions_.size() > first.size(); }, kLongWait));
  dispatcher_.reset();
  completions_.clear();
  DispatcherOptions options = Options();
  options.endpoint = endpoint;
  ASSERT_TRUE(StartDispatcher(options));
  EXPECT_EQ(dispatcher_->endpoint(), endpoint);
  Submit(second);
  ASSERT_TRUE(ServeUntilAllDone());

  ExpectEachCompletedOnceAsEvaluatedDirectly(second);
  EXPECT_EQ(CompletingWorkers(), std::set<std::string>{worker.name()});
  EXPECT_TRUE(worker.Running());
  EXPECT_EQ(log_.Count({"worker " + worker.name() + " joined"}), 2)
      << log_.Dump();
}

// Three workers in turn take the suspect and vanish with it, without a
// word: that is no evidence against the genome, which is then evaluated
// alone and completes with its true result; the individual that was on
// the first dying worker with it is retried (alone) and done elsewhere.
TEST_F(DispatchTest, SuspectWhoseWorkersVanishThreeTimesGetsItsTrueResult) {
  const Individual suspect = Population({DataGenome("seed-139")}, 900)[0];
  const Individual companion = Population({DataGenome("seed-1198")}, 901)[0];
  const std::vector<Individual> others = Population(MixedGenomes(10), 910);
  ASSERT_TRUE(StartDispatcher(WithIsolation(SimulatedOptions())));
  Submit({suspect, companion});
  Submit(others);

  // The first also holds the companion; later ones ask for one item only.
  for (int round = 1; round <= 3; ++round) {
    SCOPED_TRACE("round " + std::to_string(round));
    const uint64_t pid = 7000 + round;
    {
      FakeWorker fake(context_, dispatcher_->endpoint(), clock_);
      fake.Hello(1, pid);
      ASSERT_TRUE(Serve([&] { return fake.welcomed(); }, kShortWait,
                        [&] { fake.Pump(); }));
      fake.Credit(round == 1 ? 2 : 1);
      ASSERT_TRUE(
          Serve([&] { return Ids(fake.work_items()).count(suspect.id) != 0; },
                kShortWait, [&] { fake.Pump(); }));
      if (round == 1) {
        EXPECT_EQ(Ids(fake.work_items()),
                  (std::set<uint64_t>{suspect.id, companion.id}));
      } else {
        EXPECT_EQ(Ids(fake.work_items()), std::set<uint64_t>{suspect.id});
        ASSERT_EQ(fake.work_messages().size(), 1u);
        EXPECT_EQ(fake.work_messages()[0].items_size(), 1);
      }
    }  // Vanishes.
    ASSERT_TRUE(Serve(
        [&] {
          return log_.Count({"worker fake-worker:" + std::to_string(pid) +
                             " silent"}) == 1;
        },
        kShortWait));
  }
  EXPECT_EQ(log_.Count({"individual 900: 3 leases ended without a result",
                        "evaluating it alone"}),
            1)
      << log_.Dump();
  ASSERT_TRUE(Serve([&] { return FindCompletion(suspect.id) != nullptr; },
                    kLongWait, LetChildrenRun))
      << log_.Dump();
  const Completion* alone = FindCompletion(suspect.id);
  ExpectSameResult(alone->result, suspect.expected, suspect.id);
  EXPECT_NE(alone->worker.find("(isolated)"), std::string::npos)
      << alone->worker;
  EXPECT_EQ(alone->attempts, 3);
  EXPECT_EQ(log_.Count({"individual 900 evaluated alone: OK"}), 1);

  // The others, the companion included, complete normally on a worker
  // that answers.
  FakeWorker worker(context_, dispatcher_->endpoint(), clock_);
  worker.Hello(2, 7900);
  worker.Credit(4);
  size_t answered = 0;
  ASSERT_TRUE(ServeUntilAllDone(kLongWait, [&] { Answer(worker, &answered); }));
  std::vector<Individual> evaluated = others;
  evaluated.push_back(companion);
  evaluated.push_back(suspect);
  ExpectEachCompletedOnceAsEvaluatedDirectly(evaluated);
  const Completion* retried = FindCompletion(companion.id);
  ASSERT_NE(retried, nullptr);
  EXPECT_EQ(retried->attempts, 1);
  EXPECT_EQ(retried->worker, "fake-worker:7900");
  EXPECT_EQ(dispatcher_->stats().isolated, 1);
  EXPECT_EQ(dispatcher_->stats().crashed, 0);
  EXPECT_EQ(isolation_->running(), 0u);
}

// A worker that takes the individual each time it is offered and never
// answers: three expired leases, then the evaluation alone gives the true
// result.
TEST_F(DispatchTest, IndividualWhoseLeaseExpiresThreeTimesGetsItsTrueResult) {
  const Individual stuck = Population({DataGenome("seed-139")}, 1300)[0];
  DispatcherOptions options = SimulatedOptions();
  options.lease_ms = 200;
  ASSERT_TRUE(StartDispatcher(WithIsolation(options)));
  Submit({stuck});

  FakeWorker fake(context_, dispatcher_->endpoint(), clock_);
  auto pump = [&] { fake.Pump(); };
  fake.Hello(1, 4444);
  ASSERT_TRUE(Serve([&] { return fake.welcomed(); }, kShortWait, pump));
  for (int lease = 1; lease <= protocol::kMaxAttempts; ++lease) {
    SCOPED_TRACE("lease " + std::to_string(lease));
    fake.Credit(1);
    ASSERT_TRUE(Serve(
        [&] { return fake.work_items().size() == static_cast<size_t>(lease); },
        kShortWait, pump));
    ASSERT_TRUE(Serve(
        [&] {
          return log_.Count({"lease of individual 1300 on fake-worker:4444 "
                             "expired"}) == lease;
        },
        kShortWait, pump));
  }
  ASSERT_TRUE(Serve([&] { return CompletionsOf(stuck.id) == 1; }, kLongWait,
                    [&] {
                      pump();
                      LetChildrenRun();
                    }))
      << log_.Dump();
  ExpectSameResult(completions_[0].result, stuck.expected, stuck.id);
  EXPECT_EQ(completions_[0].attempts, 3);
  EXPECT_EQ(dispatcher_->pending(), 0u);
  EXPECT_EQ(dispatcher_->stats().isolated, 1);
  EXPECT_EQ(log_.Count({"fake-worker:4444 silent"}), 0);
}

// Regression: when a
// worker vanishes (its connection closes), every heartbeat to it fails
// with EHOSTUNREACH; Send() logs "could not send heartbeat" but leaves
// last_sent unchanged, so Housekeep tries again on every pass of Poll's
// loop until the worker is presumed dead, and that loop spins without
// waiting during the last millisecond of each Poll (the remaining time is
// truncated to 0 ms). Thousands of lines per vanished worker.
TEST_F(DispatchTest, VanishedWorkerCostsAFewLogLinesNotThousands) {
  ASSERT_TRUE(StartDispatcher(SimulatedOptions()));
  {
    FakeWorker fake(context_, dispatcher_->endpoint(), clock_);
    fake.Hello(1, 8080);
    ASSERT_TRUE(Serve([&] { return fake.welcomed(); }, kShortWait,
                      [&] { fake.Pump(); }));
  }  // Vanishes.
  ASSERT_TRUE(
      Serve([&] { return log_.Count({"worker fake-worker:8080 silent"}) == 1; },
            kShortWait));
  EXPECT_LE(log_.Count({"could not send"}), protocol::kLiveness) << log_.Dump();
}

// Whether a --log-items worker's `output` says it received `individual`.
bool SaysReceived(const std::string& output, uint64_t individual) {
  // "received 1001 1002; 2 queued or running": each individual is
  // followed by a space or the semicolon.
  const std::string id = " " + std::to_string(individual);
  std::istringstream lines(output);
  for (std::string line; std::getline(lines, line);) {
    if (line.find("received ") == std::string::npos) continue;
    if (line.find(id + " ") != std::string::npos ||
        line.find(id + ";") != std::string::npos) {
      return true;
    }
  }
  return false;
}

// The counts of a worker's "stopping: handing back N items, finishing M"
// line; {-1, -1} without one.
std::pair<int, int> StoppingCounts(const std::string& output) {
  const std::string prefix = "stopping: handing back ";
  const size_t at = output.find(prefix);
  if (at == std::string::npos) return {-1, -1};
  int handed_back = -1;
  int finishing = -1;
  if (std::sscanf(output.c_str() + at + prefix.size(), "%d items, finishing %d",
                  &handed_back, &finishing) != 2) {
    return {-1, -1};
  }
  return {handed_back, finishing};
}

TEST_F(DispatchTest, TerminatedWorkerHandsBackUnstartedWorkAndExitsCleanly) {
  // One fast individual, then slow ones (some 0.6 s each, more under
  // load). After the fast one, the one-thread worker A receives the first
  // slow one (1001) and the next (1002) together, and is terminated as
  // soon as it logs having received 1002: its thread is then on 1001 (or
  // has not yet taken it), so 1002 at least is handed back unstarted.
  // That holds while this side reacts to the log within 1001's
  // evaluation, hence three times the usual slow steps: a loaded machine
  // may starve this process for a few hundred milliseconds. Nothing here
  // waits on liveness, so the heartbeat is slow: a loaded machine that
  // starves either side for 300 ms must not make it look lost (A would
  // then exit without its goodbye).
  config_.evaluation.motion_steps = 3 * kSlowMotionSteps;
  const v1::Genome slow = DataGenome("seed-1198");
  const std::vector<Individual> population = Population(
      {DataGenome("example"), slow, slow, DataGenome("seed-1-nonviable"),
       DataGenome("seed-2-too-few-cells")},
      1000);
  ASSERT_TRUE(StartDispatcher(PatientOptions()));
  Submit(population);
  WorkerArgs args = PatientWorker(1);
  args.log_items = true;
  WorkerProcess a(args);
  ASSERT_TRUE(a.started());
  ASSERT_TRUE(Serve([&] { return SaysReceived(a.output(), 1002); }, kLongWait))
      << a.output();
  ASSERT_TRUE(a.Signal(SIGTERM));
  WorkerProcess b(PatientWorker(2));
  ASSERT_TRUE(a.WaitExit(kLongWait, [&] { ServeFor(milliseconds(10)); }));
  EXPECT_EQ(a.exit_code(), 0) << a.Describe();
  ASSERT_TRUE(ServeUntilAllDone());

  ExpectEachCompletedOnceAsEvaluatedDirectly(population);
  const auto [handed_back, finishing] = StoppingCounts(a.output());
  ASSERT_GE(handed_back, 1) << a.output();
  EXPECT_EQ(handed_back + finishing, 2) << a.output();
  EXPECT_EQ(log_.Count({a.name() + " said goodbye (worker stopping)",
                        "handing back " + std::to_string(handed_back)}),
            1)
      << log_.Dump();
  EXPECT_EQ(log_.Count({"worker " + a.name() + " silent"}), 0);
  for (const Completion& c : completions_) {
    EXPECT_EQ(c.attempts, 0) << "individual " << c.individual;
  }
  // A finished the evaluation it had started (if any); B did the ones
  // handed back.
  ASSERT_NE(FindCompletion(1000), nullptr);
  EXPECT_EQ(FindCompletion(1000)->worker, a.name());
  ASSERT_NE(FindCompletion(1001), nullptr);
  EXPECT_EQ(FindCompletion(1001)->worker, finishing == 1 ? a.name() : b.name());
  ASSERT_NE(FindCompletion(1002), nullptr);
  EXPECT_EQ(FindCompletion(1002)->worker, b.name());
}

TEST_F(DispatchTest, NullEvaluationWorkersAreRefusedUnlessAccepted) {
  const std::vector<Individual> population = Population(MixedGenomes(10), 1100);
  ASSERT_TRUE(StartDispatcher());
  WorkerArgs args = Worker(1);
  args.null_evaluation = true;
  {
    WorkerProcess refused(args);
    ASSERT_TRUE(
        refused.WaitExit(kShortWait, [&] { ServeFor(milliseconds(10)); }));
    EXPECT_EQ(refused.exit_code(), 3) << refused.Describe();
    EXPECT_EQ(log_.Count({"refused worker " + refused.name(),
                          "null-evaluation workers are not accepted"}),
              1)
        << log_.Dump();
    EXPECT_NE(refused.output().find("refused by the master: null-evaluation"),
              std::string::npos)
        << refused.output();
    EXPECT_EQ(dispatcher_->stats().refused, 1);
  }

  dispatcher_.reset();
  DispatcherOptions options = Options();
  options.accept_null_workers = true;
  ASSERT_TRUE(StartDispatcher(options));
  args.endpoint = dispatcher_->endpoint();
  WorkerProcess accepted(args);
  Submit(population);
  ASSERT_TRUE(ServeUntilAllDone());
  std::map<uint64_t, int> count;
  for (const Completion& c : completions_) {
    ++count[c.individual];
    EXPECT_EQ(c.result.status(), v1::EvaluationResult::NOT_EVALUATED);
    EXPECT_EQ(c.result.reason(), "null-evaluation worker");
    EXPECT_FALSE(c.result.has_fitness());
    EXPECT_TRUE(c.null_evaluation);
    EXPECT_EQ(c.worker, accepted.name());
  }
  for (const Individual& individual : population) {
    EXPECT_EQ(count[individual.id], 1) << "individual " << individual.id;
  }
  EXPECT_EQ(completions_.size(), population.size());
}

TEST_F(DispatchTest, ExpiredLeaseGoesToAnotherWorkerAndTheLateResultIsIgnored) {
  std::vector<v1::Genome> genomes = MixedGenomes(18);
  genomes.erase(genomes.begin(), genomes.begin() + 6);
  const std::vector<Individual> population = Population(genomes, 1200);
  const Individual& held = population[0];
  DispatcherOptions options = SimulatedOptions();
  options.lease_ms = 300;
  ASSERT_TRUE(StartDispatcher(options));
  Submit({held});

  // A worker that takes the individual, keeps heart-beating, and does not
  // answer.
  FakeWorker fake(context_, dispatcher_->endpoint(), clock_);
  fake.Hello(1, 4321);
  ASSERT_TRUE(
      Serve([&] { return fake.welcomed(); }, kShortWait, [&] { fake.Pump(); }));
  fake.Credit(1);
  ASSERT_TRUE(Serve([&] { return !fake.work_items().empty(); }, kShortWait,
                    [&] { fake.Pump(); }));
  // And one that answers everything at once.
  FakeWorker worker(context_, dispatcher_->endpoint(), clock_);
  worker.Hello(2, 4322);
  worker.Credit(4);
  size_t answered = 0;
  const auto pump = [&] {
    fake.Pump();
    Answer(worker, &answered);
  };
  Submit({population.begin() + 1, population.end()});

  ASSERT_TRUE(ServeUntilAllDone(kLongWait, pump));
  EXPECT_EQ(
      log_.Count({"lease of individual 1200 on fake-worker:4321 expired"}), 1)
      << log_.Dump();
  ASSERT_NE(FindCompletion(held.id), nullptr);
  EXPECT_EQ(FindCompletion(held.id)->worker, "fake-worker:4322");
  EXPECT_EQ(FindCompletion(held.id)->attempts, 1);

  // Now the fake answers, late and wrong: ignored.
  const int64_t ignored = dispatcher_->stats().ignored;
  v1::Envelope late;
  v1::WorkResult* r = late.mutable_results()->add_results();
  r->set_individual(held.id);
  r->set_genome_hash(fake.work_items()[0].genome_hash());
  r->mutable_result()->set_status(v1::EvaluationResult::OK);
  r->mutable_result()->set_fitness(12345.0);
  fake.Send(late);
  ASSERT_TRUE(Serve([&] { return dispatcher_->stats().ignored > ignored; },
                    kShortWait, pump));
  EXPECT_EQ(log_.Count({"ignored a result for individual 1200 from "
                        "fake-worker:4321 (unknown or already complete)"}),
            1)
      << log_.Dump();
  ServeFor(milliseconds(50), pump);

  ExpectEachCompletedOnceAsEvaluatedDirectly(population);
  EXPECT_EQ(fake.work_items().size(), 1u);  // Not given to it again.
  EXPECT_EQ(dispatcher_->workers(), 2u);    // Kept alive by heartbeats.
  EXPECT_EQ(log_.Count({"fake-worker:4321 silent"}), 0);
}

}  // namespace
}  // namespace animat::testing
