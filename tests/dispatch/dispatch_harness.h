// The fixture of the dispatch tests: an in-process Dispatcher with short
// heartbeats, its log lines captured, populations of genomes with their
// results computed directly (animat::Evaluate in this process), and a serve
// loop that records every completion so a test can check that each
// individual completed exactly once, with the same bits as the direct
// evaluation, whichever worker did it.
//
// Two kinds of time. With real animat-worker processes the dispatcher is on
// a free loopback port and keeps real time. With workers played by the test
// (FakeWorker) it can run on simulated time instead (SimulatedOptions): an
// inproc:// endpoint, where a message sent is there to read at once, and a
// ManualClock that the serve loop advances by kSimulatedStep between
// passes, so that leases, heartbeats and liveness take no real time and
// expire exactly when they should.
#ifndef ANIMAT_TESTS_DISPATCH_DISPATCH_HARNESS_H_
#define ANIMAT_TESTS_DISPATCH_DISPATCH_HARNESS_H_

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <utility>
#include <vector>
#include <zmq.hpp>

#include "animat/v1/genome.pb.h"
#include "animat/v1/trace.pb.h"
#include "common/base/clock.h"
#include "common/base/rng.h"
#include "common/evaluation/evaluator.h"
#include "common/evaluation/model_config.h"
#include "common/genome/genome_proto.h"
#include "common/genome/random_genome.h"
#include "common/io/proto_file.h"
#include "common/protocol/genome_wire.h"
#include "common/protocol/protocol.h"
#include "master/dispatch/dispatcher.h"
#include "master/run/child_isolation.h"
#include "tests/dispatch/fake_peers.h"
#include "tests/dispatch/worker_process.h"
#include "tests/test_util.h"

namespace animat::testing {

using std::chrono::milliseconds;
using Steady = std::chrono::steady_clock;

// Heartbeat interval of the tests that exercise liveness: a peer silent
// for 300 ms is dead.
inline constexpr int kHeartbeatMs = 100;
// Heartbeat interval of the tests with real worker processes that do not
// exercise liveness (PatientOptions, PatientWorker): a loaded machine that
// starves a process for a few hundred milliseconds must not make a live
// peer look lost.
inline constexpr int kPatientHeartbeatMs = 1000;
// Motion steps that make a viable genome's evaluation last long enough for
// a test to act during it (the tests that do use it): some 0.2 s in an
// optimised build (about 5 us a step under the default physics), and some
// 0.4 s in a build with assertions, which takes a tenth of the steps (the
// sanitizer builds at -O1; about three times longer at -O0).
#ifdef NDEBUG
inline constexpr int kSlowMotionSteps = 40000;
#else
inline constexpr int kSlowMotionSteps = 4000;
#endif
// Bounds on waits that normally end far sooner (they end as soon as the
// condition holds); generous for sanitizer builds. On simulated time, of
// the simulated clock.
inline constexpr milliseconds kLongWait{30000};
inline constexpr milliseconds kShortWait{10000};
// On simulated time: how far the clock moves between two passes of the
// serve loop.
inline constexpr milliseconds kSimulatedStep{5};

// A genome of tests/data/genomes.
inline v1::Genome DataGenome(const std::string& name) {
  v1::Genome genome;
  const Status status =
      ReadProtoFile(TestData("genomes/" + name + ".json"), &genome);
  EXPECT_TRUE(status.ok()) << status.ToString();
  return genome;
}

// The three viable genomes of tests/data: each runs the whole motion phase.
inline std::vector<v1::Genome> ViableGenomes() {
  return {DataGenome("seed-1198"), DataGenome("seed-1203"),
          DataGenome("seed-139")};
}

// `count` genomes: the six of tests/data (three viable, three failing at
// different stages), then random ones (RandomGenome, run seed 2024, stream
// of the genome's index).
inline std::vector<v1::Genome> MixedGenomes(int count) {
  std::vector<v1::Genome> genomes = {
      DataGenome("seed-1198"),        DataGenome("seed-1203"),
      DataGenome("seed-139"),         DataGenome("example"),
      DataGenome("seed-1-nonviable"), DataGenome("seed-2-too-few-cells")};
  genomes.resize(std::min<size_t>(genomes.size(), count));
  for (int i = static_cast<int>(genomes.size()); i < count; ++i) {
    RandomStream stream(2024, static_cast<uint64_t>(i),
                        StreamPurpose::kRandomGenome);
    genomes.push_back(GenomeToProto(RandomGenome(stream)));
  }
  return genomes;
}

// The result of evaluating `genome` here, directly (no cache).
inline v1::EvaluationResult EvaluateDirectly(const v1::Genome& genome,
                                             const ModelConfig& config) {
  Result<Genome> parsed = GenomeFromProto(genome);
  if (parsed.ok()) return EvaluationResultToProto(Evaluate(*parsed, config));
  // As the worker reports a genome that fails validation.
  EvaluationResult invalid;
  invalid.status = EvalStatus::kInvalidGenome;
  invalid.reason = parsed.status().message();
  return EvaluationResultToProto(invalid);
}

// The direct results of `genomes`: what every worker must answer. Cached
// by genome and configuration hashes; genomes not seen yet are evaluated
// on several threads at once (Evaluate shares nothing between calls).
inline std::vector<v1::EvaluationResult> DirectResults(
    const std::vector<v1::Genome>& genomes, const ModelConfig& config) {
  using Key = std::pair<uint64_t, uint64_t>;
  static std::map<Key, v1::EvaluationResult> cache;
  const uint64_t config_hash = protocol::ConfigHash(ConfigToProto(config));
  std::map<Key, const v1::Genome*> missing;
  for (const v1::Genome& genome : genomes) {
    const Key key = {protocol::GenomeHash(genome), config_hash};
    if (cache.count(key) == 0) missing.emplace(key, &genome);
  }
  std::vector<std::pair<Key, const v1::Genome*>> work(missing.begin(),
                                                      missing.end());
  std::vector<v1::EvaluationResult> computed(work.size());
  std::atomic<size_t> next{0};
  auto run = [&] {
    for (size_t i = next++; i < work.size(); i = next++) {
      computed[i] = EvaluateDirectly(*work[i].second, config);
    }
  };
  std::vector<std::thread> threads;
  const unsigned count = std::max(1u, std::thread::hardware_concurrency());
  for (unsigned t = 1; t < count && t < work.size(); ++t) {
    threads.emplace_back(run);
  }
  run();
  for (std::thread& t : threads) t.join();
  for (size_t i = 0; i < work.size(); ++i) {
    cache.emplace(work[i].first, computed[i]);
  }
  std::vector<v1::EvaluationResult> results;
  for (const v1::Genome& genome : genomes) {
    results.push_back(cache.at({protocol::GenomeHash(genome), config_hash}));
  }
  return results;
}

inline v1::EvaluationResult DirectResult(const v1::Genome& genome,
                                         const ModelConfig& config) {
  return DirectResults({genome}, config)[0];
}

struct Individual {
  uint64_t id = 0;
  v1::Genome genome;
  v1::EvaluationResult expected;  // The direct evaluation's.
};

// Checks every field of `actual` against `expected`, fitness and body
// spreads bit for bit.
inline void ExpectSameResult(const v1::EvaluationResult& actual,
                             const v1::EvaluationResult& expected,
                             uint64_t individual) {
  SCOPED_TRACE("individual " + std::to_string(individual));
  EXPECT_EQ(v1::EvaluationResult::Status_Name(actual.status()),
            v1::EvaluationResult::Status_Name(expected.status()))
      << actual.reason();
  EXPECT_EQ(actual.reason(), expected.reason());
  ASSERT_EQ(actual.has_fitness(), expected.has_fitness());
  if (expected.has_fitness()) {
    EXPECT_EQ(std::bit_cast<uint64_t>(actual.fitness()),
              std::bit_cast<uint64_t>(expected.fitness()))
        << actual.fitness() << " vs " << expected.fitness();
  }
  EXPECT_EQ(actual.cells(), expected.cells());
  EXPECT_EQ(actual.steps(), expected.steps());
  EXPECT_EQ(actual.state_hash(), expected.state_hash());
  ASSERT_EQ(actual.has_body(), expected.has_body());
  if (expected.has_body()) {
    const v1::BodySummary& a = actual.body();
    const v1::BodySummary& e = expected.body();
    EXPECT_EQ(a.cells(), e.cells());
    EXPECT_EQ(a.springs(), e.springs());
    EXPECT_EQ(a.chambers(), e.chambers());
    EXPECT_EQ(a.skin_edges(), e.skin_edges());
    EXPECT_EQ(std::bit_cast<uint64_t>(a.spread_major()),
              std::bit_cast<uint64_t>(e.spread_major()));
    EXPECT_EQ(std::bit_cast<uint64_t>(a.spread_minor()),
              std::bit_cast<uint64_t>(e.spread_minor()));
  }
}

// The dispatcher's log lines, in order. Like every LogSink (common/base/
// log.h) it may be called from any thread: the ZAP handler logs from its
// own. The questions read a copy taken under the lock.
class LogLines {
 public:
  LogSink Sink() {
    return [this](std::string_view line) {
      std::lock_guard<std::mutex> lock(mutex_);
      lines_.emplace_back(line);
    };
  }
  std::vector<std::string> lines() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return lines_;
  }
  size_t size() const { return lines().size(); }
  // Lines (from the `from`-th on) that contain every one of `parts`.
  int Count(const std::vector<std::string>& parts, size_t from = 0) const {
    const std::vector<std::string> all_lines = lines();
    int n = 0;
    for (size_t i = from; i < all_lines.size(); ++i) {
      n += HasAll(all_lines[i], parts) ? 1 : 0;
    }
    return n;
  }
  // The first such line, or "".
  std::string Find(const std::vector<std::string>& parts,
                   size_t from = 0) const {
    const std::vector<std::string> all_lines = lines();
    for (size_t i = from; i < all_lines.size(); ++i) {
      if (HasAll(all_lines[i], parts)) return all_lines[i];
    }
    return "";
  }
  // The lines, a run of identical ones shown once with its count.
  std::string Dump(size_t from = 0) const {
    const std::vector<std::string> all_lines = lines();
    std::string text;
    for (size_t i = from; i < all_lines.size();) {
      size_t end = i + 1;
      while (end < all_lines.size() && all_lines[end] == all_lines[i]) ++end;
      text += all_lines[i];
      if (end - i > 1) text += "  [" + std::to_string(end - i) + " times]";
      text += "\n";
      i = end;
    }
    return text;
  }

 private:
  static bool HasAll(const std::string& line,
                     const std::vector<std::string>& parts) {
    for (const std::string& part : parts) {
      if (line.find(part) == std::string::npos) return false;
    }
    return true;
  }

  mutable std::mutex mutex_;
  std::vector<std::string> lines_;
};

class DispatchTest : public ::testing::Test {
 protected:
  DispatchTest() { config_.evaluation.motion_steps = 300; }

  // The log is printed when the test failed, or always with
  // ANIMAT_DISPATCH_TEST_LOG=1 in the environment.
  void TearDown() override {
    if (HasFailure() || std::getenv("ANIMAT_DISPATCH_TEST_LOG") != nullptr) {
      std::cerr << "--- dispatcher log ---\n"
                << log_.Dump() << "--- end of dispatcher log ---\n";
    }
  }

  DispatcherOptions Options() {
    DispatcherOptions options;
    options.endpoint = "tcp://127.0.0.1:*";
    options.heartbeat_ms = kHeartbeatMs;
    options.log = log_.Sink();
    return options;
  }
  // On simulated time (clock_), for workers played by the test: a fresh
  // inproc:// endpoint in context_.
  DispatcherOptions SimulatedOptions() {
    static int count = 0;
    DispatcherOptions options = Options();
    options.endpoint = "inproc://dispatch-test-" + std::to_string(++count);
    options.clock = &clock_;
    return options;
  }
  bool simulated() const {
    return dispatcher_ != nullptr && &dispatcher_->clock() == &clock_;
  }

  // `options` with an Isolation (isolation_) that runs `command` (by
  // default the animat-worker of ANIMAT_BIN_DIR) on the options' clock,
  // with a time limit of kLongWait (leases in tests are short, and a
  // child on a loaded machine slow).
  DispatcherOptions WithIsolation(DispatcherOptions options,
                                  std::vector<std::string> command = {
                                      std::string(ANIMAT_BIN_DIR) +
                                      "/animat-worker"}) {
    Result<std::unique_ptr<ChildIsolation>> isolation = ChildIsolation::Create(
        {std::move(command), static_cast<int>(kLongWait.count()),
         options.clock});
    EXPECT_TRUE(isolation.ok()) << isolation.status().ToString();
    if (isolation.ok()) isolation_ = std::move(isolation).value();
    options.isolation = isolation_.get();
    return options;
  }
  // A tick for Serve while an isolated evaluation runs: a real process,
  // which simulated time does not hurry.
  static void LetChildrenRun() { std::this_thread::sleep_for(milliseconds(1)); }

  // Binds a dispatcher for config_ (retrying while the address is still
  // held by a dispatcher just destroyed); false on failure.
  bool StartDispatcher(DispatcherOptions options) {
    const auto end = Steady::now() + kShortWait;
    for (;;) {
      Result<std::unique_ptr<Dispatcher>> created =
          Dispatcher::Create(&context_, options, ConfigToProto(config_));
      if (created.ok()) {
        dispatcher_ = std::move(created).value();
        return true;
      }
      if (Steady::now() >= end) {
        ADD_FAILURE() << created.status().ToString();
        return false;
      }
      std::this_thread::sleep_for(milliseconds(20));
    }
  }
  bool StartDispatcher() { return StartDispatcher(Options()); }

  DispatcherOptions PatientOptions() {
    DispatcherOptions options = Options();
    options.heartbeat_ms = kPatientHeartbeatMs;
    return options;
  }
  WorkerArgs PatientWorker(int threads) const {
    WorkerArgs args = Worker(threads);
    args.heartbeat_ms = kPatientHeartbeatMs;
    return args;
  }

  WorkerArgs Worker(int threads) const {
    WorkerArgs args;
    args.endpoint = dispatcher_->endpoint();
    args.threads = threads;
    args.heartbeat_ms = kHeartbeatMs;
    return args;
  }

  // Individuals first_id, first_id + 1, ... carrying `genomes`, with their
  // direct results under config_ (computed now, before any worker runs).
  std::vector<Individual> Population(const std::vector<v1::Genome>& genomes,
                                     uint64_t first_id) const {
    const std::vector<v1::EvaluationResult> expected =
        DirectResults(genomes, config_);
    std::vector<Individual> population;
    for (size_t i = 0; i < genomes.size(); ++i) {
      Individual individual;
      individual.id = first_id + i;
      individual.genome = genomes[i];
      individual.expected = expected[i];
      population.push_back(std::move(individual));
    }
    return population;
  }

  void Submit(const std::vector<Individual>& population) {
    for (const Individual& individual : population) {
      dispatcher_->Submit(individual.id, individual.genome);
    }
  }

  // Serves (Poll in short slices, calling `tick` before each) until `done`
  // holds or `timeout` passes; returns `done()`. Every completion is kept.
  // On simulated time each slice is one pass (Poll(0)), after which the
  // clock moves kSimulatedStep: no real time is waited for.
  bool Serve(const std::function<bool()>& done, milliseconds timeout,
             const std::function<void()>& tick = {}) {
    const bool simulated_time = simulated();
    const Clock& clock = dispatcher_->clock();
    const auto end = clock.Now() + timeout;
    for (;;) {
      if (tick) tick();
      for (Completion& c : dispatcher_->Poll(simulated_time ? 0 : 10)) {
        completions_.push_back(std::move(c));
      }
      if (done()) return true;
      if (clock.Now() >= end) return false;
      if (simulated_time) clock_.Advance(kSimulatedStep);
    }
  }
  // On simulated time: moves the clock by `by`, then makes one pass.
  void AdvanceAndPoll(milliseconds by, const std::function<void()>& tick = {}) {
    clock_.Advance(by);
    if (tick) tick();
    for (Completion& c : dispatcher_->Poll(0)) {
      completions_.push_back(std::move(c));
    }
  }
  // Serves for `duration`, whatever happens.
  void ServeFor(milliseconds duration, const std::function<void()>& tick = {}) {
    Serve([] { return false; }, duration, tick);
  }
  bool ServeUntilAllDone(milliseconds timeout = kLongWait,
                         const std::function<void()>& tick = {}) {
    return Serve([this] { return dispatcher_->pending() == 0; }, timeout, tick);
  }

  // A tick that makes `fake` a worker that works instantly: it pumps it
  // and answers every item it holds and has not answered yet with the
  // direct result under config_, giving the credit back. `answered`
  // counts the items answered so far.
  void Answer(FakeWorker& fake, size_t* answered) {
    fake.Pump();
    for (; *answered < fake.work_items().size(); ++*answered) {
      const v1::WorkItem& item = fake.work_items()[*answered];
      v1::Envelope results;
      v1::WorkResult* r = results.mutable_results()->add_results();
      r->set_individual(item.individual());
      r->set_genome_hash(item.genome_hash());
      *r->mutable_result() = DirectResult(item.genome(), config_);
      fake.Send(results);
      fake.Credit(1);
    }
  }

  int CompletionsOf(uint64_t id) const {
    int n = 0;
    for (const Completion& c : completions_) n += c.individual == id ? 1 : 0;
    return n;
  }
  const Completion* FindCompletion(uint64_t id) const {
    for (const Completion& c : completions_) {
      if (c.individual == id) return &c;
    }
    return nullptr;
  }
  std::set<std::string> CompletingWorkers() const {
    std::set<std::string> names;
    for (const Completion& c : completions_) names.insert(c.worker);
    return names;
  }

  // Every individual of `population` completed exactly once, with its
  // direct result; nothing else completed.
  void ExpectEachCompletedOnceAsEvaluatedDirectly(
      const std::vector<Individual>& population) {
    std::map<uint64_t, const Individual*> by_id;
    for (const Individual& individual : population) {
      by_id[individual.id] = &individual;
    }
    std::map<uint64_t, int> count;
    for (const Completion& c : completions_) {
      const int n = ++count[c.individual];
      EXPECT_EQ(n, 1) << "individual " << c.individual
                      << " completed again, by " << c.worker;
      const auto it = by_id.find(c.individual);
      if (it == by_id.end()) {
        ADD_FAILURE() << "completion for individual " << c.individual
                      << ", never submitted";
        continue;
      }
      if (n == 1)
        ExpectSameResult(c.result, it->second->expected, c.individual);
    }
    for (const Individual& individual : population) {
      EXPECT_EQ(count[individual.id], 1)
          << "individual " << individual.id << " completed "
          << count[individual.id] << " times";
    }
    EXPECT_EQ(dispatcher_->pending(), 0u);
  }

  zmq::context_t context_{1};
  ManualClock clock_;  // Simulated time (SimulatedOptions).
  ModelConfig config_;
  LogLines log_;
  std::unique_ptr<ChildIsolation> isolation_;  // Outlives dispatcher_.
  std::unique_ptr<Dispatcher> dispatcher_;
  std::vector<Completion> completions_;
};

}  // namespace animat::testing

#endif  // ANIMAT_TESTS_DISPATCH_DISPATCH_HARNESS_H_
