// The lease scheduler (master/dispatch/lease_scheduler.h) driven directly:
// messages in, a recording outbox out, a manual clock for time. No socket,
// no worker process: each test says exactly which events happen when.
#include "master/dispatch/lease_scheduler.h"

#include <gtest/gtest.h>

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

v1::Envelope Hello(int threads, uint32_t pid) {
  v1::Envelope envelope;
  envelope.set_protocol_version(protocol::kVersion);
  v1::Hello* hello = envelope.mutable_hello();
  hello->set_protocol_version(protocol::kVersion);
  hello->set_build_id(protocol::BuildId());
  hello->set_threads(static_cast<uint32_t>(threads));
  hello->set_host("test-worker");
  hello->set_pid(pid);
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

}  // namespace
}  // namespace animat
