// One evaluation service shared by several runs' lanes
// (master/campaign/shared_evaluators.h): ids kept apart by lane, each
// completion back to its own lane, acknowledgements passed on, and a lane
// waiting in Poll woken by the pump.
#include "master/campaign/shared_evaluators.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <map>
#include <thread>
#include <vector>

#include "common/protocol/genome_wire.h"

namespace animat {
namespace {

// An evaluation service whose individuals complete when the test says.
class ScriptedService final : public MultiConfigService {
 public:
  void Submit(uint64_t individual, const v1::Genome& genome) override {
    Submit(individual, protocol::SerializeGenome(genome));
  }
  void Submit(uint64_t individual,
              const protocol::SerializedGenome& genome) override {
    SubmitUnder(0, individual, genome);
  }
  Result<size_t> AddConfig(const v1::Config&) override {
    return Status::Internal("not used here");
  }
  void SubmitUnder(size_t config, uint64_t individual,
                   const protocol::SerializedGenome& genome) override {
    submitted.push_back(individual);
    hashes[individual] = genome.hash;
    configs[individual] = config;
  }
  std::vector<Completion> Poll(int) override {
    std::vector<Completion> done;
    done.swap(ready);
    return done;
  }
  void Acknowledge(const std::vector<uint64_t>& individuals) override {
    acknowledged.insert(acknowledged.end(), individuals.begin(),
                        individuals.end());
  }
  size_t pending() const override { return submitted.size(); }
  const Clock& clock() const override { return RealClock(); }

  void Complete(uint64_t key, double fitness) {
    Completion c;
    c.individual = key;
    c.result.set_status(v1::EvaluationResult::OK);
    c.result.set_fitness(fitness);
    ready.push_back(c);
  }

  std::vector<uint64_t> submitted;
  std::map<uint64_t, uint64_t> hashes;
  std::map<uint64_t, size_t> configs;
  std::vector<uint64_t> acknowledged;
  std::vector<Completion> ready;
};

v1::Genome GenomeWith(double x) {
  v1::Genome genome;
  genome.add_elements()->set_x(x);
  return genome;
}

constexpr uint64_t kLane1 = uint64_t{1} << SharedEvaluators::kIdBits;

TEST(SharedEvaluatorsTest, OneIdInTwoRunsIsTwoIndividualsEachBackToItsRun) {
  ScriptedService service;
  SharedEvaluators shared(&service);
  EvaluationService* a = shared.AddLane(0);
  EvaluationService* b = shared.AddLane(5);
  a->Submit(1, GenomeWith(1));
  b->Submit(1, GenomeWith(2));
  a->Submit(1, GenomeWith(1));  // Pending already: left as it is.
  EXPECT_EQ(a->pending(), 1u);
  EXPECT_EQ(b->pending(), 1u);
  shared.Pump(0);
  EXPECT_EQ(service.submitted, (std::vector<uint64_t>{1, kLane1 | 1}));
  EXPECT_EQ(service.hashes[kLane1 | 1],
            protocol::SerializeGenome(GenomeWith(2)).hash);
  // Each under its run's configuration.
  EXPECT_EQ(service.configs[1], 0u);
  EXPECT_EQ(service.configs[kLane1 | 1], 5u);

  service.Complete(kLane1 | 1, 2.5);
  shared.Pump(0);
  EXPECT_TRUE(a->Poll(0).empty());
  std::vector<Completion> done = b->Poll(0);
  ASSERT_EQ(done.size(), 1u);
  EXPECT_EQ(done[0].individual, 1u);
  EXPECT_EQ(done[0].result.fitness(), 2.5);
  EXPECT_EQ(a->pending(), 1u);
  EXPECT_EQ(b->pending(), 0u);

  b->Acknowledge({1});
  shared.Pump(0);
  EXPECT_EQ(service.acknowledged, std::vector<uint64_t>{kLane1 | 1});
  EXPECT_TRUE(shared.error(0).ok());
  EXPECT_TRUE(shared.error(1).ok());
}

TEST(SharedEvaluatorsTest, AnIdBeyondTheLanesBitsIsAnErrorAndNotSubmitted) {
  ScriptedService service;
  SharedEvaluators shared(&service);
  EvaluationService* lane = shared.AddLane(0);
  lane->Submit(uint64_t{1} << SharedEvaluators::kIdBits, GenomeWith(1));
  shared.Pump(0);
  EXPECT_TRUE(service.submitted.empty());
  EXPECT_EQ(lane->pending(), 0u);
  EXPECT_FALSE(shared.error(0).ok());
  EXPECT_NE(shared.error(0).message().find("44-bit"), std::string::npos);
}

TEST(SharedEvaluatorsTest, ARunWaitingInPollIsWokenByThePump) {
  ScriptedService service;
  SharedEvaluators shared(&service);
  EvaluationService* lane = shared.AddLane(0);
  lane->Submit(3, GenomeWith(3));
  shared.Pump(0);
  std::vector<Completion> done;
  std::thread run([&] { done = lane->Poll(60000); });
  service.Complete(3, 1.0);
  shared.Pump(0);
  run.join();  // Long before the minute, or the test times out.
  ASSERT_EQ(done.size(), 1u);
  EXPECT_EQ(done[0].individual, 3u);
}

}  // namespace
}  // namespace animat
