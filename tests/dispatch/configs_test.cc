// Several model configurations per master (docs/protocol.md, "Work"): a
// real worker evaluates each Work under the configuration it names, kept
// from the Work that carried it; refuses a carried configuration whose
// hash is not its hash, and work of a configuration it was never given or
// has forgotten (its items left out, their credit given back); and keeps
// no more than kMaxConfigs however many a master sends.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "common/evaluation/model_config.h"
#include "tests/dispatch/dispatch_harness.h"
#include "tests/dispatch/fake_peers.h"
#include "tests/dispatch/worker_process.h"

namespace animat::testing {
namespace {

v1::Envelope WorkOf(uint64_t hash, const v1::Config* carried,
                    const std::vector<std::pair<uint64_t, v1::Genome>>& items) {
  v1::Envelope envelope;
  envelope.mutable_work()->set_config_hash(hash);
  if (carried != nullptr) *envelope.mutable_work()->mutable_config() = *carried;
  for (const auto& [individual, genome] : items) {
    v1::WorkItem* item = envelope.mutable_work()->add_items();
    item->set_individual(individual);
    *item->mutable_genome() = genome;
    item->set_genome_hash(protocol::GenomeHash(genome));
  }
  return envelope;
}

TEST_F(DispatchTest, WorkerKeepsTheConfigurationsItIsGivenAndNoMore) {
  FakeMaster master(context_);
  const v1::Config welcome_config = ConfigToProto(config_);
  ModelConfig dragged = config_;
  dragged.physics.drag_normal = 10;
  const v1::Config other = ConfigToProto(dragged);
  const uint64_t other_hash = protocol::ConfigHash(other);
  ASSERT_NE(other_hash, protocol::ConfigHash(welcome_config));
  const v1::Genome genome = DataGenome("seed-1198");
  const v1::EvaluationResult expected = DirectResult(genome, dragged);
  ASSERT_EQ(expected.status(), v1::EvaluationResult::OK);
  ASSERT_NE(expected.fitness(), DirectResult(genome, config_).fitness());

  WorkerArgs args;
  args.endpoint = master.endpoint();
  args.threads = 1;
  args.heartbeat_ms = 1000;  // Slack: this test is not about liveness.
  WorkerProcess worker(args);
  const std::optional<RoutedMessage> hello = master.ReceiveEnvelope(
      "", kShortWait, [](const v1::Envelope& e) { return e.has_hello(); });
  ASSERT_TRUE(hello.has_value());
  const std::string& id = hello->identity;
  master.Send(id, FakeWelcome(welcome_config, 1000,
                              protocol::ConfigHash(welcome_config)));

  // Carried once, then named only; both evaluated under it.
  master.Send(id, WorkOf(other_hash, &other, {{10, genome}}));
  master.Send(id, WorkOf(other_hash, nullptr, {{11, genome}}));
  // A carried configuration that does not hash to its name: not kept.
  v1::Config lying = other;
  lying.mutable_physics()->set_drag_normal(3);
  master.Send(id, WorkOf(other_hash + 1, &lying, {{12, genome}}));
  master.Send(id, WorkOf(other_hash + 1, nullptr, {{13, genome}}));
  std::map<uint64_t, v1::WorkResult> results;
  int credit = 0;
  const auto receive = [&](int wanted_credit, size_t wanted_results) {
    const auto end = Steady::now() + kLongWait;
    while ((credit < wanted_credit || results.size() < wanted_results) &&
           Steady::now() < end) {
      master.ReceiveEnvelope(id, milliseconds(50), [&](const v1::Envelope& e) {
        for (const v1::WorkResult& r : e.results().results()) {
          results[r.individual()] = r;
        }
        if (e.has_credit()) credit += static_cast<int>(e.credit().credit());
        return false;
      });
    }
  };
  // The welcome's credit, two left-out items' back, and one per result.
  receive(protocol::kPrefetch + 4, 2);
  ASSERT_EQ(results.size(), 2u) << worker.output();
  for (uint64_t id_done : {10u, 11u}) {
    ExpectSameResult(results[id_done].result(), expected, id_done);
  }
  EXPECT_NE(worker.output().find("hashes to"), std::string::npos)
      << worker.output();

  // A master that floods it with configurations: the oldest are forgotten.
  for (size_t i = 0; i < protocol::kMaxConfigs; ++i) {
    ModelConfig flood = config_;
    flood.physics.drag_normal = 20 + static_cast<double>(i);
    const v1::Config message = ConfigToProto(flood);
    master.Send(id, WorkOf(protocol::ConfigHash(message), &message, {}));
  }
  master.Send(id, WorkOf(other_hash, nullptr, {{14, genome}}));
  receive(protocol::kPrefetch + 5, 2);
  EXPECT_EQ(results.count(14), 0u);
  EXPECT_EQ(credit, protocol::kPrefetch + 5) << worker.output();
  EXPECT_NE(worker.output().find("was never given to this worker, or "
                                 "forgotten"),
            std::string::npos)
      << worker.output();
  EXPECT_TRUE(worker.Running());
}

}  // namespace
}  // namespace animat::testing
