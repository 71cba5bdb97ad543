// The master benchmarks' evaluation service (master/dispatch/
// evaluation_service.h): a service (a Dispatcher, or a campaign's lane of
// one) whose null-evaluation workers simulate nothing, with each of their
// results scored here as OK with the stand-in fitness
// NullEvaluationFitness(seed, id), so that an
// EvolutionRun served through it selects generation after generation and
// records every result by the same store writes as a real one. No command
// line reaches it: animat-master serves its run with the Dispatcher
// itself, and a run refuses null results (evolution_run.h).
//
// Header-only, so that the run tests use it without the benchmarks being
// built. Not thread-safe, like the service it wraps.
#ifndef ANIMAT_BENCH_NULL_SCORING_H_
#define ANIMAT_BENCH_NULL_SCORING_H_

#include <cstdint>
#include <vector>

#include "common/base/rng.h"
#include "master/dispatch/evaluation_service.h"

namespace animat::bench {

// The stand-in fitness of individual `id` of a run of `seed`: uniform in
// [0, 1), a pure function of the two.
inline double NullEvaluationFitness(uint64_t seed, uint64_t id) {
  return RandomStream(seed, id, StreamPurpose::kNullFitness).NextDouble();
}

class NullScoring final : public EvaluationService {
 public:
  // `service` (its dispatcher accepting null workers) must outlive this
  // object.
  NullScoring(EvaluationService* service, uint64_t seed)
      : service_(service), seed_(seed) {}

  void Submit(uint64_t individual, const v1::Genome& genome) override {
    service_->Submit(individual, genome);
  }
  void Submit(uint64_t individual,
              const protocol::SerializedGenome& genome) override {
    service_->Submit(individual, genome);
  }
  std::vector<Completion> Poll(int timeout_ms) override {
    std::vector<Completion> done = service_->Poll(timeout_ms);
    for (Completion& c : done) {
      if (!c.null_evaluation) continue;
      c.result.Clear();
      c.result.set_status(v1::EvaluationResult::OK);
      c.result.set_fitness(NullEvaluationFitness(seed_, c.individual));
      c.null_evaluation = false;
    }
    return done;
  }
  void Acknowledge(const std::vector<uint64_t>& individuals) override {
    service_->Acknowledge(individuals);
  }
  size_t pending() const override { return service_->pending(); }
  const Clock& clock() const override { return service_->clock(); }
  // The stand-in fitness depends on the id: a copy of a genome scores
  // differently from its original.
  bool results_follow_genome() const override { return false; }

 private:
  EvaluationService* service_;
  uint64_t seed_;
};

}  // namespace animat::bench

#endif  // ANIMAT_BENCH_NULL_SCORING_H_
