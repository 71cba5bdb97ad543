// Results are not lost between a worker and a master that dies before
// recording them: the dispatcher acknowledges each result on receipt, or,
// for a master that records results (acknowledge_on_receipt off), once it
// says they are recorded; a worker keeps every result it sent until then
// and sends it again to the next master that welcomes it.
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/dispatch/dispatch_harness.h"
#include "tests/dispatch/fake_peers.h"
#include "tests/dispatch/worker_process.h"

namespace animat::testing {
namespace {

// The individuals of every Acknowledge `fake` received, in order.
std::vector<uint64_t> Acknowledged(const FakeWorker& fake) {
  std::vector<uint64_t> ids;
  for (const v1::Envelope& e : fake.received()) {
    if (!e.has_acknowledge()) continue;
    for (uint64_t id : e.acknowledge().individuals()) ids.push_back(id);
  }
  return ids;
}

// A Results envelope with `item`'s result as evaluated directly.
v1::Envelope ResultOf(const v1::WorkItem& item,
                      const v1::EvaluationResult& result) {
  v1::Envelope envelope;
  v1::WorkResult* r = envelope.mutable_results()->add_results();
  r->set_individual(item.individual());
  r->set_genome_hash(item.genome_hash());
  *r->mutable_result() = result;
  r->set_wall_seconds(0.5);
  return envelope;
}

TEST_F(DispatchTest, ResultsAreAcknowledgedOnReceiptByDefault) {
  const Individual one = Population({DataGenome("seed-1198")}, 10)[0];
  ASSERT_TRUE(StartDispatcher(SimulatedOptions()));
  Submit({one});
  FakeWorker fake(context_, dispatcher_->endpoint(), clock_);
  auto pump = [&] { fake.Pump(); };
  fake.Hello(1, 5151);
  ASSERT_TRUE(Serve([&] { return fake.welcomed(); }, kShortWait, pump));
  fake.Credit(1);
  ASSERT_TRUE(
      Serve([&] { return fake.work_items().size() == 1; }, kShortWait, pump));
  fake.Send(ResultOf(fake.work_items()[0], one.expected));
  // A result for an individual the master does not know: of no use to it,
  // so acknowledged too (the worker may forget it).
  v1::WorkItem unknown = fake.work_items()[0];
  unknown.set_individual(999999);
  fake.Send(ResultOf(unknown, one.expected));
  ASSERT_TRUE(
      Serve([&] { return Acknowledged(fake).size() == 2; }, kShortWait, pump));
  EXPECT_EQ(Acknowledged(fake), (std::vector<uint64_t>{10, 999999}));
  EXPECT_EQ(CompletionsOf(one.id), 1);
}

TEST_F(DispatchTest, ARecordingMasterAcknowledgesOnceRecordedToWhoeverHoldsIt) {
  const std::vector<Individual> two =
      Population({DataGenome("seed-1198"), DataGenome("seed-1203")}, 20);
  DispatcherOptions options = SimulatedOptions();
  options.acknowledge_on_receipt = false;
  ASSERT_TRUE(StartDispatcher(options));
  Submit(two);
  FakeWorker fake(context_, dispatcher_->endpoint(), clock_);
  FakeWorker again(context_, dispatcher_->endpoint(), clock_);
  auto pump = [&] {
    fake.Pump();
    again.Pump();
  };
  fake.Hello(1, 5252, 77);
  ASSERT_TRUE(Serve([&] { return fake.welcomed(); }, kShortWait, pump));
  fake.Credit(2);
  ASSERT_TRUE(
      Serve([&] { return fake.work_items().size() == 2; }, kShortWait, pump));
  const v1::WorkItem first = fake.work_items()[0];
  const v1::WorkItem second = fake.work_items()[1];
  const auto expected = [&](const v1::WorkItem& item) {
    return item.individual() == two[0].id ? two[0].expected : two[1].expected;
  };
  fake.Send(ResultOf(first, expected(first)));
  fake.Send(ResultOf(second, expected(second)));
  ASSERT_TRUE(
      Serve([&] { return completions_.size() == 2; }, kShortWait, pump));
  // Completed, not yet recorded: nothing acknowledged.
  ServeFor(milliseconds(3 * kHeartbeatMs), pump);
  EXPECT_TRUE(Acknowledged(fake).empty());

  // The first is recorded: acknowledged to the worker that sent it.
  dispatcher_->Acknowledge({first.individual()});
  ASSERT_TRUE(
      Serve([&] { return Acknowledged(fake).size() == 1; }, kShortWait, pump));
  EXPECT_EQ(Acknowledged(fake), std::vector<uint64_t>{first.individual()});

  // The same process reconnects (same instance) and sends the second again:
  // not ignored, and acknowledged on the new connection once recorded.
  again.Hello(1, 5252, 77);
  ASSERT_TRUE(Serve([&] { return again.welcomed(); }, kShortWait, pump));
  const size_t ignored_before = log_.Count({"ignored a result"});
  again.Send(ResultOf(second, expected(second)));
  ServeFor(milliseconds(kHeartbeatMs), pump);
  EXPECT_EQ(log_.Count({"ignored a result"}), ignored_before) << log_.Dump();
  dispatcher_->Acknowledge({first.individual(), second.individual()});
  ASSERT_TRUE(
      Serve([&] { return Acknowledged(again).size() == 1; }, kShortWait, pump));
  EXPECT_EQ(Acknowledged(again), std::vector<uint64_t>{second.individual()});
  EXPECT_EQ(Acknowledged(fake), std::vector<uint64_t>{first.individual()});
  EXPECT_EQ(CompletionsOf(two[0].id), 1);
  EXPECT_EQ(CompletionsOf(two[1].id), 1);
}

// A real worker against a master played by the test: a result the master
// did not acknowledge is sent again after the worker reconnects (the master
// fell silent, as a dead one does); once acknowledged, it is not.
TEST_F(DispatchTest, WorkerSendsUnacknowledgedResultsAgainToItsNextMaster) {
  FakeMaster master(context_);
  const v1::Config config = ConfigToProto(config_);
  const uint64_t config_hash = protocol::ConfigHash(config);
  const v1::Genome genome = DataGenome("seed-1198");
  const v1::EvaluationResult expected = DirectResult(genome, config_);
  WorkerArgs args;
  args.endpoint = master.endpoint();
  args.threads = 1;
  WorkerProcess worker(args);
  ASSERT_TRUE(worker.started());

  // Silent for 300 ms: master lost.
  const v1::Envelope welcome = FakeWelcome(config, kHeartbeatMs, config_hash);
  const auto is_hello = [](const v1::Envelope& e) { return e.has_hello(); };
  const auto results_of_7 = [](const v1::Envelope& e) {
    return e.has_results() && e.results().results_size() > 0 &&
           e.results().results(0).individual() == 7;
  };
  // Waits for the worker's next hello (on a new connection) and welcomes
  // it; its identity.
  const auto session = [&]() -> std::string {
    std::optional<RoutedMessage> hello =
        master.ReceiveEnvelope("", kShortWait, is_hello);
    if (!hello) return "";
    master.Send(hello->identity, welcome);
    return hello->identity;
  };

  const std::string first = session();
  ASSERT_FALSE(first.empty()) << worker.output();
  v1::Envelope work;
  work.mutable_work()->set_config_hash(config_hash);
  v1::WorkItem* item = work.mutable_work()->add_items();
  item->set_individual(7);
  *item->mutable_genome() = genome;
  item->set_genome_hash(protocol::GenomeHash(genome));
  master.Send(first, work);
  std::vector<v1::Envelope> seen;
  ASSERT_TRUE(master.ReceiveEnvelope(first, kShortWait, results_of_7, &seen))
      << worker.output();
  ExpectSameResult(seen.back().results().results(0).result(), expected, 7);

  // Silence: the worker takes this master for lost and greets the next.
  const std::string second = session();
  ASSERT_FALSE(second.empty()) << worker.output();
  EXPECT_NE(second, first);
  seen.clear();
  ASSERT_TRUE(master.ReceiveEnvelope(second, kShortWait, results_of_7, &seen))
      << "the unacknowledged result was not sent again\n"
      << worker.output();
  const v1::WorkResult& resent = seen.back().results().results(0);
  EXPECT_EQ(resent.genome_hash(), protocol::GenomeHash(genome));
  ExpectSameResult(resent.result(), expected, 7);

  v1::Envelope acknowledge;
  acknowledge.mutable_acknowledge()->add_individuals(7);
  master.Send(second, acknowledge);
  // Heartbeats for a while, so the acknowledgement is surely read.
  (void)master.ReceiveEnvelope(second, milliseconds(4 * kHeartbeatMs / 2),
                               [](const v1::Envelope&) { return false; });
  const std::string third = session();
  ASSERT_FALSE(third.empty()) << worker.output();
  seen.clear();
  EXPECT_FALSE(master.ReceiveEnvelope(third, milliseconds(5 * kHeartbeatMs),
                                      results_of_7, &seen))
      << "an acknowledged result was sent again\n"
      << worker.output();
  // It said so, once.
  const std::string log = worker.output();
  const std::string line = "sending again 1 results not acknowledged";
  const size_t at = log.find(line);
  EXPECT_NE(at, std::string::npos) << log;
  EXPECT_EQ(log.find(line, at + 1), std::string::npos) << log;
}

}  // namespace
}  // namespace animat::testing
