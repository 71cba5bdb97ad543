// Bad input on both sides of the dispatch: garbage from a raw socket to the
// master while a real worker keeps working, garbage from a fake master to
// a real worker process, and refusals (another protocol version, another
// build, a null-evaluation worker). Each bad input gets one log line and
// changes no result.
#include <unistd.h>

#include <csignal>
#include <cstdlib>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/dispatch/dispatch_harness.h"
#include "tests/dispatch/fake_peers.h"
#include "tests/dispatch/worker_process.h"

namespace animat::testing {
namespace {

// "protocol version V+1, expected V" and friends, for this build's V.
const std::string kThis = std::to_string(protocol::kVersion);
const std::string kNext = std::to_string(protocol::kVersion + 1);

// `size` bytes drawn from a fixed stream.
std::string RandomBytes(uint64_t seed, size_t size) {
  RandomStream stream(seed, 0, StreamPurpose::kRandomGenome);
  std::string bytes;
  while (bytes.size() < size) {
    const uint64_t word = stream.NextU64();
    for (int i = 0; i < 8 && bytes.size() < size; ++i) {
      bytes.push_back(static_cast<char>((word >> (8 * i)) & 0xff));
    }
  }
  return bytes;
}

struct BadInput {
  std::string what;
  std::function<void()> send;
  std::vector<std::string> logged;  // The line it must produce, in parts.
};

TEST_F(DispatchTest, MasterSurvivesGarbageAndKeepsServingCorrectWork) {
  const std::vector<Individual> population = Population(MixedGenomes(60), 1);
  // Made before anything runs (filling 64 MiB takes long enough in a
  // sanitizer build for peers to look dead) and sent without a copy; static
  // because ZeroMQ may read it until the context ends.
  static const std::string huge(protocol::kMaxMessageBytes + 1, '\0');
  const Individual& held = population[0];  // Leased to the garbage peer.
  size_t next = 1;                         // The next to submit.
  ASSERT_TRUE(StartDispatcher());
  Submit({held});

  // The garbage comes from a peer that said hello properly and holds a
  // lease (so that bad results for a pending individual reach the checks).
  FakeWorker peer(context_, dispatcher_->endpoint());
  peer.Hello(1, 4242);
  const std::string name = "fake-worker:4242";
  auto pump = [&] { peer.Pump(); };
  ASSERT_TRUE(Serve([&] { return peer.welcomed(); }, kShortWait, pump));
  peer.Credit(1);
  ASSERT_TRUE(
      Serve([&] { return !peer.work_items().empty(); }, kShortWait, pump));
  WorkerProcess worker(Worker(2));
  ASSERT_TRUE(worker.started());
  ASSERT_TRUE(
      Serve([&] { return dispatcher_->workers() == 2; }, kShortWait, pump));

  auto result_for_held = [&](const std::function<void(v1::WorkResult*)>& edit) {
    v1::Envelope envelope;
    v1::WorkResult* r = envelope.mutable_results()->add_results();
    r->set_individual(held.id);
    r->set_genome_hash(protocol::GenomeHash(held.genome));
    *r->mutable_result() = held.expected;
    r->mutable_result()->set_status(v1::EvaluationResult::OK);
    r->mutable_result()->set_fitness(1.0);
    edit(r);
    return envelope;
  };
  auto send_from_stranger = [&](const std::string& bytes) {
    FakeWorker stranger(context_, dispatcher_->endpoint());
    stranger.SendRaw(bytes);
    ServeFor(milliseconds(50));  // Delivered before the socket closes.
  };
  v1::Envelope other_version;
  other_version.set_protocol_version(protocol::kVersion + 1);
  other_version.mutable_heartbeat();
  v1::Envelope welcome_from_worker;
  welcome_from_worker.mutable_welcome()->set_build_id("x");
  welcome_from_worker.mutable_welcome()->set_heartbeat_ms(1000);
  v1::Envelope unknown_results;
  unknown_results.mutable_results()->add_results()->set_individual(999999);
  v1::Envelope huge_credit;
  huge_credit.mutable_credit()->set_credit(1u << 31);
  // This version (field 1, a one-byte varint), then field 99 (unknown to
  // this protocol) and nothing else.
  const std::string unknown_type = std::string("\x08") +
                                   static_cast<char>(protocol::kVersion) +
                                   std::string("\x98\x06\x01", 3);

  const std::vector<BadInput> inputs = {
      {"random bytes",
       [&] { peer.SendRaw(RandomBytes(7, 64)); },
       {"ignored a malformed message from " + name}},
      {"an empty frame",
       [&] { peer.SendRaw(""); },
       {"ignored a malformed message from " + name, "protocol version 0"}},
      {"a multi-frame message",
       [&] {
         peer.SendFrames({protocol::Encode(huge_credit), "b"});
       },
       {"ignored a message of 3 frames"}},
      {"another protocol version",
       [&] { peer.SendRaw(other_version.SerializeAsString()); },
       {"ignored a malformed message from " + name,
        "protocol version " + kNext + ", expected " + kThis}},
      {"an envelope without a body",
       [&] { peer.Send(v1::Envelope()); },
       {"ignored a malformed message from " + name, "without a body"}},
      {"an unknown message type",
       [&] { peer.SendRaw(unknown_type); },
       {"ignored a malformed message from " + name, "without a body"}},
      {"a message only a master sends",
       [&] { peer.Send(welcome_from_worker); },
       {"ignored an unexpected welcome from " + name}},
      {"results for an unknown individual",
       [&] { peer.Send(unknown_results); },
       {"ignored a result for individual 999999 from " + name,
        "unknown or already complete"}},
      {"a result for another genome",
       [&] {
         peer.Send(result_for_held([](v1::WorkResult* r) {
           r->set_genome_hash(r->genome_hash() + 1);
         }));
       },
       {"ignored a result for individual 1 from " + name, "another genome"}},
      {"a NaN fitness",
       [&] {
         peer.Send(result_for_held([](v1::WorkResult* r) {
           r->mutable_result()->set_fitness(
               std::numeric_limits<double>::quiet_NaN());
         }));
       },
       {"ignored an invalid result for individual 1 from " + name,
        "fitness nan"}},
      {"an infinite fitness",
       [&] {
         peer.Send(result_for_held([](v1::WorkResult* r) {
           r->mutable_result()->set_fitness(
               std::numeric_limits<double>::infinity());
         }));
       },
       {"ignored an invalid result for individual 1 from " + name,
        "fitness inf"}},
      {"a negative fitness",
       [&] {
         peer.Send(result_for_held([](v1::WorkResult* r) {
           r->mutable_result()->set_fitness(-1.0);
         }));
       },
       {"ignored an invalid result for individual 1", "fitness -1"}},
      {"status OK without a fitness",
       [&] {
         peer.Send(result_for_held(
             [](v1::WorkResult* r) { r->mutable_result()->clear_fitness(); }));
       },
       {"ignored an invalid result for individual 1",
        "status OK without a fitness"}},
      {"a body with a negative chamber count",
       [&] {
         peer.Send(result_for_held([](v1::WorkResult* r) {
           r->mutable_result()->mutable_body()->set_chambers(-3);
         }));
       },
       {"ignored an invalid result for individual 1 from " + name,
        "body chambers -3"}},
      {"a body with a negative spring count",
       [&] {
         peer.Send(result_for_held([](v1::WorkResult* r) {
           r->mutable_result()->mutable_body()->set_springs(-1);
         }));
       },
       {"ignored an invalid result for individual 1", "body springs -1"}},
      {"a body with a NaN spread",
       [&] {
         peer.Send(result_for_held([](v1::WorkResult* r) {
           r->mutable_result()->mutable_body()->set_spread_minor(
               std::numeric_limits<double>::quiet_NaN());
         }));
       },
       {"ignored an invalid result for individual 1", "body spread_minor nan"}},
      {"a body with an infinite spread",
       [&] {
         peer.Send(result_for_held([](v1::WorkResult* r) {
           r->mutable_result()->mutable_body()->set_spread_major(
               std::numeric_limits<double>::infinity());
         }));
       },
       {"ignored an invalid result for individual 1", "body spread_major inf"}},
      {"an unknown status",
       [&] {
         peer.Send(result_for_held([](v1::WorkResult* r) {
           r->mutable_result()->set_status(
               static_cast<v1::EvaluationResult::Status>(99));
         }));
       },
       {"ignored an invalid result for individual 1", "unknown status 99"}},
      {"a credit of 2^31",
       [&] { peer.Send(huge_credit); },
       {"ignored a malformed message from " + name,
        "credit.credit 2147483648 outside [1, 262144]"}},
      {"credit beyond the worker's cap",
       [&] { peer.Credit(5); },
       {"ignored credit beyond 4 from " + name}},
      {"random bytes from a stranger",
       [&] { send_from_stranger(RandomBytes(8, 100)); },
       {"ignored a malformed message from an unknown peer"}},
      {"results from a stranger",
       [&] { send_from_stranger(protocol::Encode(unknown_results)); },
       {"ignored a results message from a peer that has not said hello"}},
  };

  for (const BadInput& input : inputs) {
    SCOPED_TRACE(input.what);
    // Meanwhile, real work.
    Submit({population[next], population[next + 1]});
    next += 2;
    const size_t from = log_.size();
    const int64_t ignored = dispatcher_->stats().ignored;
    input.send();
    ASSERT_TRUE(Serve([&] { return log_.Count(input.logged, from) >= 1; },
                      kShortWait, pump))
        << log_.Dump(from);
    ServeFor(milliseconds(20), pump);  // A second line would show now.
    EXPECT_EQ(log_.Count({"ignored"}, from), 1) << log_.Dump(from);
    EXPECT_EQ(dispatcher_->stats().ignored, ignored + 1);
  }

  {
    SCOPED_TRACE("an oversize message");
    // ZeroMQ drops the connection (ZMQ_MAXMSGSIZE): nothing arrives, so
    // nothing is logged, and the master goes on.
    Submit({population[next], population[next + 1]});
    next += 2;
    const size_t from = log_.size();
    const int64_t ignored = dispatcher_->stats().ignored;
    FakeWorker oversize(context_, dispatcher_->endpoint());
    oversize.set_silent(true);
    oversize.WatchDisconnects(context_);
    oversize.SendZeroCopy(huge.data(), huge.size());
    EXPECT_TRUE(Serve([&] { return oversize.disconnects() > 0; }, kShortWait,
                      [&] {
                        pump();
                        oversize.Pump();
                      }));
    ServeFor(milliseconds(100), pump);
    EXPECT_EQ(log_.Count({"ignored"}, from), 0) << log_.Dump(from);
    EXPECT_EQ(dispatcher_->stats().ignored, ignored);
  }

  {
    SCOPED_TRACE("a hello of another build");
    Submit({population[next], population[next + 1]});
    next += 2;
    FakeWorker other_build(context_, dispatcher_->endpoint());
    other_build.set_silent(true);
    v1::Envelope hello = FakeHello(1, 4343);
    hello.mutable_hello()->set_build_id("animat 0.0.0 elsewhere");
    other_build.Send(hello);
    ASSERT_TRUE(Serve([&] { return other_build.refusal().has_value(); },
                      kShortWait,
                      [&] {
                        pump();
                        other_build.Pump();
                      }));
    const std::string& reason = *other_build.refusal();
    EXPECT_NE(reason.find("\"animat 0.0.0 elsewhere\""), std::string::npos)
        << reason;
    EXPECT_NE(reason.find("\"" + protocol::BuildId() + "\""), std::string::npos)
        << reason;
    EXPECT_FALSE(other_build.welcomed());
    EXPECT_EQ(log_.Count({"refused worker fake-worker:4343: build"}), 1)
        << log_.Dump();
    EXPECT_EQ(dispatcher_->stats().refused, 1);
  }

  // The peer leaves, handing back what it holds; everything submitted
  // completes once, as evaluated directly.
  v1::Envelope goodbye;
  for (const v1::WorkItem& item : peer.work_items()) {
    goodbye.mutable_goodbye()->add_returned(item.individual());
  }
  goodbye.mutable_goodbye()->set_reason("garbage over");
  peer.Send(goodbye);
  ASSERT_TRUE(ServeUntilAllDone());
  EXPECT_EQ(log_.Count({name + " said goodbye (garbage over), handing back " +
                        std::to_string(peer.work_items().size())}),
            1)
      << log_.Dump();
  EXPECT_EQ(dispatcher_->stats().ignored, static_cast<int64_t>(inputs.size()));
  ExpectEachCompletedOnceAsEvaluatedDirectly(
      {population.begin(), population.begin() + next});
  EXPECT_EQ(CompletingWorkers(), std::set<std::string>{worker.name()});
  EXPECT_TRUE(worker.Running());
}

TEST_F(DispatchTest, RefusesAWorkerOfAnotherProtocolVersionSayingWhich) {
  ASSERT_TRUE(StartDispatcher(SimulatedOptions()));
  FakeWorker peer(context_, dispatcher_->endpoint(), clock_);
  peer.set_silent(true);
  v1::Envelope hello = FakeHello(1, 5151);
  hello.mutable_hello()->set_protocol_version(protocol::kVersion + 1);
  peer.Send(hello);
  ASSERT_TRUE(Serve([&] { return peer.refusal().has_value(); }, kShortWait,
                    [&] { peer.Pump(); }))
      << log_.Dump();
  EXPECT_NE(peer.refusal()->find("protocol version " + kNext),
            std::string::npos)
      << *peer.refusal();
  EXPECT_NE(peer.refusal()->find("master's " + kThis), std::string::npos)
      << *peer.refusal();
  EXPECT_FALSE(peer.welcomed());
  EXPECT_EQ(dispatcher_->workers(), 0u);
  EXPECT_EQ(log_.Count(
                {"refused worker fake-worker:5151: protocol version " + kNext}),
            1)
      << log_.Dump();
}

// Regression: a worker of another protocol version stamps its envelopes with
// its own version, so protocol::Decode rejects its hello before
// Dispatcher::Greet can compare versions; the master logs "ignored a
// malformed message ... protocol version 2, expected 1" and never sends
// the Refuse, and the worker retries for ever without being told why.
TEST_F(DispatchTest, RefusesAWorkerWhoseEnvelopesCarryAnotherVersion) {
  ASSERT_TRUE(StartDispatcher(SimulatedOptions()));
  FakeWorker peer(context_, dispatcher_->endpoint(), clock_);
  peer.set_silent(true);
  v1::Envelope hello = FakeHello(1, 5252);
  hello.set_protocol_version(protocol::kVersion + 1);
  hello.mutable_hello()->set_protocol_version(protocol::kVersion + 1);
  peer.SendRaw(hello.SerializeAsString());
  // Until the master has dealt with the hello (a log line either way),
  // then a little longer for a refusal to arrive.
  Serve([&] { return peer.refusal().has_value() || log_.size() > 1; },
        kShortWait, [&] { peer.Pump(); });
  Serve([&] { return peer.refusal().has_value(); }, milliseconds(300),
        [&] { peer.Pump(); });
  ASSERT_TRUE(peer.refusal().has_value())
      << "no Refuse for a worker of protocol version 2; master log:\n"
      << log_.Dump();
  EXPECT_NE(peer.refusal()->find("protocol version " + kNext),
            std::string::npos)
      << *peer.refusal();
}

// Regression: Hello.threads is a uint32 taken as an int, and the credit cap
// threads * kPrefetch * 2 overflows for threads >= 2^29 (undefined
// behaviour: UBSan aborts the master; in an optimised build the cap wraps
// to a negative number and the worker never gets any work). Now a hello
// beyond kMaxThreads is refused (limits_test.cc); one at the limit gets
// work. Run in a child process so that a sanitizer abort does not take the
// other tests down.
TEST_F(DispatchTest, HelloClaimingHugeThreadCountDoesNotOverflowTheCreditCap) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  const auto gets_work = [this]() -> int {
    if (!StartDispatcher(SimulatedOptions())) return 2;
    Submit(Population(MixedGenomes(1), 1));
    FakeWorker peer(context_, dispatcher_->endpoint(), clock_);
    peer.Send(FakeHello(protocol::kMaxThreads, 6161));
    if (!Serve([&] { return peer.welcomed(); }, kShortWait,
               [&] { peer.Pump(); })) {
      return 3;
    }
    peer.Credit(1);
    Serve([&] { return !peer.work_items().empty(); }, milliseconds(500),
          [&] { peer.Pump(); });
    std::cerr << log_.Dump();
    return peer.work_items().empty() ? 1 : 0;
  };
  EXPECT_EXIT(_exit(gets_work()), ::testing::ExitedWithCode(0), "");
}

TEST_F(DispatchTest, WorkerSurvivesGarbageFromItsMasterAndAnswersCorrectly) {
  // No dispatcher: the test plays the master.
  FakeMaster master(context_);
  const v1::Config config = ConfigToProto(config_);
  const uint64_t config_hash = protocol::ConfigHash(config);
  const v1::Genome valid = DataGenome("seed-1198");
  v1::Genome zero_sign = valid;
  zero_sign.mutable_elements(0)->set_sign(0);
  v1::Genome infinite = valid;
  infinite.mutable_elements(3)->set_y(std::numeric_limits<double>::infinity());
  const v1::EvaluationResult valid_expected = DirectResult(valid, config_);
  ASSERT_EQ(valid_expected.status(), v1::EvaluationResult::OK);

  WorkerArgs args;
  args.endpoint = master.endpoint();
  args.threads = 1;
  args.heartbeat_ms = 1000;  // Slack: this test is not about liveness.
  WorkerProcess worker(args);
  ASSERT_TRUE(worker.started());
  const std::optional<RoutedMessage> hello = master.ReceiveEnvelope(
      "", kShortWait, [](const v1::Envelope& e) { return e.has_hello(); });
  ASSERT_TRUE(hello.has_value());
  const std::string& id = hello->identity;
  {
    const v1::Hello h = protocol::Decode(hello->frames[0])->hello();
    EXPECT_EQ(h.protocol_version(), protocol::kVersion);
    EXPECT_EQ(h.build_id(), protocol::BuildId());
    EXPECT_EQ(h.threads(), 1u);
    EXPECT_EQ(h.pid(), static_cast<uint64_t>(worker.pid()));
    EXPECT_FALSE(h.null_evaluation());
  }

  auto work = [&](uint64_t hash,
                  const std::vector<std::pair<uint64_t, v1::Genome>>& items) {
    v1::Envelope envelope;
    envelope.mutable_work()->set_config_hash(hash);
    for (const auto& [individual, genome] : items) {
      v1::WorkItem* item = envelope.mutable_work()->add_items();
      item->set_individual(individual);
      *item->mutable_genome() = genome;
      item->set_genome_hash(protocol::GenomeHash(genome));
    }
    return envelope;
  };
  auto welcome = [](const v1::Config& c, uint64_t hash) {
    return FakeWelcome(c, 1000, hash);
  };
  v1::Config bad_config = config;
  bad_config.mutable_evaluation()->set_motion_steps(-1);
  v1::Envelope other_version;
  other_version.set_protocol_version(protocol::kVersion + 1);
  other_version.mutable_heartbeat();

  master.SendFrames(id, {RandomBytes(9, 64)});
  master.SendFrames(id, {"a", "b"});
  master.SendFrames(id, {""});
  master.SendFrames(id, {other_version.SerializeAsString()});
  master.Send(id, v1::Envelope());
  master.Send(id, work(config_hash, {{1, valid}}));  // Before any welcome.
  master.Send(id, welcome(config, config_hash + 1));
  master.Send(id, welcome(bad_config, protocol::ConfigHash(bad_config)));
  master.Send(id, protocol::Decode(hello->frames[0]).value());  // Unexpected.
  master.Send(id, welcome(config, config_hash));

  std::vector<v1::Envelope> seen;
  const std::optional<RoutedMessage> credit = master.ReceiveEnvelope(
      id, kShortWait, [](const v1::Envelope& e) { return e.has_credit(); },
      &seen);
  ASSERT_TRUE(credit.has_value()) << worker.output();
  EXPECT_EQ(protocol::Decode(credit->frames[0])->credit().credit(),
            static_cast<uint32_t>(protocol::kPrefetch));

  master.Send(id, work(config_hash + 1, {{9, valid}}));  // Another config.
  master.Send(id,
              work(config_hash, {{1, valid}, {2, zero_sign}, {3, infinite}}));
  std::map<uint64_t, std::vector<v1::WorkResult>> results;
  auto all_answered = [&] {
    return results.count(1) != 0 && results.count(2) != 0 &&
           results.count(3) != 0;
  };
  const auto end = Steady::now() + kLongWait;
  while (!all_answered() && Steady::now() < end) {
    master.ReceiveEnvelope(
        id, milliseconds(50),
        [&](const v1::Envelope& e) {
          for (const v1::WorkResult& r : e.results().results()) {
            results[r.individual()].push_back(r);
          }
          return e.has_results();
        },
        &seen);
  }
  ASSERT_TRUE(all_answered()) << worker.output();
  master.ReceiveEnvelope(
      id, milliseconds(200), [](const v1::Envelope&) { return false; }, &seen);
  EXPECT_EQ(results.count(9), 0u);  // Work of another config: not run.
  for (const auto& [individual, answers] : results) {
    EXPECT_EQ(answers.size(), 1u) << "individual " << individual;
  }
  const v1::WorkResult& ok = results[1][0];
  ExpectSameResult(ok.result(), valid_expected, 1);
  EXPECT_EQ(ok.genome_hash(), protocol::GenomeHash(valid));
  for (const auto& [individual, field] :
       std::vector<std::pair<uint64_t, std::string>>{{2, "elements[0].sign"},
                                                     {3, "elements[3].y"}}) {
    const v1::EvaluationResult& r = results[individual][0].result();
    EXPECT_EQ(r.status(), v1::EvaluationResult::INVALID_GENOME)
        << "individual " << individual;
    EXPECT_NE(r.reason().find(field), std::string::npos) << r.reason();
    EXPECT_FALSE(r.has_fitness());
  }
  ExpectSameResult(results[2][0].result(), DirectResult(zero_sign, config_), 2);
  ExpectSameResult(results[3][0].result(), DirectResult(infinite, config_), 3);
  EXPECT_TRUE(worker.Running());

  // One line in the worker's log for each bad message.
  const std::string log = worker.output();
  for (const std::string& line : {
           std::string("ignored a malformed message from the master: not an "),
           std::string("ignored a multi-frame message from the master"),
           std::string("ignored a malformed message from the master: "
                       "protocol version 0"),
           "ignored a malformed message from the master: protocol version " +
               kNext + ", expected " + kThis,
           std::string("ignored a malformed message from the master: "
                       "envelope without a body"),
           std::string("before a welcome"),
           std::string("ignored a welcome with a bad configuration: "
                       "configuration "),
           std::string("evaluation.motion_steps"),
           std::string("ignored an unexpected hello from the master"),
           std::string("was never given to this worker, or forgotten"),
       }) {
    EXPECT_NE(log.find(line), std::string::npos) << line << "\n" << log;
  }

  // And it still stops cleanly: a goodbye, exit code 0.
  ASSERT_TRUE(worker.Signal(SIGTERM));
  const std::optional<RoutedMessage> goodbye = master.ReceiveEnvelope(
      id, kShortWait, [](const v1::Envelope& e) { return e.has_goodbye(); });
  ASSERT_TRUE(goodbye.has_value()) << worker.output();
  ASSERT_TRUE(worker.WaitExit(kShortWait));
  EXPECT_EQ(worker.exit_code(), 0) << worker.Describe();
}

TEST_F(DispatchTest, RefusedWorkerExitsWithCode3AndSaysWhy) {
  FakeMaster master(context_);
  WorkerArgs args;
  args.endpoint = master.endpoint();
  WorkerProcess worker(args);
  ASSERT_TRUE(worker.started());
  const std::optional<RoutedMessage> hello = master.ReceiveEnvelope(
      "", kShortWait, [](const v1::Envelope& e) { return e.has_hello(); });
  ASSERT_TRUE(hello.has_value());
  v1::Envelope refuse;
  refuse.mutable_refuse()->set_reason("the test master refuses you");
  master.Send(hello->identity, refuse);
  ASSERT_TRUE(worker.WaitExit(kShortWait)) << worker.output();
  EXPECT_EQ(worker.exit_code(), 3) << worker.Describe();
  EXPECT_NE(worker.output().find(
                "refused by the master: the test master refuses you"),
            std::string::npos)
      << worker.output();
}

// Regression: the Refuse of a master of another protocol version carries that
// version, so protocol::Decode rejects it and the worker logs "ignored a
// malformed message" and goes on retrying instead of exiting with the reason.
TEST_F(DispatchTest, WorkerRefusedByAMasterOfAnotherVersionExitsWithCode3) {
  FakeMaster master(context_);
  WorkerArgs args;
  args.endpoint = master.endpoint();
  WorkerProcess worker(args);
  ASSERT_TRUE(worker.started());
  const std::optional<RoutedMessage> hello = master.ReceiveEnvelope(
      "", kShortWait, [](const v1::Envelope& e) { return e.has_hello(); });
  ASSERT_TRUE(hello.has_value());
  v1::Envelope refuse;
  refuse.set_protocol_version(protocol::kVersion + 1);
  refuse.mutable_refuse()->set_reason("protocol version " + kThis +
                                      " differs from the master's " + kNext);
  master.SendFrames(hello->identity, {refuse.SerializeAsString()});
  // Until the worker has read the refusal (a log line either way), then a
  // little longer for it to exit.
  const auto end = Steady::now() + kShortWait;
  while (worker.Running() && Steady::now() < end &&
         worker.output().find("refuse") == std::string::npos &&
         worker.output().find("ignored") == std::string::npos) {
    std::this_thread::sleep_for(milliseconds(10));
  }
  const bool exited = worker.WaitExit(milliseconds(500));
  EXPECT_TRUE(exited) << "a worker refused by a master of protocol version 2 "
                         "goes on; its log:\n"
                      << worker.output();
  if (exited) {
    EXPECT_EQ(worker.exit_code(), 3) << worker.Describe();
  }
}

}  // namespace
}  // namespace animat::testing
