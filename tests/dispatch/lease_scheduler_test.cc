// The lease scheduler (master/dispatch/lease_scheduler.h) driven directly:
// messages in, a recording outbox out, a manual clock for time. No socket,
// no worker process: each test says exactly which events happen when.
#include "master/dispatch/lease_scheduler.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "common/base/clock.h"
#include "common/protocol/genome_wire.h"
#include "common/protocol/protocol.h"

namespace animat {
namespace {

using std::chrono::milliseconds;

// What the scheduler sent, decoded, per peer; deliveries to the peers in
// `refuse` fail.
class RecordingOutbox : public Outbox {
 public:
  struct Sent {
    std::string identity;
    v1::Envelope envelope;
  };
  bool Deliver(const std::string& identity, const std::string& bytes,
               std::string* problem) override {
    if (identity == unreachable) {
      *problem = "its queue is full";
      return false;
    }
    Result<v1::Envelope> decoded = protocol::Decode(bytes);
    EXPECT_TRUE(decoded.ok()) << decoded.status().message();
    if (decoded.ok()) sent.push_back({identity, *decoded});
    return true;
  }
  // The messages of one kind sent to `identity`, oldest first.
  std::vector<v1::Envelope> Of(const std::string& identity,
                               v1::Envelope::BodyCase body) const {
    std::vector<v1::Envelope> found;
    for (const Sent& s : sent) {
      if (s.identity == identity && s.envelope.body_case() == body) {
        found.push_back(s.envelope);
      }
    }
    return found;
  }
  std::vector<Sent> sent;
  std::string unreachable;
};

// `instance`: Hello.instance (0: none).
v1::Envelope Hello(int threads, uint32_t pid, uint64_t instance = 0) {
  v1::Envelope envelope;
  envelope.set_protocol_version(protocol::kVersion);
  v1::Hello* hello = envelope.mutable_hello();
  hello->set_protocol_version(protocol::kVersion);
  hello->set_build_id(protocol::BuildId());
  hello->set_threads(static_cast<uint32_t>(threads));
  hello->set_host("test-worker");
  hello->set_pid(pid);
  hello->set_instance(instance);
  return envelope;
}

v1::Envelope Credit(uint32_t credit) {
  v1::Envelope envelope;
  envelope.mutable_credit()->set_credit(credit);
  return envelope;
}

// A genome the scheduler only carries: any bytes do, a distinct one per
// individual.
protocol::SerializedGenome GenomeOf(uint64_t individual) {
  v1::Genome genome;
  v1::Element* element = genome.add_elements();
  element->set_x(static_cast<double>(individual));
  return protocol::SerializeGenome(genome);
}

v1::Envelope Heartbeat() {
  v1::Envelope envelope;
  envelope.mutable_heartbeat();
  return envelope;
}

v1::Envelope ResultFor(uint64_t individual, double fitness) {
  v1::Envelope envelope;
  v1::WorkResult* r = envelope.mutable_results()->add_results();
  r->set_individual(individual);
  r->set_genome_hash(GenomeOf(individual).hash);
  r->mutable_result()->set_status(v1::EvaluationResult::OK);
  r->mutable_result()->set_fitness(fitness);
  r->set_wall_seconds(0.5);
  return envelope;
}

std::vector<uint64_t> ItemsOf(const std::vector<v1::Envelope>& works) {
  std::vector<uint64_t> ids;
  for (const v1::Envelope& w : works) {
    for (const v1::WorkItem& item : w.work().items()) {
      ids.push_back(item.individual());
    }
  }
  return ids;
}

class LeaseSchedulerTest : public ::testing::Test {
 protected:
  LeaseSchedulerTest() {
    options_.clock = &clock_;
    options_.heartbeat_ms = 100;
    options_.lease_ms = 1000;
    options_.log = [this](std::string_view line) {
      log_.push_back(std::string(line));
    };
    options_.idle_notice_ms = 0;
  }
  LeaseScheduler& Start() {
    scheduler_ =
        std::make_unique<LeaseScheduler>(options_, v1::Config{}, &outbox_);
    return *scheduler_;
  }
  // Hands `envelope` from `identity` to the scheduler, then lets it
  // dispatch.
  void From(const std::string& identity, const v1::Envelope& envelope) {
    scheduler_->Handle(identity, envelope, &done_);
    scheduler_->Dispatch();
  }
  void Pass(milliseconds time) {
    clock_.Advance(time);
    scheduler_->Housekeep(&done_);
    scheduler_->Dispatch();
  }

  ManualClock clock_;
  SchedulerOptions options_;
  RecordingOutbox outbox_;
  // The log lines containing `part`.
  int Logged(std::string_view part) const {
    int n = 0;
    for (const std::string& line : log_) {
      n += line.find(part) != std::string::npos;
    }
    return n;
  }

  std::vector<std::string> log_;
  std::vector<Completion> done_;
  std::unique_ptr<LeaseScheduler> scheduler_;
};

TEST_F(LeaseSchedulerTest, AGreetedWorkerWithCreditGetsTheQueueInOrder) {
  LeaseScheduler& s = Start();
  for (uint64_t id : {7u, 3u, 5u}) s.Submit(id, GenomeOf(id));
  From("a", Hello(1, 11));
  ASSERT_EQ(outbox_.Of("a", v1::Envelope::kWelcome).size(), 1u);
  EXPECT_TRUE(outbox_.Of("a", v1::Envelope::kWork).empty());  // No credit.
  From("a", Credit(2));
  EXPECT_EQ(ItemsOf(outbox_.Of("a", v1::Envelope::kWork)),
            (std::vector<uint64_t>{7, 3}));
  From("a", ResultFor(7, 1.5));
  ASSERT_EQ(done_.size(), 1u);
  EXPECT_EQ(done_[0].individual, 7u);
  EXPECT_EQ(done_[0].result.fitness(), 1.5);
  EXPECT_EQ(done_[0].worker, "test-worker:11");
  EXPECT_EQ(s.pending(), 2u);
  // Acknowledged on receipt.
  ASSERT_EQ(outbox_.Of("a", v1::Envelope::kAcknowledge).size(), 1u);
  From("a", Credit(1));
  EXPECT_EQ(ItemsOf(outbox_.Of("a", v1::Envelope::kWork)),
            (std::vector<uint64_t>{7, 3, 5}));
}

TEST_F(LeaseSchedulerTest,
       AnExpiredLeaseGoesToAnotherWorkerAndTheFirstResultWins) {
  LeaseScheduler& s = Start();
  s.Submit(1, GenomeOf(1));
  From("a", Hello(1, 11));
  From("a", Credit(1));
  ASSERT_EQ(ItemsOf(outbox_.Of("a", v1::Envelope::kWork)),
            std::vector<uint64_t>{1});
  From("b", Hello(1, 12));
  From("b", Credit(1));
  // Both keep talking; the lease runs out.
  for (int i = 0; i < 11; ++i) {
    From("a", Heartbeat());
    From("b", Heartbeat());
    Pass(milliseconds(100));
  }
  EXPECT_EQ(s.stats().requeued, 1);
  EXPECT_EQ(ItemsOf(outbox_.Of("b", v1::Envelope::kWork)),
            std::vector<uint64_t>{1});
  From("b", ResultFor(1, 2.0));
  From("a", ResultFor(1, 3.0));  // Late: ignored.
  ASSERT_EQ(done_.size(), 1u);
  EXPECT_EQ(done_[0].result.fitness(), 2.0);
  EXPECT_EQ(done_[0].attempts, 1);
  EXPECT_EQ(s.stats().ignored, 1);
}

// Each completion carries the instruction-set path its worker named, in
// lower case as the store records it; none from a worker that names none.
TEST_F(LeaseSchedulerTest, ACompletionCarriesThePathThatEvaluatedIt) {
  LeaseScheduler& s = Start();
  for (uint64_t id : {7u, 3u}) s.Submit(id, GenomeOf(id));
  From("a", Hello(1, 11));
  From("a", Credit(2));
  v1::Envelope seven = ResultFor(7, 1.5);
  seven.mutable_results()->mutable_results(0)->set_isa(v1::WorkResult::AVX2);
  From("a", seven);
  From("a", ResultFor(3, 2.5));
  ASSERT_EQ(done_.size(), 2u);
  EXPECT_EQ(done_[0].isa, "avx2");
  EXPECT_EQ(done_[0].wall_seconds, 0.5);
  EXPECT_EQ(done_[1].isa, "");
  EXPECT_EQ(s.pending(), 0u);
}

TEST_F(LeaseSchedulerTest, ASilentWorkerIsDroppedAndItsLeasesGoBack) {
  LeaseScheduler& s = Start();
  s.Submit(1, GenomeOf(1));
  s.Submit(2, GenomeOf(2));
  From("a", Hello(1, 11));
  From("a", Credit(2));
  ASSERT_EQ(ItemsOf(outbox_.Of("a", v1::Envelope::kWork)),
            (std::vector<uint64_t>{1, 2}));
  // kLiveness heartbeat intervals of silence, and a little more.
  Pass(milliseconds(protocol::kLiveness * 100 + 1));
  EXPECT_EQ(s.workers(), 0u);
  EXPECT_EQ(s.stats().requeued, 2);
  // A worker that dies with work is evidence of nothing yet: each is a
  // suspect, then sent alone to a worker holding nothing else.
  From("b", Hello(1, 12));
  From("b", Credit(2));
  const std::vector<v1::Envelope> works = outbox_.Of("b", v1::Envelope::kWork);
  ASSERT_EQ(works.size(), 1u);
  EXPECT_EQ(works[0].work().items_size(), 1);
}

TEST_F(LeaseSchedulerTest, WorkThatCannotBeDeliveredReturnsWithItsCredit) {
  LeaseScheduler& s = Start();
  s.Submit(1, GenomeOf(1));
  From("a", Hello(1, 11));
  outbox_.unreachable = "a";
  From("a", Credit(1));
  EXPECT_EQ(s.stats().requeued, 1);
  EXPECT_EQ(s.pending(), 1u);
  outbox_.unreachable.clear();
  Pass(milliseconds(1));
  EXPECT_EQ(ItemsOf(outbox_.Of("a", v1::Envelope::kWork)),
            std::vector<uint64_t>{1});
}

TEST_F(LeaseSchedulerTest, RefusalsSayWhyAndGreetNobody) {
  LeaseScheduler& s = Start();
  v1::Envelope other_build = Hello(1, 11);
  other_build.mutable_hello()->set_build_id("another build");
  From("a", other_build);
  ASSERT_EQ(outbox_.Of("a", v1::Envelope::kRefuse).size(), 1u);
  EXPECT_NE(outbox_.Of("a", v1::Envelope::kRefuse)[0].refuse().reason().find(
                "differs from the master's"),
            std::string::npos);
  s.RefuseMalformed("b", Hello(0, 12).hello(),
                    "hello.threads 0 outside [1, 65536]");
  ASSERT_EQ(outbox_.Of("b", v1::Envelope::kRefuse).size(), 1u);
  EXPECT_EQ(s.workers(), 0u);
  EXPECT_EQ(s.stats().refused, 2);
  // A message from a peer never greeted: logged once, then only counted.
  From("c", Credit(1));
  From("c", Credit(1));
  EXPECT_EQ(s.stats().ignored, 2);
  EXPECT_EQ(s.PeerName("c"), "an unknown peer");
}

TEST_F(LeaseSchedulerTest, ResultsAreAcknowledgedOnlyOnceRecordedWhenAsked) {
  options_.acknowledge_on_receipt = false;
  LeaseScheduler& s = Start();
  s.Submit(1, GenomeOf(1));
  s.Submit(2, GenomeOf(2));
  From("a", Hello(1, 11));
  From("a", Credit(2));
  From("a", ResultFor(1, 1.0));
  From("a", ResultFor(2, 2.0));
  ASSERT_EQ(done_.size(), 2u);
  EXPECT_TRUE(outbox_.Of("a", v1::Envelope::kAcknowledge).empty());
  s.Acknowledge({2, 9});  // 9 was never completed here: nothing.
  const std::vector<v1::Envelope> acks =
      outbox_.Of("a", v1::Envelope::kAcknowledge);
  ASSERT_EQ(acks.size(), 1u);
  ASSERT_EQ(acks[0].acknowledge().individuals_size(), 1);
  EXPECT_EQ(acks[0].acknowledge().individuals(0), 2u);
  s.Acknowledge({2});  // Already acknowledged: nothing more.
  EXPECT_EQ(outbox_.Of("a", v1::Envelope::kAcknowledge).size(), 1u);
}

TEST_F(LeaseSchedulerTest, CreditBeyondTheCapIsCappedAndSaidOnce) {
  LeaseScheduler& s = Start();
  for (uint64_t id = 1; id <= 20; ++id) s.Submit(id, GenomeOf(id));
  From("a", Hello(1, 11));
  From("a", Credit(1000));
  // One thread: threads x kPrefetch x kCreditCapFactor.
  const size_t cap = protocol::kPrefetch * protocol::kCreditCapFactor;
  EXPECT_EQ(ItemsOf(outbox_.Of("a", v1::Envelope::kWork)).size(), cap);
  EXPECT_EQ(s.stats().ignored, 1);
}

TEST_F(LeaseSchedulerTest, AGoodbyeHandsWorkBackWithoutCountingAnAttempt) {
  LeaseScheduler& s = Start();
  s.Submit(1, GenomeOf(1));
  s.Submit(2, GenomeOf(2));
  From("a", Hello(1, 11));
  From("a", Credit(1));
  v1::Envelope goodbye;
  goodbye.mutable_goodbye()->set_reason("stopping");
  goodbye.mutable_goodbye()->add_returned(1);
  goodbye.mutable_goodbye()->add_returned(2);  // Not its lease: ignored.
  From("a", goodbye);
  EXPECT_EQ(s.workers(), 0u);
  // Next in line again, not a suspect: a new worker gets both at once.
  From("b", Hello(1, 12));
  From("b", Credit(2));
  EXPECT_EQ(ItemsOf(outbox_.Of("b", v1::Envelope::kWork)),
            (std::vector<uint64_t>{1, 2}));
  From("b", ResultFor(1, 1.0));
  ASSERT_EQ(done_.size(), 1u);
  EXPECT_EQ(done_[0].attempts, 0);
}

// On the manual clock the deadlines hold to the millisecond.

TEST_F(LeaseSchedulerTest, ALeaseEndsOnceLeaseMsHavePassedAndNotBefore) {
  options_.lease_ms = 200;  // Shorter than the liveness (300 ms).
  LeaseScheduler& s = Start();
  s.Submit(1, GenomeOf(1));
  From("a", Hello(1, 11));
  From("a", Credit(1));
  ASSERT_EQ(ItemsOf(outbox_.Of("a", v1::Envelope::kWork)),
            std::vector<uint64_t>{1});
  Pass(milliseconds(200));
  EXPECT_EQ(Logged("expired"), 0);
  EXPECT_EQ(s.stats().requeued, 0);
  Pass(milliseconds(1));
  EXPECT_EQ(Logged("lease of individual 1 on test-worker:11 expired"), 1);
  EXPECT_EQ(s.stats().requeued, 1);
  EXPECT_EQ(s.workers(), 1u);  // Not silent for long enough.
}

TEST_F(LeaseSchedulerTest, AWorkerIsDroppedOnlyAfterThreeHeartbeatsOfSilence) {
  LeaseScheduler& s = Start();
  s.Submit(1, GenomeOf(1));
  From("a", Hello(1, 11));
  From("a", Credit(1));
  // Any message is a sign of life: the silence starts again.
  Pass(milliseconds(250));
  From("a", Heartbeat());
  Pass(milliseconds(protocol::kLiveness * 100));
  EXPECT_EQ(s.workers(), 1u);
  Pass(milliseconds(1));
  EXPECT_EQ(s.workers(), 0u);
  EXPECT_EQ(Logged("worker test-worker:11 silent for 300 ms; 1 leases back "
                   "in the queue"),
            1);
  EXPECT_EQ(s.stats().requeued, 1);
}

TEST_F(LeaseSchedulerTest, AHeartbeatGoesOutAfterAnIntervalWithoutMessages) {
  Start();
  From("a", Hello(1, 11));  // Welcomed, now.
  ASSERT_EQ(outbox_.Of("a", v1::Envelope::kWelcome).size(), 1u);
  const auto heartbeats = [&] {
    return outbox_.Of("a", v1::Envelope::kHeartbeat).size();
  };
  Pass(milliseconds(99));
  EXPECT_EQ(heartbeats(), 0u);
  Pass(milliseconds(1));
  EXPECT_EQ(heartbeats(), 1u);
  Pass(milliseconds(99));
  EXPECT_EQ(heartbeats(), 1u);
  Pass(milliseconds(1));
  EXPECT_EQ(heartbeats(), 2u);
}

// A worker process that took its master for lost reconnects on a new
// connection with the Hello.instance of its first: its old session ends
// at once, and the work it held goes back without an attempt counted,
// however often it happens. Another process that shares host:pid (another
// instance) is another worker.
TEST_F(LeaseSchedulerTest, AWorkerReconnectingUnderItsInstanceCostsNoAttempt) {
  LeaseScheduler& s = Start();
  s.Submit(1, GenomeOf(1));
  constexpr uint64_t kInstance = 0x5eed5eed5eed5eedull;
  std::string session;
  for (int n = 1; n <= protocol::kMaxAttempts + 2; ++n) {
    SCOPED_TRACE("session " + std::to_string(n));
    session = "session-" + std::to_string(n);
    From(session, Hello(1, 11, kInstance));
    ASSERT_EQ(outbox_.Of(session, v1::Envelope::kWelcome).size(), 1u);
    EXPECT_EQ(Logged("worker test-worker:11 reconnected; 1 leases of its old "
                     "session back in the queue"),
              n - 1);
    From(session, Credit(1));
    EXPECT_EQ(ItemsOf(outbox_.Of(session, v1::Envelope::kWork)),
              std::vector<uint64_t>{1});
    EXPECT_EQ(s.workers(), 1u);
  }
  From("other", Hello(1, 11, kInstance + 1));
  EXPECT_EQ(s.workers(), 2u);
  From(session, ResultFor(1, 4.0));
  ASSERT_EQ(done_.size(), 1u);
  EXPECT_EQ(done_[0].attempts, 0);
  EXPECT_EQ(s.stats().isolated, 0);
  EXPECT_EQ(Logged("silent"), 0);
}

// A suspect goes alone to a worker holding nothing else, so a genome that
// kills its workers does not use up the attempts of the others. Each
// worker here dies (falls silent) whenever it holds the suspect, and
// answers everything else.
TEST_F(LeaseSchedulerTest, ASuspectIsLeasedAloneSoItTakesNobodyDownWithIt) {
  LeaseScheduler& s = Start();
  constexpr uint64_t kSuspect = 1;
  constexpr uint64_t kCompanion = 2;
  s.Submit(kSuspect, GenomeOf(kSuspect));
  s.Submit(kCompanion, GenomeOf(kCompanion));
  for (int round = 1; round <= protocol::kMaxAttempts; ++round) {
    SCOPED_TRACE("round " + std::to_string(round));
    const std::string worker = "worker-" + std::to_string(round);
    From(worker, Hello(1, static_cast<uint32_t>(100 + round)));
    From(worker, Credit(2));
    // Answers what it holds until it holds the suspect.
    for (size_t answered = 0;;) {
      const std::vector<uint64_t> held =
          ItemsOf(outbox_.Of(worker, v1::Envelope::kWork));
      if (std::count(held.begin(), held.end(), kSuspect) != 0) {
        if (round > 1) {
          EXPECT_EQ(held, std::vector<uint64_t>{kSuspect});
        }
        break;
      }
      ASSERT_LT(answered, held.size()) << "neither the suspect nor work";
      for (; answered < held.size(); ++answered) {
        From(worker, ResultFor(held[answered], 1.0));
        From(worker, Credit(1));
      }
    }
    Pass(milliseconds(protocol::kLiveness * 100 + 1));  // Dies.
    EXPECT_EQ(s.workers(), 0u);
  }
  // Without an isolation the suspect is offered to workers again; the
  // companion died once with it, in the first round, and no more.
  From("last", Hello(1, 200));
  From("last", Credit(2));
  for (size_t answered = 0;; ++answered) {
    const std::vector<uint64_t> held =
        ItemsOf(outbox_.Of("last", v1::Envelope::kWork));
    if (answered == held.size()) break;
    From("last", ResultFor(held[answered], 1.0));
    From("last", Credit(1));
  }
  EXPECT_EQ(s.pending(), 0u);
  for (const Completion& c : done_) {
    if (c.individual == kCompanion) {
      EXPECT_EQ(c.attempts, 1);
    } else {
      EXPECT_EQ(c.attempts, protocol::kMaxAttempts);
    }
  }
}

// Several configurations: a Work holds items of one, in queue order, and
// carries it to a worker the first time only.
TEST_F(LeaseSchedulerTest, EachWorkIsOfOneConfigurationCarriedOncePerWorker) {
  LeaseScheduler& s = Start();
  v1::Config other;
  other.mutable_physics()->set_drag_normal(10);
  Result<size_t> added = s.AddConfig(other);
  ASSERT_TRUE(added.ok());
  EXPECT_EQ(*added, 1u);
  EXPECT_EQ(*s.AddConfig(other), 1u);         // Again: the same index.
  EXPECT_EQ(*s.AddConfig(v1::Config{}), 0u);  // The welcome's.
  s.Submit(1, GenomeOf(1), 0);
  s.Submit(2, GenomeOf(2), 1);
  s.Submit(3, GenomeOf(3), 1);
  s.Submit(4, GenomeOf(4), 0);
  s.Submit(5, GenomeOf(5), 1);
  for (const std::string worker : {"a", "b"}) {
    From(worker, Hello(1, worker == "a" ? 11 : 12));
  }
  From("a", Credit(4));
  From("b", Credit(1));
  const std::vector<v1::Envelope> a = outbox_.Of("a", v1::Envelope::kWork);
  ASSERT_EQ(a.size(), 3u);
  const uint64_t other_hash = protocol::ConfigHash(other);
  EXPECT_EQ(a[0].work().config_hash(), s.config_hash());
  EXPECT_EQ(ItemsOf({a[0]}), std::vector<uint64_t>{1});
  EXPECT_FALSE(a[0].work().has_config());  // The welcome gave it.
  EXPECT_EQ(a[1].work().config_hash(), other_hash);
  EXPECT_EQ(ItemsOf({a[1]}), (std::vector<uint64_t>{2, 3}));
  ASSERT_TRUE(a[1].work().has_config());
  EXPECT_EQ(protocol::ConfigHash(a[1].work().config()), other_hash);
  EXPECT_EQ(ItemsOf({a[2]}), std::vector<uint64_t>{4});
  const std::vector<v1::Envelope> b = outbox_.Of("b", v1::Envelope::kWork);
  ASSERT_EQ(b.size(), 1u);
  EXPECT_EQ(ItemsOf(b), std::vector<uint64_t>{5});
  EXPECT_TRUE(b[0].work().has_config());  // New to b.
  // a, given more, gets configuration 1 named only.
  s.Submit(6, GenomeOf(6), 1);
  From("a", Credit(1));
  const std::vector<v1::Envelope> again = outbox_.Of("a", v1::Envelope::kWork);
  ASSERT_EQ(again.size(), 4u);
  EXPECT_EQ(again[3].work().config_hash(), other_hash);
  EXPECT_FALSE(again[3].work().has_config());
}

TEST_F(LeaseSchedulerTest, AtMostMaxConfigsConfigurationsAreServed) {
  LeaseScheduler& s = Start();
  for (size_t i = 1; i < protocol::kMaxConfigs; ++i) {
    v1::Config config;
    config.mutable_physics()->set_drag_normal(static_cast<double>(i));
    ASSERT_TRUE(s.AddConfig(config).ok()) << i;
  }
  v1::Config one_more;
  one_more.mutable_physics()->set_drag_normal(1000);
  Result<size_t> refused = s.AddConfig(one_more);
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.status().message().find("at most 64 model configurations"),
            std::string::npos);
}

}  // namespace
}  // namespace animat
