#include "master/run/initial_population.h"

#include "master/evolution/operators.h"

namespace animat {

Result<std::unique_ptr<InitialPopulation>> InitialPopulation::Load(
    lineage::Store* store, int64_t run) {
  Result<std::vector<lineage::Score>> stored = store->ScoresOf(run, 0);
  if (!stored.ok()) return stored.status();
  for (size_t i = 0; i < stored->size(); ++i) {
    if ((*stored)[i].id != i) {
      return Status::Internal(store->path() +
                              ": the random candidates of generation 0 are "
                              "not numbered 0, 1, ...: individual " +
                              std::to_string((*stored)[i].id) +
                              " is candidate " + std::to_string(i));
    }
  }
  return std::unique_ptr<InitialPopulation>(
      new InitialPopulation(std::move(stored).value()));
}

InitialPopulation::Step InitialPopulation::Next(
    const EvolutionParams& p) const {
  const size_t population = static_cast<size_t>(p.population);
  // The evaluated prefix (candidates [0, prefix) all evaluated) and the
  // accepted candidates in it, in id order.
  uint64_t prefix = 0;
  std::vector<uint64_t> accepted;
  for (const lineage::Score& c : candidates_) {
    if (!c.evaluated) break;
    prefix = c.id + 1;
    if (c.fitness && *c.fitness > p.initial_min_fitness) {
      accepted.push_back(c.id);
    }
  }
  // Block k (ids k*B .. (k+1)*B - 1) is made when blocks 0..k-2 are all
  // evaluated and hold fewer than `population` accepted candidates, so
  // one block is always ahead to keep workers busy. It comes before
  // choosing the population, which could otherwise end the making of
  // blocks at a moment that depends on timing.
  const uint64_t k = candidates_.size() / kCandidateBlock;
  bool make = k < 2;
  if (!make && prefix >= (k - 1) * kCandidateBlock) {
    const uint64_t limit = (k - 1) * kCandidateBlock;
    size_t before = 0;
    while (before < accepted.size() && accepted[before] < limit) ++before;
    make = before < population;
  }
  Step step;
  if (make) {
    for (uint64_t id = k * kCandidateBlock; id < (k + 1) * kCandidateBlock;
         ++id) {
      lineage::NewIndividual n;
      n.id = id;
      n.generation = 0;
      n.operators = {"random"};
      n.serialized = protocol::SerializeGenome(InitialCandidate(id, p));
      step.block.push_back(std::move(n));
    }
  } else if (accepted.size() >= population) {
    // The first `population` above the threshold, every candidate before
    // the last of them evaluated.
    accepted.resize(population);
    step.population = std::move(accepted);
  }
  return step;
}

void InitialPopulation::Made(const std::vector<lineage::NewIndividual>& block) {
  for (const lineage::NewIndividual& n : block) {
    lineage::Score score;
    score.id = n.id;
    candidates_.push_back(score);
  }
}

void InitialPopulation::Record(
    const std::vector<lineage::Evaluation>& committed) {
  for (const lineage::Evaluation& e : committed) {
    if (e.id >= candidates_.size() || candidates_[e.id].evaluated) continue;
    lineage::Score& c = candidates_[e.id];
    c.evaluated = true;
    if (e.result.has_fitness()) c.fitness = e.result.fitness();
  }
}

}  // namespace animat
