// The initial-population phase of a run (docs/evolution.md): random
// candidates, ids 0, 1, ..., made kCandidateBlock at a time and evaluated;
// the population is the first `population` candidates whose fitness is
// above initial_min_fitness.
//
// Determinism: block k is made only once blocks 0..k-2 are all evaluated
// and hold fewer than `population` accepted candidates, and the population
// is chosen only once every candidate before its last member is
// evaluated: decisions on evaluated candidates only, so every run of a
// seed makes the same blocks and chooses the same population whatever the
// order results arrive in.
//
// Keeps the candidates' scores as committed to the store (read once by
// Load, then kept in step by Made and Record), so that deciding does not
// read every candidate back at every commit. Not thread-safe.
#ifndef ANIMAT_MASTER_RUN_INITIAL_POPULATION_H_
#define ANIMAT_MASTER_RUN_INITIAL_POPULATION_H_

#include <cstdint>
#include <memory>
#include <vector>

#include "common/base/status.h"
#include "master/evolution/evolution_params.h"
#include "master/lineage/store.h"

namespace animat {

// Initial candidates are made this many at a time.
inline constexpr int kCandidateBlock = 1024;

class InitialPopulation {
 public:
  // The candidates of `run` made so far, with their scores; fails on a
  // store whose candidates are not numbered 0, 1, ...
  static Result<std::unique_ptr<InitialPopulation>> Load(lineage::Store* store,
                                                         int64_t run);

  // What to do next: make and evaluate a block of candidates, or take the
  // population (ids, increasing), or neither (waiting for evaluations).
  struct Step {
    std::vector<lineage::NewIndividual> block;
    std::vector<uint64_t> population;
  };
  Step Next(const EvolutionParams& params) const;

  // Next's block is in the store: its candidates await evaluation.
  void Made(const std::vector<lineage::NewIndividual>& block);
  // These evaluations are committed (the store keeps an individual's first
  // evaluation; so does this). Others than candidates' are ignored.
  void Record(const std::vector<lineage::Evaluation>& committed);

 private:
  explicit InitialPopulation(std::vector<lineage::Score> candidates)
      : candidates_(std::move(candidates)) {}

  std::vector<lineage::Score> candidates_;  // Candidate i has id i.
};

}  // namespace animat

#endif  // ANIMAT_MASTER_RUN_INITIAL_POPULATION_H_
