// The protocol's limits (common/protocol/protocol.h, docs/protocol.md
// "Limits") at work on both sides: every numeric field out of its range is
// refused with a logged reason, by the master and by a real worker; a
// 16 MiB hello costs the master at most a line and no worker; peers'
// strings reach the log escaped and cut short.
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <cstdint>
#include <functional>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/dispatch/dispatch_harness.h"
#include "tests/dispatch/fake_peers.h"
#include "tests/dispatch/worker_process.h"

namespace animat::testing {
namespace {

constexpr uint64_t kBeyondIndividuals = protocol::kMaxIndividual + 1;

struct Case {
  std::string what;
  v1::Envelope envelope;
  std::string reason;  // What the logged line must hold.
};

v1::Envelope Hello(const std::function<void(v1::Hello*)>& edit) {
  v1::Envelope envelope = FakeHello(1, 4747);
  edit(envelope.mutable_hello());
  return envelope;
}

v1::Envelope Credit(uint32_t credit) {
  v1::Envelope envelope;
  envelope.mutable_credit()->set_credit(credit);
  return envelope;
}

TEST_F(DispatchTest, MasterRefusesEveryNumericFieldOutOfRangeSayingWhy) {
  const Individual held = Population({DataGenome("seed-1198")}, 1)[0];
  ASSERT_TRUE(StartDispatcher(SimulatedOptions()));
  Submit({held});
  FakeWorker peer(context_, dispatcher_->endpoint(), clock_);
  auto pump = [&] { peer.Pump(); };
  peer.Hello(1, 4242);
  const std::string name = "fake-worker:4242";
  ASSERT_TRUE(Serve([&] { return peer.welcomed(); }, kShortWait, pump));
  peer.Credit(1);
  ASSERT_TRUE(
      Serve([&] { return !peer.work_items().empty(); }, kShortWait, pump));

  // A result for the held individual, as valid as can be but for `edit`.
  const auto result = [&](const std::function<void(v1::WorkResult*)>& edit) {
    v1::Envelope envelope;
    v1::WorkResult* r = envelope.mutable_results()->add_results();
    r->set_individual(held.id);
    r->set_genome_hash(protocol::GenomeHash(held.genome));
    *r->mutable_result() = held.expected;
    edit(r);
    return envelope;
  };
  v1::Envelope too_many_results;
  for (int i = 0; i <= protocol::kMaxBatch; ++i) {
    too_many_results.mutable_results()->add_results()->set_individual(i);
  }
  v1::Envelope too_many_returned;
  for (uint32_t i = 0; i <= protocol::kMaxCredit; ++i) {
    too_many_returned.mutable_goodbye()->add_returned(i);
  }
  v1::Envelope returned_beyond;
  returned_beyond.mutable_goodbye()->add_returned(kBeyondIndividuals);

  const std::string malformed = "ignored a malformed message from " + name;
  const std::string invalid =
      "ignored an invalid result for individual 1 "
      "from " +
      name;
  const std::vector<Case> cases = {
      {"credit 0", Credit(0), "credit.credit 0 outside [1, 262144]"},
      {"credit 262145", Credit(protocol::kMaxCredit + 1),
       "credit.credit 262145 outside [1, 262144]"},
      {"credit 2^32 - 1", Credit(UINT32_MAX),
       "credit.credit 4294967295 outside [1, 262144]"},
      {"257 results", too_many_results,
       "results.results holds 257, above the limit of 256"},
      {"a result for individual 2^63",
       result([](v1::WorkResult* r) { r->set_individual(kBeyondIndividuals); }),
       "results.results[0].individual 9223372036854775808 outside [0, "
       "9223372036854775807]"},
      {"a result of -1 cells",
       result([](v1::WorkResult* r) { r->mutable_result()->set_cells(-1); }),
       "cells -1"},
      {"a result of -1 steps",
       result([](v1::WorkResult* r) { r->mutable_result()->set_steps(-1); }),
       "steps -1"},
      {"a negative fitness",
       result([](v1::WorkResult* r) { r->mutable_result()->set_fitness(-2); }),
       "fitness -2"},
      {"an infinite fitness", result([](v1::WorkResult* r) {
         r->mutable_result()->set_fitness(
             std::numeric_limits<double>::infinity());
       }),
       "fitness inf"},
      {"a negative skin edge count", result([](v1::WorkResult* r) {
         r->mutable_result()->mutable_body()->set_skin_edges(-5);
       }),
       "body skin_edges -5"},
      {"a negative spread", result([](v1::WorkResult* r) {
         r->mutable_result()->mutable_body()->set_spread_minor(-0.5);
       }),
       "body spread_minor -0.5"},
      {"a negative wall time",
       result([](v1::WorkResult* r) { r->set_wall_seconds(-1); }),
       "wall time -1"},
      {"a NaN wall time", result([](v1::WorkResult* r) {
         r->set_wall_seconds(std::numeric_limits<double>::quiet_NaN());
       }),
       "wall time nan"},
      {"an unknown status", result([](v1::WorkResult* r) {
         r->mutable_result()->set_status(
             static_cast<v1::EvaluationResult::Status>(-4));
       }),
       "unknown status -4"},
      {"a goodbye returning 262145", too_many_returned,
       "goodbye.returned holds 262145, above the limit of 262144"},
      {"a goodbye returning individual 2^63", returned_beyond,
       "goodbye.returned[0] 9223372036854775808 outside"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.what);
    const size_t from = log_.size();
    const int64_t ignored = dispatcher_->stats().ignored;
    peer.Send(c.envelope);
    ASSERT_TRUE(Serve(
        [&] {
          return log_.Count({"ignored", c.reason}, from);
        },
        kShortWait, pump))
        << log_.Dump(from);
    ServeFor(milliseconds(20), pump);  // A second line would show now.
    EXPECT_EQ(log_.size(), from + 1) << log_.Dump(from);
    const std::string line = log_.lines()[from];
    EXPECT_TRUE(line.rfind(malformed, 0) == 0 || line.rfind(invalid, 0) == 0)
        << line;
    EXPECT_EQ(dispatcher_->stats().ignored, ignored + 1);
  }
  // Nothing of it counted: the peer is still greeted, with its lease, and
  // its true result completes the individual.
  EXPECT_EQ(dispatcher_->workers(), 1u);
  EXPECT_EQ(dispatcher_->stats().refused, 0);
  peer.Send(result([](v1::WorkResult*) {}));
  ASSERT_TRUE(ServeUntilAllDone(kShortWait, pump));
  ExpectEachCompletedOnceAsEvaluatedDirectly({held});
}

// A Hello with a field out of its limits is refused, and told why: the
// peer learns what to fix, and nothing else of the master changes.
TEST_F(DispatchTest, MasterRefusesAHelloOutOfRangeTellingThePeerWhy) {
  ASSERT_TRUE(StartDispatcher(SimulatedOptions()));
  const std::vector<Case> cases = {
      {"hello.threads 0", Hello([](v1::Hello* h) { h->set_threads(0); }),
       "hello.threads 0 outside [1, 65536]"},
      {"hello.threads 65537",
       Hello([](v1::Hello* h) { h->set_threads(protocol::kMaxThreads + 1); }),
       "hello.threads 65537 outside [1, 65536]"},
      {"hello.threads 2^32 - 1",
       Hello([](v1::Hello* h) { h->set_threads(UINT32_MAX); }),
       "hello.threads 4294967295 outside [1, 65536]"},
      {"hello.pid 2^31",
       Hello([](v1::Hello* h) { h->set_pid(protocol::kMaxPid + 1); }),
       "hello.pid 2147483648 outside [0, 2147483647]"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.what);
    const size_t from = log_.size();
    const int64_t refused = dispatcher_->stats().refused;
    FakeWorker peer(context_, dispatcher_->endpoint(), clock_);
    peer.Send(c.envelope);
    ASSERT_TRUE(Serve([&] { return peer.refusal().has_value(); }, kShortWait,
                      [&] { peer.Pump(); }))
        << log_.Dump(from);
    EXPECT_NE(peer.refusal()->find(c.reason), std::string::npos)
        << *peer.refusal();
    EXPECT_FALSE(peer.welcomed());
    EXPECT_EQ(log_.Count({"refused worker fake-worker:", c.reason}, from), 1)
        << log_.Dump(from);
    EXPECT_EQ(dispatcher_->stats().refused, refused + 1);
    EXPECT_EQ(dispatcher_->workers(), 0u);
  }
}

// A real worker of one thread for `master`, with slack in its heartbeat:
// these tests are not about liveness.
WorkerArgs SlackWorker(const FakeMaster& master) {
  WorkerArgs args;
  args.endpoint = master.endpoint();
  args.threads = 1;
  args.heartbeat_ms = 1000;
  return args;
}

TEST_F(DispatchTest, WorkerRefusesEveryNumericFieldOutOfRangeSayingWhy) {
  FakeMaster master(context_);
  WorkerProcess worker(SlackWorker(master));
  ASSERT_TRUE(worker.started());
  const std::optional<RoutedMessage> hello = master.ReceiveEnvelope(
      "", kShortWait, [](const v1::Envelope& e) { return e.has_hello(); });
  ASSERT_TRUE(hello.has_value());
  const std::string& id = hello->identity;

  const v1::Config config = ConfigToProto(config_);
  const auto welcome = [&](uint32_t heartbeat_ms) {
    return FakeWelcome(config, heartbeat_ms);
  };
  const v1::Genome genome = DataGenome("seed-1198");
  const auto work = [&](int items, uint64_t first) {
    v1::Envelope envelope;
    envelope.mutable_work()->set_config_hash(protocol::ConfigHash(config));
    for (int i = 0; i < items; ++i) {
      v1::WorkItem* item = envelope.mutable_work()->add_items();
      item->set_individual(first + static_cast<uint64_t>(i));
      *item->mutable_genome() = genome;
      item->set_genome_hash(protocol::GenomeHash(genome));
    }
    return envelope;
  };
  const auto acknowledge = [](int count, uint64_t first) {
    v1::Envelope envelope;
    for (int i = 0; i < count; ++i) {
      envelope.mutable_acknowledge()->add_individuals(first + i);
    }
    return envelope;
  };
  const std::vector<Case> cases = {
      {"heartbeat 0", welcome(0),
       "welcome.heartbeat_ms 0 outside [10, 600000]"},
      {"heartbeat 9", welcome(9), "welcome.heartbeat_ms 9 outside"},
      {"heartbeat 600001", welcome(600001),
       "welcome.heartbeat_ms 600001 outside"},
      // kLiveness times it overflowed an int (undefined behaviour).
      {"heartbeat 715827883", welcome(715827883),
       "welcome.heartbeat_ms 715827883 outside"},
      {"heartbeat 2^32 - 1", welcome(UINT32_MAX),
       "welcome.heartbeat_ms 4294967295 outside"},
      {"257 items", work(protocol::kMaxBatch + 1, 1),
       "work.items holds 257, above the limit of 256"},
      {"4097 acknowledged", acknowledge(protocol::kMaxAcknowledged + 1, 1),
       "acknowledge.individuals holds 4097, above the limit of 4096"},
      {"individual 2^63 acknowledged", acknowledge(1, kBeyondIndividuals),
       "acknowledge.individuals[0] 9223372036854775808 outside"},
  };
  for (const Case& c : cases) master.Send(id, c.envelope);
  // Then a welcome within the limits: the worker asks for work, and does
  // what it is given.
  master.Send(id, welcome(1000));
  ASSERT_TRUE(
      master
          .ReceiveEnvelope(id, kShortWait,
                           [](const v1::Envelope& e) { return e.has_credit(); })
          .has_value())
      << worker.output();
  master.Send(id, work(1, 5));
  const std::optional<RoutedMessage> results = master.ReceiveEnvelope(
      id, kLongWait, [](const v1::Envelope& e) { return e.has_results(); });
  ASSERT_TRUE(results.has_value()) << worker.output();
  const Result<v1::Envelope> decoded = protocol::Decode(results->frames[0]);
  ASSERT_TRUE(decoded.ok());
  const v1::WorkResult& r = decoded->results().results(0);
  EXPECT_EQ(r.individual(), 5u);
  ExpectSameResult(r.result(), DirectResult(genome, config_), 5);

  const std::string log = worker.output();
  for (const Case& c : cases) {
    EXPECT_NE(
        log.find("ignored a malformed message from the master: " + c.reason),
        std::string::npos)
        << c.what << "\n"
        << log;
  }
  EXPECT_TRUE(worker.Running());
  ASSERT_TRUE(worker.Signal(SIGTERM));
  ASSERT_TRUE(worker.WaitExit(kShortWait));
  EXPECT_EQ(worker.exit_code(), 0) << worker.Describe();
}

// A Work with one item out of range (an individual of 2^63, which only a
// non-conforming master sends) beside three valid ones: the worker
// evaluates the three, gives back the credit of the fourth at once, and
// says which item it left out.
TEST_F(DispatchTest, WorkerEvaluatesTheValidItemsBesideAnOutOfRangeOne) {
  FakeMaster master(context_);
  WorkerProcess worker(SlackWorker(master));
  ASSERT_TRUE(worker.started());
  const std::optional<RoutedMessage> hello = master.ReceiveEnvelope(
      "", kShortWait, [](const v1::Envelope& e) { return e.has_hello(); });
  ASSERT_TRUE(hello.has_value());
  const std::string& id = hello->identity;

  const v1::Config config = ConfigToProto(config_);
  master.Send(id, FakeWelcome(config, 1000));
  ASSERT_TRUE(
      master
          .ReceiveEnvelope(id, kShortWait,
                           [](const v1::Envelope& e) { return e.has_credit(); })
          .has_value())
      << worker.output();

  const v1::Genome genome = DataGenome("seed-1198");
  v1::Envelope work;
  work.mutable_work()->set_config_hash(protocol::ConfigHash(config));
  for (const uint64_t individual :
       {uint64_t{5}, uint64_t{6}, kBeyondIndividuals, uint64_t{8}}) {
    v1::WorkItem* item = work.mutable_work()->add_items();
    item->set_individual(individual);
    *item->mutable_genome() = genome;
    item->set_genome_hash(protocol::GenomeHash(genome));
  }
  master.Send(id, work);
  std::set<uint64_t> returned;
  std::vector<v1::Envelope> seen;
  ASSERT_TRUE(master
                  .ReceiveEnvelope(
                      id, kLongWait,
                      [&](const v1::Envelope& e) {
                        for (const v1::WorkResult& r : e.results().results()) {
                          returned.insert(r.individual());
                          ExpectSameResult(r.result(),
                                           DirectResult(genome, config_),
                                           r.individual());
                        }
                        return returned.size() == 3;
                      },
                      &seen)
                  .has_value())
      << worker.output();
  EXPECT_EQ(returned, (std::set<uint64_t>{5, 6, 8}));
  // The first credit after the Work is the left-out item's, before any
  // result could earn one.
  const auto credit = std::find_if(seen.begin(), seen.end(),
                                   [](auto& e) { return e.has_credit(); });
  ASSERT_NE(credit, seen.end());
  EXPECT_EQ(credit->credit().credit(), 1u);
  EXPECT_LT(credit - seen.begin(),
            std::find_if(seen.begin(), seen.end(), [](auto& e) {
              return e.has_results();
            }) - seen.begin());
  EXPECT_NE(worker.output().find(
                "ignored a work item from the master: work.items[2].individual "
                "9223372036854775808 outside [0, 9223372036854775807]"),
            std::string::npos)
      << worker.output();
  EXPECT_TRUE(worker.Running());
  ASSERT_TRUE(worker.Signal(SIGTERM));
  ASSERT_TRUE(worker.WaitExit(kShortWait));
}

// The hello of issue 14: a host name of 16 MiB. ZeroMQ drops it on the
// master's socket limit (kMaxWorkerMessageBytes) before anything reads it;
// one of 1 MiB, within that limit, is refused from its frame's size,
// unparsed, in one line. Meanwhile a real worker is served throughout.
TEST_F(DispatchTest, HugeHelloIsRefusedWithoutStallingTheMasterOrItsLog) {
  // The hellos are made before anything runs and sent without a copy, as
  // a peer in another process would send them: the test's thread is the
  // master's, and making 16 MiB takes it a while. Static, because ZeroMQ
  // may read them until the context ends.
  static const std::vector<std::string> hellos = [] {
    std::vector<std::string> made;
    for (const size_t host_bytes : {size_t{16} << 20, size_t{1} << 20}) {
      v1::Envelope hello = FakeHello(1, 6666);
      hello.mutable_hello()->set_host(std::string(host_bytes, 'h'));
      made.push_back(protocol::Encode(hello));
    }
    return made;
  }();
  const std::vector<Individual> population = Population(MixedGenomes(40), 1);
  ASSERT_TRUE(StartDispatcher());
  WorkerProcess worker(Worker(1));
  ASSERT_TRUE(worker.started());
  ASSERT_TRUE(Serve([&] { return dispatcher_->workers() == 1; }, kShortWait));
  size_t next = 0;
  for (const std::string& hello : hellos) {
    SCOPED_TRACE("a hello of " + std::to_string(hello.size()) + " bytes");
    Submit({population.begin() + next, population.begin() + next + 20});
    next += 20;
    const size_t from = log_.size();
    {
      FakeWorker stranger(context_, dispatcher_->endpoint());
      stranger.set_silent(true);
      stranger.SendZeroCopy(hello.data(), hello.size());
      // Until the real worker has done all there is (the stranger's bytes
      // arrive meanwhile), and a little longer.
      ASSERT_TRUE(ServeUntilAllDone(kLongWait, [&] { stranger.Pump(); }))
          << log_.Dump(from);
      ServeFor(milliseconds(100), [&] { stranger.Pump(); });
      EXPECT_FALSE(stranger.welcomed());
      EXPECT_FALSE(stranger.refusal().has_value());
    }
    EXPECT_LE(log_.size(), from + 1) << log_.Dump(from);
    for (size_t i = from; i < log_.size(); ++i) {
      const std::string line = log_.lines()[i];
      EXPECT_LT(line.size(), 200u) << line;
    }
    if (hello.size() < static_cast<size_t>(protocol::kMaxWorkerMessageBytes)) {
      // Within the socket's limit: refused by its size, unparsed.
      EXPECT_EQ(log_.Count({"ignored a malformed message from an unknown "
                            "peer: a hello of " +
                            std::to_string(hello.size()) +
                            " bytes, above the limit of 4096"},
                           from),
                1)
          << log_.Dump(from);
    }
  }
  ExpectEachCompletedOnceAsEvaluatedDirectly(
      {population.begin(), population.begin() + next});
  EXPECT_EQ(CompletingWorkers(), std::set<std::string>{worker.name()});
  EXPECT_EQ(log_.Count({"silent"}), 0) << log_.Dump();
  EXPECT_EQ(log_.Count({"reconnected"}), 0) << log_.Dump();
  EXPECT_EQ(dispatcher_->workers(), 1u);
}

TEST_F(DispatchTest, PeersStringsReachTheLogEscapedAndCutShort) {
  ASSERT_TRUE(StartDispatcher(SimulatedOptions()));
  const size_t from = log_.size();
  FakeWorker peer(context_, dispatcher_->endpoint(), clock_);
  v1::Envelope hello = FakeHello(1, 5353);
  hello.mutable_hello()->set_host("evil\n2026-01-01T00:00:00.000Z master: " +
                                  std::string(200, 'x'));
  hello.mutable_hello()->set_build_id("other\r\nbuild");
  peer.Send(hello);
  ASSERT_TRUE(Serve([&] { return peer.refusal().has_value(); }, kShortWait,
                    [&] { peer.Pump(); }))
      << log_.Dump();
  ASSERT_EQ(log_.size(), from + 1) << log_.Dump();
  const std::string line = log_.lines()[from];
  EXPECT_EQ(line.find('\n'), std::string::npos) << line;
  EXPECT_EQ(line.find('\r'), std::string::npos) << line;
  EXPECT_NE(line.find("refused worker evil\\n2026-01-01T00:00:00.000Z master: "
                      "xxxxxxxxxx"),
            std::string::npos)
      << line;
  EXPECT_NE(line.find("...:5353"), std::string::npos) << line;
  EXPECT_NE(line.find("build \"other\\r\\nbuild\""), std::string::npos) << line;
  EXPECT_LT(line.size(), 400u) << line;
  EXPECT_EQ(peer.refusal()->find('\n'), std::string::npos) << *peer.refusal();

  // A host beyond kMaxHostBytes is refused, told why, and named cut short.
  const size_t long_from = log_.size();
  FakeWorker long_host(context_, dispatcher_->endpoint(), clock_);
  v1::Envelope long_hello = FakeHello(1, 5454);
  long_hello.mutable_hello()->set_host(
      std::string(protocol::kMaxHostBytes + 1, 'h'));
  long_host.Send(long_hello);
  ASSERT_TRUE(Serve([&] { return long_host.refusal().has_value(); }, kShortWait,
                    [&] { long_host.Pump(); }))
      << log_.Dump();
  EXPECT_EQ(*long_host.refusal(),
            "hello.host of 256 bytes, above the limit of 255");
  ASSERT_EQ(log_.size(), long_from + 1) << log_.Dump();
  const std::string long_line = log_.lines()[long_from];
  EXPECT_EQ(long_line.rfind("refused worker " + std::string(64, 'h') +
                                "...:5454: hello.host of 256 bytes",
                            0),
            0u)
      << long_line;
  EXPECT_LT(long_line.size(), 200u) << long_line;
  EXPECT_FALSE(long_host.welcomed());
}

}  // namespace
}  // namespace animat::testing
